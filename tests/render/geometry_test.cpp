// terrain_foliage_layer, wire, deformable and granular as rscene-render
// draws them: what prepareScene() makes of them (counts, places, limits)
// and pixel facts of the images on the CPU backend.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "gl_test_context.hpp"
#include "core/loader.hpp"
#include "render/camera.hpp"
#include "render/image.hpp"
#include "render/mesh.hpp"
#include "render/render_foliage.hpp"
#include "render/render_scene.hpp"
#include "render/renderer.hpp"

using namespace rscene;
using namespace rscene::render;

namespace {

const char* kBlack = "environment 0 0 0 0.3 0.3 0.3 0 true false 10 - backgroundMode=plain_color colorMode=linear\n";
const char* kWhite = "environment 1 1 1 0.3 0.3 0.3 0 true false 10 - backgroundMode=plain_color colorMode=linear\n";
const char* kSun = "light /World/Sun 0.2 0.1 -1 2 type=directional\n";
const char* kRed = "material red 0.8 0.1 0.1 1 0 0.6 0 0 0 0 false - - - - - - id=red\n";
// Looks straight down from 20 m, orthographic over 9 m: image up is world
// +x, image right world -y.
const char* kTopDown =
    "camera /World/Top 0 0 20 0.70710678 0 0.70710678 0 60 0.05 100 200 200 rgb true id=top "
    "projection=orthographic orthoScale=9\n";
// At the origin looking along +x.
const char* kForward = "camera /World/Cam 0 0 0 1 0 0 0 60 0.05 100 200 200 rgb true id=cam\n";

struct Built {
  Scene scene;
  RenderScene render;
  Diagnostics diags;
  bool ok = false;
};

std::unique_ptr<Built> build(const std::string& body, const DrawLimits& limits = {}, const std::string& dir = ".") {
  auto b = std::make_unique<Built>();
  LoadResult loaded = parse("raisim_engine_scene 1\n" + body);
  EXPECT_TRUE(loaded.ok());
  SceneOptions so;
  so.sceneDir = dir;
  b->ok = buildRenderScene(loaded.document, so, b->scene, b->render, b->diags, limits);
  return b;
}

Image draw(const Built& b, RenderOptions options = {}) {
  Image out;
  if (!context()) return out;
  Camera cam;
  std::string err;
  EXPECT_TRUE(chooseCamera(b.render, "", cam, &err)) << err;
  options.width = options.height = 200;
  Diagnostics diags;
  EXPECT_TRUE(renderScene(b.render, cam, options, out, diags));
  return out;
}

const Instanced* batchOf(const RenderScene& s, const std::string& kind) {
  for (const Instanced& b : s.instanced)
    if (b.kind == kind) return &b;
  return nullptr;
}

bool hasCode(const Diagnostics& d, const std::string& code) {
  return std::any_of(d.begin(), d.end(), [&](const Diagnostic& x) { return x.code == code; });
}

// A 21 x 21 terrain of 8 x 8 m at the origin: flat where x < 0, rising 0.5 m
// per 0.4 m (51 degrees) where x > 0.  `density` 1 where y < 0, 0 elsewhere
// when `halfDensity`.
std::string terrain(bool halfDensity, const std::string& layerKeys) {
  const int n = 21;
  std::string heights, density;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      if (!heights.empty()) heights += ",", density += ",";
      heights += std::to_string(x <= n / 2 ? 0.0 : (x - n / 2) * 0.5);
      density += y < n / 2 ? "1" : "0";
    }
  std::string layer = "terrain_foliage_layer /World/T id=grass densityPerSquareMeter=60 size=0.12,0.12,0.3 "
                      "colorA=0,1,0,1 colorB=0,1,0,1 maxSlopeDegrees=30 " + layerKeys;
  if (halfDensity) layer += " density=" + density;
  return "terrain_region /World/T 21 21 8 8 0 0 0 id=terrain heights=" + heights + "\n" + layer + "\n";
}

// Green-dominant pixels (grass) in the image rectangle [x0, x1) x [y0, y1).
int green(const Image& im, int x0, int y0, int x1, int y1) {
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const std::uint8_t* p = im.pixel(x, y);
      if (p[1] > p[0] + 40 && p[1] > p[2] + 40) ++n;
    }
  return n;
}

}  // namespace

