// The Renderer's passes (view.hpp) on the CPU backend: depth is the exact
// plane distance (perspective and orthographic), segmentation covers what
// RGB shows in the legend's color, intrinsics land a point where
// u = cx - fx*y/x says, noise is seeded, updatePoses moves drawables, and
// sensor views draw world objects only.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "gl_test_context.hpp"
#include "asset/image.hpp"
#include "core/loader.hpp"
#include "render/gl_context.hpp"
#include "render/view.hpp"

using namespace rscene;
using namespace rscene::render;

namespace {

const char* kHeader =
    "raisim_engine_scene 1\n"
    "environment 0 0 0 0.2 0.2 0.2 0 true true 10 - backgroundMode=plain_color colorMode=linear\n"
    "material red 0.8 0.1 0.1 1 0 0.6 0 0 0 0 false - - - - - - id=red\n"
    "light /World/Sun 1 0.4 -0.4 3 type=directional shadows=false\n";

// A box of size (sx, sy, sz) centred at (x, y, z); `mode`: static,
// dynamic, visual_only.
std::string box(const std::string& path, double x, double y, double z, double sx, double sy, double sz,
                const std::string& mode = "static", const std::string& extra = "") {
  char b[512];
  std::snprintf(b, sizeof b,
                "object %s box %g %g %g 1 0 0 0 %g %g %g 0.5 1 1 default red false true false - %s true 1 "
                "18446744073709551615 %s\n",
                path.c_str(), x, y, z, sx, sy, sz, mode.c_str(), extra.c_str());
  return b;
}

struct Built {
  Scene model;
  RenderScene scene;
  Diagnostics diags;
  bool ok = false;
};

std::unique_ptr<Built> build(const std::string& body) {
  auto b = std::make_unique<Built>();
  LoadResult loaded = parse(kHeader + body);
  EXPECT_TRUE(loaded.ok());
  b->ok = buildRenderScene(loaded.document, SceneOptions{}, b->model, b->scene, b->diags);
  EXPECT_TRUE(b->ok);
  return b;
}

// A view at the origin looking along +x (identity orientation).
View view(int w, int h, std::vector<Pass> passes, double vfov = 60) {
  View v;
  v.name = "test";
  v.camera.width = w;
  v.camera.height = h;
  v.camera.verticalFov = vfov;
  v.camera.nearPlane = 0.05;
  v.camera.farPlane = 100;
  v.camera.projection = "perspective";
  v.camera.enabled = true;
  v.passes = std::move(passes);
  return v;
}

ViewImages draw(const RenderScene& scene, const View& v, RenderOptions options = {}) {
  ViewImages out;
  if (!context()) return out;
  Diagnostics d;
  auto r = Renderer::create(scene, options, d);
  EXPECT_TRUE(r) << (d.empty() ? "" : d.front().message);
  if (r) {
    EXPECT_TRUE(r->render(v, out, d)) << (d.empty() ? "" : d.front().message);
  }
  return out;
}

bool black(const Image& im, int x, int y) {
  const std::uint8_t* p = im.pixel(x, y);
  return p[0] == 0 && p[1] == 0 && p[2] == 0;
}

void writeDebug(const Image& im, const std::string& name) {
  // Set RSCENE_TEST_IMAGES=DIR to look at what the tests render.
  if (const char* dir = std::getenv("RSCENE_TEST_IMAGES")) {
    std::string png = encodePng(im);
    FILE* f = std::fopen((std::string(dir) + "/" + name + ".png").c_str(), "wb");
    if (f) {
      std::fwrite(png.data(), 1, png.size(), f);
      std::fclose(f);
    }
  }
}

}  // namespace

TEST(Passes, DepthOfAPlaneAt5mIsExactPerspective) {
  // A wall whose near face is the plane x = 5, larger than the view.
  auto b = build(box("/World/Wall", 5.5, 0, 0, 1, 40, 40));
  ViewImages im = draw(b->scene, view(160, 120, {Pass::Depth}));
  ASSERT_EQ(im.depth.size(), 160u * 120u);
  double worst = 0;
  for (float d : im.depth) worst = std::max(worst, std::isfinite(d) ? std::abs(d - 5.0) : 1e9);
  EXPECT_LT(worst, 1e-3);  // every pixel within 1 mm, corners included (plane distance, not range)
}

