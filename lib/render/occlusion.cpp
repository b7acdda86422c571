#include "render/occlusion.hpp"

#include <algorithm>
#include <cmath>

namespace rscene::render::detail {
namespace {

// Nearer than this (NDC depth) in front of an occluder is not "behind it":
// surfaces that touch stay drawn, the depth test decides between them.
constexpr double kDepthMargin = 1e-6;

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

}  // namespace

OcclusionBuffer::OcclusionBuffer(const Eigen::Matrix4d& viewProj, int imageWidth, int imageHeight, int cells)
    : viewProj_(viewProj) {
  w_ = std::max(1, std::min(cells, imageWidth));
  h_ = std::max(1, int(std::lround(double(w_) * imageHeight / std::max(imageWidth, 1))));
  depth_.assign(std::size_t(w_) * std::size_t(h_), 1.0);
}

bool OcclusionBuffer::project(const Eigen::Vector3d& p, Point& out) const {
  Eigen::Vector4d c = viewProj_ * Eigen::Vector4d(p.x(), p.y(), p.z(), 1);
  if (!(c.w() > 1e-9)) return false;
  out.x = (c.x() / c.w() + 1) * 0.5 * w_;
  out.y = (c.y() / c.w() + 1) * 0.5 * h_;
  out.z = c.z() / c.w();
  return std::isfinite(out.x) && std::isfinite(out.y) && std::isfinite(out.z);
}

bool OcclusionBuffer::hidden(const Eigen::AlignedBox3d& box) const {
  if (box.isEmpty()) return false;
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY, zmin = INFINITY;
  for (int i = 0; i < 8; ++i) {
    Point p;
    if (!project(box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)), p)) return false;
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
    zmin = std::min(zmin, p.z);
  }
  // Every cell the rectangle touches (a cell edge counts as touching).
  int i0 = std::max(0, int(std::floor(x0))), i1 = std::min(w_ - 1, int(std::floor(x1)));
  int j0 = std::max(0, int(std::floor(y0))), j1 = std::min(h_ - 1, int(std::floor(y1)));
  if (i0 > i1 || j0 > j1) return false;  // off the buffer: the frustum test decides
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i)
      if (!(depth_[std::size_t(j) * w_ + i] + kDepthMargin < zmin)) return false;
  return true;
}

void OcclusionBuffer::fill(const std::vector<Point>& poly, bool planar, double flat) {
  const std::size_t n = poly.size();
  if (n < 3) return;
  double area = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const Point &a = poly[k], &b = poly[(k + 1) % n];
    area += a.x * b.y - b.x * a.y;
  }
  if (std::abs(area) < 1e-9) return;
  double sign = area > 0 ? 1 : -1;
  // Depth as a plane over the cells: NDC depth is affine in screen space
  // on a planar face, so its largest value over a cell is at a corner.
  double A = 0, B = 0, C = flat;
  if (planar) {
    const Point &p0 = poly[0], &p1 = poly[1], &p2 = poly[2];
    double det = (p1.x - p0.x) * (p2.y - p0.y) - (p2.x - p0.x) * (p1.y - p0.y);
    if (std::abs(det) < 1e-12) return;
    A = ((p1.z - p0.z) * (p2.y - p0.y) - (p2.z - p0.z) * (p1.y - p0.y)) / det;
    B = ((p2.z - p0.z) * (p1.x - p0.x) - (p1.z - p0.z) * (p2.x - p0.x)) / det;
    C = p0.z - A * p0.x - B * p0.y;
  }
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (const Point& p : poly) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  // Cells entirely inside: [i, i+1] x [j, j+1] within the bounding box.
  int i0 = std::max(0, int(std::ceil(x0))), i1 = std::min(w_, int(std::floor(x1))) - 1;
  int j0 = std::max(0, int(std::ceil(y0))), j1 = std::min(h_, int(std::floor(y1))) - 1;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      bool inside = true;
      for (std::size_t k = 0; k < n && inside; ++k) {
        Eigen::Vector2d a(poly[k].x, poly[k].y), b(poly[(k + 1) % n].x, poly[(k + 1) % n].y);
        for (int c = 0; c < 4 && inside; ++c)
          inside = sign * cross(a, b, Eigen::Vector2d(i + (c & 1), j + (c >> 1))) > 1e-9;
      }
      if (!inside) continue;
      double z = flat;
      if (planar) {
        z = -INFINITY;
        for (int c = 0; c < 4; ++c) z = std::max(z, A * (i + (c & 1)) + B * (j + (c >> 1)) + C);
      }
      double& cell = depth_[std::size_t(j) * w_ + i];
      cell = std::min(cell, z);
    }
}

void OcclusionBuffer::addBox(const Eigen::Matrix4d& model) {
  Point p[8];
  double zmax = -INFINITY;
  for (int i = 0; i < 8; ++i) {
    Eigen::Vector4d local((i & 1) ? 0.5 : -0.5, (i & 2) ? 0.5 : -0.5, (i & 4) ? 0.5 : -0.5, 1);
    Eigen::Vector4d world = model * local;
    // Only a box wholly between the near and far planes: a clipped part
    // would hide nothing.
    if (!project(world.head<3>(), p[i]) || p[i].z < -1 || p[i].z > 1) return;
    zmax = std::max(zmax, p[i].z);
  }
  // The silhouette (the convex hull of the corners) at the box's farthest
  // depth: covers the cells between its faces.
  std::vector<Eigen::Vector2d> pts;
  for (const Point& q : p) pts.emplace_back(q.x, q.y);
  std::sort(pts.begin(), pts.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  std::vector<Eigen::Vector2d> hull(16);
  int k = 0;
  for (int i = 0; i < 8; ++i) {
    while (k >= 2 && cross(hull[std::size_t(k - 2)], hull[std::size_t(k - 1)], pts[std::size_t(i)]) <= 0) --k;
    hull[std::size_t(k++)] = pts[std::size_t(i)];
  }
  for (int i = 6, t = k + 1; i >= 0; --i) {
    while (k >= t && cross(hull[std::size_t(k - 2)], hull[std::size_t(k - 1)], pts[std::size_t(i)]) <= 0) --k;
    hull[std::size_t(k++)] = pts[std::size_t(i)];
  }
  std::vector<Point> poly;
  for (int i = 0; i + 1 < k; ++i) poly.push_back({hull[std::size_t(i)].x(), hull[std::size_t(i)].y(), zmax});
  fill(poly, false, zmax);
  // Each face at its own depth: nearer where one face covers a cell.
  static const int kFaces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
  for (const auto& f : kFaces) {
    std::vector<Point> quad = {p[f[0]], p[f[1]], p[f[2]], p[f[3]]};
    fill(quad, true, 0);
  }
}

}  // namespace rscene::render::detail