TEST(GrassBlade, IsAThinTaperedBladeOfHeightOne) {
  MeshData m = grassBlade();
  ASSERT_EQ(m.vertexCount(), 5u);
  EXPECT_EQ(m.indices.size(), 9u);  // 3 triangles
  float top = 0, widthAtBase = 0;
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    top = std::max(top, m.vertices[v * 8 + 2]);
    if (m.vertices[v * 8 + 2] == 0) widthAtBase = std::max(widthAtBase, 2 * std::abs(m.vertices[v * 8]));
  }
  EXPECT_FLOAT_EQ(top, 1.0f);
  EXPECT_FLOAT_EQ(widthAtBase, 1.0f);
  EXPECT_EQ(grassBladeShading().size(), m.vertexCount());
}

TEST(Foliage, ExpectedCountFollowsDensityTimesArea) {
  auto b = build(terrain(false, "maxSlopeDegrees=90"));
  const Terrain& t = b->scene.terrains.at(0);
  FoliageScatter s = countFoliage(t, t.foliageLayers.at(0));
  // 60 per square metre over 64 m^2: 3840, give or take the cells' rounding.
  EXPECT_NEAR(double(s.generated), 3840.0, 3840 * 0.05);
  EXPECT_EQ(s.drawn, s.generated);
}

TEST(Foliage, OnlyWhereDenseAndFlat) {
  auto b = build(std::string(kBlack) + kSun + kTopDown + terrain(true, "seed=3"));
  ASSERT_TRUE(b->ok);
  const Instanced* grass = batchOf(b->render, "terrain_foliage_layer");
  ASSERT_NE(grass, nullptr);
  EXPECT_EQ(grass->shape, Shape::GrassBlade);
  EXPECT_TRUE(grass->doubleSided);
  ASSERT_FALSE(grass->worlds.empty());
  for (const Eigen::Affine3d& m : grass->worlds) {
    Eigen::Vector3d p = m.translation();
    EXPECT_LE(p.x(), 0.2 + 1e-9);   // the flat half (the first steep quad starts at x = 0)
    EXPECT_LE(p.y(), 0.2 + 1e-9);   // the dense half (the last dense cell ends 0.2 m past y = 0)
    EXPECT_NEAR(p.z(), 0.0, 1e-9);  // on the flat surface
  }
  EXPECT_TRUE(b->render.skipped.empty());
  Image im = draw(*b);
  ASSERT_EQ(im.width, 200);
  // Image up = +x, right = -y: the flat dense quarter is the bottom right.
  int flatDense = green(im, 110, 110, 200, 200);
  int others = green(im, 0, 0, 90, 200) + green(im, 110, 0, 200, 90);
  EXPECT_GT(flatDense, 1000);
  EXPECT_LT(others, 20);
}

TEST(Foliage, SameSeedSameImageAnotherSeedAnother) {
  auto a = build(std::string(kBlack) + kSun + kTopDown + terrain(true, "seed=3"));
  auto same = build(std::string(kBlack) + kSun + kTopDown + terrain(true, "seed=3"));
  auto other = build(std::string(kBlack) + kSun + kTopDown + terrain(true, "seed=4"));
  Image ia = draw(*a), is = draw(*same), io = draw(*other);
  ASSERT_FALSE(ia.rgba.empty());
  EXPECT_EQ(ia.rgba, is.rgba);
  EXPECT_NE(ia.rgba, io.rgba);
  EXPECT_NE(batchOf(a->render, "terrain_foliage_layer")->worlds.front().translation(),
            batchOf(other->render, "terrain_foliage_layer")->worlds.front().translation());
}

TEST(Foliage, MaxRenderedInstancesCapsTheDrawnCountAcrossTheWholeRegion) {
  auto b = build(terrain(false, "maxSlopeDegrees=90 maxRenderedInstances=500"));
  ASSERT_TRUE(b->ok);
  const Instanced* grass = batchOf(b->render, "terrain_foliage_layer");
  ASSERT_NE(grass, nullptr);
  EXPECT_GT(grass->generated, 3000u);
  EXPECT_LE(grass->worlds.size(), 500u);
  EXPECT_GE(grass->worlds.size(), 450u);
  // Spread over the terrain, not its first rows.
  double minY = 1e9, maxY = -1e9;
  for (const Eigen::Affine3d& m : grass->worlds) {
    minY = std::min(minY, m.translation().y());
    maxY = std::max(maxY, m.translation().y());
  }
  EXPECT_LT(minY, -3.5);
  EXPECT_GT(maxY, 3.5);
}