TEST(Passes, DepthOfAPlaneAt5mIsExactOrthographic) {
  auto b = build(box("/World/Wall", 5.5, 0, 0, 1, 40, 40));
  View v = view(160, 120, {Pass::Depth});
  v.camera.projection = "orthographic";
  v.camera.orthoScale = 4;
  ViewImages im = draw(b->scene, v);
  ASSERT_EQ(im.depth.size(), 160u * 120u);
  double worst = 0;
  for (float d : im.depth) worst = std::max(worst, std::isfinite(d) ? std::abs(d - 5.0) : 1e9);
  EXPECT_LT(worst, 1e-3);
  // A 2 m wall in a 4 m high (5.33 m wide) orthographic view: the middle
  // 60 of 120 rows and 60 of 160 columns are hit, the rest is NaN.
  auto small = build(box("/World/Wall", 5.5, 0, 0, 1, 2, 2));
  ViewImages part = draw(small->scene, v);
  ASSERT_EQ(part.depth.size(), 160u * 120u);
  int hit = 0;
  for (float d : part.depth)
    if (std::isfinite(d)) {
      ++hit;
      EXPECT_NEAR(d, 5.0, 1e-3);
    }
  EXPECT_NEAR(hit, 60 * 60, 2 * 60 + 2 * 60);  // within a pixel row or column on each side
  EXPECT_TRUE(std::isnan(part.depth[0]));
  EXPECT_TRUE(std::isnan(part.depth[60 * 160 + 40]));
  EXPECT_FALSE(std::isnan(part.depth[60 * 160 + 80]));
}

TEST(Passes, DepthIsNanWhereNothingIsHitOrBeyondFar) {
  // A 2 m wall at 5 m in a 60 degree view: the middle is hit, the border is not.
  auto b = build(box("/World/Wall", 5.5, 0, 0, 1, 2, 2));
  View v = view(160, 120, {Pass::Depth, Pass::Segmentation});
  ViewImages im = draw(b->scene, v);
  ASSERT_EQ(im.depth.size(), 160u * 120u);
  EXPECT_NEAR(im.depth[60 * 160 + 80], 5.0, 1e-3);
  EXPECT_TRUE(std::isnan(im.depth[0]));
  EXPECT_TRUE(std::isnan(im.depth[60 * 160 + 2]));
  // Where depth is NaN segmentation is the background, and the other way round.
  for (std::size_t i = 0; i < im.depth.size(); ++i)
    ASSERT_EQ(std::isnan(im.depth[i]), black(im.segmentation, int(i % 160), int(i / 160))) << i;
  // The same wall beyond the far plane: nothing at all.
  v.camera.farPlane = 4.5;
  ViewImages far = draw(b->scene, v);
  for (float d : far.depth) ASSERT_TRUE(std::isnan(d));
}

TEST(Passes, SegmentationCoversWhatRgbShowsInTheLegendColor) {
  auto b = build(box("/World/Box", 5, 0.4, -0.2, 1, 1.2, 0.8, "static", "id=box semanticClass=crate instanceId=7"));
  RenderOptions one;
  one.samples = 1;  // the color pass samples pixel centres, as the data pass does
  ViewImages im = draw(b->scene, view(200, 150, {Pass::Color, Pass::Segmentation}), one);
  ASSERT_EQ(im.color.width, 200);
  ASSERT_EQ(im.segmentation.width, 200);
  writeDebug(im.color, "passes_box_rgb");
  writeDebug(im.segmentation, "passes_box_seg");
  ASSERT_EQ(b->scene.segments.size(), 1u);
  const std::uint8_t* legend = b->scene.segments[0].rgb;
  int rgbPixels = 0, mismatched = 0;
  for (int y = 0; y < 150; ++y)
    for (int x = 0; x < 200; ++x) {
      bool inRgb = !black(im.color, x, y);
      bool inSeg = !black(im.segmentation, x, y);
      rgbPixels += inRgb;
      mismatched += inRgb != inSeg;
      const std::uint8_t* s = im.segmentation.pixel(x, y);
      EXPECT_EQ(s[3], 255);
      if (inSeg) {
        ASSERT_EQ(s[0], legend[0]);
        ASSERT_EQ(s[1], legend[1]);
        ASSERT_EQ(s[2], legend[2]);
      }
    }
  EXPECT_GT(rgbPixels, 700);  // about 35 x 23 px
  EXPECT_EQ(mismatched, 0);
}

