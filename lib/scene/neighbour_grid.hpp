// The pairs of spheres whose surfaces are closer than `reach`, found
// through a uniform grid of cells at least 2 x the largest radius + reach
// wide.  The scene model's granular check (scene/granular.hpp: grains that
// start overlapping) and the granular solver's Verlet list
// (sim/granular_pairs.hpp) both ask this one question, so it has one
// answer.
//
// Deterministic by construction: spheres are sorted by (cell key, index),
// an order that does not depend on the sorting algorithm or on history;
// pairs come out sorted by (i, j) with i < j.  Memory is O(spheres + pairs)
// whatever their spread: the grid is a sorted array of occupied cells when
// the spheres are spread far apart, a dense box of at most 4 cells per
// sphere when they fill it.
#pragma once
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace rscene {

class NeighbourGrid {
 public:
  // Replaces `i` and `j` with every (i < j) with |xi - xj| < ri + rj + reach.
  // The grid keeps its sort between calls: spheres that moved little are
  // re-sorted in linear time.
  void pairs(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& r, double rMax, double reach,
             std::vector<std::uint32_t>& i, std::vector<std::uint32_t>& j);

 private:
  void denseCandidates(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& r, double reach,
                       std::array<std::uint64_t, 3> dims, std::vector<std::uint32_t>& i, std::vector<std::uint32_t>& j);
  void sparseCandidates(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& r, double reach,
                        std::vector<std::uint32_t>& i, std::vector<std::uint32_t>& j);
  void emit(std::uint32_t a, std::vector<std::uint32_t>& i, std::vector<std::uint32_t>& j);

  std::vector<std::uint64_t> keys_;       // sorted cell keys, parallel to order_ (sparse grid)
  std::vector<std::uint32_t> order_;      // spheres sorted by (cell key, index)
  std::vector<std::uint64_t> keyOf_;      // cell key per sphere
  std::vector<std::uint32_t> cellStart_, cursor_;  // dense grid: spheres of cell c at order_[start[c], start[c+1])
  std::vector<std::uint32_t> candidates_; // scratch
};

}  // namespace rscene
