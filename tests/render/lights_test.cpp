// Lights and shadows: the CPU side (light reach, light boxes, the tile
// grid, shadow fitting, atlas packing) and pixel tests on the CPU backend
// (llvmpipe): 32 point lights light 32 patches, spot and point lights cast
// shadows where the occluder projects from the light, shadowStrength=0
// casts none, shadowedLightBudget keeps the strongest caster.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "gl_test_context.hpp"
#include "core/loader.hpp"
#include "render/camera.hpp"
#include "render/light_grid.hpp"
#include "render/render_scene.hpp"
#include "render/renderer.hpp"
#include "render/shadow_fit.hpp"

using namespace rscene;
using namespace rscene::render;

namespace {

constexpr double kPi = 3.14159265358979323846;

RenderLight pointLight(Eigen::Vector3d p, float intensity, Eigen::Vector3f att) {
  RenderLight l;
  l.type = LightType::Point;
  l.position = p;
  l.color = Eigen::Vector3f::Constant(intensity);
  l.attenuation = att;
  return l;
}

// ---- CPU side

TEST(LightReach, IsWhereTheAttenuatedLightFallsBelowTheCutoff) {
  RenderLight l = pointLight({0, 0, 0}, 2, {1, 0.5f, 0.25f});
  float r = lightReach(l);
  double at = 2 / (1 + 0.5 * r + 0.25 * r * r);
  EXPECT_NEAR(at, kLightCutoff, 1e-5);
  l.range = 3;
  EXPECT_FLOAT_EQ(lightReach(l), 3);  // the record's range when shorter
  l.range = 0;
  l.attenuation = {0, 0, 0};
  EXPECT_EQ(lightReach(l), kMaxLightReach);  // no attenuation: everywhere
  l.color = Eigen::Vector3f::Zero();
  EXPECT_EQ(lightReach(l), 0);  // no light at all
  RenderLight sun;
  EXPECT_EQ(lightReach(sun), kMaxLightReach);
}

TEST(LightBounds, SpotBoxHoldsEveryPointOfItsConeAndNoMore) {
  RenderLight l;
  l.type = LightType::Spot;
  l.position = {1, 2, 3};
  l.direction = Eigen::Vector3d(0.3, -0.4, -1).normalized();
  l.coneDegrees = 35;
  Eigen::AlignedBox3d b = lightBounds(l, 4);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int inside = 0;
  for (int i = 0; i < 20000; ++i) {
    Eigen::Vector3d d(u(rng), u(rng), u(rng));
    if (d.norm() > 1 || d.norm() < 1e-6) continue;
    if (d.normalized().dot(l.direction) < std::cos(35 * kPi / 180)) continue;
    Eigen::Vector3d p = l.position + d * 4;
    ++inside;
    EXPECT_TRUE(((b.min().array() - 1e-9) <= p.array()).all() && (p.array() <= (b.max().array() + 1e-9)).all()) << p.transpose();
  }
  EXPECT_GT(inside, 100);
  // Tighter than the sphere of the reach.
  EXPECT_LT(b.volume(), 0.5 * 8 * 4 * 4 * 4);
}

TEST(LightGrid, ListsALightOnlyInTheTilesItsBoxCovers) {
  Camera cam;  // at the origin looking along +x
  cam.world.position = {0, 0, 0};
  cam.verticalFov = 60;
  cam.nearPlane = 0.05;
  cam.farPlane = 100;
  Eigen::Matrix4d vp = projectionMatrix(cam, 1.0) * viewMatrix(cam);
  // A small light straight ahead: the centre tiles; one behind the eye
  // whose box holds the eye: every tile; one far to the side: none.
  std::vector<Eigen::AlignedBox3d> boxes = {
      Eigen::AlignedBox3d(Eigen::Vector3d(9.5, -0.5, -0.5), Eigen::Vector3d(10.5, 0.5, 0.5)),
      Eigen::AlignedBox3d(Eigen::Vector3d(-2, -2, -2), Eigen::Vector3d(1, 2, 2)),
      Eigen::AlignedBox3d(Eigen::Vector3d(0, 50, 0), Eigen::Vector3d(1, 51, 1))};
  LightGrid g;
  buildLightGrid(boxes, {7, 8, 9}, vp, 256, 256, 16, g);
  ASSERT_EQ(g.tilesX, 16);
  ASSERT_EQ(g.tilesY, 16);
  EXPECT_EQ(g.count(8, 8), 2);  // the small light and the one around the eye
  EXPECT_EQ(g.count(0, 0), 1);
  EXPECT_EQ(g.count(15, 15), 1);
  int withSmall = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      std::int32_t off = g.data[std::size_t(3 * (y * 16 + x))];
      for (int k = 0; k < g.count(x, y); ++k) {
        EXPECT_NE(g.data[std::size_t(off + k)], 9);
        withSmall += g.data[std::size_t(off + k)] == 7;
      }
    }
  // The 1 m box at 10 m spans about 0.1 / tan(30 deg) of the half image: 2 to 4 tiles a side.
  EXPECT_GE(withSmall, 4);
  EXPECT_LE(withSmall, 16);
  // A cap on the lists: refused at 16-pixel tiles (the eye's light alone
  // covers 256 tiles), taken at 64-pixel ones, `g` untouched in between.
  EXPECT_FALSE(buildLightGrid(boxes, {7, 8, 9}, vp, 256, 256, 16, g, 100));
  EXPECT_EQ(g.tilesX, 16);
  EXPECT_TRUE(buildLightGrid(boxes, {7, 8, 9}, vp, 256, 256, 64, g, 100));
  EXPECT_EQ(g.tilesX, 4);
  EXPECT_EQ(g.count(0, 0), 1);
  // Lights from index 1 on cast shadows: the centre tile lists the small
  // light first, as its one unshadowed light.
  ASSERT_TRUE(buildLightGrid(boxes, {7, 8, 9}, vp, 256, 256, 16, g, std::size_t(-1), 1));
  EXPECT_EQ(g.count(8, 8), 2);
  EXPECT_EQ(g.unshadowed(8, 8), 1);
  EXPECT_EQ(g.data[std::size_t(g.data[3 * (8 * 16 + 8)])], 7);
  EXPECT_EQ(g.unshadowed(0, 0), 0);
}

