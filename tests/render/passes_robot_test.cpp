// The passes on a real robot (ANYmal C from ../shared, skipped without
// it): RGB, depth and segmentation at 640x480 agree with each other, a
// sensor view still sees the robot (a world object), and moving the robot
// with updatePoses() moves it in the images.  The time per frame is
// bench/render/passes_robot.cpp's, on the same scene (anymal_passes.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "anymal_passes.hpp"
#include "gl_test_context.hpp"
#include "render/gl_context.hpp"
#include "render/view_output.hpp"

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

bool black(const Image& im, int x, int y) {
  const std::uint8_t* p = im.pixel(x, y);
  return p[0] == 0 && p[1] == 0 && p[2] == 0;
}

}  // namespace

TEST(PassesRobot, AnymalRgbDepthSegmentationAgreeAndMove) {
  if (!std::filesystem::exists(test::anymalUrdf())) GTEST_SKIP() << "no ../shared corpus";
  ASSERT_TRUE(context());
  Diagnostics diags;
  std::unique_ptr<test::AnymalScene> s = test::makeAnymalScene(diags);
  ASSERT_TRUE(s) << (diags.empty() ? std::string("the scene does not parse") : diags.back().message);
  ASSERT_EQ(s->rest.robotLinks.size(), 1u);
  RenderScene& scene = s->scene;
  View v = test::anymalView();

  // The first and the last of five frames: the robot 0.3 m apart.
  const int frames = 5;
  ViewImages first, last;
  for (int f : {0, frames - 1}) {
    test::poseFrame(*s, f, frames);
    ASSERT_TRUE(s->renderer->render(v, f == 0 ? first : last, diags)) << diags.back().message;
  }
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
  ASSERT_TRUE(s->renderer->render(v, sensor, diags));
  EXPECT_EQ(sensor.segmentation.rgba, last.segmentation.rgba);
}
