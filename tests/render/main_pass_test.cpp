// The lit pass's strategy (main_pass.hpp) and occlusion culling
// (occlusion.hpp): the estimates and the buffer without GL, then on the CPU
// backend that a deep scene drawn with jittered passes and culled
// instances looks like the shallow scene of what is visible, drawn with
// MSAA.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "gl_test_context.hpp"
#include "core/loader.hpp"
#include "render/camera.hpp"
#include "render/main_pass.hpp"
#include "render/occlusion.hpp"
#include "render/view.hpp"

using namespace rscene;
using namespace rscene::render;
using namespace rscene::render::detail;

namespace {

// A camera at the origin looking along +x, 90 degrees vertically, 160x120.
Camera lookingAlongX(int w = 160, int h = 120) {
  Camera c;
  c.width = w;
  c.height = h;
  c.verticalFov = 90;
  c.nearPlane = 0.05;
  c.farPlane = 100;
  c.projection = "perspective";
  c.enabled = true;
  return c;
}

Eigen::Matrix4d viewProjOf(const Camera& c) { return projectionMatrix(c, double(c.width) / c.height) * viewMatrix(c); }

Eigen::AlignedBox3d cube(double x, double y, double z, double side) {
  Eigen::Vector3d h(side / 2, side / 2, side / 2), c(x, y, z);
  return {c - h, c + h};
}

Eigen::Matrix4d boxModel(double x, double y, double z, double sx, double sy, double sz) {
  Eigen::Affine3d a = Eigen::Translation3d(x, y, z) * Eigen::Scaling(sx, sy, sz);
  return a.matrix();
}

}  // namespace

TEST(MainPass, DepthComplexityCountsLayers) {
  Eigen::Matrix4d vp = viewProjOf(lookingAlongX());
  DepthComplexity one(vp);
  one.add(cube(5, 0, 0, 40));  // fills the view
  EXPECT_NEAR(one.value(), 1.0, 1e-9);
  DepthComplexity three(vp);
  for (double x : {5.0, 7.0, 9.0}) three.add(Eigen::AlignedBox3d(Eigen::Vector3d(x, -50, -50), Eigen::Vector3d(x + 1, 50, 50)));
  EXPECT_NEAR(three.value(), 3.0, 1e-9);
  // 10 m away the view is 20 m high and 26.67 m wide: a 10 m square from
  // the centre up and to the left covers 0.75 x 1 of NDC's 2 x 2.
  DepthComplexity part(vp);
  part.add(Eigen::AlignedBox3d(Eigen::Vector3d(10, 0, 0), Eigen::Vector3d(10, 10, 10)));
  EXPECT_NEAR(part.value(), 0.75 / 4, 1e-9);
  DepthComplexity around(vp);
  around.add(cube(0, 0, 0, 2), 2);  // holds the eye: may cover everything, twice
  EXPECT_NEAR(around.value(), 2.0, 1e-9);
}

TEST(MainPass, JitterOnlyForDeepViewsAndSeveralSamples) {
  EXPECT_FALSE(preferJitteredPasses(100, 1));  // one sample: nothing to jitter
  EXPECT_FALSE(preferJitteredPasses(2, 4));    // the 5000-object yard's depth
  EXPECT_TRUE(preferJitteredPasses(17, 4));    // the warehouse's, after culling
}

TEST(MainPass, JitterMovesThePixelCentreToTheSample) {
  Camera c = lookingAlongX(100, 50);
  Eigen::Matrix4d vp = viewProjOf(c);
  Eigen::Vector4d p = vp * Eigen::Vector4d(10, 1, 2, 1);
  Eigen::Matrix4d j = jittered(vp, Eigen::Vector2f(0.875f, 0.125f), 100, 50);
  Eigen::Vector4d q = j * Eigen::Vector4d(10, 1, 2, 1);
  // In pixels: the scene moves by (0.5 - 0.875, 0.5 - 0.125).
  EXPECT_NEAR((q.x() / q.w() - p.x() / p.w()) * 50, -0.375, 1e-9);
  EXPECT_NEAR((q.y() / q.w() - p.y() / p.w()) * 25, 0.375, 1e-9);
  EXPECT_NEAR(q.z() / q.w(), p.z() / p.w(), 1e-12);
}