TEST(ShadowFit, DirectionalBoxCoversWhatTheViewSeesNotTheWholeScene) {
  // A 200 m row of casters; the camera sees 10 m of it from close by.
  Eigen::AlignedBox3d casters(Eigen::Vector3d(-100, -1, 0), Eigen::Vector3d(100, 1, 2));
  Camera cam;
  cam.world.position = {0, -8, 3};
  cam.world.orientation = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()) *
                          Eigen::AngleAxisd(0.35, Eigen::Vector3d::UnitY());  // along +y, a little down
  cam.verticalFov = 50;
  cam.nearPlane = 0.05;
  cam.farPlane = 100;
  Eigen::Matrix4d vp = projectionMatrix(cam, 1.0) * viewMatrix(cam);
  Eigen::Vector3d dir = Eigen::Vector3d(-0.3, 0.2, -1).normalized();
  ShadowView fitted = fitDirectionalShadow(dir, vp, casters, 0, 1024, 3);
  ASSERT_FALSE(fitted.empty);
  // texelWorld = box side / resolution: far less than the 200 m row.
  EXPECT_LT(fitted.texelWorld * 1024, 60);
  // A visible caster point and its shadow on the floor map inside the box.
  for (Eigen::Vector3d p : {Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(0.6, -0.4, 0)}) {
    Eigen::Vector4d c = fitted.viewProj * Eigen::Vector4d(p.x(), p.y(), p.z(), 1);
    EXPECT_LT(c.head<3>().cwiseAbs().maxCoeff(), 1.0) << p.transpose();
  }
  // Nothing seen: nothing to draw.
  Camera away = cam;
  away.world.orientation = Eigen::AngleAxisd(-kPi / 2, Eigen::Vector3d::UnitZ());
  away.world.position = {0, -20, 3};
  Eigen::Matrix4d vpAway = projectionMatrix(away, 1.0) * viewMatrix(away);
  EXPECT_TRUE(fitDirectionalShadow(dir, vpAway, casters, 0, 1024, 3).empty);
}