TEST(Passes, SegmentationColorsAreFlatAndDistinctPerRecord) {
  auto b = build(box("/World/A", 5, 1, 0, 1, 1, 1, "static", "segmentationColor=0.2,0.4,0.6,1") +
                 box("/World/B", 5, -1, 0, 1, 1, 1, "static", "semanticClass=crate"));
  ViewImages im = draw(b->scene, view(200, 150, {Pass::Segmentation}));
  ASSERT_EQ(im.segmentation.width, 200);
  // /World/A is at +y (left in the image), /World/B at -y (right).
  const std::uint8_t* a = im.segmentation.pixel(60, 75);
  EXPECT_EQ(a[0], 51);
  EXPECT_EQ(a[1], 102);
  EXPECT_EQ(a[2], 153);
  const std::uint8_t* c = im.segmentation.pixel(140, 75);
  const std::uint8_t* legend = b->scene.segments[1].rgb;
  EXPECT_EQ(c[0], legend[0]);
  EXPECT_EQ(c[1], legend[1]);
  EXPECT_EQ(c[2], legend[2]);
  EXPECT_TRUE(black(im.segmentation, 100, 5));
}

TEST(Passes, IntrinsicsProjectAPointWhereTheFormulaSays) {
  // The camera somewhere, turned; the sphere at a known point of its frame.
  View v = view(160, 120, {Pass::Segmentation});
  v.fx = 150, v.fy = 140, v.cx = 70, v.cy = 65;
  v.camera.world.position = Eigen::Vector3d(1, 2, 0.5);
  v.camera.world.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) *
                                                  Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()));
  const Eigen::Vector3d local(4, 0.5, -0.3);  // forward, left, up
  Eigen::Vector3d world = v.camera.world.position + v.camera.world.orientation * local;
  char sphere[400];
  std::snprintf(sphere, sizeof sphere,
                "object /World/Ball sphere %.9g %.9g %.9g 1 0 0 0 1 1 1 0.2 1 1 default red false true false - "
                "static true 1 18446744073709551615\n",
                world.x(), world.y(), world.z());
  auto b = build(sphere);
  ViewImages im = draw(b->scene, v);
  ASSERT_EQ(im.segmentation.width, 160);
  writeDebug(im.segmentation, "passes_intrinsics");
  double su = 0, sv = 0;
  int n = 0;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x)
      if (!black(im.segmentation, x, y)) {
        su += x + 0.5;  // pixel centres at +0.5 (camera.hpp)
        sv += y + 0.5;
        ++n;
      }
  ASSERT_GT(n, 50);
  double u = v.cx - v.fx * local.y() / local.x(), w = v.cy - v.fy * local.z() / local.x();
  EXPECT_NEAR(su / n, u, 0.2);  // 51.25
  EXPECT_NEAR(sv / n, w, 0.2);  // 75.5
  // The sphere's radius in pixels follows fx and fy too (about 7.5 and 7 px).
  EXPECT_NEAR(n, 3.14159 * (150 * 0.05) * (140 * 0.05), 12);
}

TEST(Passes, IntrinsicsCentredEqualTheFieldOfView) {
  // fx = (w/2) / tan(hfov/2), cx = w/2: the same image as the field of view.
  auto b = build(box("/World/Box", 5, 0.7, 0.3, 1, 1, 1));
  View fov = view(160, 120, {Pass::Segmentation}, 60);
  View pin = fov;
  pin.fy = pin.fx = 60 / std::tan(3.14159265358979 / 6);
  pin.cx = 80, pin.cy = 60;
  ViewImages a = draw(b->scene, fov), c = draw(b->scene, pin);
  ASSERT_EQ(a.segmentation.rgba.size(), c.segmentation.rgba.size());
  int differ = 0;
  for (std::size_t i = 0; i < a.segmentation.rgba.size(); i += 4)
    differ += a.segmentation.rgba[i] != c.segmentation.rgba[i];
  EXPECT_LE(differ, 2);  // rounding on an edge at most
}

