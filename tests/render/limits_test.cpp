// The bounds rscene-render keeps under hostile input (README, "Resource
// limits: rscene-render"): what a record asks to draw is honoured, big
// terrains are decimated, instance and image caps are errors with a place.
// No GL context is needed: all of this is decided before drawing.
#include <gtest/gtest.h>

#include <string>

#include "core/loader.hpp"
#include "render/limits.hpp"
#include "render/render_scene.hpp"
#include "render/renderer.hpp"

using namespace rscene;
using namespace rscene::render;

namespace {

struct Built {
  bool ok = false;
  RenderScene scene;
  Diagnostics diags;
  Document doc;
};

Built build(const std::string& body, DrawLimits limits = {}) {
  Built b;
  LoadResult loaded = parse("raisim_engine_scene 2\n" + body);
  EXPECT_TRUE(loaded.ok());
  b.ok = buildRenderScene(loaded.document, {}, b.scene, b.diags, limits);
  b.doc = std::move(loaded.document);
  return b;
}

// `n` instances along x, 1 m apart, with optional extra fields.
std::string instanced(int n, const std::string& extra = "") {
  std::string s = "instanced_visual /World/I box size=0.1,0.1,0.1 " + extra + " instances=";
  for (int i = 0; i < n; ++i) s += (i ? ";" : "") + std::to_string(i) + ",0,0,1,0,0,0,1,1,1";
  return s + "\n";
}

bool hasCode(const Diagnostics& d, const std::string& code) {
  for (const Diagnostic& x : d)
    if (x.code == code) return true;
  return false;
}

}  // namespace

TEST(RenderLimits, InstancedRecordsDrawWhatTheyAskFor) {
  Built all = build(instanced(10));
  ASSERT_TRUE(all.ok);
  ASSERT_EQ(all.scene.instanced.size(), 1u);
  EXPECT_EQ(all.scene.instanced[0].worlds.size(), 10u);

  Built capped = build(instanced(10, "maxRenderedInstances=4"));
  ASSERT_EQ(capped.scene.instanced[0].worlds.size(), 4u);
  EXPECT_DOUBLE_EQ(capped.scene.instanced[0].worlds[3].translation().x(), 3);

  // Every 3rd: 0, 3, 6, 9.
  Built strided = build(instanced(10, "renderedInstanceStride=3"));
  ASSERT_EQ(strided.scene.instanced[0].worlds.size(), 4u);
  EXPECT_DOUBLE_EQ(strided.scene.instanced[0].worlds[3].translation().x(), 9);
  EXPECT_EQ(strided.scene.instanced[0].colors.size(), 4u);
  EXPECT_EQ(strided.scene.instanced[0].instanceBounds.size(), 4u);

  Built both = build(instanced(10, "maxRenderedInstances=2 renderedInstanceStride=4"));
  ASSERT_EQ(both.scene.instanced[0].worlds.size(), 2u);
  EXPECT_DOUBLE_EQ(both.scene.instanced[0].worlds[1].translation().x(), 4);

  // A stride below 1 draws every instance, as 1 does.
  EXPECT_EQ(build(instanced(5, "renderedInstanceStride=0")).scene.instanced[0].worlds.size(), 5u);
}

TEST(RenderLimits, InstancesPastTheCapAreAnErrorAtTheRecord) {
  DrawLimits limits;
  limits.maxInstances = 15;
  Built b = build(instanced(10) + instanced(10).replace(0, 25, "instanced_visual /World/J"), limits);
  EXPECT_FALSE(b.ok);
  ASSERT_TRUE(hasCode(b.diags, "RS9014"));
  for (const Diagnostic& d : b.diags)
    if (d.code == "RS9014") {
      EXPECT_EQ(d.line, 3u);  // the second record crosses the cap
      EXPECT_EQ(d.column, 1u);
      EXPECT_NE(d.message.find("10 instances, more than the 5 left of --max-instances 15"), std::string::npos)
          << d.message;
    }
  ASSERT_EQ(b.scene.instanced.size(), 1u);  // the first is kept, nothing allocated for the second

  // The record's own maxRenderedInstances counts, not the instances stored.
  Built fits = build(instanced(10) + instanced(10, "maxRenderedInstances=5").replace(0, 25, "instanced_visual /World/J"),
                     limits);
  EXPECT_TRUE(fits.ok);
  EXPECT_FALSE(hasCode(fits.diags, "RS9014"));
}

TEST(RenderLimits, PointCloudsDrawWhatTheyAskFor) {
  std::string pts = "points=0,0,0;1,0,0;2,0,0;3,0,0;4,0,0;5,0,0";
  Built b = build("point_cloud /World/P " + pts + " maxRenderedPoints=2 renderedPointStride=2\n");
  ASSERT_TRUE(b.ok);
  ASSERT_EQ(b.scene.pointClouds.size(), 1u);
  ASSERT_EQ(b.scene.pointClouds[0].points.size(), 2u);
  EXPECT_FLOAT_EQ(b.scene.pointClouds[0].points[1].x(), 2);
  EXPECT_EQ(build("point_cloud /World/P " + pts + "\n").scene.pointClouds[0].points.size(), 6u);
}