TEST(MainPass, StandardPatternsAreInsideThePixelAndDistinct) {
  for (int n : {2, 4, 8, 16, 3}) {
    std::vector<Eigen::Vector2f> s = standardSamplePattern(n);
    ASSERT_EQ(int(s.size()), n);
    for (std::size_t i = 0; i < s.size(); ++i) {
      EXPECT_GE(s[i].x(), 0.f);  // 16 samples: one on the pixel's left edge
      EXPECT_LT(s[i].x(), 1.f);
      EXPECT_GE(s[i].y(), 0.f);
      EXPECT_LT(s[i].y(), 1.f);
      for (std::size_t k = 0; k < i; ++k) EXPECT_GT((s[i] - s[k]).norm(), 0.01f) << n;
    }
  }
  EXPECT_NEAR(standardSamplePattern(4)[0].x(), 0.375f, 1e-6);
  EXPECT_NEAR(standardSamplePattern(4)[0].y(), 0.125f, 1e-6);
}

TEST(MainPass, NearnessOrdersFrontToBack) {
  Eigen::Vector3d eye(0, 0, 0), fwd(1, 0, 0);
  EXPECT_LT(nearness(cube(3, 0, 0, 1), eye, fwd, false), nearness(cube(6, 0, 0, 1), eye, fwd, false));
  EXPECT_EQ(nearness(cube(0, 0, 0, 1), eye, fwd, false), 0);  // holds the eye
  EXPECT_LT(nearness(cube(3, 9, 0, 1), eye, fwd, true), nearness(cube(6, 0, 0, 1), eye, fwd, true));
}

TEST(Occlusion, AWallHidesWhatIsWhollyBehindIt) {
  Camera c = lookingAlongX();
  OcclusionBuffer ob(viewProjOf(c), c.width, c.height);
  EXPECT_FALSE(ob.hidden(cube(10, 0, 0, 1)));  // nothing added yet
  ob.addBox(boxModel(5, 0, 0, 0.2, 20, 20));   // a wall filling the view at x = 4.9
  EXPECT_TRUE(ob.hidden(cube(10, 0, 0, 1)));
  EXPECT_TRUE(ob.hidden(cube(8, 2, -1, 3)));
  EXPECT_FALSE(ob.hidden(cube(3, 0, 0, 1)));    // in front of it
  EXPECT_FALSE(ob.hidden(cube(5.5, 0, 0, 1.2)));  // through it: its near face is in front
  EXPECT_TRUE(ob.hidden(cube(10, 0, 0, 9.9)));    // from inside the wall backwards
  EXPECT_FALSE(ob.hidden(cube(10, 0, 0, 11)));    // reaches in front of it
}

TEST(Occlusion, OnlyWhatTheOccluderCoversEntirely) {
  Camera c = lookingAlongX();
  OcclusionBuffer ob(viewProjOf(c), c.width, c.height);
  ob.addBox(boxModel(5, 0, 0, 0.2, 2, 2));  // a 2 m panel: covers the middle of the view
  EXPECT_TRUE(ob.hidden(cube(10, 0, 0, 1)));
  EXPECT_TRUE(ob.hidden(cube(10, 0, 0, 3)));    // larger, but farther: smaller on the screen
  EXPECT_FALSE(ob.hidden(cube(10, 0, 0, 4.5)));  // larger on the screen
  EXPECT_FALSE(ob.hidden(cube(10, 2.4, 0, 1)));  // peeks out beside it
}

TEST(Occlusion, TouchingSurfacesAreNotHidden) {
  Camera c = lookingAlongX();
  OcclusionBuffer ob(viewProjOf(c), c.width, c.height);
  ob.addBox(boxModel(5, 0, 0, 2, 20, 20));  // near face at x = 4
  // A box whose near face is the wall's near face: the depth test decides.
  EXPECT_FALSE(ob.hidden(Eigen::AlignedBox3d(Eigen::Vector3d(4, -1, -1), Eigen::Vector3d(5, 1, 1))));
  EXPECT_TRUE(ob.hidden(Eigen::AlignedBox3d(Eigen::Vector3d(4.01, -1, -1), Eigen::Vector3d(5, 1, 1))));
}

TEST(Occlusion, ClippedOccludersHideNothing) {
  Camera c = lookingAlongX();
  OcclusionBuffer ob(viewProjOf(c), c.width, c.height);
  ob.addBox(boxModel(0, 0, 0, 10, 10, 10));      // holds the eye: cut by the near plane
  ob.addBox(boxModel(100, 0, 0, 10, 500, 500));  // across the far plane (100 m)
  EXPECT_FALSE(ob.hidden(cube(3, 0, 0, 1)));
  EXPECT_FALSE(ob.hidden(cube(98, 0, 0, 1)));
}