TEST(Foliage, MaxInstancesCapsWhatIsGenerated) {
  auto b = build(terrain(false, "maxSlopeDegrees=90 maxInstances=1000"));
  const Instanced* grass = batchOf(b->render, "terrain_foliage_layer");
  ASSERT_NE(grass, nullptr);
  EXPECT_LE(grass->generated, 1000u);
  EXPECT_GT(grass->generated, 900u);  // scaled down everywhere, so nearly all of it still fits
  // A density that overflows when multiplied by the area is capped too.
  std::string text = terrain(false, "maxSlopeDegrees=90 maxInstances=50");
  text.replace(text.find("densityPerSquareMeter=60"), 24, "densityPerSquareMeter=1e308");
  auto huge = build(text);
  ASSERT_NE(batchOf(huge->render, "terrain_foliage_layer"), nullptr);
  EXPECT_LE(batchOf(huge->render, "terrain_foliage_layer")->generated, 50u);
  EXPECT_GT(batchOf(huge->render, "terrain_foliage_layer")->generated, 40u);
}

TEST(Foliage, GlobalInstanceLimitIsRS9014) {
  DrawLimits limits;
  limits.maxInstances = 100;
  auto b = build(terrain(false, "maxSlopeDegrees=90"), limits);
  EXPECT_FALSE(b->ok);
  EXPECT_TRUE(hasCode(b->diags, "RS9014"));
  EXPECT_EQ(batchOf(b->render, "terrain_foliage_layer"), nullptr);
}

TEST(Foliage, HolesAndHeightLimitsReject) {
  auto b = build(terrain(false, "maxSlopeDegrees=90 minHeight=1"));
  const Instanced* grass = batchOf(b->render, "terrain_foliage_layer");
  ASSERT_NE(grass, nullptr);
  for (const Eigen::Affine3d& m : grass->worlds) EXPECT_GE(m.translation().z(), 1.0);
  std::string holes = "holes=";
  for (int i = 0; i < 21 * 21; ++i) holes += i ? ",1" : "1";
  std::string text = terrain(false, "maxSlopeDegrees=90");
  text.replace(text.find(" heights="), 0, " " + holes);
  auto none = build(text);
  EXPECT_EQ(batchOf(none->render, "terrain_foliage_layer"), nullptr);
}

TEST(Foliage, UnknownPrimitiveWarnsAndDrawsBlades) {
  auto b = build(terrain(false, "primitive=fern"));
  EXPECT_TRUE(hasCode(b->diags, "RS9072"));
  ASSERT_NE(batchOf(b->render, "terrain_foliage_layer"), nullptr);
  EXPECT_EQ(batchOf(b->render, "terrain_foliage_layer")->shape, Shape::GrassBlade);
}

TEST(InstancedVisual, GrassPatchDrawsBladesOnItsBoundTerrain) {
  auto b = build(
      "terrain_region /World/T 2 2 4 4 0 0 2 id=terrain\n"
      "instanced_visual /World/G box size=0.05,0.05,0.3 grassPatch=true terrainBinding=terrain "
      "instances=0.5,0.5,0.1,1,0,0,0,1,1,1;9,9,0.1,1,0,0,0,1,1,1\n");
  const Instanced* g = batchOf(b->render, "instanced_visual");
  ASSERT_NE(g, nullptr);
  EXPECT_EQ(g->shape, Shape::GrassBlade);
  ASSERT_EQ(g->worlds.size(), 2u);
  EXPECT_NEAR(g->worlds[0].translation().z(), 2.1, 1e-9);  // 0.1 above the surface at z = 2
  EXPECT_NEAR(g->worlds[1].translation().z(), 0.1, 1e-9);  // beyond the terrain: as written
}

