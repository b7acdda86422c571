#include "scene/deformable_fill.hpp"

#include <algorithm>
#include <cmath>

namespace rscene {
namespace {

// Tests of a ray against a triangle or of a pair of points: past this, a
// fill or a strut search is refused rather than left to run for minutes.
constexpr double kMaxWork = 1e9;

using Edge = std::pair<std::uint32_t, std::uint32_t>;

}  // namespace

bool closedSurface(const std::vector<std::array<std::uint32_t, 3>>& triangles, std::string& error) {
  std::vector<Edge> edges;
  edges.reserve(triangles.size() * 3);
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) edges.push_back(std::minmax(t[k], t[(k + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i != 2) {
      error = "the edge between vertices " + std::to_string(edges[i].first) + " and " +
              std::to_string(edges[i].second) + " belongs to " + std::to_string(j - i) +
              (j - i == 1 ? " triangle" : " triangles") + " (a closed surface has two at every edge)";
      return false;
    }
    i = j;
  }
  return true;
}

bool fillClosedSurface(const std::vector<Eigen::Vector3d>& v, const std::vector<std::array<std::uint32_t, 3>>& tris,
                       double s, std::uint64_t maxTotal, std::vector<Eigen::Vector3d>& out, std::string& error) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (const auto& p : v) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  // Grid points per axis, centred in the bounds: n = floor(extent / s).
  double n[3];
  for (int k = 0; k < 3; ++k) n[k] = std::floor((hi[k] - lo[k]) / s);
  if (!(n[0] * n[1] <= kMaxWork) || !(n[2] <= kMaxWork)) {
    error = "a fill at this spacing would test " + std::to_string(n[0] * n[1]) + " grid columns (more than 1e9)";
    return false;
  }
  const long nx = static_cast<long>(n[0]), ny = static_cast<long>(n[1]), nz = static_cast<long>(n[2]);
  auto coord = [&](int k, long i) { return lo[k] + ((hi[k] - lo[k]) - (n[k] - 1) * s) / 2 + i * s; };
  // The rays run off the grid by a tiny irrational offset, so that none
  // passes exactly through a vertex or along an edge shared by two
  // triangles (counted twice or not at all).
  const double jx = s * 7.548776662e-7, jy = s * 5.698402910e-7;

  // Two passes: count, refuse past maxTotal, then append.
  for (int pass = 0; pass < 2; ++pass) {
    std::uint64_t count = 0;
    double work = 0;
    std::vector<std::uint32_t> row;
    std::vector<double> hits;
    for (long i = 0; i < nx; ++i) {
      const double x = coord(0, i) + jx;
      row.clear();
      for (std::uint32_t t = 0; t < tris.size(); ++t) {
        const auto& tr = tris[t];
        double a = v[tr[0]].x(), b = v[tr[1]].x(), c = v[tr[2]].x();
        if (std::min({a, b, c}) <= x && x <= std::max({a, b, c})) row.push_back(t);
      }
      work += static_cast<double>(tris.size()) + static_cast<double>(row.size()) * static_cast<double>(ny);
      if (work > kMaxWork) {
        error = "a fill at this spacing would take more than 1e9 ray tests (a coarser particleSpacing or a simpler mesh)";
        return false;
      }
      for (long j = 0; j < ny; ++j) {
        const double y = coord(1, j) + jy;
        hits.clear();
        for (std::uint32_t t : row) {
          const Eigen::Vector3d &p0 = v[tris[t][0]], &p1 = v[tris[t][1]], &p2 = v[tris[t][2]];
          // Barycentric coordinates of (x, y) in the triangle's xy projection.
          double d = (p1.x() - p0.x()) * (p2.y() - p0.y()) - (p2.x() - p0.x()) * (p1.y() - p0.y());
          if (d == 0) continue;  // seen edge-on: the neighbours carry the crossing
          double u = ((x - p0.x()) * (p2.y() - p0.y()) - (p2.x() - p0.x()) * (y - p0.y())) / d;
          double w = ((p1.x() - p0.x()) * (y - p0.y()) - (x - p0.x()) * (p1.y() - p0.y())) / d;
          if (u < 0 || w < 0 || u + w > 1) continue;
          hits.push_back(p0.z() + u * (p1.z() - p0.z()) + w * (p2.z() - p0.z()));
        }
        std::sort(hits.begin(), hits.end());
        // Inside between the 1st and 2nd crossing, the 3rd and 4th ...
        for (std::size_t h = 0; h + 1 < hits.size(); h += 2) {
          double z0 = hits[h] + s / 4, z1 = hits[h + 1] - s / 4;
          if (!(z0 <= z1)) continue;
          const double base = coord(2, 0);
          long k0 = std::max(0L, static_cast<long>(std::ceil((z0 - base) / s)));
          long k1 = std::min(nz - 1, static_cast<long>(std::floor((z1 - base) / s)));
          if (k1 < k0) continue;
          if (pass == 0) {
            count += static_cast<std::uint64_t>(k1 - k0 + 1);
            if (count + out.size() > maxTotal) {
              error = "a fill at this spacing makes more than " + std::to_string(maxTotal) + " particles";
              return false;
            }
          } else {
            for (long k = k0; k <= k1; ++k) out.emplace_back(coord(0, i), coord(1, j), coord(2, k));
          }
        }
      }
    }
    if (pass == 0) out.reserve(out.size() + count);
  }
  return true;
}

bool pairsWithinRadius(const std::vector<Eigen::Vector3d>& p, double r, std::uint64_t maxPairs,
                       std::vector<std::pair<std::uint32_t, std::uint32_t>>& out, std::string& error) {
  if (p.empty()) return true;
  Eigen::Vector3d lo = p[0], hi = p[0];
  for (const auto& x : p) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  if (!(((hi - lo) / r).maxCoeff() < 1e9)) {
    error = "the strut radius is too small for the body's size (more than 1e9 cells a side)";
    return false;
  }
  // Points sorted by their cell of side r: the neighbours of a point are
  // in the 27 cells around its own, each a range of the sorted list.
  using Cell = std::array<std::int64_t, 3>;
  auto cellOf = [&](const Eigen::Vector3d& x) {
    Eigen::Vector3d c = ((x - lo) / r).array().floor();
    return Cell{static_cast<std::int64_t>(c.x()), static_cast<std::int64_t>(c.y()), static_cast<std::int64_t>(c.z())};
  };
  std::vector<std::pair<Cell, std::uint32_t>> sorted(p.size());
  for (std::uint32_t i = 0; i < p.size(); ++i) sorted[i] = {cellOf(p[i]), i};
  std::sort(sorted.begin(), sorted.end());
  const double r2 = r * r;
  double work = 0;
  for (std::uint32_t i = 0; i < p.size(); ++i) {
    Cell c = cellOf(p[i]);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          Cell n{c[0] + dx, c[1] + dy, c[2] + dz};
          auto first = std::lower_bound(sorted.begin(), sorted.end(), std::pair<Cell, std::uint32_t>{n, 0});
          for (auto it = first; it != sorted.end() && it->first == n; ++it) {
            if (++work > kMaxWork) {
              error = "the strut search would test more than 1e9 pairs (the mesh is much denser than particleSpacing)";
              return false;
            }
            std::uint32_t j = it->second;
            if (j <= i || (p[j] - p[i]).squaredNorm() > r2) continue;
            if (out.size() >= maxPairs) {
              error = "more than " + std::to_string(maxPairs) + " struts";
              return false;
            }
            out.emplace_back(i, j);
          }
        }
  }
  std::sort(out.begin(), out.end());
  return true;
}

}  // namespace rscene
