#include "sim/granular_pairs.hpp"

namespace rscene::sim {

void GranularPairs::build(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& r, double rMax,
                          double reach) {
  grid_.pairs(x, r, rMax, reach, newI_, newJ_);
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
