// Shadow map projections and the atlas packing (shadow_fit.hpp).
#include "render/shadow_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace rscene::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Orthonormal light frame: x `left`, y `up`, looking along `fwd`.
void lightFrame(const Eigen::Vector3d& dir, Eigen::Vector3d& fwd, Eigen::Vector3d& left, Eigen::Vector3d& up) {
  fwd = dir.norm() > 1e-12 ? dir.normalized() : Eigen::Vector3d(0, 0, -1);
  Eigen::Vector3d hint = std::abs(fwd.z()) > 0.99 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
  left = hint.cross(fwd).normalized();
  up = fwd.cross(left);
}

// Orthographic clip matrix of the light-space box [x0,x1] x [y0,y1] x [z0,z1].
ShadowView orthoView(const Eigen::Vector3d& fwd, const Eigen::Vector3d& left, const Eigen::Vector3d& up, double x0,
                     double x1, double y0, double y1, double z0, double z1, int resolution) {
  ShadowView v;
  double hx = std::max(0.5 * (x1 - x0), 0.05), hy = std::max(0.5 * (y1 - y0), 0.05);
  double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  if (!(z1 - z0 > 0.01)) z1 = z0 + 0.01;
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m.block<1, 3>(0, 0) = left.transpose() / hx;
  m(0, 3) = -cx / hx;
  m.block<1, 3>(1, 0) = up.transpose() / hy;
  m(1, 3) = -cy / hy;
  m.block<1, 3>(2, 0) = fwd.transpose() * (2 / (z1 - z0));
  m(2, 3) = -2 * z0 / (z1 - z0) - 1;
  m(3, 3) = 1;
  v.viewProj = m;
  v.nearPlane = z0;
  v.farPlane = z1;
  v.texelWorld = 2 * std::max(hx, hy) / std::max(resolution, 1);
  v.perspective = false;
  v.empty = false;
  return v;
}

// Perspective view from `eye`: rows right, up, -forward; x and y scaled by `scale`.
ShadowView frustumView(const Eigen::Vector3d& eye, const Eigen::Vector3d& fwd, const Eigen::Vector3d& right,
                       double scale, double n, double f, int resolution) {
  Eigen::Vector3d up = right.cross(fwd);
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
  view.block<1, 3>(0, 0) = right.transpose();
  view.block<1, 3>(1, 0) = up.transpose();
  view.block<1, 3>(2, 0) = -fwd.transpose();
  view.block<3, 1>(0, 3) = -view.block<3, 3>(0, 0) * eye;
  n = std::max(n, 1e-3);
  if (!(f > n * 1.01)) f = n * 1.01 + 0.01;
  Eigen::Matrix4d proj = Eigen::Matrix4d::Zero();
  proj(0, 0) = scale;
  proj(1, 1) = scale;
  proj(2, 2) = -(f + n) / (f - n);
  proj(2, 3) = -2 * f * n / (f - n);
  proj(3, 2) = -1;
  ShadowView v;
  v.viewProj = proj * view;
  v.nearPlane = n;
  v.farPlane = f;
  v.texelWorld = 2 / scale / std::max(resolution, 1);
  v.perspective = true;
  v.empty = false;
  return v;
}

using Polygon = std::vector<Eigen::Vector3d>;

// Sutherland-Hodgman: the part of `poly` where p[axis] * sign <= limit * sign.
Polygon clip(const Polygon& poly, int axis, double limit, double sign) {
  Polygon out;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector3d& a = poly[i];
    const Eigen::Vector3d& b = poly[(i + 1) % poly.size()];
    double da = sign * (a[axis] - limit), db = sign * (b[axis] - limit);
    if (da <= 0) out.push_back(a);
    if ((da < 0 && db > 0) || (da > 0 && db < 0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

// The corners of the polytope where the view's frustum and `box` overlap.
std::vector<Eigen::Vector3d> frustumBoxPoints(const Eigen::Matrix4d& viewProj, const Eigen::AlignedBox3d& box) {
  std::vector<Eigen::Vector3d> points;
  Eigen::Matrix4d inv = viewProj.inverse();
  if (!inv.allFinite()) return points;
  Eigen::Vector3d c[8];
  for (int i = 0; i < 8; ++i) {
    Eigen::Vector4d h = inv * Eigen::Vector4d(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1, 1);
    c[i] = h.head<3>() / h.w();
  }
  static const int faces[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
  for (const auto& f : faces) {
    Polygon poly{c[f[0]], c[f[1]], c[f[2]], c[f[3]]};
    for (int axis = 0; axis < 3 && !poly.empty(); ++axis) {
      poly = clip(poly, axis, box.max()[axis], 1);
      if (!poly.empty()) poly = clip(poly, axis, box.min()[axis], -1);
    }
    points.insert(points.end(), poly.begin(), poly.end());
  }
  for (int i = 0; i < 8; ++i) {
    Eigen::Vector3d p = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i));
    Eigen::Vector4d h = viewProj * Eigen::Vector4d(p.x(), p.y(), p.z(), 1);
    if (h.w() > 0 && std::abs(h.x()) <= h.w() && std::abs(h.y()) <= h.w() && std::abs(h.z()) <= h.w())
      points.push_back(p);
  }
  return points;
}

}  // namespace

Eigen::AlignedBox3d withShadowFootprint(const Eigen::AlignedBox3d& casters, const Eigen::Vector3d& dir,
                                        double floorZ, double maxDrop) {
  Eigen::AlignedBox3d out = casters;
  if (casters.isEmpty()) return out;
  Eigen::Vector3d fwd = dir.normalized();
  floorZ = std::min(floorZ, casters.min().z());
  if (fwd.z() < -0.05)
    for (int i = 0; i < 8; ++i) {
      Eigen::Vector3d p = casters.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i));
      out.extend(p + fwd * std::min((p.z() - floorZ) / -fwd.z(), maxDrop));
    }
  return out;
}

