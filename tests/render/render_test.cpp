// Pixel tests of lib/render on the CPU backend (llvmpipe).  They assert
// geometry and lighting facts that do not depend on a baseline; one test
// compares with a baseline PNG under a stated tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "gl_test_context.hpp"
#include "core/io.hpp"
#include "core/loader.hpp"
#include "render/camera.hpp"
#include "render/gl_context.hpp"
#include "render/image.hpp"
#include "render/render_scene.hpp"
#include "render/renderer.hpp"
#include "test_images.hpp"

using namespace rscene;
using namespace rscene::render;

namespace {

const char* kPlainBlack = "environment 0 0 0 0.2 0.2 0.2 0 true true 10 - backgroundMode=plain_color colorMode=linear\n";
const char* kPlainWhite = "environment 1 1 1 0.2 0.2 0.2 0 true true 10 - backgroundMode=plain_color colorMode=linear\n";
const char* kMaterials =
    "material red 0.8 0.1 0.1 1 0 0.6 0 0 0 0 false - - - - - - id=red\n"
    "material gray 0.5 0.5 0.5 1 0 0.9 0 0 0 0 false - - - - - - id=gray\n";
// Camera at the origin with the identity orientation (looks along +x).
const char* kCameraIdentity = "camera /World/Cam 0 0 0 1 0 0 0 60 0.05 100 200 200 rgb true id=cam\n";

std::string box(const std::string& path, double x, double y, double z, const std::string& material = "red",
                bool visible = true) {
  return "object " + path + " box " + std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) +
         " 1 0 0 0 1 1 1 0.5 1 1 default " + material + " false " + (visible ? "true" : "false") +
         " false - static true 1 18446744073709551615\n";
}

struct Result {
  bool ok = false;
  Image image;
  Diagnostics diags;
};

Result renderText(const std::string& body, const std::string& env = kPlainBlack, RenderOptions options = {},
              const std::string& cameraSel = "", const std::string& sceneDir = ".") {
  Result r;
  if (!context()) return r;
  LoadResult loaded = parse("raisim_engine_scene 1\n" + env + kMaterials + body);
  EXPECT_TRUE(loaded.ok());
  RenderScene scene;
  SceneOptions so;
  so.sceneDir = sceneDir;
  buildRenderScene(loaded.document, so, scene, r.diags);
  Camera cam;
  std::string err;
  EXPECT_TRUE(chooseCamera(scene, cameraSel, cam, &err)) << err;
  if (options.width == 1280) options.width = options.height = 200;
  if (cam.path == "auto") cam = autoCamera(scene, double(options.width) / options.height);
  r.ok = renderScene(scene, cam, options, r.image, r.diags);
  return r;
}

int luminance(const Image& im, int x, int y) {
  const std::uint8_t* p = im.pixel(x, y);
  return p[0] + p[1] + p[2];
}

}  // namespace

TEST(Render, BoxInFrontShowsMaterialColorAtCenter) {
  Result r = renderText(std::string(kCameraIdentity) + "light /World/Sun 1 0.4 -0.4 3 type=directional\n" +
                    box("/World/Box", 5, 0, 0));
  ASSERT_TRUE(r.ok);
  const std::uint8_t* c = r.image.pixel(100, 100);
  EXPECT_GT(c[0], 100);
  EXPECT_GT(c[0], 2 * c[1]);
  EXPECT_GT(c[0], 2 * c[2]);
  EXPECT_EQ(luminance(r.image, 2, 2), 0);  // corner: the black background
}

TEST(Render, CameraLooksAlongLocalPlusX) {
  Result behind = renderText(std::string(kCameraIdentity) + box("/World/Box", -5, 0, 0));
  ASSERT_TRUE(behind.ok);
  EXPECT_EQ(luminance(behind.image, 100, 100), 0);
  // Yawed 90 degrees about z: looks along +y.
  Result yawed = renderText("camera /World/Cam 0 0 0 0.70710678 0 0 0.70710678 60 0.05 100 200 200 rgb true\n" +
                        box("/World/Box", 0, 5, 0));
  ASSERT_TRUE(yawed.ok);
  EXPECT_GT(luminance(yawed.image, 100, 100), 30);
}

