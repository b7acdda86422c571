// The pairs of spheres whose surfaces are closer than `reach`, found
// through a uniform grid of cells at least 2 x the largest radius + reach
// wide.  The scene model's granular check (scene/granular.hpp: grains that
// start overlapping) and the granular solver's Verlet list
// (sim/granular_pairs.hpp) both ask this one question, so it has one
// answer.
//
// Deterministic by construction: spheres are sorted by (cell, index), an
// order that does not depend on the sorting algorithm or on history; pairs
// come out sorted by (i, j) with i < j.  Memory is O(spheres + pairs)
// whatever their spread: the grid is a sorted array of occupied cells when
// the spheres are spread far apart, a dense box of at most 4 cells per
// sphere when they fill it.  Cells are numbered with 62 bits per axis
// from the lowest sphere, so a sphere a million metres away from the others
// has a cell of its own and leaves their search linear (only spheres more
// than 2^62 cells out share the last cell of their axis).
#pragma once
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace rscene {

class NeighbourGrid {
 public:
  // Replaces `i` and `j` with every (i < j) with |xi - xj| < ri + rj + reach.
  // The grid keeps its sort between calls: spheres that moved little are
  // re-sorted in linear time.  False, with the lists holding only the first
  // maxPairs, when there are more pairs than `maxPairs`: the search stops
  // there, so memory stays bounded by the cap.
  bool pairs(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& r, double rMax, double reach,
             std::vector<std::uint32_t>& i, std::vector<std::uint32_t>& j,
             std::size_t maxPairs = std::numeric_limits<std::size_t>::max());
  // Distances the last pairs() measured: a few dozen per sphere for a bed,
  // whatever a far-away sphere does (the search's cost, for tests).
  std::uint64_t distanceTests() const { return tests_; }

 private:
  using Cell = std::array<std::uint64_t, 3>;  // (z, y, x): sorted rows of x
  bool denseCandidates(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& r, double reach,
                       std::array<std::uint64_t, 3> dims, std::vector<std::uint32_t>& i,
                       std::vector<std::uint32_t>& j, std::size_t maxPairs);
  bool sparseCandidates(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& r, double reach,
                        std::vector<std::uint32_t>& i, std::vector<std::uint32_t>& j, std::size_t maxPairs);
  bool emit(std::uint32_t a, std::vector<std::uint32_t>& i, std::vector<std::uint32_t>& j, std::size_t maxPairs);

  std::vector<Cell> keys_;                // sorted cells, parallel to order_ (sparse grid)
  std::vector<std::uint32_t> order_;      // spheres sorted by (cell, index)
  std::vector<Cell> cellOf_;              // cell per sphere
  std::vector<std::uint32_t> cellStart_, cursor_;  // dense grid: spheres of cell c at order_[start[c], start[c+1])
  std::vector<std::uint32_t> candidates_; // scratch
  std::uint64_t tests_ = 0;
};

}  // namespace rscene
