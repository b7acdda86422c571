// Post-processing (gl_post.cpp, post_plan.hpp) on the CPU backend: each
// effect is drawn with and without, and pixels say what changed: bloom
// lights the pixels around a bright sphere, FXAA softens a hard diagonal
// edge, SSAO darkens a corner more than an open floor, auto exposure
// brings a dark and a bright scene closer, depth of field blurs a far
// checkerboard and keeps the focused one sharp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "gl_test_context.hpp"
#include "core/loader.hpp"
#include "render/camera.hpp"
#include "render/post_plan.hpp"
#include "render/view.hpp"

using namespace rscene;
using namespace rscene::render;

namespace {

// Black plain background, no ambient light, linear tone map: a pixel's
// value is the light that reaches it, clamped.
const char* kEnvironment =
    "raisim_engine_scene 1\n"
    "environment 0 0 0 0 0 0 0 true true 10 - backgroundMode=plain_color colorMode=fast_linear\n"
    "material white 1 1 1 1 0 0.5 1 1 1 5 false - - - - - - id=white\n"
    "material grey 0.6 0.6 0.6 1 0 0.8 0 0 0 0 false - - - - - - id=grey\n";

std::string box(const std::string& path, double x, double y, double z, double sx, double sy, double sz,
                const std::string& material, const char* quat = "1 0 0 0") {
  char b[512];
  std::snprintf(b, sizeof b,
                "object %s box %g %g %g %s %g %g %g 0.5 1 1 default %s false true false - static true 1 "
                "18446744073709551615\n",
                path.c_str(), x, y, z, quat, sx, sy, sz, material.c_str());
  return b;
}

struct Built {
  Scene model;
  RenderScene scene;
};

std::unique_ptr<Built> build(const std::string& text) {
  auto b = std::make_unique<Built>();
  LoadResult loaded = parse(text);
  EXPECT_TRUE(loaded.ok());
  Diagnostics d;
  EXPECT_TRUE(buildRenderScene(loaded.document, SceneOptions{}, b->model, b->scene, d));
  return b;
}

// From the origin along +x, or pitched down by `pitchDegrees`.
View view(int w, int h, double pitchDegrees = 0) {
  View v;
  v.name = "post";
  v.camera.width = w;
  v.camera.height = h;
  v.camera.verticalFov = 60;
  v.camera.nearPlane = 0.05;
  v.camera.farPlane = 100;
  v.camera.projection = "perspective";
  v.camera.enabled = true;
  v.camera.world.orientation = Eigen::AngleAxisd(pitchDegrees * M_PI / 180, Eigen::Vector3d::UnitY());
  v.passes = {Pass::Color};
  return v;
}

Image draw(const RenderScene& scene, const View& v, int samples = 4, bool post = true) {
  Image out;
  if (!context()) return out;
  RenderOptions o;
  o.samples = samples;
  o.post = post;
  Diagnostics d;
  auto r = Renderer::create(scene, o, d);
  EXPECT_TRUE(r) << (d.empty() ? "" : d.front().message);
  ViewImages im;
  if (r) {
    EXPECT_TRUE(r->render(v, im, d)) << (d.empty() ? "" : d.front().message);
  }
  if (const char* dir = std::getenv("RSCENE_TEST_IMAGES")) {  // to look at what the tests render
    static int n = 0;
    std::string png = encodePng(im.color);
    if (FILE* f = std::fopen((std::string(dir) + "/post_" + std::to_string(n++) + ".png").c_str(), "wb")) {
      std::fwrite(png.data(), 1, png.size(), f);
      std::fclose(f);
    }
  }
  return std::move(im.color);
}

double luma(const Image& im, int x, int y) {
  const std::uint8_t* p = im.pixel(x, y);
  return (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / 255.0;
}

// Mean luma over a square of side 2r+1.
double meanLuma(const Image& im, int cx, int cy, int r) {
  double s = 0;
  int n = 0;
  for (int y = cy - r; y <= cy + r; ++y)
    for (int x = cx - r; x <= cx + r; ++x)
      if (x >= 0 && y >= 0 && x < im.width && y < im.height) s += luma(im, x, y), ++n;
  return n ? s / n : 0;
}

// Where a world point lands (column, row), as the renderer projects it.
Eigen::Vector2i pixelOf(const View& v, const Eigen::Vector3d& p) {
  Eigen::Vector4d c = viewProjection(v) * p.homogeneous();
  Eigen::Vector2d ndc = c.head<2>() / c.w();
  return {int((ndc.x() + 1) / 2 * v.camera.width), int((1 - ndc.y()) / 2 * v.camera.height)};
}

}  // namespace

TEST(PostPlan, FollowsTheLookAndNoPost) {
  Look look;
  EXPECT_FALSE(postPlan(look, true).any());  // the defaults ask for nothing
  look.bloomIntensity = 0.2f;
  look.ssao = look.fxaa = look.autoExposure = true;
  look.depthOfField = true;
  look.aperture = 0.05f;
  PostPlan p = postPlan(look, true);
  EXPECT_TRUE(p.bloom && p.ssao && p.fxaa && p.autoExposure && p.depthOfField);
  EXPECT_FALSE(postPlan(look, false).any());  // --no-post
  look.aperture = 0;                          // a pinhole: nothing out of focus
  look.bloomIntensity = 0;
  p = postPlan(look, true);
  EXPECT_FALSE(p.depthOfField || p.bloom);
}

TEST(PostPlan, RecordsReachTheLook) {
  auto b = build(
      "raisim_engine_scene 1\n"
      "environment 0 0 0 0 0 0 0 true true 10 - backgroundMode=plain_color bloomIntensity=0.3 bloomThreshold=1.5 "
      "bloomRadius=6 fxaa=true ssao=true\n"
      "rayrai_render preset=high custom=false autoExposure=true autoExposureKey=0.25 depthOfField=true "
      "depthOfFieldFocusDistance=7 depthOfFieldAperture=0.04\n");
  const Look& l = b->scene.environment;
  EXPECT_FLOAT_EQ(l.bloomIntensity, 0.3f);
  EXPECT_FLOAT_EQ(l.bloomThreshold, 1.5f);
  EXPECT_FLOAT_EQ(l.bloomRadius, 6.0f);
  EXPECT_FLOAT_EQ(l.autoExposureKey, 0.25f);
  EXPECT_FLOAT_EQ(l.focusDistance, 7.0f);
  EXPECT_FLOAT_EQ(l.aperture, 0.04f);
  PostPlan p = postPlan(l, true);
  EXPECT_TRUE(p.bloom && p.ssao && p.fxaa && p.autoExposure && p.depthOfField);
}

TEST(PostPlan, AutoExposureBringsTheMeanToTheKeyWithinItsClamp) {
  float logs[4] = {std::log(0.09f), std::log(0.09f), std::log(0.09f), std::log(0.09f)};
  EXPECT_NEAR(autoExposureFactor(logs, 4, 0.18f), 2.0f, 1e-4);  // geometric mean 0.09 -> x2
  float bright[2] = {std::log(3.6f), std::log(3.6f)};
  EXPECT_NEAR(autoExposureFactor(bright, 2, 0.18f), 0.1f, 1e-6);  // 0.05 clamped to 0.1
  float black[1] = {std::log(1e-4f)};
  EXPECT_NEAR(autoExposureFactor(black, 1, 0.18f), kAutoExposureMax, 1e-6);  // not 1800
  EXPECT_EQ(autoExposureFactor(nullptr, 0, 0.18f), 1.0f);
  float nan[2] = {NAN, std::log(0.18f)};
  EXPECT_NEAR(autoExposureFactor(nan, 2, 0.18f), 1.0f, 1e-5);  // a NaN is skipped, not spread
}

TEST(PostPlan, CircleOfConfusionIsZeroAtFocusAndGrowsAway) {
  EXPECT_EQ(cocRadiusPixels(5, 5, 0.1f, 600), 0.0f);
  // 0.5 x 0.1 m x 600 px x |1/5 - 1/20| = 4.5 px
  EXPECT_NEAR(cocRadiusPixels(20, 5, 0.1f, 600), 4.5f, 1e-4);
  EXPECT_GT(cocRadiusPixels(2, 5, 0.1f, 600), cocRadiusPixels(4, 5, 0.1f, 600));
  EXPECT_EQ(maxCocPixels(720), 16.0f);
  EXPECT_EQ(bloomLevels(1280, 720), 5);
  EXPECT_EQ(bloomLevels(8, 8), 2);  // 4x4, 2x2
  EXPECT_EQ(bloomLevels(3, 3), 0);
}

TEST(PostPlan, BloomGainIsFiniteForAnyExposure) {
  EXPECT_FLOAT_EQ(bloomGain(0.5f, 5, 2.0f), 0.05f);
  EXPECT_TRUE(std::isfinite(bloomGain(0.5f, 5, 0.0f)));  // environment exposure=0
  EXPECT_TRUE(std::isfinite(bloomGain(1e30f, 0, 1e-30f)));
  EXPECT_EQ(bloomGain(NAN, 5, 1), 0.0f);
}

TEST(Post, BloomLightsThePixelsAroundABrightSphereOnly) {
  auto b = build(std::string(kEnvironment) +
                 "object /World/Lamp sphere 5 0 0 1 0 0 0 1 1 1 0.5 1 1 default white false true false - static "
                 "true 1 18446744073709551615\n");
  View v = view(160, 120);
  Image plain = draw(b->scene, v);
  b->scene.environment.bloomIntensity = 0.5f;
  b->scene.environment.bloomThreshold = 1.0f;
  Image glow = draw(b->scene, v);
  ASSERT_EQ(glow.width, 160);
  // The sphere is ~10 px in radius around (80, 60); a ring 14..20 px out.
  double ringPlain = 0, ringGlow = 0;
  int n = 0;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x) {
      double r = std::hypot(x + 0.5 - 80, y + 0.5 - 60);
      if (r < 14 || r > 20) continue;
      ringPlain += luma(plain, x, y), ringGlow += luma(glow, x, y), ++n;
    }
  ringPlain /= n, ringGlow /= n;
  EXPECT_LT(ringPlain, 0.01);  // without bloom: the black background
  EXPECT_GT(ringGlow, 0.08);   // with bloom: lit by the sphere
  EXPECT_GT(luma(glow, 80, 60), 0.95);
  // The glow fades with distance: the corners, 100 px away, get a quarter
  // of the ring's at most (and nothing without bloom).
  EXPECT_LT(luma(glow, 1, 1), 0.25 * ringGlow);
  EXPECT_EQ(plain.pixel(1, 1)[0], 0);
  EXPECT_EQ(glow.pixel(1, 1)[3], 255);
}