TEST(Render, VisibleFalseHides) {
  Result r = renderText(std::string(kCameraIdentity) + box("/World/Box", 5, 0, 0, "red", false));
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(luminance(r.image, 100, 100), 0);
}

TEST(Render, SphereHasExpectedPixelRadius) {
  // radius 1 at distance 10, vertical fov 60, 400 px high:
  // 200 * tan(asin(0.1)) / tan(30 deg) = 34.8 px.  Tolerance 1.5 px (MSAA edge).
  Result r = renderText(
      "camera /World/Cam 0 0 0 1 0 0 0 60 0.05 100 400 400 rgb true\n"
      "light /World/Sun 1 0 0 3 type=directional\n"
      "object /World/Ball sphere 10 0 0 1 0 0 0 1 1 1 1 1 1 default red false true false - static true 1 "
      "18446744073709551615\n",
      kPlainWhite, RenderOptions{400, 400, 4, false, false});
  ASSERT_TRUE(r.ok);
  int covered = 0;
  for (int x = 0; x < 400; ++x) covered += luminance(r.image, x, 200) < 3 * 255 - 3 * 64;
  double expected = 200 * std::tan(std::asin(0.1)) / std::tan(30 * M_PI / 180);
  EXPECT_NEAR(covered / 2.0, expected, 1.5);
}

TEST(Render, TransparentBackgroundHasAlphaZero) {
  Result r = renderText(std::string(kCameraIdentity) + box("/World/Box", 5, 0, 0), kPlainWhite,
                    RenderOptions{200, 200, 4, true, false});
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.image.pixel(3, 3)[3], 0);
  EXPECT_EQ(r.image.pixel(100, 100)[3], 255);
}

TEST(Render, SkyAboveGroundBelow) {
  Result r = renderText(
      "camera /World/Cam 0 0 1.5 1 0 0 0 60 0.05 500 200 200 rgb true\n" +
          std::string("object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 1 0 0 default red false true true - static "
                      "true 1 18446744073709551615\n"),
      "environment 0.1 0.1 0.1 0.2 0.2 0.2 0 true true 10 - backgroundMode=rayrai_sky\nweather true preset=clear "
      "timeOfDay=12\n");
  ASSERT_TRUE(r.ok);
  const std::uint8_t* top = r.image.pixel(100, 5);
  const std::uint8_t* bottom = r.image.pixel(100, 195);
  EXPECT_GT(top[2], top[0]);     // blue sky
  EXPECT_GT(bottom[0], bottom[2]);  // red/gray ground
}

// Issue 10: an intensity past float range was infinite in the shaders and
// turned the lit faces black (NaN); it is drawn as the brightest light.
TEST(Render, ALightPastFloatRangeSaturatesInsteadOfGoingBlack) {
  for (const char* intensity : {"1e38", "1e39", "1e300"}) {
    Result r = renderText(
        "camera /World/Cam 0 -6 0 0.70710678 0 0 0.70710678 40 0.05 100 200 200 rgb true\n"
        "light /World/Sun -1 0 0 " + std::string(intensity) + " type=directional\n"
        "object /World/Box box 0 0 0 0.92387953 0 0 0.38268343 1.5 1.5 1.5 0.5 1 1 default gray false true false - "
        "static true 1 18446744073709551615\n");
    ASSERT_TRUE(r.ok);
    EXPECT_GT(luminance(r.image, 125, 100), 700) << intensity;  // the lit face is white, not black
  }
}

TEST(Render, LightMakesLitFaceBrighter) {
  // Box turned 45 degrees, seen from -y: the right face's normal has +x, the
  // light travels along -x.
  Result r = renderText(
      "camera /World/Cam 0 -6 0 0.70710678 0 0 0.70710678 40 0.05 100 200 200 rgb true\n"
      "light /World/Sun -1 0 0 3 type=directional\n"
      "object /World/Box box 0 0 0 0.92387953 0 0 0.38268343 1.5 1.5 1.5 0.5 1 1 default gray false true false - "
      "static true 1 18446744073709551615\n");
  ASSERT_TRUE(r.ok);
  EXPECT_GT(luminance(r.image, 125, 100), luminance(r.image, 75, 100) + 60);
}

