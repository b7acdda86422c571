#include "scene/neighbour_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace rscene {
namespace {

// 62 bits per axis: the cell numbers of spheres 1e9 m apart in cells of
// a nanometre still fit.  Past it a sphere shares the last cell of its
// axis: clamping is monotonic, so spheres in touch stay in neighbouring
// cells, and only the (far, rare) clamped ones cost extra distance tests.
constexpr std::uint64_t kLastCell = std::uint64_t{1} << 62;

std::uint64_t axisCell(double coordinate, double origin, double inverseCell) {
  double c = std::floor((coordinate - origin) * inverseCell);
  if (!(c > 0)) return 0;  // NaN too: such a run is stopped as non-finite after the step
  return c >= double(kLastCell) ? kLastCell : static_cast<std::uint64_t>(c);
}

}  // namespace

bool NeighbourGrid::pairs(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& r, double rMax,
                          double reach, std::vector<std::uint32_t>& i, std::vector<std::uint32_t>& j,
                          std::size_t maxPairs) {
  const std::size_t n = x.size();
  Eigen::Vector3d origin = Eigen::Vector3d::Constant(INFINITY);
  for (const Eigen::Vector3d& p : x) origin = origin.cwiseMin(p);
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(origin[a])) origin[a] = 0;
  const double inverse = 1 / (2 * rMax + reach);
  cellOf_.resize(n);
  std::uint64_t top[3] = {0, 0, 0};
  for (std::size_t k = 0; k < n; ++k) {
    std::uint64_t c[3];
    for (int a = 0; a < 3; ++a) c[a] = axisCell(x[k][a], origin[a], inverse), top[a] = std::max(top[a], c[a]);
    cellOf_[k] = {c[2], c[1], c[0]};
  }
  i.clear();
  j.clear();
  tests_ = 0;
  // A bed fills its bounding box: a dense grid of cells (a counting sort,
  // O(1) per neighbour cell) costs memory in proportion to the grains.
  // Grains flung far apart do not: then the sorted occupied cells.
  const double cells = double(top[0] + 1) * double(top[1] + 1) * double(top[2] + 1);
  if (cells <= 4.0 * double(n) + 1024) return denseCandidates(x, r, reach, {top[0] + 1, top[1] + 1, top[2] + 1}, i, j, maxPairs);
  return sparseCandidates(x, r, reach, i, j, maxPairs);
}

// Every pair (a < b) within reach, for a in index order, b ascending.
bool NeighbourGrid::emit(std::uint32_t a, std::vector<std::uint32_t>& i, std::vector<std::uint32_t>& j,
                         std::size_t maxPairs) {
  std::sort(candidates_.begin(), candidates_.end());
  for (std::uint32_t b : candidates_) {
    if (i.size() >= maxPairs) return false;
    i.push_back(a);
    j.push_back(b);
  }
  return true;
}