TEST(Wire, LineSpansItsTwoPoints) {
  // From a box's underside (x = 6) down to a world point; seen along +x.
  auto b = build(std::string(kWhite) + kSun + kForward + kRed +
                 "object /World/Box box 6 0 1.5 1 0 0 0 0.4 0.4 0.4 0.5 1 1 default red false true false - static "
                 "true 1 18446744073709551615 id=box\n"
                 "wire /World/W stiff box - 2 localPositionA=0,0,-0.2 localPositionB=6,0,-1 visualizationWidth=0.05\n");
  ASSERT_TRUE(b->ok);
  ASSERT_EQ(b->render.wires.size(), 1u);
  EXPECT_TRUE((b->render.wires[0].a - Eigen::Vector3d(6, 0, 1.3)).norm() < 1e-9);
  EXPECT_TRUE((b->render.wires[0].b - Eigen::Vector3d(6, 0, -1)).norm() < 1e-9);
  EXPECT_TRUE(b->render.skipped.empty());
  Image im = draw(*b);
  ASSERT_EQ(im.width, 200);
  // 60 degrees over 200 px at 6 m: z = 1.3 is row ~100 - 1.3 / 6 / tan(30) * 100 = 62, z = -1 row ~129.
  // The line is under 2 px wide: dark in column 99 or 100.
  auto dark = [&](int x, int y) {
    const std::uint8_t* p = im.pixel(x, y);
    return p[0] + p[1] + p[2] < 400;
  };
  for (int y : {70, 100, 125}) EXPECT_TRUE(dark(99, y) || dark(100, y)) << "row " << y;
  for (int y : {135, 180}) EXPECT_FALSE(dark(99, y) || dark(100, y)) << "row " << y;  // below the world end
  for (int y : {70, 100, 125}) EXPECT_FALSE(dark(110, y) || dark(90, y)) << "beside, row " << y;
}

TEST(Wire, FollowsBothEndsWhenBodiesMove) {
  auto b = build(
      "object /World/A box 0 0 1 1 0 0 0 0.2 0.2 0.2 1 1 1 default engine_default false true false - dynamic true 1 "
      "18446744073709551615 id=a\n"
      "object /World/B box 2 0 1 1 0 0 0 0.2 0.2 0.2 1 1 1 default engine_default false true false - dynamic true 1 "
      "18446744073709551615 id=b\n"
      "wire /World/W stiff a b 2\n");
  ASSERT_EQ(b->render.wires.size(), 1u);
  std::vector<Pose> objects(2);
  objects[0].position = {0, 0, 5};
  objects[1].position = {0, 3, 5};
  BodyPoseView view;
  view.objects = &objects;
  poseScene(b->render, view);
  const WireSpan& w = b->render.wires[0];
  EXPECT_TRUE((w.a - Eigen::Vector3d(0, 0, 5)).norm() < 1e-9);
  EXPECT_TRUE((w.b - Eigen::Vector3d(0, 3, 5)).norm() < 1e-9);
  const Drawable& d = b->render.drawables[w.drawable];
  EXPECT_TRUE((d.world * Eigen::Vector3d(0, 0, -0.5) - w.a).norm() < 1e-9);
  EXPECT_TRUE((d.world * Eigen::Vector3d(0, 0, 0.5) - w.b).norm() < 1e-9);
}

TEST(Granular, BoxFillDrawsItsSpheresInItsBox) {
  auto b = build(std::string(kBlack) + kSun + kForward +
                 "granular /World/Sand particles 6 0 -0.25 1 0 0 0 1 1 1 boxMin=-0.5,-0.5,0 boxMax=0.5,0.5,0.5 "
                 "radius=0.05 spacing=0.1\n");
  ASSERT_TRUE(b->ok);
  const Instanced* sand = batchOf(b->render, "granular");
  ASSERT_NE(sand, nullptr);
  EXPECT_EQ(sand->worlds.size(), 10u * 10u * 5u);
  EXPECT_EQ(sand->shape, Shape::Sphere);
  Eigen::AlignedBox3d box(Eigen::Vector3d(5.5, -0.5, -0.25), Eigen::Vector3d(6.5, 0.5, 0.25));
  for (const Eigen::Affine3d& m : sand->worlds) {
    EXPECT_TRUE(box.contains(m.translation()));
    EXPECT_NEAR(m.linear()(0, 0), 0.05, 1e-12);  // the radius
  }
  EXPECT_TRUE(b->render.skipped.empty());
  Image im = draw(*b);
  ASSERT_EQ(im.width, 200);
  const std::uint8_t* c = im.pixel(100, 100);
  EXPECT_GT(c[0], 20);                 // lit, not the background
  EXPECT_GT(c[0] * 10, c[2] * 13);     // sandy: a third more red than blue
  EXPECT_EQ(im.pixel(100, 20)[0], 0);  // above the box: background
}

