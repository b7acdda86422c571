// Image-based light and reflection probes (gl_reflections.cpp,
// environment_light.cpp): the CPU pieces against closed forms, then pixels
// on the CPU backend: a mirror sphere shows the sky along the reflected
// direction, a rough dielectric keeps its colour, a probe in a red room
// turns a chrome sphere red, box projection moves what it reflects.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "gl_test_context.hpp"
#include "core/loader.hpp"
#include "render/environment_light.hpp"
#include "render/image.hpp"
#include "render/view.hpp"

using namespace rscene;
using namespace rscene::render;

namespace {

// ---- CPU pieces

// Six faces of `size` texels, RGBA, radiance f(direction).
template <typename F>
std::vector<float> cubeOf(int size, F f) {
  std::vector<float> rgba;
  for (int face = 0; face < 6; ++face)
    for (int row = 0; row < size; ++row)
      for (int col = 0; col < size; ++col) {
        Eigen::Vector3f d =
            cubeFaceDirection(face, (col + 0.5f) / size * 2 - 1, (row + 0.5f) / size * 2 - 1).normalized();
        Eigen::Vector3f c = f(d);
        rgba.insert(rgba.end(), {c.x(), c.y(), c.z(), 1.0f});
      }
  return rgba;
}

}  // namespace

TEST(EnvironmentLight, FaceCentresAreTheAxesInGlOrder) {
  const Eigen::Vector3f axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < 6; ++f) EXPECT_TRUE(cubeFaceDirection(f, 0, 0).isApprox(axes[f])) << f;
  // GL table 8.19: on +x, s grows towards -z and t towards -y.
  EXPECT_TRUE(cubeFaceDirection(0, 1, 0).isApprox(Eigen::Vector3f(1, 0, -1)));
  EXPECT_TRUE(cubeFaceDirection(0, 0, 1).isApprox(Eigen::Vector3f(1, -1, 0)));
  // On +z, s grows towards +x and t towards -y.
  EXPECT_TRUE(cubeFaceDirection(4, 1, 0).isApprox(Eigen::Vector3f(1, 0, 1)));
  EXPECT_TRUE(cubeFaceDirection(4, 0, 1).isApprox(Eigen::Vector3f(0, -1, 1)));
}

TEST(EnvironmentLight, UniformRadianceGivesItsOwnValueForEveryNormal) {
  IrradianceSh sh = irradianceFromCube(cubeOf(16, [](const Eigen::Vector3f&) { return Eigen::Vector3f(0.5f, 1, 2); }), 16);
  for (Eigen::Vector3f n : {Eigen::Vector3f(0, 0, 1), Eigen::Vector3f(1, 0, 0), Eigen::Vector3f(0, -0.6f, -0.8f)}) {
    Eigen::Vector3f e = sh(n);
    EXPECT_NEAR(e.x(), 0.5, 0.005);
    EXPECT_NEAR(e.y(), 1.0, 0.01);
    EXPECT_NEAR(e.z(), 2.0, 0.02);
  }
}

TEST(EnvironmentLight, CosineSkyIsTwoThirdsUpAndAboutNothingDown) {
  // Radiance max(z, 0): irradiance / pi at n = up is the integral of
  // cos^2 over the hemisphere / pi = 2/3; at n = down it is 0 (order-2
  // harmonics ring a little).
  IrradianceSh sh = irradianceFromCube(
      cubeOf(32, [](const Eigen::Vector3f& d) { return Eigen::Vector3f::Constant(std::max(d.z(), 0.0f)); }), 32);
  EXPECT_NEAR(sh(Eigen::Vector3f(0, 0, 1)).x(), 2.0 / 3, 0.03);
  EXPECT_LT(sh(Eigen::Vector3f(0, 0, -1)).x(), 0.05);
  // Sideways: the quarter sphere x, z > 0 of x z, (4/3)(1/2), over pi.
  EXPECT_NEAR(sh(Eigen::Vector3f(1, 0, 0)).x(), 2 / (3 * M_PI), 0.01);
}