bool NeighbourGrid::denseCandidates(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& r, double reach,
                                    std::array<std::uint64_t, 3> dims, std::vector<std::uint32_t>& i,
                                    std::vector<std::uint32_t>& j, std::size_t maxPairs) {
  const std::size_t n = x.size();
  auto index = [&](std::uint64_t cx, std::uint64_t cy, std::uint64_t cz) { return cx + dims[0] * (cy + dims[1] * cz); };
  const std::size_t cells = dims[0] * dims[1] * dims[2];
  cellStart_.assign(cells + 1, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const Cell& c = cellOf_[k];
    ++cellStart_[index(c[2], c[1], c[0]) + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) cellStart_[c + 1] += cellStart_[c];
  order_.resize(n);
  cursor_.assign(cellStart_.begin(), cellStart_.end() - 1);
  for (std::uint32_t k = 0; k < n; ++k) {  // stable: by cell, then index
    const Cell& c = cellOf_[k];
    order_[cursor_[index(c[2], c[1], c[0])]++] = k;
  }
  for (std::uint32_t a = 0; a < n; ++a) {
    const std::uint64_t cx = cellOf_[a][2], cy = cellOf_[a][1], cz = cellOf_[a][0];
    candidates_.clear();
    for (std::uint64_t z = cz ? cz - 1 : 0; z <= std::min(cz + 1, dims[2] - 1); ++z)
      for (std::uint64_t y = cy ? cy - 1 : 0; y <= std::min(cy + 1, dims[1] - 1); ++y) {
        // The three cells along x of one (y, z) row are one run.
        const std::size_t lo = cellStart_[index(cx ? cx - 1 : 0, y, z)];
        const std::size_t hi = cellStart_[index(std::min(cx + 1, dims[0] - 1), y, z) + 1];
        for (std::size_t k = lo; k < hi; ++k) {
          const std::uint32_t b = order_[k];
          if (b <= a) continue;
          ++tests_;
          const double limit = r[a] + r[b] + reach;
          if ((x[a] - x[b]).squaredNorm() < limit * limit) candidates_.push_back(b);
        }
      }
    if (!emit(a, i, j, maxPairs)) return false;
  }
  // The sparse path's nearly-sorted order is gone: it sorts afresh.
  keys_.clear();
  return true;
}

bool NeighbourGrid::sparseCandidates(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& r,
                                     double reach, std::vector<std::uint32_t>& i, std::vector<std::uint32_t>& j,
                                     std::size_t maxPairs) {
  const std::size_t n = x.size();
  // Grains move little between builds, so the last order is nearly sorted
  // and an insertion sort is linear; past a budget of moves, std::sort.
  // Either gives the one order sorted by (key, index).
  auto less = [&](std::uint32_t a, std::uint32_t b) { return cellOf_[a] != cellOf_[b] ? cellOf_[a] < cellOf_[b] : a < b; };
  if (order_.size() != n || keys_.size() != n) {
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), 0u);
    std::sort(order_.begin(), order_.end(), less);
  } else {
    std::size_t moves = 0, budget = 8 * n + 64;
    for (std::size_t k = 1; k < n && moves <= budget; ++k) {
      std::uint32_t v = order_[k];
      std::size_t m = k;
      for (; m > 0 && less(v, order_[m - 1]) && moves <= budget; --m, ++moves) order_[m] = order_[m - 1];
      order_[m] = v;
    }
    if (moves > budget) std::sort(order_.begin(), order_.end(), less);
  }
  keys_.resize(n);
  for (std::size_t k = 0; k < n; ++k) keys_[k] = cellOf_[order_[k]];

  for (std::uint32_t a = 0; a < n; ++a) {
    const std::uint64_t cx = cellOf_[a][2], cy = cellOf_[a][1], cz = cellOf_[a][0];
    const std::uint64_t x0 = cx ? cx - 1 : 0, x1 = std::min(cx + 1, kLastCell);
    candidates_.clear();
    for (std::uint64_t z = cz ? cz - 1 : 0; z <= std::min(cz + 1, kLastCell); ++z)
      for (std::uint64_t y = cy ? cy - 1 : 0; y <= std::min(cy + 1, kLastCell); ++y) {
        // The three cells along x of one (y, z) row are one run of keys.
        auto lo = std::lower_bound(keys_.begin(), keys_.end(), Cell{z, y, x0});
        auto hi = std::upper_bound(lo, keys_.end(), Cell{z, y, x1});
        for (auto it = lo; it != hi; ++it) {
          const std::uint32_t b = order_[static_cast<std::size_t>(it - keys_.begin())];
          if (b <= a) continue;
          ++tests_;
          const double limit = r[a] + r[b] + reach;
          if ((x[a] - x[b]).squaredNorm() < limit * limit) candidates_.push_back(b);
        }
      }
    if (!emit(a, i, j, maxPairs)) return false;
  }
  return true;
}

}  // namespace rscene