TEST(Post, BloomKeepsAPlainBackgroundColorExact) {
  auto b = build(std::string(kEnvironment) + box("/World/Box", 5, 0, 0, 0.5, 0.5, 0.5, "grey"));
  b->scene.environment.background = Eigen::Vector3f(0.2f, 0.4f, 0.6f);
  b->scene.environment.toneMap = ToneMap::Aces;  // a curve that would shift it
  b->scene.environment.bloomIntensity = 0.1f;
  b->scene.environment.bloomThreshold = 5;
  Image im = draw(b->scene, view(96, 64));
  ASSERT_EQ(im.width, 96);
  const std::uint8_t* p = im.pixel(3, 3);
  EXPECT_NEAR(p[0], 51, 1);
  EXPECT_NEAR(p[1], 102, 1);
  EXPECT_NEAR(p[2], 153, 1);
}

TEST(Post, FxaaSoftensAHardDiagonalEdge) {
  // A white square turned 30 degrees about the view axis, one sample per
  // pixel: without FXAA its edges are stairs of pure white and black.
  auto b = build(std::string(kEnvironment) + box("/World/Card", 5, 0, 0, 0.05, 3, 3, "white", "0.9659 0.2588 0 0"));
  View v = view(160, 120);
  Image hard = draw(b->scene, v, 1);
  b->scene.environment.fxaa = true;
  Image soft = draw(b->scene, v, 1);
  ASSERT_EQ(soft.width, 160);
  auto intermediate = [](const Image& im) {
    int n = 0;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x) {
        double l = luma(im, x, y);
        n += l > 0.08 && l < 0.92;
      }
    return n;
  };
  int before = intermediate(hard), after = intermediate(soft);
  EXPECT_LT(before, 20);  // 1 sample: (nearly) no partial pixels
  EXPECT_GT(after, 150);  // four edges of ~60 px, most of their stair steps blended
  // The inside of the square and the background far from it are untouched.
  EXPECT_GT(luma(soft, 80, 60), 0.99);
  EXPECT_LT(luma(soft, 2, 2), 0.01);
}