TEST(ShadowFit, CubeFacesCoverEveryDirectionOnce) {
  double scale = cubeFaceScale(256, 3);
  EXPECT_LT(scale, 1.0);
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0, 1);
  Eigen::Vector3d eye(1, 2, 3);
  for (int i = 0; i < 500; ++i) {
    Eigen::Vector3d d(n(rng), n(rng), n(rng));
    Eigen::Vector3d p = eye + d.normalized() * 5;
    int covering = 0;
    for (int f = 0; f < 6; ++f) {
      ShadowView v = cubeFaceShadow(eye, f, 0.1, 20, scale, 256);
      Eigen::Vector4d c = v.viewProj * Eigen::Vector4d(p.x(), p.y(), p.z(), 1);
      // The face of the largest axis holds the point inside its margin.
      Eigen::Vector3d a = d.cwiseAbs();
      int major = a.x() >= a.y() && a.x() >= a.z() ? 0 : a.y() >= a.z() ? 1 : 2;
      int face = 2 * major + (d[major] >= 0 ? 0 : 1);
      if (f == face) {
        EXPECT_GT(c.w(), 0);
        EXPECT_LE(std::abs(c.x() / c.w()), scale + 1e-9);
        EXPECT_LE(std::abs(c.y() / c.w()), scale + 1e-9);
        EXPECT_NEAR(c.w(), std::abs(d.normalized()[major]) * 5, 1e-9);  // depth along the face's axis
        ++covering;
      }
    }
    EXPECT_EQ(covering, 1);
  }
}

TEST(ShadowFit, AtlasPacksMapsWithoutOverlapOrRefuses) {
  std::vector<Eigen::Vector2i> sizes = {{512, 512}, {768, 512}, {256, 256}, {256, 256}, {1024, 1024}}, origins;
  ASSERT_TRUE(packAtlas(sizes, 2048, origins));
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    EXPECT_LE(origins[i].x() + sizes[i].x(), 2048);
    EXPECT_LE(origins[i].y() + sizes[i].y(), 2048);
    for (std::size_t j = 0; j < i; ++j) {
      bool apart = origins[i].x() + sizes[i].x() <= origins[j].x() || origins[j].x() + sizes[j].x() <= origins[i].x() ||
                   origins[i].y() + sizes[i].y() <= origins[j].y() || origins[j].y() + sizes[j].y() <= origins[i].y();
      EXPECT_TRUE(apart) << i << " overlaps " << j;
    }
  }
  EXPECT_FALSE(packAtlas(sizes, 1024, origins));
}

// ---- pixels

struct Shot {
  bool ok = false;
  Image image;
  Diagnostics diags;
  Camera camera;
  // Image pixel of world point p (row 0 at the top).
  Eigen::Vector2i pixel(const Eigen::Vector3d& p) const {
    Eigen::Matrix4d vp = projectionMatrix(camera, double(image.width) / image.height) * viewMatrix(camera);
    Eigen::Vector4d c = vp * Eigen::Vector4d(p.x(), p.y(), p.z(), 1);
    return {int((c.x() / c.w() * 0.5 + 0.5) * image.width), int((0.5 - c.y() / c.w() * 0.5) * image.height)};
  }
  int luminance(const Eigen::Vector3d& p) const {
    Eigen::Vector2i q = pixel(p);
    int s = 0;
    for (int y = -1; y <= 1; ++y)
      for (int x = -1; x <= 1; ++x) {
        const std::uint8_t* c = image.pixel(q.x() + x, q.y() + y);
        s += c[0] + c[1] + c[2];
      }
    return s / 9;
  }
};

// Looking straight down from 12 m at a flat gray floor (a box, no checker).
Shot shoot(const std::string& body, const std::string& env = "") {
  Shot r;
  if (!context()) return r;
  std::string text =
      "raisim_engine_scene 1\n" +
      (env.empty() ? std::string("environment 0 0 0 0 0 0 0 true true 10 - backgroundMode=plain_color colorMode=linear\n")
                   : env) +
      "material gray 0.6 0.6 0.6 1 0 0.9 0 0 0 0 false - - - - - - id=gray\n"
      "camera /World/Cam 0 0 12 0.70710678 0 0.70710678 0 60 0.05 100 240 240 rgb true\n"
      "object /World/Floor box 0 0 -0.05 1 0 0 0 16 16 0.1 1 1 1 default gray false true false - static true 1 "
      "18446744073709551615\n" +
      body;
  LoadResult loaded = parse(text);
  EXPECT_TRUE(loaded.ok());
  RenderScene scene;
  buildRenderScene(loaded.document, SceneOptions{}, scene, r.diags);
  std::string err;
  EXPECT_TRUE(chooseCamera(scene, "", r.camera, &err)) << err;
  RenderOptions o;
  o.width = o.height = 240;
  r.camera.width = r.camera.height = 240;
  r.ok = renderScene(scene, r.camera, o, r.image, r.diags);
  return r;
}

