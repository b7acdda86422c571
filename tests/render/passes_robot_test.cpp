// The passes on a real robot (ANYmal C from ../shared, skipped without
// it): RGB, depth and segmentation at 640x480 agree with each other, a
// sensor view still sees the robot (a world object), and moving the robot
// with updatePoses() moves it in the images.  Prints the time per frame
// (bench/ measures; nothing here asserts a speed).
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "gl_test_context.hpp"
#include "asset/cache.hpp"
#include "core/loader.hpp"
#include "render/gl_context.hpp"
#include "render/view.hpp"
#include "render/view_output.hpp"
#include "robot/sensors.hpp"

using namespace rscene;
using namespace rscene::render;

namespace {

void save(const std::string& name, const std::string& bytes) {
  // Set RSCENE_TEST_IMAGES=DIR to look at what the test renders.
  const char* dir = std::getenv("RSCENE_TEST_IMAGES");
  if (!dir) return;
  if (FILE* f = std::fopen((std::string(dir) + "/" + name).c_str(), "wb")) {
    std::fwrite(bytes.data(), 1, bytes.size(), f);
    std::fclose(f);
  }
}

// CPU seconds of the process, llvmpipe's threads included: steadier than
// wall time on a shared machine.
double cpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

bool black(const Image& im, int x, int y) {
  const std::uint8_t* p = im.pixel(x, y);
  return p[0] == 0 && p[1] == 0 && p[2] == 0;
}

}  // namespace

