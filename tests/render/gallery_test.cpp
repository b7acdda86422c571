// examples/gallery.rscene, the scene that holds every record kind
// rscene-render draws: every kind reaches the renderer, its look lands where
// the scene puts it, and the image matches a baseline under a stated
// tolerance (make demo renders the same scene at 1280x720).
#include <gtest/gtest.h>

#include <fstream>

#include "core/io.hpp"
#include "core/loader.hpp"
#include "gl_test_context.hpp"
#include "render/image.hpp"
#include "render/render_scene.hpp"
#include "render/renderer.hpp"

using namespace rscene;
using namespace rscene::render;

namespace {

struct Gallery {
  RenderScene scene;
  Diagnostics diags;
  Image image;
  bool built = false, drawn = false;
};

// The gallery from its own camera at 320x180.
const Gallery& gallery() {
  static Gallery g = [] {
    Gallery out;
    std::string dir = std::string(RSCENE_EXAMPLES) + "/", text, err;
    if (!readFile(dir + "gallery.rscene", text, &err)) {
      ADD_FAILURE() << err;
      return out;
    }
    LoadResult loaded = parse(text);
    SceneOptions so;
    so.sceneDir = dir;
    out.built = loaded.ok() && buildRenderScene(loaded.document, so, out.scene, out.diags);
    if (!out.built || out.scene.cameras.empty() || !context()) return out;
    out.drawn = renderScene(out.scene, out.scene.cameras[0], RenderOptions{320, 180, 4, false, false}, out.image,
                            out.diags);
    return out;
  }();
  return g;
}

// Pixels of the box [x0, x1) x [y0, y1) for which `test` holds.
template <typename Test>
int count(const Image& im, int x0, int y0, int x1, int y1, Test test) {
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) n += test(im.pixel(x, y));
  return n;
}

TEST(Gallery, EveryRecordKindReachesTheRenderer) {
  const Gallery& g = gallery();
  ASSERT_TRUE(g.built);
  for (const Diagnostic& d : g.diags) EXPECT_NE(d.severity, Severity::Error) << d.code << " " << d.message;
  EXPECT_TRUE(g.scene.skipped.empty());
  EXPECT_EQ(g.scene.decals.size(), 1u);
  EXPECT_EQ(g.scene.fogs.size(), 1u);
  EXPECT_EQ(g.scene.irradianceVolumes.size(), 1u);
  EXPECT_EQ(g.scene.probes.size(), 1u);
  EXPECT_EQ(g.scene.lights.size(), 5u);  // directional, spot, two points, area
  EXPECT_GE(g.scene.pointClouds.size(), 1u);
  EXPECT_GE(g.scene.terrains.size(), 1u);
  // Pebbles, the grass patch, the terrain's grass and the sand's particles.
  EXPECT_GE(g.scene.instanced.size(), 4u);
}

TEST(Gallery, RecordsLandWhereTheSceneSaysAndMatchTheBaseline) {
  const Gallery& g = gallery();
  ASSERT_TRUE(g.drawn);
  const Image& im = g.image;
  // The warning-stripe decal on the floor right of the crate: yellow and
  // near-black texels, where the floor is gray.
  auto yellow = [](const std::uint8_t* p) { return p[0] > 140 && p[1] > 120 && p[2] + 50 < p[0]; };
  EXPECT_GT(count(im, 186, 102, 226, 112, yellow), 10);
  EXPECT_EQ(count(im, 186, 116, 226, 124, yellow), 0);  // the floor in front of it
  // The grass on the flat part of the terrain behind the chrome sphere.
  auto green = [](const std::uint8_t* p) { return p[1] > p[0] + 10 && p[1] > p[2] + 10; };
  EXPECT_GT(count(im, 125, 65, 205, 80, green), 40);
  // The flag (cloth, mat_fabric blue) right of its pole.
  auto blue = [](const std::uint8_t* p) { return p[2] > p[0] + 60 && p[2] > p[1] + 20; };
  EXPECT_GT(count(im, 176, 52, 192, 66, blue), 20);

  // Tolerance: at most 3% of pixels may differ by more than 16/255 (the
  // renderer's llvmpipe output is deterministic; the margin is for other
  // Mesa versions).
  std::string baselinePath = std::string(RSCENE_RENDER_BASELINES) + "/gallery.png", bytes, err;
  Image baseline;
  if (!readFile(baselinePath, bytes, &err)) {
    std::ofstream(baselinePath, std::ios::binary) << encodePng(im);
    FAIL() << "baseline was missing; wrote " << baselinePath;
  }
  ASSERT_TRUE(decodePng(bytes, baseline, &err)) << err;
  Comparison cmp = compareImages(im, baseline);
  ASSERT_TRUE(cmp.sameSize);
  EXPECT_LE(cmp.differingFraction, 0.03);
}

}  // namespace