TEST(Passes, NoiseIsSeededAndOnlyOnReturns) {
  auto b = build(box("/World/Wall", 5.5, 0, 0, 1, 3, 3));
  View v = view(160, 120, {Pass::Depth});
  v.noiseMean = 0.01;
  v.noiseStddev = 0.05;
  v.noiseSeed = 42;
  ViewImages a = draw(b->scene, v), again = draw(b->scene, v);
  v.noiseSeed = 43;
  ViewImages other = draw(b->scene, v);
  ASSERT_EQ(a.depth.size(), 160u * 120u);
  int finite = 0, same = 0, differ = 0;
  double sum = 0, sum2 = 0;
  for (std::size_t i = 0; i < a.depth.size(); ++i) {
    ASSERT_EQ(std::isnan(a.depth[i]), std::isnan(again.depth[i]));
    if (std::isnan(a.depth[i])) continue;
    ++finite;
    same += a.depth[i] == again.depth[i];
    differ += a.depth[i] != other.depth[i];
    sum += a.depth[i] - 5.0;
    sum2 += (a.depth[i] - 5.0) * (a.depth[i] - 5.0);
  }
  ASSERT_GT(finite, 1000);
  ASSERT_LT(finite, 160 * 120);  // NaN stays NaN where nothing is hit
  EXPECT_EQ(same, finite);
  EXPECT_GT(differ, finite * 9 / 10);
  double mean = sum / finite, stddev = std::sqrt(sum2 / finite - mean * mean);
  EXPECT_NEAR(mean, 0.01, 0.005);
  EXPECT_NEAR(stddev, 0.05, 0.005);
}

TEST(Passes, NoiseValuesAreFixedAcrossPlatforms) {
  // The generator is ours (splitmix64 + Box-Muller): these numbers are the
  // contract, whatever the standard library.
  std::vector<float> d = {1.0f, NAN, 2.0f, 3.0f};
  addDepthNoise(d, 0, 0.1, 7);
  EXPECT_TRUE(std::isnan(d[1]));
  std::vector<float> e = {1.0f, 5.0f, 2.0f, 3.0f};
  addDepthNoise(e, 0, 0.1, 7);
  EXPECT_EQ(d[0], e[0]);  // a pixel's noise does not depend on its neighbours
  EXPECT_EQ(d[2], e[2]);
  // Pinned: a change of generator changes every noisy image users compared.
  std::vector<float> f = {1.0f, 2.0f, 3.0f, 4.0f};
  addDepthNoise(f, 0, 0.1, 7);
  EXPECT_NEAR(f[0], 1.00543582, 1e-6);
  EXPECT_NEAR(f[1], 1.85910928, 1e-6);
  EXPECT_NEAR(f[2], 2.89418769, 1e-6);
  EXPECT_NEAR(f[3], 4.00341606, 1e-6);
  std::vector<float> zero = {1.0f};
  addDepthNoise(zero, 0, 0, 7);
  EXPECT_EQ(zero[0], 1.0f);
}

TEST(Passes, UpdatePosesMovesADrawable) {
  auto b = build(box("/World/Crate", 5, 1.2, 0, 1, 1, 1, "dynamic"));
  ASSERT_TRUE(context());
  Diagnostics d;
  auto r = Renderer::create(b->scene, RenderOptions{}, d);
  ASSERT_TRUE(r);
  View v = view(160, 120, {Pass::Segmentation, Pass::Depth});
  ViewImages before, after;
  ASSERT_TRUE(r->render(v, before, d));
  // Left of the centre (+y) at first; moved to the right (-y) by a new pose.
  int left = 50, right = 115, row = 60;
  EXPECT_FALSE(black(before.segmentation, left, row));
  EXPECT_TRUE(black(before.segmentation, right, row));
  std::vector<Pose> objects(b->model.objects.size());
  for (std::size_t i = 0; i < objects.size(); ++i) objects[i] = b->model.objects[i].world;
  objects[0].position = Eigen::Vector3d(4, -1.2, 0);
  BodyPoseView poses;
  poses.objects = &objects;
  poseScene(b->scene, poses);
  r->updatePoses();
  ASSERT_TRUE(r->render(v, after, d));
  EXPECT_TRUE(black(after.segmentation, left, row));
  EXPECT_FALSE(black(after.segmentation, right, row));
  EXPECT_NEAR(after.depth[std::size_t(row) * 160 + right], 3.5, 1e-3);  // its near face moved to x = 3.5
}

