// The candidate pairs of a granular body: a Verlet list of grains whose
// surfaces are closer than `reach` (contact range + cohesion range + a
// skin), found through a uniform grid of cells at least 2 x the largest
// radius + reach wide, and rebuilt only when a grain has moved more than
// half the skin since the last build.
//
// Deterministic by construction: grains are sorted by (cell key, index),
// an order that does not depend on the sorting algorithm or on history;
// pairs are kept sorted by (i, j) with i < j; the tangential history of a
// pair that survives a rebuild is carried over by a linear merge of the
// two sorted lists (no hash-map iteration anywhere).  Memory is O(grains +
// pairs) whatever the spread of the grains: the grid is a sorted array of
// occupied cells when the grains are spread far apart, a dense box of
// at most 4 cells per grain when they fill it.
#pragma once
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "sim/granular_contact.hpp"

namespace rscene::sim {

class GranularPairs {
 public:
  // Rebuilds the list from positions and radii: every (i < j) with
  // |xi - xj| < ri + rj + reach.  Histories of surviving pairs are kept,
  // those of new pairs start at zero.
  void build(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& r, double rMax, double reach);

  std::size_t size() const { return i.size(); }
  std::vector<std::uint32_t> i, j;
  std::vector<GranularHistory> history;  // the pair's springs

 private:
  void denseCandidates(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& r, double reach,
                       std::array<std::uint64_t, 3> dims);
  void sparseCandidates(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& r, double reach);
  void emit(std::uint32_t a);

  std::vector<std::uint64_t> keys_;       // sorted cell keys, parallel to order_ (sparse grid)
  std::vector<std::uint32_t> order_;      // grains sorted by (cell key, index)
  std::vector<std::uint64_t> keyOf_;      // cell key per grain
  std::vector<std::uint32_t> cellStart_, cursor_;  // dense grid: grains of cell c at order_[start[c], start[c+1])
  std::vector<std::uint32_t> candidates_; // scratch
  std::vector<std::uint32_t> newI_, newJ_;
  std::vector<GranularHistory> newHistory_;
};

}  // namespace rscene::sim