// The record's own limits are the scene model's rule (RS7082 at the key,
// as validate and sim say it, and nothing more); --max-instances is the
// renderer's own cap (RS9070).
TEST(Granular, OwnLimitIsTheModelsRS7082AndTheDrawLimitIsRS9070) {
  std::string rec = "granular /World/Sand particles 0 0 0 1 0 0 0 1 1 1 boxMin=0,0,0 boxMax=1,1,1 radius=0.05 spacing=0.1";
  auto own = build(rec + " maxParticles=100\n");
  EXPECT_FALSE(own->ok);
  EXPECT_TRUE(hasCode(own->diags, "RS7082"));
  EXPECT_FALSE(hasCode(own->diags, "RS9070"));
  DrawLimits limits;
  limits.maxInstances = 999;
  auto global = build(rec + "\n", limits);
  EXPECT_FALSE(global->ok);
  EXPECT_TRUE(hasCode(global->diags, "RS9070"));
  EXPECT_FALSE(hasCode(global->diags, "RS7082"));
  auto bad = build("granular /World/S particles 0 0 0 1 0 0 0 1 1 1 boxMax=1,1,1 spacing=0\n");
  EXPECT_FALSE(bad->ok);
  EXPECT_TRUE(hasCode(bad->diags, "RS7082"));
  EXPECT_EQ(bad->diags.size(), 1u);
}

TEST(Deformable, MeshAppearsAtItsPose) {
  auto dir = std::filesystem::temp_directory_path() / "rscene_geometry_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "sheet.obj") << "v -0.5 0 0\nv 0.5 0 0\nv 0.5 0 1\nv -0.5 0 1\nf 1 2 3\nf 1 3 4\n";
  // The sheet faces -y; turned -90 degrees about z it faces the camera
  // (-x), 2 m square, its lower edge at z = -1.
  auto b = build(std::string(kBlack) + kSun + kForward + kRed +
                     "deformable /World/Sheet cloth sheet.obj 5 0 -1 0.70710678 0 0 -0.70710678 2 2 2 material=red\n",
                 {}, dir.string());
  ASSERT_TRUE(b->ok);
  EXPECT_TRUE(b->render.skipped.empty());
  ASSERT_EQ(b->render.drawables.size(), 1u);
  EXPECT_NEAR(b->render.drawables[0].bounds.min().z(), -1, 1e-9);
  EXPECT_NEAR(b->render.drawables[0].bounds.max().z(), 1, 1e-9);
  Image im = draw(*b);
  ASSERT_EQ(im.width, 200);
  const std::uint8_t* c = im.pixel(100, 100);
  EXPECT_GT(c[0], 2 * c[1] + 10);  // red
  EXPECT_EQ(im.pixel(5, 100)[0], 0);  // beside it: background
  // Turned away from the camera: a cloth shows its back, a one-sided fem
  // surface does not.
  for (std::string kind : {"cloth", "fem"}) {
    auto back = build(std::string(kBlack) + kSun + kForward + kRed + "deformable /World/Sheet " + kind +
                          " sheet.obj 5 0 -1 0.70710678 0 0 0.70710678 2 2 2 material=red\n",
                      {}, dir.string());
    Image bi = draw(*back);
    ASSERT_EQ(bi.width, 200);
    if (kind == "cloth") EXPECT_GT(bi.pixel(100, 100)[0], 2 * bi.pixel(100, 100)[1] + 10) << kind;
    else EXPECT_EQ(bi.pixel(100, 100)[0], 0) << kind;
  }
  // A missing mesh: RS5001, an error unless missing assets are allowed.
  auto missing = build(std::string(kForward) + "deformable /World/Gone cloth gone.obj 5 0 0 1 0 0 0 1 1 1\n", {},
                       dir.string());
  Image none;
  Diagnostics diags;
  Camera cam;
  ASSERT_TRUE(chooseCamera(missing->render, "", cam, nullptr));
  RenderOptions strict;
  EXPECT_FALSE(renderScene(missing->render, cam, strict, none, diags));
  EXPECT_TRUE(hasCode(diags, "RS5001"));
  RenderOptions allow;
  allow.allowMissingAssets = true;
  Diagnostics warned;
  EXPECT_TRUE(renderScene(missing->render, cam, allow, none, warned));
  std::filesystem::remove_all(dir);
}