TEST(EnvironmentLight, SplitSumTableHasTheKnownShape) {
  const int n = 32;
  std::vector<float> lut = splitSumLut(n, 256);
  ASSERT_EQ(lut.size(), std::size_t(n) * n * 2);
  auto at = [&](int i, int j) { return Eigen::Vector2f(lut[2 * (j * n + i)], lut[2 * (j * n + i) + 1]); };
  for (float v : lut) {
    EXPECT_GE(v, 0.0f);
    EXPECT_LE(v, 1.0f);
  }
  // Smooth and facing: a mirror, A ~ 1, B ~ 0.
  EXPECT_GT(at(n - 1, 0).x(), 0.95f);
  EXPECT_LT(at(n - 1, 0).y(), 0.02f);
  // Grazing adds Fresnel bias; rough loses energy to masking.
  EXPECT_GT(at(2, 0).y(), at(n - 1, 0).y() + 0.1f);
  EXPECT_LT((at(n - 1, n - 1).x() + at(n - 1, n - 1).y()), 0.9f);
  for (int j = 0; j < n; ++j) EXPECT_LE(at(n / 2, j).x() + at(n / 2, j).y(), 1.01f);
  // The renderer's table is the same function at its own size.
  EXPECT_EQ(brdfLut().size(), std::size_t(kBrdfLutSize) * kBrdfLutSize * 2);
}

TEST(EnvironmentLight, ShrinkEquirectAveragesBlocks) {
  FloatImage im;
  im.width = 8;
  im.height = 4;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) im.rgb.insert(im.rgb.end(), {float(x), float(y), 1.0f});
  FloatImage small = shrinkEquirect(im, 2);  // factor 4: 2 x 1
  ASSERT_EQ(small.width, 2);
  ASSERT_EQ(small.height, 1);
  EXPECT_FLOAT_EQ(small.rgb[0], 1.5f);  // mean of x 0..3
  EXPECT_FLOAT_EQ(small.rgb[1], 1.5f);  // mean of y 0..3
  EXPECT_FLOAT_EQ(small.rgb[3], 5.5f);  // mean of x 4..7
  EXPECT_EQ(shrinkEquirect(im, 8).width, 8);  // already small enough: unchanged
}

// ---- pixels