TEST(Occlusion, ARotatedBoxOccludesByItsFacesNotItsBounds) {
  Camera c = lookingAlongX();
  OcclusionBuffer ob(viewProjOf(c), c.width, c.height);
  // A 4 m square plate turned 45 degrees about x: a diamond on the screen.
  Eigen::Affine3d a = Eigen::Translation3d(5, 0, 0) * Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitX()) *
                      Eigen::Scaling(0.1, 4.0, 4.0);
  ob.addBox(a.matrix());
  EXPECT_TRUE(ob.hidden(cube(10, 0, 0, 1)));       // behind its middle
  EXPECT_FALSE(ob.hidden(cube(10, 3.2, 3.2, 1)));  // behind a corner of its bounds, beside the diamond
}

namespace {

const char* kDeepHeader =
    "raisim_engine_scene 1\n"
    "environment 0 0 0 0.2 0.2 0.2 0 false true 10 - backgroundMode=plain_color colorMode=linear\n"
    "material red 0.8 0.1 0.1 1 0 0.6 0 0 0 0 false - - - - - - id=red\n"
    "material blue 0.1 0.2 0.8 1 0 0.6 0 0 0 0 false - - - - - - id=blue\n"
    "material glass 0.2 0.9 0.4 0.4 0 0.3 0 0 0 0 false - - - - - - id=glass\n"
    "light /World/Sun 1 0.4 -0.4 3 type=directional shadows=false\n";

// An object of `shape` centred at (x, y, z), of size s or sx x sy x sz,
// radius s / 2 (a sphere's radius scales with its size: give it 1 1 1).
std::string object(const std::string& path, const std::string& shape, double x, double y, double z, double s,
                   const std::string& material, double sx = 0, double sy = 0, double sz = 0) {
  char b[512];
  std::snprintf(b, sizeof b,
                "object %s %s %g %g %g 1 0 0 0 %g %g %g %g 1 1 default %s false true false - static true 1 "
                "18446744073709551615\n",
                path.c_str(), shape.c_str(), x, y, z, sx > 0 ? sx : s, sy > 0 ? sy : s, sz > 0 ? sz : s, s / 2,
                material.c_str());
  return b;
}

struct Drawn {
  Image color;
  std::vector<float> depth;
  RenderTimings timings;
};

Drawn draw(const std::string& body, int samples = 4, bool depth = false) {
  Drawn out;
  if (!context()) return out;
  LoadResult loaded = parse(std::string(kDeepHeader) + body);
  EXPECT_TRUE(loaded.ok());
  Scene model;
  RenderScene scene;
  Diagnostics d;
  EXPECT_TRUE(buildRenderScene(loaded.document, SceneOptions{}, model, scene, d));
  View v;
  v.name = "test";
  v.camera = lookingAlongX(200, 150);
  v.camera.verticalFov = 50;
  v.passes = {Pass::Color};
  if (depth) v.passes.push_back(Pass::Depth);
  v.samples = samples;
  RenderOptions o;
  auto r = Renderer::create(scene, o, d);
  EXPECT_TRUE(r) << (d.empty() ? "" : d.front().message);
  if (!r) return out;
  ViewImages im;
  EXPECT_TRUE(r->render(v, im, d)) << (d.empty() ? "" : d.front().message);
  out.color = std::move(im.color);
  out.depth = std::move(im.depth);
  out.timings = r->timings();
  return out;
}

// Fraction of pixels whose channels differ by more than 16 / 255.
double differing(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height || a.rgba.empty()) return 1;
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.rgba.size(); i += 4)
    for (int k = 0; k < 3; ++k)
      if (std::abs(int(a.rgba[i + k]) - int(b.rgba[i + k])) > 16) {
        ++n;
        break;
      }
  return double(n) / double(a.rgba.size() / 4);
}

}  // namespace