TEST(RenderLimits, FlatTerrainWithoutHeightsIsDrawnAsItsCorners) {
  // The 128-byte scene: 8192x8192 samples, no heights.
  Built b = build("terrain_region /World/T 8192 8192 100 50 1 2 3\n");
  ASSERT_TRUE(b.ok);
  ASSERT_EQ(b.scene.terrains.size(), 1u);
  const TerrainMesh& t = b.scene.terrains[0];
  EXPECT_EQ(t.xSamples, 2);
  EXPECT_EQ(t.ySamples, 2);
  ASSERT_EQ(t.positions.size(), 4u);
  // Its extent is kept.
  EXPECT_FLOAT_EQ(t.positions[0].x(), 1 - 50);
  EXPECT_FLOAT_EQ(t.positions[3].x(), 1 + 50);
  EXPECT_FLOAT_EQ(t.positions[3].y(), 2 + 25);
  EXPECT_FLOAT_EQ(t.positions[3].z(), 3);
}

TEST(RenderLimits, BigTerrainIsDecimatedKeepingTheLastSample) {
  // 9x5 samples with a ramp in x, at most 12 vertices drawn: every 3rd
  // sample (0, 3, 6, 8 by 0, 3, 4).
  std::string heights;
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 9; ++x) heights += (heights.empty() ? "" : ",") + std::to_string(x);
  DrawLimits limits;
  limits.maxTerrainVertices = 12;
  Built b = build("terrain_region /World/T 9 5 8 4 0 0 0 heights=" + heights + "\n", limits);
  ASSERT_TRUE(b.ok);
  const TerrainMesh& t = b.scene.terrains[0];
  EXPECT_EQ(t.xSamples, 4);
  EXPECT_EQ(t.ySamples, 3);
  ASSERT_EQ(t.positions.size(), 12u);
  EXPECT_LE(t.positions.size(), limits.maxTerrainVertices);
  EXPECT_FLOAT_EQ(t.positions[1].z(), 3);  // sample x=3
  EXPECT_FLOAT_EQ(t.positions[3].z(), 8);  // the last column
  EXPECT_FLOAT_EQ(t.positions[3].x(), 4);
  EXPECT_FLOAT_EQ(t.positions[11].y(), 2);  // the last row

  // Under the cap everything is drawn.
  Built full = build("terrain_region /World/T 9 5 8 4 0 0 0 heights=" + heights + "\n");
  EXPECT_EQ(full.scene.terrains[0].positions.size(), 45u);
}

TEST(RenderLimits, ImageSizeProblems) {
  EXPECT_EQ(imageSizeProblem(4096, 4096, kDefaultMaxPixels), "");
  EXPECT_EQ(imageSizeProblem(16384, 16384, kDefaultMaxPixels),
            "16384x16384 is 268435456 pixels, more than --max-pixels 16777216");
  EXPECT_EQ(imageSizeProblem(16384, 16384, std::uint64_t{1} << 28), "");
  EXPECT_EQ(imageSizeProblem(16385, 1, kDefaultMaxPixels), "16385x1 is outside 1..16384 on a side");
  EXPECT_EQ(imageSizeProblem(0, 10, kDefaultMaxPixels), "0x10 is outside 1..16384 on a side");
}

TEST(RenderLimits, CameraSizeErrorsPointAtTheWidthField) {
  // Past 16384 on a side: the scene model's RS7028, which validate reports too.
  Built wide = build("camera /World/Cam 0 0 0 1 0 0 0 60 0.05 100 20000 100 rgb true id=cam\n");
  EXPECT_FALSE(wide.ok);
  ASSERT_FALSE(wide.diags.empty());
  EXPECT_EQ(wide.diags[0].code, "RS7028");
  EXPECT_EQ(wide.diags[0].column, 45u);
  // Within it but past --max-pixels: render's RS9013 at the same field.
  Built b = build("camera /World/Cam 0 0 0 1 0 0 0 60 0.05 100 10000 10000 rgb true id=cam\n");
  ASSERT_TRUE(b.ok);
  ASSERT_EQ(b.scene.cameras.size(), 1u);
  Diagnostics diags;
  EXPECT_FALSE(checkCameraImageSize(b.doc, b.scene.cameras[0], 10000, 10000, kDefaultMaxPixels, diags));
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].code, "RS9013");
  EXPECT_EQ(diags[0].line, 2u);
  EXPECT_EQ(diags[0].column, 45u);
  EXPECT_EQ(diags[0].message, "camera image 10000x10000 is 100000000 pixels, more than --max-pixels 16777216");
}

TEST(RenderLimits, CameraWidthPastIntRangeIsAnErrorNotAWrap) {
  // 4294967297 = 2^32 + 1 used to become a 1-pixel-wide image.
  Built b = build("camera /World/Cam 0 0 0 1 0 0 0 60 0.05 100 4294967297 48 rgb true id=cam\n");
  EXPECT_FALSE(b.ok);
  ASSERT_FALSE(b.diags.empty());
  EXPECT_EQ(b.diags[0].code, "RS2003");
  EXPECT_EQ(b.diags[0].line, 2u);
  EXPECT_EQ(b.diags[0].column, 45u);
  EXPECT_EQ(b.diags[0].message, "expected a 32-bit integer, found '4294967297'");  // validate's words
}