std::string cube(const std::string& path, double x, double y, double z, double side, const std::string& extra = "") {
  return "object " + path + " box " + std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) +
         " 1 0 0 0 " + std::to_string(side) + " " + std::to_string(side) + " " + std::to_string(side) +
         " 1 1 1 default gray false true false - static true 1 18446744073709551615 " + extra + "\n";
}

TEST(LightPixels, ThirtyTwoPointLightsLightThirtyTwoPatches) {
  std::string body;
  std::vector<Eigen::Vector3d> at;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 4; ++j) {
      Eigen::Vector3d p(-5.25 + 1.5 * i, -2.25 + 1.5 * j, 0.4);
      at.push_back(p);
      body += "light /World/L" + std::to_string(i * 4 + j) + " 0 0 -1 4 type=point position=" + std::to_string(p.x()) +
              "," + std::to_string(p.y()) + "," + std::to_string(p.z()) +
              " shadows=false attenuationConstant=1 attenuationLinear=0 attenuationQuadratic=20\n";
    }
  Shot s = shoot(body);
  ASSERT_TRUE(s.ok);
  for (const Diagnostic& d : s.diags) EXPECT_NE(d.code, "RS9004") << d.message;  // no light is dropped
  for (const Eigen::Vector3d& p : at) {
    int under = s.luminance({p.x(), p.y(), 0});
    int between = s.luminance({p.x() + 0.75, p.y() + 0.75, 0});  // the middle of four lights
    EXPECT_GT(under, 60) << p.transpose();
    EXPECT_LT(s.luminance({p.x(), p.y() + (p.y() < 0 ? -3.0 : 3.0), 0}), under / 2);  // outside the grid: dark
    // Gamma-encoded: a ratio of 1.5 here is about 2.5 in linear light.
    EXPECT_GT(2 * under, 3 * between) << p.transpose();
  }
}

// A light 3 m above the floor at the origin; a 1 m cube centred on (1, 0, 0.5).
// The cube's top (z = 1) projects from the light to 1.5 times its offset:
// its shadow on the floor spans x in [1.5, 2.25] beyond the cube.  The
// mirror point on the -x side is lit as much, without the cube.
void expectCubeShadow(const std::string& light, bool shadowed) {
  Shot s = shoot(light + cube("/World/Cube", 1, 0, 0.5, 1));
  ASSERT_TRUE(s.ok);
  int shadow = s.luminance({1.9, 0, 0}), lit = s.luminance({-1.9, 0, 0});
  EXPECT_GT(lit, 60) << light;
  if (shadowed) {
    EXPECT_LT(shadow, lit / 3) << light;
    // Just past the predicted edge it is lit again.
    EXPECT_GT(s.luminance({2.5, 0, 0}), s.luminance({-2.5, 0, 0}) * 3 / 4) << light;
    EXPECT_GT(s.luminance({1.9, 1.0, 0}), s.luminance({-1.9, 1.0, 0}) * 3 / 4) << light;
  } else {
    EXPECT_NEAR(shadow, lit, lit / 10 + 3) << light;
  }
}

TEST(LightPixels, SpotLightShadowFallsWhereTheCubeProjects) {
  expectCubeShadow("light /World/Spot 0 0 -1 8 type=spot position=0,0,3 coneAngle=55 innerConeAngle=50 "
                   "attenuationConstant=1 attenuationLinear=0 attenuationQuadratic=0.3 shadows=true\n",
                   true);
}