TEST(Passes, SensorViewsDrawWorldObjectsOnly) {
  std::string text = box("/World/Body", 5, 0, 0, 1, 1, 1) +
                     box("/World/Marker", 5, 1.5, 0, 0.5, 0.5, 0.5, "visual_only") +
                     "instanced_visual /World/Trees box size=0.5,0.5,0.5 instances=5,-1.5,0,1,0,0,0,1,1,1\n";
  auto b = build(text);
  View v = view(160, 120, {Pass::Segmentation, Pass::Depth, Pass::Color});
  ViewImages camera = draw(b->scene, v);
  v.sensor = true;
  ViewImages sensor = draw(b->scene, v);
  writeDebug(camera.segmentation, "passes_camera_view");
  writeDebug(sensor.segmentation, "passes_sensor_view");
  writeDebug(sensor.color, "passes_sensor_rgb");
  // Columns of the three: marker (+y, left), body (centre), instance (-y, right).
  int marker = 47, body = 80, instance = 113, row = 60;
  EXPECT_FALSE(black(camera.segmentation, marker, row));
  EXPECT_FALSE(black(camera.segmentation, body, row));
  EXPECT_FALSE(black(camera.segmentation, instance, row));
  EXPECT_TRUE(black(sensor.segmentation, marker, row));
  EXPECT_FALSE(black(sensor.segmentation, body, row));
  EXPECT_TRUE(black(sensor.segmentation, instance, row));
  EXPECT_TRUE(std::isnan(sensor.depth[std::size_t(row) * 160 + marker]));
  EXPECT_FALSE(std::isnan(sensor.depth[std::size_t(row) * 160 + body]));
  EXPECT_TRUE(black(sensor.color, marker, row));  // plain black background
  EXPECT_FALSE(black(camera.color, marker, row));
}

TEST(Passes, OneRendererDrawsManyViewsLikeFreshOnes) {
  auto b = build(box("/World/A", 5, 1, 0, 1, 1, 1) + box("/World/B", -5, -1, 0, 1, 1, 1));
  ASSERT_TRUE(context());
  Diagnostics d;
  auto r = Renderer::create(b->scene, RenderOptions{}, d);
  ASSERT_TRUE(r);
  View front = view(120, 90, {Pass::Color, Pass::Segmentation});
  View back = view(64, 48, {Pass::Color, Pass::Depth});
  back.camera.world.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(3.14159265358979, Eigen::Vector3d::UnitZ()));
  ViewImages f1, b1, f2;
  ASSERT_TRUE(r->render(front, f1, d));
  ASSERT_TRUE(r->render(back, b1, d));
  ASSERT_TRUE(r->render(front, f2, d));  // another size in between: targets remade
  EXPECT_EQ(f1.color.rgba, f2.color.rgba);
  EXPECT_EQ(f1.segmentation.rgba, f2.segmentation.rgba);
  EXPECT_EQ(f1.color.rgba, draw(b->scene, front).color.rgba);
  EXPECT_EQ(b1.width, 64);
  EXPECT_NEAR(b1.depth[24 * 64 + 22], 4.5, 1e-3);  // B's near face, seen from behind the origin
  RenderTimings t = r->timings();
  EXPECT_GT(t.uploadSeconds, 0);
  EXPECT_GT(t.drawSeconds, 0);
}