namespace {

const char* kSkyHeader =
    "raisim_engine_scene 1\n"
    "environment 0.08 0.10 0.13 0.2 0.2 0.2 0 true true 10 - backgroundMode=rayrai_sky pbrEnvironmentIntensity=%g\n"
    "weather true preset=clear quality=balanced timeOfDay=9\n"
    "material chrome 1 1 1 1 1 0.05 0 0 0 0 false - - - - - - id=chrome\n"
    "material rough 0.7 0.1 0.1 1 0 1 0 0 0 0 false - - - - - - id=rough\n"
    "material red 0.8 0.05 0.05 1 0 0.7 0 0 0 0 false - - - - - - id=red\n"
    "material green 0.05 0.8 0.05 1 0 0.7 0 0 0 0 false - - - - - - id=green\n"
    "material blue 0.05 0.05 0.8 1 0 0.7 0 0 0 0 false - - - - - - id=blue\n"
    "material white 0.8 0.8 0.8 1 0 0.7 0 0 0 0 false - - - - - - id=white\n";

std::string sphere(const std::string& path, double x, double y, double z, double r, const std::string& material) {
  char b[512];
  std::snprintf(b, sizeof b,
                "object %s sphere %g %g %g 1 0 0 0 %g %g %g 1 1 1 default %s false true false - static true 1 "
                "18446744073709551615\n",
                path.c_str(), x, y, z, r, r, r, material.c_str());
  return b;
}

std::string box(const std::string& path, double x, double y, double z, double sx, double sy, double sz,
                const std::string& material) {
  char b[512];
  std::snprintf(b, sizeof b,
                "object %s box %g %g %g 1 0 0 0 %g %g %g 1 1 1 default %s false true false - static true 1 "
                "18446744073709551615\n",
                path.c_str(), x, y, z, sx, sy, sz, material.c_str());
  return b;
}

// A closed 6 x 6 x 3 m room centred on the origin's vertical, floor at z = 0,
// lit by a lamp under its ceiling; walls +x, -x, +y, -y of the given materials.
std::string room(const std::string& px, const std::string& nx, const std::string& py, const std::string& ny) {
  return "light /World/Lamp 0 0 -1 8 type=point position=0,0,2.6 shadows=false\n" +
         box("/World/Floor", 0, 0, -0.05, 6.2, 6.2, 0.1, "white") + box("/World/Ceiling", 0, 0, 3.05, 6.2, 6.2, 0.1, "white") +
         box("/World/WallPX", 3.05, 0, 1.5, 0.1, 6.2, 3, px) + box("/World/WallNX", -3.05, 0, 1.5, 0.1, 6.2, 3, nx) +
         box("/World/WallPY", 0, 3.05, 1.5, 6.2, 0.1, 3, py) + box("/World/WallNY", 0, -3.05, 1.5, 6.2, 0.1, 3, ny);
}

std::string probe(bool boxProjection) {
  return std::string("reflection_probe /World/Probe -1 0 1.5 5 id=probe strength=1 boxProjection=") +
         (boxProjection ? "true" : "false") + " boxMin=-3,-3,0 boxMax=3,3,3 cubemapSize=64 prefilteredResolution=64\n";
}

struct Built {
  Scene model;
  RenderScene scene;
  Diagnostics diags;
};

std::unique_ptr<Built> build(const std::string& text) {
  auto b = std::make_unique<Built>();
  LoadResult loaded = parse(text);
  EXPECT_TRUE(loaded.ok());
  EXPECT_TRUE(buildRenderScene(loaded.document, SceneOptions{}, b->model, b->scene, b->diags));
  return b;
}

std::string skyScene(double environmentIntensity, const std::string& body) {
  char b[2048];
  std::snprintf(b, sizeof b, kSkyHeader, environmentIntensity);
  return b + body;
}

// A view from `at` along `forward` (unit), +z up unless looking straight up.
View view(const Eigen::Vector3d& at, const Eigen::Vector3d& forward, int w = 320, int h = 240, double vfov = 60) {
  View v;
  v.name = "test";
  v.camera.width = w;
  v.camera.height = h;
  v.camera.verticalFov = vfov;
  v.camera.nearPlane = 0.05;
  v.camera.farPlane = 100;
  v.camera.projection = "perspective";
  v.camera.enabled = true;
  v.camera.world.position = at;
  Eigen::Vector3d up = std::abs(forward.z()) > 0.99 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
  Eigen::Matrix3d rot;
  rot.col(0) = forward.normalized();
  rot.col(1) = up.cross(rot.col(0)).normalized();
  rot.col(2) = rot.col(0).cross(rot.col(1));
  v.camera.world.orientation = Eigen::Quaterniond(rot);
  v.passes = {Pass::Color};
  return v;
}

std::vector<Image> draw(const RenderScene& scene, const std::vector<View>& views, Diagnostics* diagsOut = nullptr) {
  std::vector<Image> out;
  if (!context()) return out;
  Diagnostics d;
  auto r = Renderer::create(scene, RenderOptions{}, d);
  EXPECT_TRUE(r) << (d.empty() ? "" : d.front().message);
  if (!r) return out;
  for (const View& v : views) {
    ViewImages im;
    EXPECT_TRUE(r->render(v, im, d)) << (d.empty() ? "" : d.back().message);
    out.push_back(std::move(im.color));
  }
  if (diagsOut) *diagsOut = d;
  return out;
}

void writeDebug(const Image& im, const std::string& name) {
  // Set RSCENE_TEST_IMAGES=DIR to look at what the tests render.
  if (const char* dir = std::getenv("RSCENE_TEST_IMAGES")) {
    std::string png = encodePng(im);
    if (FILE* f = std::fopen((std::string(dir) + "/" + name + ".png").c_str(), "wb")) {
      std::fwrite(png.data(), 1, png.size(), f);
      std::fclose(f);
    }
  }
}

Eigen::Vector3i rgb(const Image& im, int x, int y) {
  const std::uint8_t* p = im.pixel(x, y);
  return {p[0], p[1], p[2]};
}

// Mean colour of the pixels within radius r of (cx, cy).
Eigen::Vector3d meanIn(const Image& im, int cx, int cy, int r) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (int y = cy - r; y <= cy + r; ++y)
    for (int x = cx - r; x <= cx + r; ++x)
      if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r) {
        sum += rgb(im, x, y).cast<double>();
        ++n;
      }
  return sum / std::max(n, 1);
}

}  // namespace