TEST(LightPixels, PointLightShadowFallsWhereTheCubeProjects) {
  expectCubeShadow("light /World/Bulb 0 0 -1 8 type=point position=0,0,3 attenuationConstant=1 "
                   "attenuationLinear=0 attenuationQuadratic=0.3 shadows=true\n",
                   true);
}

TEST(LightPixels, WideSpotAndAreaLightsCastThroughCubeMaps) {
  expectCubeShadow("light /World/Wide 0 0 -1 8 type=spot position=0,0,3 coneAngle=80 innerConeAngle=75 "
                   "attenuationConstant=1 attenuationLinear=0 attenuationQuadratic=0.3 shadows=true\n",
                   true);
  expectCubeShadow("light /World/Panel 0 0 -1 8 type=area position=0,0,3 areaSize=0.5,0.5,0 "
                   "attenuationConstant=1 attenuationLinear=0 attenuationQuadratic=0.3 shadows=true\n",
                   true);
}

TEST(LightPixels, ShadowStrengthZeroAndShadowsFalseCastNoShadow) {
  expectCubeShadow("light /World/Spot 0 0 -1 8 type=spot position=0,0,3 coneAngle=55 innerConeAngle=50 "
                   "attenuationConstant=1 attenuationLinear=0 attenuationQuadratic=0.3 shadowStrength=0\n",
                   false);
  expectCubeShadow("light /World/Bulb 0 0 -1 8 type=point position=0,0,3 attenuationConstant=1 "
                   "attenuationLinear=0 attenuationQuadratic=0.3 shadows=false\n",
                   false);
}

TEST(LightPixels, HalfStrengthShadowIsHalfDark) {
  Shot s = shoot("light /World/Spot 0 0 -1 8 type=spot position=0,0,3 coneAngle=55 innerConeAngle=50 "
                 "attenuationConstant=1 attenuationLinear=0 attenuationQuadratic=0.3 shadowStrength=0.5\n" +
                 cube("/World/Cube", 1, 0, 0.5, 1));
  ASSERT_TRUE(s.ok);
  int shadow = s.luminance({1.9, 0, 0}), lit = s.luminance({-1.9, 0, 0});
  EXPECT_GT(shadow, lit / 4);
  EXPECT_LT(shadow, lit * 3 / 4);
}

TEST(LightPixels, EnvironmentShadowsFalseTurnsEveryShadowOff) {
  Shot s = shoot("light /World/Bulb 0 0 -1 8 type=point position=0,0,3 attenuationConstant=1 "
                 "attenuationLinear=0 attenuationQuadratic=0.3\n" +
                     cube("/World/Cube", 1, 0, 0.5, 1),
                 "environment 0 0 0 0 0 0 0 false true 10 - backgroundMode=plain_color colorMode=linear\n");
  ASSERT_TRUE(s.ok);
  EXPECT_NEAR(s.luminance({1.9, 0, 0}), s.luminance({-1.9, 0, 0}), 8);
}

TEST(LightPixels, ShadowedLightBudgetKeepsTheStrongestCaster) {
  // Two spot lights; a cube under each at mirrored places.  Budget 1: only
  // the brighter light (on +y) casts.
  std::string lights =
      "light /World/Strong 0 0 -1 8 type=spot position=0,3,3 coneAngle=55 innerConeAngle=50 "
      "attenuationConstant=1 attenuationLinear=0 attenuationQuadratic=0.3\n"
      "light /World/Weak 0 0 -1 6 type=spot position=0,-3,3 coneAngle=55 innerConeAngle=50 "
      "attenuationConstant=1 attenuationLinear=0 attenuationQuadratic=0.3\n";
  std::string cubes = cube("/World/A", 1, 3, 0.5, 1) + cube("/World/B", 1, -3, 0.5, 1);
  Shot s = shoot(lights + cubes,
                 "environment 0 0 0 0 0 0 0 true true 10 - backgroundMode=plain_color colorMode=linear "
                 "shadowedLightBudget=1\n");
  ASSERT_TRUE(s.ok);
  EXPECT_LT(s.luminance({1.9, 3, 0}), s.luminance({-1.9, 3, 0}) / 3);             // the strong light's shadow
  EXPECT_GT(s.luminance({1.9, -3, 0}), s.luminance({-1.9, -3, 0}) * 3 / 4);       // the weak one casts none
}