// Eighty large spheres in a row down the view (each hidden by the one in
// front but the first; spheres occlude nothing in the estimate, so the
// view is deep and drawn with jittered passes) look like the first alone,
// which is shallow and drawn with MSAA: the same coverage, the same edges.
TEST(MainPass, JitteredPassesMatchMsaa) {
  // Along the ray from the eye through (6, 3, 1): the first sphere's
  // outline crosses the view; each next one is farther on the same ray,
  // as large, so smaller on the screen and inside the first's disc.
  Eigen::Vector3d ray = Eigen::Vector3d(6, 3, 1).normalized();
  auto sphere = [&](int i) {
    Eigen::Vector3d c = ray * (6.7 + 0.25 * i);
    return object("/World/S" + std::to_string(i), "sphere", c.x(), c.y(), c.z(), 6, "red", 1, 1, 1);  // radius 3
  };
  std::string deep, shallow = sphere(0);
  for (int i = 0; i < 80; ++i) deep += sphere(i);
  Drawn s = draw(shallow), d = draw(deep), aliased = draw(deep, 1);
  std::printf("jittered against msaa %.5f, against one sample %.5f\n", differing(d.color, s.color),
              differing(d.color, aliased.color));
  ASSERT_FALSE(d.color.rgba.empty());
  EXPECT_EQ(d.timings.jitteredViews, 1u);
  EXPECT_EQ(s.timings.jitteredViews, 0u);
  EXPECT_EQ(aliased.timings.jitteredViews, 0u);  // one sample: nothing to jitter
  EXPECT_LT(differing(d.color, s.color), 0.002);
  // Anti-aliased: the outline differs from the one-sample drawing.
  EXPECT_GT(differing(d.color, aliased.color), 0.002);
  // The 79 spheres behind the first are seen by no sample: not drawn.
  EXPECT_EQ(d.timings.occludedInstances, 79u);
}

// A blended pane in front, over the deep row and over the shallow one:
// blended once per sample in both (the passes after the first keep the
// stencil for the blended layers too), and its edges are anti-aliased.
TEST(MainPass, BlendedLayersInJitteredPassesMatchMsaa) {
  Eigen::Vector3d ray = Eigen::Vector3d(6, 3, 1).normalized();
  std::string deep, shallow;
  for (int i = 0; i < 80; ++i) {
    Eigen::Vector3d c = ray * (6.7 + 0.25 * i);
    std::string o = object("/World/S" + std::to_string(i), "sphere", c.x(), c.y(), c.z(), 6, "red", 1, 1, 1);
    deep += o;
    if (i == 0) shallow = o;
  }
  std::string pane = object("/World/Pane", "box", 3, -0.3, -0.2, 1, "glass", 0.05, 1.5, 1.2);
  Drawn d = draw(deep + pane), s = draw(shallow + pane);
  EXPECT_EQ(d.timings.jitteredViews, 1u);
  EXPECT_EQ(s.timings.jitteredViews, 0u);
  EXPECT_LT(differing(d.color, s.color), 0.002);
  EXPECT_GT(differing(d.color, draw(deep).color), 0.02);  // the pane shows
}

// The data pass of a jittered view draws what it selects itself: the same
// depth as the shallow scene's.
TEST(MainPass, DepthAfterJitteredPassesIsExact) {
  Eigen::Vector3d ray = Eigen::Vector3d(6, 3, 1).normalized();
  std::string deep, shallow;
  for (int i = 0; i < 80; ++i) {
    Eigen::Vector3d c = ray * (6.7 + 0.25 * i);
    std::string o = object("/World/S" + std::to_string(i), "sphere", c.x(), c.y(), c.z(), 6, "red", 1, 1, 1);
    deep += o;
    if (i == 0) shallow = o;
  }
  Drawn d = draw(deep, 4, true), s = draw(shallow, 4, true);
  EXPECT_EQ(d.timings.jitteredViews, 1u);
  ASSERT_EQ(d.depth.size(), s.depth.size());
  ASSERT_FALSE(d.depth.empty());
  std::size_t same = 0;
  for (std::size_t i = 0; i < d.depth.size(); ++i)
    same += (std::isnan(d.depth[i]) && std::isnan(s.depth[i])) || d.depth[i] == s.depth[i];
  EXPECT_EQ(same, d.depth.size());
}

// Boxes behind a wall are left out and the image is that of the wall and
// what is in front of it.
TEST(Occlusion, CulledBoxesLeaveTheImageAsItWas) {
  std::string front =
      object("/World/Wall", "box", 8, 0, 0, 1, "blue", 0.5, 12, 12) + object("/World/Near", "box", 4, 0.5, 0.2, 1, "red");
  std::string hidden;
  for (int i = 0; i < 30; ++i)
    hidden += object("/World/H" + std::to_string(i), "box", 16 + i % 3, -2 + i % 5, -1 + i % 4, 1.5, "red");
  Drawn with = draw(front + hidden), without = draw(front);
  ASSERT_FALSE(with.color.rgba.empty());
  EXPECT_EQ(with.timings.occludedInstances, 30u);
  EXPECT_EQ(without.timings.occludedInstances, 0u);
  EXPECT_EQ(differing(with.color, without.color), 0.0);
}