TEST(Passes, ABadViewIsAnErrorNotACrash) {
  auto b = build(box("/World/A", 5, 0, 0, 1, 1, 1));
  ASSERT_TRUE(context());
  Diagnostics d;
  auto r = Renderer::create(b->scene, RenderOptions{}, d);
  ASSERT_TRUE(r);
  ViewImages out;
  View zero = view(0, 10, {Pass::Color});
  EXPECT_FALSE(r->render(zero, out, d));
  View partial = view(10, 10, {Pass::Depth});
  partial.fx = 10;
  EXPECT_FALSE(r->render(partial, out, d));
  View none = view(10, 10, {});
  EXPECT_FALSE(r->render(none, out, d));
  ASSERT_EQ(d.size(), 3u);
  for (const Diagnostic& x : d) EXPECT_EQ(x.code, "RS9040");
  EXPECT_EQ(d[1].message, "view 'test': intrinsics fx and fy must both be positive (or both 0: none)");
}

TEST(Passes, PointCloudsAreInCameraViewsNotSensorViews) {
  // A square of 9 fat points 5 m ahead, in the cloud's legend color.
  std::string points, colors;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j) {
      points +=
          (points.empty() ? "" : ";") + std::string("5,") + std::to_string(0.05 * i) + "," + std::to_string(0.05 * j);
      colors += (colors.empty() ? "" : ";") + std::string("1,1,1,1");
    }
  auto b = build("point_cloud /World/Cloud points=" + points + " colors=" + colors + " pointSize=8 id=cloud\n");
  ASSERT_EQ(b->scene.segments.size(), 1u);
  View v = view(160, 120, {Pass::Segmentation, Pass::Depth});
  ViewImages camera = draw(b->scene, v);
  ASSERT_EQ(camera.segmentation.width, 160);
  const std::uint8_t* c = camera.segmentation.pixel(80, 60);
  EXPECT_TRUE(std::equal(c, c + 3, b->scene.segments[0].rgb));
  EXPECT_NEAR(camera.depth[60 * 160 + 80], 5.0, 1e-3);
  v.sensor = true;
  ViewImages sensor = draw(b->scene, v);
  EXPECT_TRUE(black(sensor.segmentation, 80, 60));
  EXPECT_TRUE(std::isnan(sensor.depth[60 * 160 + 80]));
}

TEST(Passes, SensorColorViewsHaveNoShadowsOfVisuals) {
  // Looking straight down from 10 m (image up = +x); the sun travels
  // towards -x and down, so a box's shadow lies on the -x side (image
  // bottom).  The box is visual-only: a camera sees it and its shadow, a
  // sensor neither.  Camera, sensor, camera on one renderer: the shadow map
  // follows the kind of view.
  auto b = build(
      "light /World/Key -1 0 -1 3 type=directional shadows=true\n"
      "object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 1 0 0 default red false true true - static true 1 "
      "18446744073709551615\n" +
      box("/World/Marker", 0, 0, 0.5, 1, 1, 1, "visual_only"));
  ASSERT_TRUE(context());
  Diagnostics d;
  auto r = Renderer::create(b->scene, RenderOptions{}, d);
  ASSERT_TRUE(r);
  View v = view(200, 200, {Pass::Color});
  v.camera.world.position = Eigen::Vector3d(0, 0, 10);
  v.camera.world.orientation = Eigen::Quaterniond(0.70710678, 0, 0.70710678, 0);
  int dy = int(std::lround(1.0 / (10 * std::tan(30 * M_PI / 180)) * 100));  // 1 m from the centre, in pixels
  auto mean = [&](const Image& im, int cx, int cy) {
    int s = 0;
    for (int y = -2; y <= 2; ++y)
      for (int x = -2; x <= 2; ++x) {
        const std::uint8_t* p = im.pixel(cx + x, cy + y);
        s += p[0] + p[1] + p[2];
      }
    return s / 25;
  };
  for (bool sensor : {false, true, false}) {
    v.sensor = sensor;
    ViewImages im;
    ASSERT_TRUE(r->render(v, im, d));
    writeDebug(im.color, sensor ? "passes_shadow_sensor" : "passes_shadow_camera");
    int shadowSide = mean(im.color, 100, 100 + dy), litSide = mean(im.color, 100, 100 - dy);
    if (sensor) {
      EXPECT_NEAR(shadowSide, litSide, 20);
    } else {
      EXPECT_LT(shadowSide, litSide - 40);
    }
  }
}
