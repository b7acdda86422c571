// PNG, HDR and the baseline metric; no GL needed.
#include <gtest/gtest.h>

#include "core/io.hpp"
#include "render/hdr.hpp"
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
std::string data(const std::string& name) { return std::string(RSCENE_TEST_DATA) + "/render_assets/" + name; }
}  // namespace

TEST(Png, RoundTripsAndIsDeterministic) {
  Image a = solid(7, 5, 10, 200, 30, 128);
  a.pixel(3, 2)[0] = 255;
  std::string png = encodePng(a);
  EXPECT_EQ(png, encodePng(a));
  Image b;
  std::string err;
  ASSERT_TRUE(decodePng(png, b, &err)) << err;
  EXPECT_EQ(b.width, 7);
  EXPECT_EQ(b.height, 5);
  EXPECT_EQ(a.rgba, b.rgba);
}

TEST(Png, RejectsGarbageAndTruncation) {
  Image out;
  std::string err;
  EXPECT_FALSE(decodePng("not a png", out, &err));
  std::string png = encodePng(solid(4, 4, 1, 2, 3));
  EXPECT_FALSE(decodePng(png.substr(0, png.size() / 2), out, &err));
  EXPECT_FALSE(err.empty());
}

TEST(Png, RefusesHugeDimensionsBeforeAllocating) {
  std::string png = encodePng(solid(64, 64, 1, 2, 3));
  Image out;
  std::string err;
  EXPECT_FALSE(decodePng(png, out, &err, 1000));
  EXPECT_EQ(err, "png image too large");
}

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

TEST(Compare, SizeMismatch) { EXPECT_FALSE(compareImages(solid(2, 2, 0, 0, 0), solid(3, 2, 0, 0, 0)).sameSize); }

TEST(Hdr, DecodesFlatRgbe) {
  std::string bytes, err;
  ASSERT_TRUE(rscene::readFile(data("sky.hdr"), bytes, &err)) << err;
  FloatImage im;
  ASSERT_TRUE(decodeHdr(bytes, im, &err)) << err;
  EXPECT_EQ(im.width, 4);
  EXPECT_EQ(im.height, 2);
  EXPECT_NEAR(im.rgb[0], 1.0, 0.01);
  EXPECT_NEAR(im.rgb[1], 0.5, 0.01);
  EXPECT_NEAR(im.rgb[2], 0.25, 0.01);
  EXPECT_EQ(im.rgb[3 * 4], 0);  // second row is black
}

TEST(Hdr, RejectsBadHeaders) {
  FloatImage im;
  std::string err;
  EXPECT_FALSE(decodeHdr("#?RADIANCE\n\n-Y 99999 +X 99999\n", im, &err));
  EXPECT_FALSE(decodeHdr("#?RADIANCE\n\n-Y 2 +X 4\n\x01", im, &err));
  EXPECT_FALSE(decodeHdr("P6 1 1", im, &err));
}

TEST(Mesh, ReadsObjWithMtlColor) {
  LoadedMesh m;
  std::string err;
  ASSERT_TRUE(loadMesh(data("crate.obj"), m, &err)) << err;
  ASSERT_EQ(m.parts.size(), 1u);
  EXPECT_EQ(m.parts[0].mesh.indices.size(), 36u);
  EXPECT_NEAR(m.parts[0].baseColor.y(), 0.8f, 1e-5);
}

TEST(Mesh, ReadsStlAndGltf) {
  LoadedMesh m;
  std::string err;
  ASSERT_TRUE(loadMesh(data("tetra.stl"), m, &err)) << err;
  EXPECT_EQ(m.parts[0].mesh.indices.size(), 12u);
  ASSERT_TRUE(loadMesh(data("triangle.gltf"), m, &err)) << err;
  EXPECT_EQ(m.parts[0].mesh.indices.size(), 3u);
  EXPECT_NEAR(m.parts[0].baseColor.z(), 0.9f, 1e-5);
}

TEST(Mesh, MissingFileIsAnError) {
  LoadedMesh m;
  std::string err;
  EXPECT_FALSE(loadMesh(data("nope.obj"), m, &err));
}

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