TEST(Reflections, MirrorSphereShowsTheSkyAlongTheReflectedDirection) {
  // A chrome sphere of radius 1 at 5 m along +x, the camera at its centre's
  // height.  The point whose normal is 45 degrees up, facing the camera,
  // lands on row 120 - 207.8 * 0.707 / 4.293 (fy = 120 / tan 30 degrees).
  auto b = build(skyScene(1, sphere("/World/Chrome", 5, 0, 0, 1, "chrome")));
  Eigen::Vector3d p(5 - std::sqrt(0.5), 0, std::sqrt(0.5)), n(-std::sqrt(0.5), 0, std::sqrt(0.5));
  Eigen::Vector3d v = p.normalized();
  Eigen::Vector3d reflected = v - 2 * v.dot(n) * n;
  int row = int(120 - 120 / std::tan(M_PI / 6) * p.z() / p.x());
  // The second view looks from the origin along that direction: its
  // centre shows the sky there (the sphere is out of its sight).
  std::vector<Image> im = draw(b->scene, {view({0, 0, 0}, {1, 0, 0}), view({0, 0, 0}, reflected)});
  ASSERT_EQ(im.size(), 2u);
  writeDebug(im[0], "mirror_sphere");
  Eigen::Vector3i mirror = rgb(im[0], 160, row), sky = rgb(im[1], 160, 120);
  EXPECT_GT(mirror.z(), mirror.x() + 30) << mirror.transpose();  // blue: the sky, not dark slate
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mirror[c], sky[c], 24) << "channel " << c << ": " << mirror.transpose()
                                                                  << " against the sky " << sky.transpose();
  // The lower half reflects the ground below the horizon: darker, not blue.
  Eigen::Vector3i lower = rgb(im[0], 160, 240 - row);
  EXPECT_LT(lower.sum(), mirror.sum() - 60) << lower.transpose();
  EXPECT_LT(lower.z(), mirror.z() - 40);
}

TEST(Reflections, RoughDielectricKeepsItsColourAndMirrorDoesNot) {
  // The same two spheres with the environment's light on and off: the
  // chrome one goes from dark to the sky's blue, the rough red one stays
  // red and changes far less.
  std::string body = "light /World/Sun 0 1 -0.2 2 type=directional shadows=false\n" +
                     sphere("/World/Chrome", 5, -1.2, 0, 1, "chrome") + sphere("/World/Rough", 5, 1.2, 0, 1, "rough");
  auto on = build(skyScene(1, body)), off = build(skyScene(0, body));
  View v = view({0, 0, 0}, {1, 0, 0});
  std::vector<Image> a = draw(on->scene, {v}), b = draw(off->scene, {v});
  ASSERT_EQ(a.size(), 1u);
  ASSERT_EQ(b.size(), 1u);
  writeDebug(a[0], "rough_and_mirror");
  // Column of a sphere centre at y = -+1.2, 5 m: 160 -+ 207.8 * 1.2 / 5.
  int chromeX = 160 + 50, roughX = 160 - 50, y = 105;  // a little above the centres
  Eigen::Vector3d chromeOn = meanIn(a[0], chromeX, y, 6), chromeOff = meanIn(b[0], chromeX, y, 6);
  Eigen::Vector3d roughOn = meanIn(a[0], roughX, y, 6), roughOff = meanIn(b[0], roughX, y, 6);
  EXPECT_GT(chromeOn.z(), chromeOn.x() + 20) << chromeOn.transpose();
  EXPECT_GT((chromeOn - chromeOff).norm(), 80) << chromeOn.transpose() << " / " << chromeOff.transpose();
  EXPECT_GT(roughOn.x(), 1.8 * roughOn.z()) << roughOn.transpose();  // still red
  EXPECT_GT(roughOn.x(), 1.8 * roughOn.y());
  EXPECT_LT((roughOn - roughOff).norm(), 0.5 * (chromeOn - chromeOff).norm())
      << roughOn.transpose() << " / " << roughOff.transpose();
}

TEST(Reflections, ProbeInARedRoomMakesAChromeSphereRed) {
  std::string body = room("red", "red", "red", "red") + sphere("/World/Chrome", 0.5, 0, 1.5, 0.6, "chrome");
  auto withProbe = build(skyScene(1, body + probe(true))), without = build(skyScene(1, body));
  EXPECT_EQ(withProbe->scene.skipped.count("reflection_probe"), 0u);  // drawn, not skipped
  ASSERT_EQ(withProbe->scene.probes.size(), 1u);
  View v = view({-2.6, 0, 1.5}, {1, 0, 0});
  Diagnostics d;
  std::vector<Image> a = draw(withProbe->scene, {v}, &d), b = draw(without->scene, {v});
  ASSERT_EQ(a.size(), 1u);
  ASSERT_EQ(b.size(), 1u);
  for (const Diagnostic& x : d) EXPECT_NE(x.severity, Severity::Error) << x.message;
  writeDebug(a[0], "probe_red_room");
  writeDebug(b[0], "probe_red_room_without");
  // The sphere's centre reflects the wall behind the camera (the room's
  // -x wall) with the probe, the outdoor sky without.
  Eigen::Vector3d red = meanIn(a[0], 160, 120, 4), sky = meanIn(b[0], 160, 120, 4);
  EXPECT_GT(red.x(), red.y() + 60) << red.transpose();
  EXPECT_GT(red.x(), red.z() + 60) << red.transpose();
  EXPECT_GT(sky.z(), sky.x()) << sky.transpose();
}