TEST(Render, ShadowFallsOppositeTheSun) {
  // Looking straight down from 10 m (image up = +x); the sun travels
  // towards -x and down, so the shadow is on the -x side (image bottom).
  Result r = renderText(
      "camera /World/Cam 0 0 10 0.70710678 0 0.70710678 0 60 0.05 100 200 200 rgb true\n"
      "light /World/Sun -1 0 -1 3 type=directional shadows=true\n"
      "object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 1 0 0 default gray false true true - static true 1 "
      "18446744073709551615\n" +
      box("/World/Box", 0, 0, 0.5, "gray"));
  ASSERT_TRUE(r.ok);
  int dy = int(std::lround(1.0 / (10 * std::tan(30 * M_PI / 180)) * 100));  // 1 m from the centre, in pixels
  // Sample between checker edges: average a small window.
  auto mean = [&](int cx, int cy) {
    int s = 0;
    for (int y = -2; y <= 2; ++y)
      for (int x = -2; x <= 2; ++x) s += luminance(r.image, cx + x, cy + y);
    return s / 25;
  };
  EXPECT_LT(mean(100, 100 + dy), mean(100, 100 - dy) - 40);
}

TEST(Render, MeshKeepsItsOwnMaterialWithEngineDefault) {
  std::string dir = std::string(RSCENE_TEST_DATA) + "/render_assets";
  Result r = renderText(std::string(kCameraIdentity) + "light /World/Sun 1 0 0 3 type=directional\n" +
                        "object /World/Crate mesh 5 0 0 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false "
                        "crate.obj static true 1 18446744073709551615\n",
                    kPlainBlack, {}, "", dir);
  ASSERT_TRUE(r.ok);
  const std::uint8_t* c = r.image.pixel(100, 100);
  EXPECT_GT(c[1], 2 * c[0]);
}

TEST(Render, MissingMeshIsAnErrorUnlessAllowed) {
  std::string body = std::string(kCameraIdentity) +
                     "object /World/Crate mesh 5 0 0 1 0 0 0 1 1 1 0.5 1 1 default red false true false "
                     "missing.obj static true 1 18446744073709551615\n";
  Result r = renderText(body, kPlainBlack, {}, "", "/nonexistent");
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.diags.empty());
  EXPECT_EQ(r.diags.back().severity, Severity::Error);
  EXPECT_EQ(r.diags.back().message, "mesh file '/nonexistent/missing.obj' does not exist");
  EXPECT_EQ(r.diags.back().line, 6u);  // header, environment, 2 materials, camera, object
  Result allowed = renderText(body, kPlainBlack, RenderOptions{200, 200, 4, false, true}, "", "/nonexistent");
  ASSERT_TRUE(allowed.ok);
  EXPECT_EQ(allowed.diags.back().severity, Severity::Warning);
  EXPECT_GT(luminance(allowed.image, 100, 100), 0);  // the placeholder box
}

TEST(Render, InstancedColorsBlendByWeight) {
  Result r = renderText(std::string(kCameraIdentity) +
                    "light /World/Sun 1 0 0 3 type=directional\n"
                    "instanced_visual /World/Batch box size=1,1,1 colorA=1,0,0,1 colorB=0,0,1,1 "
                    "instances=5,1,0,1,0,0,0,1,1,1;5,-1,0,1,0,0,0,1,1,1 colorWeights=0,1\n");
  ASSERT_TRUE(r.ok);
  // +y is image left when looking along +x.
  int px = int(std::lround(100 - 1.0 / (4.5 * std::tan(30 * M_PI / 180)) * 100));
  const std::uint8_t* left = r.image.pixel(px, 100);
  const std::uint8_t* right = r.image.pixel(200 - px, 100);
  EXPECT_GT(left[0], left[2]);
  EXPECT_GT(right[2], right[0]);
}

TEST(Render, PointCloudPointsAreDrawn) {
  Result r = renderText(std::string(kCameraIdentity) +
                    "point_cloud /World/Cloud points=5,0,0 colors=0,1,0,1 pointSize=9\n");
  ASSERT_TRUE(r.ok);
  EXPECT_GT(r.image.pixel(100, 100)[1], 200);
  EXPECT_EQ(luminance(r.image, 100, 80), 0);
}

