// The candidate pairs of a granular body: a Verlet list of grains whose
// surfaces are closer than `reach` (contact range + cohesion range + a
// skin), found by the scene model's NeighbourGrid (scene/neighbour_grid.hpp:
// deterministic, pairs sorted by (i, j) with i < j), and rebuilt only when
// a grain has moved more than half the skin since the last build.  The
// tangential history of a pair that survives a rebuild is carried over by
// a linear merge of the two sorted lists (no hash-map iteration anywhere).
#pragma once
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "scene/neighbour_grid.hpp"
#include "sim/granular_contact.hpp"

namespace rscene::sim {

class GranularPairs {
 public:
  // Rebuilds the list from positions and radii: every (i < j) with
  // |xi - xj| < ri + rj + reach.  Histories of surviving pairs are kept,
  // those of new pairs start at zero.  False, the list left as it was,
  // when there would be more than `maxPairs` pairs.
  bool build(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& r, double rMax, double reach,
             std::size_t maxPairs = std::numeric_limits<std::size_t>::max());

  std::size_t size() const { return i.size(); }
  std::vector<std::uint32_t> i, j;
  std::vector<GranularHistory> history;  // the pair's springs

 private:
  NeighbourGrid grid_;
  std::vector<std::uint32_t> newI_, newJ_;
  std::vector<GranularHistory> newHistory_;
};

}  // namespace rscene::sim
