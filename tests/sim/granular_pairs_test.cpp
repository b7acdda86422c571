// The granular pair list (lib/sim/granular_pairs.cpp) against brute force,
// on its dense grid (a compact bed) and its sparse one (a grain flung far
// away), and the carrying over of contact histories across rebuilds.
#include <gtest/gtest.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "sim/granular_pairs.hpp"

using rscene::sim::GranularPairs;

namespace {

// A jittered 8 x 8 x 8 block of grains with radii 0.01 to 0.02 (a fixed
// sequence), spacing 0.035: some pairs overlap, most are near.
void grains(std::vector<Eigen::Vector3d>& x, std::vector<double>& r) {
  std::uint32_t seed = 7;
  auto next = [&] {  // [0, 1)
    seed = seed * 1664525u + 1013904223u;
    return double(seed >> 8) / double(1u << 24);
  };
  for (int z = 0; z < 8; ++z)
    for (int y = 0; y < 8; ++y)
      for (int k = 0; k < 8; ++k) {
        x.emplace_back(0.035 * k + 0.01 * next(), 0.035 * y + 0.01 * next(), 0.035 * z + 0.01 * next());
        r.push_back(0.01 + 0.01 * next());
      }
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> bruteForce(const std::vector<Eigen::Vector3d>& x,
                                                                 const std::vector<double>& r, double reach) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (std::uint32_t a = 0; a < x.size(); ++a)
    for (std::uint32_t b = a + 1; b < x.size(); ++b) {
      double limit = r[a] + r[b] + reach;
      if ((x[a] - x[b]).squaredNorm() < limit * limit) out.emplace_back(a, b);
    }
  return out;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> listed(const GranularPairs& p) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (std::size_t k = 0; k < p.size(); ++k) out.emplace_back(p.i[k], p.j[k]);
  return out;
}

}  // namespace

TEST(GranularPairs, DenseGridFindsExactlyThePairsBruteForceFinds) {
  std::vector<Eigen::Vector3d> x;
  std::vector<double> r;
  grains(x, r);
  GranularPairs pairs;
  pairs.build(x, r, 0.02, 0.004);
  auto expected = bruteForce(x, r, 0.004);
  EXPECT_GT(expected.size(), 500u);  // enough to mean something
  EXPECT_EQ(listed(pairs), expected);  // the same pairs, in (i, j) order
}

TEST(GranularPairs, SparseGridFindsTheSamePairsWhenAGrainFliesFarAway) {
  std::vector<Eigen::Vector3d> x;
  std::vector<double> r;
  grains(x, r);
  x[100] = {1e6, -3e5, 2e4};  // the box would be ~1e24 cells: the sparse grid
  GranularPairs pairs;
  pairs.build(x, r, 0.02, 0.004);
  EXPECT_EQ(listed(pairs), bruteForce(x, r, 0.004));
  // And again from its nearly sorted order, after the grains moved a little.
  for (auto& p : x) p.x() += 0.003;
  x[5].y() += 0.02;
  pairs.build(x, r, 0.02, 0.004);
  EXPECT_EQ(listed(pairs), bruteForce(x, r, 0.004));
}

TEST(GranularPairs, HistoriesSurviveARebuildOnlyForPairsThatStay) {
  std::vector<Eigen::Vector3d> x = {{0, 0, 0}, {0.039, 0, 0}, {0.5, 0, 0}, {0.5, 0.039, 0}};
  std::vector<double> r(4, 0.02);
  GranularPairs pairs;
  pairs.build(x, r, 0.02, 0.004);
  ASSERT_EQ(pairs.size(), 2u);  // (0, 1) and (2, 3)
  pairs.history[0].slide = {1, 2, 3};
  pairs.history[1].roll = {4, 5, 6};
  x[3].y() = 0.3;   // (2, 3) parts
  x.push_back({0.02, 0.03, 0});  // a new neighbour of 0 and 1
  r.push_back(0.02);
  pairs.build(x, r, 0.02, 0.004);
  ASSERT_EQ(listed(pairs), (std::vector<std::pair<std::uint32_t, std::uint32_t>>{{0, 1}, {0, 4}, {1, 4}}));
  EXPECT_EQ(pairs.history[0].slide, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(pairs.history[1].slide, Eigen::Vector3d::Zero());
  EXPECT_EQ(pairs.history[2].roll, Eigen::Vector3d::Zero());
}

// Issue 24 (02): 64,000 grains and one at (-1e6, -1e6, -1e6) put every
// other grain into one clamped cell: each measured its distance to all
// the others.  Cells now have their own number however far apart.
TEST(NeighbourGrid, OneFarGrainLeavesTheSearchLinear) {
  std::vector<Eigen::Vector3d> x;
  std::vector<double> r;
  for (int z = 0; z < 20; ++z)
    for (int y = 0; y < 20; ++y)
      for (int k = 0; k < 20; ++k) x.emplace_back(0.043 * k, 0.043 * y, 0.02 + 0.043 * z), r.push_back(0.02);
  rscene::NeighbourGrid grid;
  std::vector<std::uint32_t> i, j;
  ASSERT_TRUE(grid.pairs(x, r, 0.02, 0.004, i, j));
  const std::uint64_t alone = grid.distanceTests(), pairsAlone = i.size();
  x.emplace_back(-1e6, -1e6, -1e6), r.push_back(0.02);
  ASSERT_TRUE(grid.pairs(x, r, 0.02, 0.004, i, j));
  EXPECT_EQ(i.size(), pairsAlone);  // the far grain touches nobody
  EXPECT_LE(grid.distanceTests(), alone + 64) << "the far grain made the others share cells";
  EXPECT_LT(grid.distanceTests(), 30 * x.size());  // a few dozen per grain, not n^2 / 2 = 3.2e7
}

// The cap stops the search before the lists outgrow it.
TEST(NeighbourGrid, ThePairCapStopsTheSearch) {
  std::vector<Eigen::Vector3d> x(500, Eigen::Vector3d(1, 2, 3));  // all at one point: 124,750 pairs
  std::vector<double> r(500, 0.02);
  rscene::NeighbourGrid grid;
  std::vector<std::uint32_t> i, j;
  EXPECT_FALSE(grid.pairs(x, r, 0.02, 0, i, j, 1000));
  EXPECT_LE(i.size(), 1000u);
  EXPECT_TRUE(grid.pairs(x, r, 0.02, 0, i, j));
  EXPECT_EQ(i.size(), 500u * 499u / 2);
  GranularPairs pairs;
  EXPECT_FALSE(pairs.build(x, r, 0.02, 0, 1000));
  EXPECT_EQ(pairs.size(), 0u);  // left as it was
}
