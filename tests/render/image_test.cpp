// The baseline metric and the unit primitives; no GL needed.  Decoding
// images and mesh files is lib/asset's (tests/asset).
#include <gtest/gtest.h>

#include "render/image.hpp"
#include "render/mesh.hpp"

using namespace rscene::render;

namespace {
Image solid(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a = 255) {
  Image im;
  im.width = w, im.height = h;
  for (int i = 0; i < w * h; ++i) im.rgba.insert(im.rgba.end(), {r, g, b, a});
  return im;
}
}  // namespace

TEST(Compare, IdenticalImagesDifferByZero) {
  Image a = solid(10, 10, 50, 60, 70);
  Comparison c = compareImages(a, a);
  EXPECT_TRUE(c.sameSize);
  EXPECT_EQ(c.differingFraction, 0);
  EXPECT_EQ(c.maxChannelDifference, 0);
}

TEST(Compare, CountsPixelsBeyondTheTolerance) {
  Image a = solid(10, 10, 50, 60, 70), b = a;
  b.pixel(0, 0)[1] = 60 + kPixelTolerance + 1;  // counted
  b.pixel(1, 0)[2] = 70 + kPixelTolerance;      // within tolerance
  Comparison c = compareImages(b, a);
  EXPECT_DOUBLE_EQ(c.differingFraction, 0.01);
  EXPECT_EQ(c.maxChannelDifference, kPixelTolerance + 1);
  EXPECT_EQ(c.diff.pixel(0, 0)[0], 255);
  EXPECT_EQ(c.diff.pixel(0, 0)[1], 0);
}

// The local measure (--fail-pixels/--pixel-threshold): pixels by their
// largest channel difference, counted past any T.
TEST(Compare, CountsStronglyDifferingPixelsForTheLocalMeasure) {
  Image a = solid(100, 100, 50, 60, 70), b = a;
  for (int i = 0; i < 30; ++i) b.pixel(i, 3)[0] = 50 + 100;  // 30 pixels off by 100
  for (int i = 0; i < 5; ++i) b.pixel(i, 7)[3] = 255 - 65;   // 5 by 65, in alpha
  b.pixel(9, 9)[2] = 70 + 64;                                 // 1 by exactly 64
  Comparison c = compareImages(b, a);
  EXPECT_DOUBLE_EQ(c.differingFraction, 0.0036);  // 36 of 10000: far under the default 0.01
  EXPECT_EQ(c.pixelsOver(kLocalPixelThreshold), 36u);  // 32: all three kinds
  EXPECT_EQ(c.pixelsOver(64), 35u);
  EXPECT_EQ(c.pixelsOver(63), 36u);
  EXPECT_EQ(c.pixelsOver(99), 30u);
  EXPECT_EQ(c.pixelsOver(100), 0u);
  EXPECT_EQ(c.pixelsOver(255), 0u);
  EXPECT_EQ(c.pixelsOver(-1), 10000u);
  EXPECT_EQ(compareImages(a, a).pixelsOver(0), 0u);
}

TEST(Compare, SizeMismatch) { EXPECT_FALSE(compareImages(solid(2, 2, 0, 0, 0), solid(3, 2, 0, 0, 0)).sameSize); }

TEST(Mesh, PrimitivesAreClosedAndUnitSized) {
  MeshData box = unitBox();
  EXPECT_EQ(box.indices.size(), 36u);
  for (std::size_t i = 0; i < box.vertices.size(); i += 8) EXPECT_FLOAT_EQ(std::abs(box.vertices[i]), 0.5f);
  MeshData sphere = unitSphere();
  for (std::size_t i = 0; i < sphere.vertices.size(); i += 8) {
    Eigen::Vector3f p(sphere.vertices[i], sphere.vertices[i + 1], sphere.vertices[i + 2]);
    EXPECT_NEAR(p.norm(), 1.0f, 1e-5);
  }
}
