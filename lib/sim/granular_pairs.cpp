#include "sim/granular_pairs.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace rscene::sim {
namespace {

// 21 bits per axis in a 63-bit key (z, y, x from the high bits).  A grain
// farther than 2^21 cells from the lowest one shares the last cell of its
// axis: clamping is monotonic, so grains in touch stay in neighbouring
// cells, and only the (far, rare) clamped ones cost extra distance tests.
constexpr std::uint64_t kAxisCells = 1u << 21;

std::uint64_t axisCell(double coordinate, double origin, double inverseCell) {
  double c = std::floor((coordinate - origin) * inverseCell);
  if (!(c > 0)) return 0;  // NaN too: such a run is stopped as non-finite after the step
  return c >= double(kAxisCells - 1) ? kAxisCells - 1 : static_cast<std::uint64_t>(c);
}

std::uint64_t pack(std::uint64_t x, std::uint64_t y, std::uint64_t z) { return (z << 42) | (y << 21) | x; }

}  // namespace

void GranularPairs::build(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& r, double rMax,
                          double reach) {
  const std::size_t n = x.size();
  Eigen::Vector3d origin = Eigen::Vector3d::Constant(INFINITY);
  for (const Eigen::Vector3d& p : x) origin = origin.cwiseMin(p);
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(origin[a])) origin[a] = 0;
  const double cell = 2 * rMax + reach, inverse = 1 / cell;
  keyOf_.resize(n);
  for (std::size_t k = 0; k < n; ++k)
    keyOf_[k] = pack(axisCell(x[k].x(), origin.x(), inverse), axisCell(x[k].y(), origin.y(), inverse),
                     axisCell(x[k].z(), origin.z(), inverse));

  // Grains move little between builds, so the last order is nearly sorted
  // and an insertion sort is linear; past a budget of moves, std::sort.
  // Either gives the one order sorted by (key, index).
  auto less = [&](std::uint32_t a, std::uint32_t b) { return keyOf_[a] != keyOf_[b] ? keyOf_[a] < keyOf_[b] : a < b; };
  if (order_.size() != n) {
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
  for (std::size_t k = 0; k < n; ++k) keys_[k] = keyOf_[order_[k]];

  newI_.clear();
  newJ_.clear();
  for (std::uint32_t a = 0; a < n; ++a) {
    const std::uint64_t key = keyOf_[a];
    const std::uint64_t cx = key & (kAxisCells - 1), cy = (key >> 21) & (kAxisCells - 1), cz = key >> 42;
    const std::uint64_t x0 = cx ? cx - 1 : 0, x1 = std::min(cx + 1, kAxisCells - 1);
    candidates_.clear();
    for (std::uint64_t z = cz ? cz - 1 : 0; z <= std::min(cz + 1, kAxisCells - 1); ++z)
      for (std::uint64_t y = cy ? cy - 1 : 0; y <= std::min(cy + 1, kAxisCells - 1); ++y) {
        // The three cells along x of one (y, z) row are one run of keys.
        auto lo = std::lower_bound(keys_.begin(), keys_.end(), pack(x0, y, z));
        auto hi = std::upper_bound(lo, keys_.end(), pack(x1, y, z));
        for (auto it = lo; it != hi; ++it) {
          std::uint32_t b = order_[static_cast<std::size_t>(it - keys_.begin())];
          if (b <= a) continue;
          double limit = r[a] + r[b] + reach;
          if ((x[a] - x[b]).squaredNorm() < limit * limit) candidates_.push_back(b);
        }
      }
    std::sort(candidates_.begin(), candidates_.end());
    for (std::uint32_t b : candidates_) {
      newI_.push_back(a);
      newJ_.push_back(b);
    }
  }

  // Carry the histories over: both lists are sorted by (i, j).
  newHistory_.assign(newI_.size(), GranularHistory{});
  for (std::size_t o = 0, k = 0; o < i.size() && k < newI_.size();) {
    if (i[o] == newI_[k] && j[o] == newJ_[k]) {
      newHistory_[k++] = history[o++];
    } else if (i[o] < newI_[k] || (i[o] == newI_[k] && j[o] < newJ_[k])) {
      ++o;
    } else {
      ++k;
    }
  }
  i.swap(newI_);
  j.swap(newJ_);
  history.swap(newHistory_);
}

}  // namespace rscene::sim