TEST(Wire, RobotEndIsRaiSimsBodyLocalIndex) {
  // Body 0 is the base; body 1 the child of the first movable joint (the
  // fixed `tip` merges into it), as rscene-sim attaches the wire.
  auto dir = std::filesystem::temp_directory_path() / "rscene_geometry_wire_robot";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "arm.urdf") << R"(<robot name="arm">
  <link name="base"><visual><geometry><box size="0.2 0.2 0.2"/></geometry></visual></link>
  <link name="arm"><visual><geometry><box size="0.1 0.1 1"/></geometry></visual></link>
  <link name="tip"/>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 1"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="f" type="fixed"><parent link="arm"/><child link="tip"/><origin xyz="0 0 0.5"/></joint>
</robot>
)";
  auto b = build(
      "articulated_resource arm_res Arm arm.urdf\n"
      "articulated /World/Arm arm_res 2 0 0 1 0 0 0 true true id=arm\n"
      "wire /World/W stiff arm - 3 localIndexA=1 localPositionA=0,0,0.5 localPositionB=0,0,0\n"
      "wire /World/Bad stiff arm - 3 localIndexA=2\n",
      {}, dir.string());
  std::filesystem::remove_all(dir);
  ASSERT_EQ(b->render.wires.size(), 1u);
  EXPECT_TRUE((b->render.wires[0].a - Eigen::Vector3d(2, 0, 1.5)).norm() < 1e-9) << b->render.wires[0].a.transpose();
  EXPECT_TRUE(b->render.wires[0].b.isZero());
  // Body 2 does not exist: validate's and sim's RS7046 at the key, not a
  // wire quietly left undrawn.
  EXPECT_FALSE(b->ok);
  EXPECT_EQ(b->render.skipped.count("wire"), 0u);
  ASSERT_FALSE(b->diags.empty());
  const Diagnostic& d = b->diags.back();
  EXPECT_EQ(d.code, "RS7046");
  EXPECT_EQ(d.line, 5u);
  EXPECT_EQ(d.field, "localIndexA");
  EXPECT_EQ(d.message, "localIndexA is 2; '/World/Arm' has bodies 0 to 1");
}

TEST(Foliage, ScaleRotationAndAlignmentWithinTheirRanges) {
  // No random rotation, scales in [0.5, 2] x size; aligned to the normal.
  auto b = build(terrain(false, "maxSlopeDegrees=90 randomYawDegrees=0 minScale=0.5 maxScale=2 alignToNormal=true"));
  const Instanced* grass = batchOf(b->render, "terrain_foliage_layer");
  ASSERT_NE(grass, nullptr);
  const Eigen::Vector3d steepNormal = Eigen::Vector3d(-0.5 / 0.4, 0, 1).normalized();
  double smallest = 1e9, largest = 0;
  int steep = 0;
  for (const Eigen::Affine3d& m : grass->worlds) {
    double height = m.linear().col(2).norm();  // the blade's height: 0.3 x scale
    smallest = std::min(smallest, height / 0.3);
    largest = std::max(largest, height / 0.3);
    Eigen::Vector3d up = m.linear().col(2).normalized();
    if (m.translation().x() > 0.5) {  // inside the steep half: along its normal
      EXPECT_NEAR(up.dot(steepNormal), 1.0, 1e-9);
      ++steep;
    } else if (m.translation().x() < -0.5) {
      EXPECT_NEAR(up.z(), 1.0, 1e-9);  // flat: upright
    }
  }
  EXPECT_GT(steep, 100);
  EXPECT_GE(smallest, 0.5 - 1e-9);
  EXPECT_LE(largest, 2 + 1e-9);
  EXPECT_LT(smallest, 0.6);  // the range is used, not one value
  EXPECT_GT(largest, 1.9);
}