TEST(LightPixels, ObjectThatCastsNoShadowLeavesTheFloorLit) {
  Shot s = shoot("light /World/Spot 0 0 -1 8 type=spot position=0,0,3 coneAngle=55 innerConeAngle=50 "
                 "attenuationConstant=1 attenuationLinear=0 attenuationQuadratic=0.3\n" +
                 cube("/World/Cube", 1, 0, 0.5, 1, "castShadow=false"));
  ASSERT_TRUE(s.ok);
  EXPECT_NEAR(s.luminance({1.9, 0, 0}), s.luminance({-1.9, 0, 0}), 10);
}

TEST(LightPixels, TerrainThatReceivesNoShadowStaysLit) {
  std::string heights;
  for (int i = 0; i < 81; ++i) heights += i ? ",0" : "0";
  for (bool receive : {true, false}) {
    Shot s = shoot("light /World/Spot 0 0 -1 8 type=spot position=0,0,3 coneAngle=55 innerConeAngle=50 "
                   "attenuationConstant=1 attenuationLinear=0 attenuationQuadratic=0.3\n"
                   "terrain_region /World/T 9 9 16 16 0 0 0.01 heights=" + heights +
                   " receiveShadow=" + (receive ? "true" : "false") + "\n" + cube("/World/Cube", 1, 0, 0.5, 1));
    ASSERT_TRUE(s.ok);
    int shadow = s.luminance({1.9, 0, 0}), lit = s.luminance({-1.9, 0, 0});
    EXPECT_GT(lit, 40);
    if (receive)
      EXPECT_LT(shadow, lit / 3);
    else
      EXPECT_NEAR(shadow, lit, lit / 10 + 3);
  }
}

TEST(LightPixels, AreaStripLightsItsWholeLength) {
  // A 10 m x 0.2 m strip 2 m above the floor along x: the floor under its
  // end (x = 4.5) is lit as under its middle; 2.5 m to the side it is darker.
  Shot s = shoot("light /World/Strip 0 0 -1 3 type=area position=0,0,2 areaSize=10,0.2,0 shadows=false "
                 "attenuationConstant=1 attenuationLinear=0 attenuationQuadratic=0.5\n");
  ASSERT_TRUE(s.ok);
  int middle = s.luminance({0, 0, 0}), end = s.luminance({4.5, 0, 0}), side = s.luminance({0, 2.5, 0});
  EXPECT_GT(middle, 100);
  EXPECT_NEAR(end, middle, middle / 10);
  EXPECT_LT(side, middle * 3 / 4);
}

TEST(LightPixels, LightsBetweenTheEyeAndTheFloorLeaveNoBlackPixel) {
  // Where a light lies on the ray from the eye to the floor the half
  // vector equals the view vector; pow() of the rounding-negative
  // 1 - dot(h, V) was NaN there: two black dots in this very image.
  if (!context()) return;
  std::string text =
      "raisim_engine_scene 2\n"
      "camera /World/Cam 0 0 14 0.70710678 0 0.70710678 0 60 0.05 100 640 480 rgb true\n"
      "object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 1 0 0 default - false true true - static true 1 "
      "18446744073709551615\n";
  for (int i = 0; i < 40; ++i)
    text += "light /World/L" + std::to_string(i) + " 0 0 -1 2 type=point position=" + std::to_string(i % 8 - 4) + "," +
            std::to_string(i / 8 - 2) + ",1.5 shadows=false\n";
  LoadResult loaded = parse(text);
  ASSERT_TRUE(loaded.ok());
  RenderScene scene;
  Diagnostics diags;
  buildRenderScene(loaded.document, SceneOptions{}, scene, diags);
  Camera cam;
  std::string err;
  ASSERT_TRUE(chooseCamera(scene, "", cam, &err)) << err;
  RenderOptions o;
  o.width = 640;
  o.height = 480;
  Image image;
  ASSERT_TRUE(renderScene(scene, cam, o, image, diags));
  int dark = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* c = image.pixel(x, y);
      dark += c[0] + c[1] + c[2] < 100;  // the floor is lit bright everywhere
    }
  EXPECT_EQ(dark, 0);
}

}  // namespace