TEST(Render, DeterministicOnTheSameMachine) {
  std::string body = std::string(kCameraIdentity) + "light /World/Sun 1 0.2 -0.3 3 type=directional\n" +
                     box("/World/Box", 5, 0, 0);
  Result a = renderText(body), b = renderText(body);
  ASSERT_TRUE(a.ok && b.ok);
  EXPECT_EQ(encodePng(a.image), encodePng(b.image));
}

TEST(Render, MinimalExampleMatchesBaseline) {
  // rscene-format.txt "A Minimal Example", --camera auto, 320x180.
  // Tolerance: at most 2% of pixels may differ by more than 16/255.
  std::string text, err;
  ASSERT_TRUE(readFile(std::string(RSCENE_TEST_DATA) + "/render_minimal.rscene", text, &err)) << err;
  ASSERT_TRUE(context());
  LoadResult loaded = parse(text);
  ASSERT_TRUE(loaded.ok());
  RenderScene scene;
  Diagnostics diags;
  buildRenderScene(loaded.document, {}, scene, diags);
  Camera cam = autoCamera(scene, 320.0 / 180.0);
  Image image;
  ASSERT_TRUE(renderScene(scene, cam, RenderOptions{320, 180, 4, false, false}, image, diags));
  // Reddish-orange box in the middle, sky above.
  const std::uint8_t* c = image.pixel(175, 100);
  EXPECT_GT(c[0], c[1] + 40);
  EXPECT_GT(image.pixel(160, 3)[2], image.pixel(160, 3)[0]);
  std::string baselinePath = std::string(RSCENE_RENDER_BASELINES) + "/minimal_auto.png";
  std::string bytes;
  Image baseline;
  if (!readFile(baselinePath, bytes, &err)) {
    std::ofstream(baselinePath, std::ios::binary) << encodePng(image);
    FAIL() << "baseline was missing; wrote " << baselinePath;
  }
  ASSERT_TRUE(decodePng(bytes, baseline, &err)) << err;
  Comparison cmp = compareImages(image, baseline);
  ASSERT_TRUE(cmp.sameSize);
  EXPECT_LE(cmp.differingFraction, 0.02);
}

TEST(Render, JpegAlbedoTextureIsDrawn) {
  // A box whose material's albedo is a white material times a red JPEG: the
  // centre pixel is red, where the untextured white material would be gray.
  char tmpl[] = "/tmp/rscene-jpeg-XXXXXX";
  std::string dir = mkdtemp(tmpl);
  std::ofstream(dir + "/red.jpg", std::ios::binary) << test::encodeJpeg(test::solidImage(16, 16, 230, 20, 20));
  std::string scene = std::string(kCameraIdentity) + "light /World/Sun 1 0.4 -0.4 3 type=directional\n" +
                      "material tex 1 1 1 1 0 0.6 0 0 0 0 false red.jpg - - - - - id=tex\n" +
                      box("/World/Box", 5, 0, 0, "tex");
  Result r = renderText(scene, kPlainBlack, {}, "", dir);
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(r.ok);
  for (const Diagnostic& d : r.diags) EXPECT_NE(d.code, "RS9002") << d.message;  // "texture ... is not drawn"
  const std::uint8_t* c = r.image.pixel(100, 100);
  EXPECT_GT(c[0], 100);
  EXPECT_GT(c[0], 3 * c[1]);
  EXPECT_GT(c[0], 3 * c[2]);
}

namespace {

TEST(Render, AnInstancedVisualsMissingMeshIsAMagentaPlaceholder) {
  // --allow-missing-assets: the instances of a mesh that is not there are
  // drawn as magenta boxes, as an object's are, not as plain boxes of the
  // record's color that would pass for real geometry.
  RenderOptions o;
  o.width = o.height = 200;
  o.allowMissingAssets = true;
  Result r = renderText(std::string(kCameraIdentity) +
                            "instanced_visual /World/I mesh meshPath=nothere.gltf colorA=0.5,0.5,0.5,1 "
                            "instances=5,0,0,1,0,0,0,1,1,1\n",
                        kPlainBlack, o);
  ASSERT_TRUE(r.ok);
  const std::uint8_t* c = r.image.pixel(100, 100);
  EXPECT_GT(c[0], 200);
  EXPECT_LT(c[1], 60);
  EXPECT_GT(c[2], 200);
}

}  // namespace