TEST(Post, SsaoDarkensACornerMoreThanAnOpenFloor) {
  // A floor (top at z = -0.9) and a wall (face at x = 6.9) meeting at a
  // corner; light from above and behind, and ambient light.
  std::string env = std::string(kEnvironment);
  env.replace(env.find("environment 0 0 0 0 0 0"), 23, "environment 0 0 0 0.4 0.4 0.4");
  auto b = build(env + "light /World/Sun -0.3 0.2 -1 2 type=directional shadows=false\n" +
                 box("/World/Floor", 4, 0, -1, 8, 12, 0.2, "grey") + box("/World/Wall", 7, 0, 0.5, 0.2, 12, 3, "grey"));
  View v = view(200, 150, 25);
  v.camera.world.position = Eigen::Vector3d(2, 0, 0.5);
  Image flat = draw(b->scene, v);
  b->scene.environment.ssao = true;
  Image ao = draw(b->scene, v);
  ASSERT_EQ(ao.width, 200);
  Eigen::Vector2i corner = pixelOf(v, {6.85, 0, -0.88}), open = pixelOf(v, {4.0, 0, -0.9});
  double cornerRatio = meanLuma(ao, corner.x(), corner.y(), 1) / meanLuma(flat, corner.x(), corner.y(), 1);
  double openRatio = meanLuma(ao, open.x(), open.y(), 2) / meanLuma(flat, open.x(), open.y(), 2);
  // 0.85 until issue 27: the bounded estimator darkens this far, grazing
  // corner less than McGuire's 1/distance weight did (0.91 here), and
  // contacts no longer go black (look_test's Ssao test).
  EXPECT_LT(cornerRatio, 0.93);
  EXPECT_GT(openRatio, 0.97);
}