TEST(PassesRobot, AnymalRgbDepthSegmentationAgreeAndMove) {
  std::filesystem::path urdf = std::filesystem::path(RSCENE_SHARED_DIR) / "corpus/robots/anymal_c/urdf/anymal.urdf";
  if (!std::filesystem::exists(urdf)) GTEST_SKIP() << "no ../shared corpus";
  ASSERT_TRUE(context());
  LoadResult loaded = parse(
      "raisim_engine_scene 1\n"
      "environment 0.38 0.38 0.38 0.15 0.16 0.2 0 true true 10 - backgroundMode=rayrai_sky\n"
      "material ground 0.45 0.47 0.5 1 0 0.8 0 0 0 0 false - - - - - - id=ground\n"
      "light /World/Sun -0.4 0.3 -1 3 type=directional shadows=true\n"
      "object /World/Ground ground 0 0 0 1 0 0 0 50 50 1 1 0 0 default ground false true true - static true 1 "
      "18446744073709551615 semanticClass=floor\n"
      "articulated_resource anymal ANYmal " +
      urdf.string() +
      "\n"
      "articulated /World/Anymal anymal 0 0 0.54 1 0 0 0 true true semanticClass=robot generalizedCoordinate=0,0,0.54,"
      "1,0,0,0,0.03,0.4,-0.8,-0.03,0.4,-0.8,0.03,-0.4,0.8,-0.03,-0.4,0.8\n");
  ASSERT_TRUE(loaded.ok());
  asset::AssetCache assets;
  Scene model;
  RenderScene scene;
  Diagnostics diags;
  ASSERT_TRUE(buildRenderScene(loaded.document, {}, model, scene, diags, {}, &assets));
  RenderOptions options;
  options.assets = &assets;
  auto r = Renderer::create(scene, options, diags);
  ASSERT_TRUE(r);

  // From 1.7 m front-right, 0.8 m up, looking at the robot (render.bats).
  View v;
  v.name = "/World/Cam";
  v.camera.world.position = Eigen::Vector3d(1.2, -1.2, 0.8);
  v.camera.world.orientation = Eigen::Quaterniond(0.37947, -0.11947, 0.04949, 0.91612).normalized();
  v.camera.verticalFov = 50;
  v.camera.nearPlane = 0.05;
  v.camera.farPlane = 100;
  v.camera.width = 640;
  v.camera.height = 480;
  v.camera.projection = "perspective";
  v.passes = {Pass::Color, Pass::Depth, Pass::Segmentation};

  robot::BodyPoses rest = robot::restPoses(model, scene.robotModels);
  ASSERT_EQ(rest.robotLinks.size(), 1u);
  // The whole robot slides 0.3 m along -y over the frames: a new pose per
  // frame (updatePoses, the shadow map redrawn), as a trajectory gives.
  const int frames = 5;  // the first compiles llvmpipe's shader variants: not timed
  auto run = [&](View view, ViewImages* first, ViewImages* last) {
    double wall = 0, cpu = 0;
    for (int f = 0; f < frames; ++f) {
      robot::BodyPoses p = rest;
      for (Pose& link : p.robotLinks[0]) link.position.y() -= 0.3 * f / (frames - 1);
      BodyPoseView pv;
      pv.robotLinks = &p.robotLinks;
      poseScene(scene, pv);
      auto t0 = std::chrono::steady_clock::now();
      double c0 = cpuSeconds();
      r->updatePoses();
      ViewImages im;
      EXPECT_TRUE(r->render(view, im, diags)) << diags.back().message;
      if (f > 0) {
        wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        cpu += cpuSeconds() - c0;
      }
      if (f == 0 && first) *first = std::move(im);
      if (f == frames - 1 && last) *last = std::move(im);
    }
    std::string passes;
    for (Pass p : view.passes) passes += std::string(passes.empty() ? "" : " + ") + passName(p);
    std::printf("ANYmal C 640x480 %s (color at %d samples): %.4f s per frame, %.4f s of CPU\n", passes.c_str(),
                view.samples ? view.samples : options.samples, wall / (frames - 1), cpu / (frames - 1));
  };
  ViewImages first, last;
  run(v, &first, &last);
  // Where the time goes (printed for the report, not asserted).
  View oneSample = v;
  oneSample.samples = 1;
  run(oneSample, nullptr, nullptr);
  for (auto passes : {std::vector<Pass>{Pass::Color}, std::vector<Pass>{Pass::Depth, Pass::Segmentation}}) {
    View one = v;
    one.passes = passes;
    run(one, nullptr, nullptr);
  }
  std::printf("upload (create): %.3f s\n", r->timings().uploadSeconds);
  save("anymal_rgb.png", encodePng(first.color));
  save("anymal_seg.png", encodePng(first.segmentation));
  save("anymal_depth.png", encodeDepthPng16(first.depth, 640, 480));
  save("anymal_last_seg.png", encodePng(last.segmentation));
  Image depthView = first.color;  // depth as gray for the eye: 1 m white, 6 m black, no return blue
  for (std::size_t i = 0; i < first.depth.size(); ++i) {
    float d = first.depth[i];
    auto g = std::uint8_t(std::isfinite(d) ? std::clamp(255.0 * (6.0 - d) / 5.0, 0.0, 255.0) : 0);
    std::uint8_t* px = &depthView.rgba[4 * i];
    px[0] = px[1] = g;
    px[2] = std::isfinite(d) ? g : 160;
  }
  save("anymal_depth_view.png", encodePng(depthView));
  save("anymal_legend.json", segmentationLegendJson(scene));

  // Segments: the ground (floor) and the robot (robot); every pixel is one
  // of them or the black background, and depth is finite exactly where a
  // segment is.
  ASSERT_EQ(scene.segments.size(), 2u);
  int robotPixels = 0, groundPixels = 0;
  double sumX = 0;
  for (int y = 0; y < 480; ++y)
    for (int x = 0; x < 640; ++x) {
      const std::uint8_t* s = first.segmentation.pixel(x, y);
      bool isRobot = std::equal(s, s + 3, scene.segments[1].rgb),
           isGround = std::equal(s, s + 3, scene.segments[0].rgb);
      ASSERT_TRUE(isRobot || isGround || black(first.segmentation, x, y)) << x << "," << y;
      robotPixels += isRobot;
      groundPixels += isGround;
      if (isRobot) sumX += x;
      ASSERT_EQ(std::isfinite(first.depth[std::size_t(y) * 640 + x]), !black(first.segmentation, x, y));
    }
  EXPECT_GT(robotPixels, 20000);
  EXPECT_GT(groundPixels, 50000);
  // Moved: the robot's pixels are further left in the last frame.
  double lastX = 0;
  int lastN = 0;
  for (int y = 0; y < 480; ++y)
    for (int x = 0; x < 640; ++x)
      if (std::equal(last.segmentation.pixel(x, y), last.segmentation.pixel(x, y) + 3, scene.segments[1].rgb)) {
        lastX += x;
        ++lastN;
      }
  ASSERT_GT(lastN, 10000);
  EXPECT_LT(lastX / lastN, sumX / robotPixels - 20);  // -y is to the left here (the view's right is +x+y)

  // A sensor view sees the robot and the ground: both are world objects.
  // (The scene is still at the last frame's pose.)
  v.sensor = true;
  ViewImages sensor;
  ASSERT_TRUE(r->render(v, sensor, diags));
  EXPECT_EQ(sensor.segmentation.rgba, last.segmentation.rgba);
}
