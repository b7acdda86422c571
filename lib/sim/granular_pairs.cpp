#include "sim/granular_pairs.hpp"

namespace rscene::sim {

bool GranularPairs::build(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& r, double rMax,
                          double reach, std::size_t maxPairs) {
  if (!grid_.pairs(x, r, rMax, reach, newI_, newJ_, maxPairs)) {
    newI_.clear(), newJ_.clear();
    return false;
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
  return true;
}

}  // namespace rscene::sim