TEST(Post, AutoExposureBringsADarkAndABrightSceneCloser) {
  // The same floor filling the view, lit by a sun 8 times brighter.
  auto scene = [](double intensity) {
    char light[128];
    std::snprintf(light, sizeof light, "light /World/Sun 0 0 -1 %g type=directional shadows=false\n", intensity);
    return build(std::string(kEnvironment).replace(std::string(kEnvironment).find("colorMode=fast_linear"), 21,
                                                   "colorMode=aces_approx") +
                 light + box("/World/Floor", 4, 0, -1, 40, 40, 0.2, "grey"));
  };
  View v = view(96, 64, 70);
  auto mean = [](const Image& im) { return meanLuma(im, im.width / 2, im.height / 2, 30); };
  auto dark = scene(0.3), bright = scene(2.4);
  double plainRatio = mean(draw(bright->scene, v)) / mean(draw(dark->scene, v));
  dark->scene.environment.autoExposure = bright->scene.environment.autoExposure = true;
  double autoRatio = mean(draw(bright->scene, v)) / mean(draw(dark->scene, v));
  EXPECT_GT(plainRatio, 2.0);  // the tone curve and gamma compress x8 to about x3
  EXPECT_LT(autoRatio, 1.15);
  EXPECT_GT(autoRatio, 0.87);
}

TEST(Post, DepthOfFieldBlursAFarCheckerboardAndKeepsTheFocusedOneSharp) {
  // White squares of a checkerboard, unlit (emissive) on black: a near one
  // of 0.1 m squares at 3 m, in focus, and a far one of 0.5 m squares at
  // 20 m; both about 7 px a square at 320x240.
  std::string text = kEnvironment;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) {
      if ((i + j) % 2) continue;
      std::string id = std::to_string(i) + "_" + std::to_string(j);
      text += box("/World/Near" + id, 3, 0.95 - 0.1 * i, -0.35 + 0.1 * j, 0.01, 0.1, 0.1, "white");
      text += box("/World/Far" + id, 20, -1.25 - 0.5 * i, -1.75 + 0.5 * j, 0.05, 0.5, 0.5, "white");
    }
  auto b = build(text);
  View v = view(320, 240);
  Image sharp = draw(b->scene, v);
  Look& l = b->scene.environment;
  l.depthOfField = true;
  l.focusDistance = 3;
  l.aperture = 0.2f;  // 20 m: a blur radius of 0.5 x 0.2 x 208 x (1/3 - 1/20) = 5.9 px (5.3 at most)
  Image blurred = draw(b->scene, v);
  ASSERT_EQ(blurred.width, 320);
  // Local contrast: the standard deviation of luma inside each board.
  auto contrast = [&](const Image& im, const Eigen::Vector3d& centre) {
    Eigen::Vector2i c = pixelOf(v, centre);
    double s = 0, s2 = 0;
    int n = 0;
    for (int y = c.y() - 18; y <= c.y() + 18; ++y)
      for (int x = c.x() - 18; x <= c.x() + 18; ++x) {
        double l = luma(im, x, y);
        s += l, s2 += l * l, ++n;
      }
    return std::sqrt(std::max(s2 / n - (s / n) * (s / n), 0.0));
  };
  Eigen::Vector3d nearCentre(3, 0.6, 0), farCentre(20, -3, 0);
  double nearBefore = contrast(sharp, nearCentre), nearAfter = contrast(blurred, nearCentre);
  double farBefore = contrast(sharp, farCentre), farAfter = contrast(blurred, farCentre);
  EXPECT_GT(nearBefore, 0.4);
  EXPECT_GT(farBefore, 0.4);
  EXPECT_GT(nearAfter, 0.95 * nearBefore);
  EXPECT_LT(farAfter, 0.5 * farBefore);
}

TEST(Post, NoPostIsTheImageWithoutEffects) {
  auto b = build(std::string(kEnvironment) + "light /World/Sun 1 0.4 -0.6 3 type=directional\n" +
                 box("/World/Box", 5, 0, 0, 1, 1, 1, "grey"));
  View v = view(64, 48);
  Image none = draw(b->scene, v);
  Look& l = b->scene.environment;
  l.bloomIntensity = 1;
  l.ssao = l.fxaa = l.autoExposure = true;
  Image skipped = draw(b->scene, v, 4, false);
  EXPECT_EQ(none.rgba, skipped.rgba);
  Image with = draw(b->scene, v, 4, true);
  EXPECT_NE(none.rgba, with.rgba);
}
