// CPU mipmap levels (render/mipmap.hpp): the 2x2 box filter, odd sides and
// sides of 1, rounding.
#include <gtest/gtest.h>

#include "render/mipmap.hpp"

using namespace rscene::render;

namespace {

// An RGBA image whose texel (x, y) has every channel `f(x, y)`.
template <class F>
std::vector<std::uint8_t> image(int w, int h, F f) {
  std::vector<std::uint8_t> im;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c) im.push_back(std::uint8_t(f(x, y) + c));
  return im;
}

}  // namespace

TEST(Mipmap, EachTexelIsTheRoundedMeanOfItsBlock) {
  // 4x2: columns 0,10,20,30 on row 0 and 100,110,120,130 on row 1.
  auto src = image(4, 2, [](int x, int y) { return 10 * x + 100 * y; });
  std::vector<std::uint8_t> out;
  halveImage(src.data(), 4, 2, out);
  ASSERT_EQ(out.size(), 2u * 1u * 4u);
  EXPECT_EQ(out[0], (0 + 10 + 100 + 110 + 2) / 4);   // 55
  EXPECT_EQ(out[3], (3 + 13 + 103 + 113 + 2) / 4);   // alpha too: 58
  EXPECT_EQ(out[4], (20 + 30 + 120 + 130 + 2) / 4);  // 75
  // Rounding to nearest: 0, 0, 0, 1 -> 0.25 -> 0; 0, 1, 1, 1 -> 0.75 -> 1.
  std::vector<std::uint8_t> q = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1};
  halveImage(q.data(), 2, 2, out);
  EXPECT_EQ(out[0], 0);
  std::vector<std::uint8_t> r = {0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
  halveImage(r.data(), 2, 2, out);
  EXPECT_EQ(out[0], 1);
}

TEST(Mipmap, OddSidesDropTheLastRowAndColumn) {
  auto src = image(3, 3, [](int x, int y) { return x == 2 || y == 2 ? 200 : 40; });
  std::vector<std::uint8_t> out;
  halveImage(src.data(), 3, 3, out);
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[0], 40);
}

TEST(Mipmap, ASideOfOneIsNotHalved) {
  auto row = image(4, 1, [](int x, int) { return 10 * x; });
  std::vector<std::uint8_t> out;
  halveImage(row.data(), 4, 1, out);
  ASSERT_EQ(out.size(), 2u * 4u);
  EXPECT_EQ(out[0], 5);   // (0 + 10) / 2
  EXPECT_EQ(out[4], 25);  // (20 + 30) / 2
  auto column = image(1, 2, [](int, int y) { return 50 * y; });
  halveImage(column.data(), 1, 2, out);
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[0], 25);
}