ShadowView fitDirectionalShadow(const Eigen::Vector3d& dir, const Eigen::Matrix4d& cameraViewProj,
                                const Eigen::AlignedBox3d& casters, double floorZ, int resolution,
                                double marginTexels) {
  ShadowView empty;
  if (casters.isEmpty()) return empty;
  Eigen::AlignedBox3d receivers = withShadowFootprint(casters, dir, floorZ);
  std::vector<Eigen::Vector3d> seen = frustumBoxPoints(cameraViewProj, receivers);
  if (seen.empty()) return empty;
  Eigen::Vector3d fwd, left, up;
  lightFrame(dir, fwd, left, up);
  double inf = std::numeric_limits<double>::infinity();
  double x0 = inf, x1 = -inf, y0 = inf, y1 = -inf, z1 = -inf, z0 = inf;
  for (const Eigen::Vector3d& p : seen) {
    x0 = std::min(x0, left.dot(p)), x1 = std::max(x1, left.dot(p));
    y0 = std::min(y0, up.dot(p)), y1 = std::max(y1, up.dot(p));
    z1 = std::max(z1, fwd.dot(p));
  }
  for (int i = 0; i < 8; ++i) z0 = std::min(z0, fwd.dot(receivers.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i))));
  // Margins: the filter's reach at the edges, a little depth either way.
  double mx = (x1 - x0) * marginTexels / std::max(resolution, 1), my = (y1 - y0) * marginTexels / std::max(resolution, 1);
  return orthoView(fwd, left, up, x0 - mx, x1 + mx, y0 - my, y1 + my, z0 - 0.05, z1 + 0.05, resolution);
}

ShadowView customDirectionalShadow(const Eigen::Vector3d& dir, const Eigen::Vector3d& centre, double halfSize,
                                   double nearPlane, double farPlane, int resolution) {
  Eigen::Vector3d fwd, left, up;
  lightFrame(dir, fwd, left, up);
  halfSize = std::max(halfSize, 0.05);
  double eye = fwd.dot(centre) - farPlane / 2;
  return orthoView(fwd, left, up, left.dot(centre) - halfSize, left.dot(centre) + halfSize, up.dot(centre) - halfSize,
                   up.dot(centre) + halfSize, eye + nearPlane, eye + std::max(farPlane, nearPlane + 0.01), resolution);
}

ShadowView perspectiveShadow(const Eigen::Vector3d& eye, const Eigen::Vector3d& dir, double halfAngleDeg,
                             double nearPlane, double farPlane, int resolution) {
  Eigen::Vector3d fwd = dir.norm() > 1e-12 ? dir.normalized() : Eigen::Vector3d(0, 0, -1);
  Eigen::Vector3d hint = std::abs(fwd.z()) > 0.99 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
  Eigen::Vector3d right = fwd.cross(hint).normalized();
  double half = std::clamp(halfAngleDeg, 1.0, 89.0) * kPi / 180;
  return frustumView(eye, fwd, right, 1 / std::tan(half), nearPlane, farPlane, resolution);
}

double cubeFaceScale(int resolution, double marginTexels) {
  return std::clamp(1 - 2 * marginTexels / std::max(resolution, 1), 0.5, 1.0);
}

ShadowView cubeFaceShadow(const Eigen::Vector3d& eye, int face, double nearPlane, double farPlane, double faceScale,
                          int resolution) {
  face = std::clamp(face, 0, 5);
  Eigen::Vector3d fwd(kCubeForward[face][0], kCubeForward[face][1], kCubeForward[face][2]);
  Eigen::Vector3d right(kCubeRight[face][0], kCubeRight[face][1], kCubeRight[face][2]);
  return frustumView(eye, fwd, right, faceScale, nearPlane, farPlane, resolution);
}

bool packAtlas(const std::vector<Eigen::Vector2i>& sizes, int side, std::vector<Eigen::Vector2i>& origins) {
  origins.assign(sizes.size(), Eigen::Vector2i::Zero());
  std::vector<std::size_t> order(sizes.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return sizes[a].y() > sizes[b].y(); });
  int x = 0, y = 0, shelf = 0;
  for (std::size_t i : order) {
    const Eigen::Vector2i& s = sizes[i];
    if (s.x() > side || s.y() > side) return false;
    if (x + s.x() > side) {
      x = 0;
      y += shelf;
      shelf = 0;
    }
    if (y + s.y() > side) return false;
    origins[i] = Eigen::Vector2i(x, y);
    x += s.x();
    shelf = std::max(shelf, s.y());
  }
  return true;
}

}  // namespace rscene::render