TEST(Reflections, BoxProjectionMovesTheReflection) {
  // The wall behind the camera is green, the others red and blue.  The
  // probe stands 1 m nearer that wall than the sphere, so without box
  // projection the wall looks as large as from the probe (+-56 degrees
  // wide) and covers more of the sphere than with it (+-46 degrees, as
  // from the sphere's surface).
  std::string body = room("red", "green", "blue", "blue") + sphere("/World/Chrome", 0.5, 0, 1.5, 0.6, "chrome");
  auto boxed = build(skyScene(1, body + probe(true))), plain = build(skyScene(1, body + probe(false)));
  View v = view({-2.6, 0, 1.5}, {1, 0, 0});
  std::vector<Image> a = draw(boxed->scene, {v}), b = draw(plain->scene, {v});
  ASSERT_EQ(a.size(), 1u);
  ASSERT_EQ(b.size(), 1u);
  writeDebug(a[0], "probe_box_projection");
  writeDebug(b[0], "probe_no_box_projection");
  auto greenPixels = [](const Image& im) {
    int n = 0;
    for (int y = 60; y < 180; ++y)
      for (int x = 100; x < 220; ++x) {
        Eigen::Vector3i c = rgb(im, x, y);
        n += c.y() > c.x() + 60 && c.y() > c.z() + 60;
      }
    return n;
  };
  int withBox = greenPixels(a[0]), without = greenPixels(b[0]);
  EXPECT_GT(withBox, 50);  // the green wall is reflected either way
  EXPECT_GT(without, withBox + withBox / 5) << without << " against " << withBox;
}

// A probe's capture draws its six faces with the shadow maps fitted to the
// view it is captured for: the maps are drawn once, as without the probe
// (refitting them to each face cost more than the capture's drawing).
TEST(Reflections, ProbeCaptureReusesTheViewsShadowMaps) {
  std::string body = "light /World/Sun -0.4 0.3 -1 3 type=directional shadows=true\n" +
                     box("/World/Floor", 0, 0, -0.05, 6.2, 6.2, 0.1, "white") +
                     sphere("/World/Chrome", 0.5, 0, 1.5, 0.6, "chrome");
  auto withProbe = build(skyScene(1, body + probe(false))), without = build(skyScene(1, body));
  if (!context()) GTEST_SKIP() << "no EGL context";
  View v = view({-2.6, 0, 1.5}, {1, 0, 0});
  std::uint64_t drawn[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    Diagnostics d;
    auto r = Renderer::create(k ? withProbe->scene : without->scene, RenderOptions{}, d);
    ASSERT_TRUE(r) << (d.empty() ? "" : d.front().message);
    ViewImages im;
    ASSERT_TRUE(r->render(v, im, d)) << (d.empty() ? "" : d.back().message);
    drawn[k] = r->timings().shadowMapsDrawn;
  }
  EXPECT_GT(drawn[0], 0u);
  EXPECT_EQ(drawn[1], drawn[0]);
}

// A probe is prefiltered at most at its captured size: a 64-texel capture
// asked to prefilter at 256 draws as one asked at 64 (the extra texels
// would only upsample it, at several times the GGX samples).
TEST(Reflections, PrefilterStopsAtTheCapturedSize) {
  std::string body = room("red", "green", "blue", "white") + sphere("/World/Chrome", 0.5, 0, 1.5, 0.6, "chrome");
  auto atProbeSize = build(skyScene(1, body + probe(false)));
  std::string larger = probe(false);
  larger.replace(larger.find("prefilteredResolution=64"), 24, "prefilteredResolution=256");
  auto asked256 = build(skyScene(1, body + larger));
  ASSERT_EQ(asked256->scene.probes.size(), 1u);
  EXPECT_EQ(asked256->scene.probes[0].prefilteredResolution, 256);
  View v = view({-2.6, 0, 1.5}, {1, 0, 0});
  std::vector<Image> a = draw(atProbeSize->scene, {v}), b = draw(asked256->scene, {v});
  if (a.empty()) GTEST_SKIP() << "no EGL context";
  ASSERT_EQ(b.size(), 1u);
  EXPECT_EQ(a[0].rgba, b[0].rgba);
}
