// The typed scene view: defaults from the schema, aliases resolved to
// canonical names, world transforms, asset paths, bounded terrain parsing.
#include "scene/scene.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "core/loader.hpp"
#include "test_util.hpp"

using namespace rscene;
namespace fs = std::filesystem;

namespace {

struct Built {
  Scene scene;
  Diagnostics diags;
  bool ok = false;
};

Built build(std::string text, SceneOptions opt = {}) {
  Built b;
  LoadResult r = parse(std::move(text));
  EXPECT_TRUE(r.ok()) << (r.diagnostics.empty() ? "" : r.diagnostics[0].message);
  b.ok = buildScene(r.document, opt, b.scene, b.diags);
  return b;
}

std::string codes(const Diagnostics& ds) {
  std::string out;
  for (const Diagnostic& d : ds) out += d.code + " ";
  return out;
}

}  // namespace

TEST(Scene, EmptySceneHasEngineDefaults) {
  Built b = build("raisim_engine_scene 1\n");
  ASSERT_TRUE(b.ok);
  EXPECT_DOUBLE_EQ(b.scene.timeStep, 0.0025);
  EXPECT_EQ(b.scene.gravity, Eigen::Vector3d(0, 0, -9.81));
  EXPECT_EQ(b.scene.solver.iterations, 80);
  EXPECT_DOUBLE_EQ(b.scene.solver.defaultFriction, 0.8);
  EXPECT_EQ(b.scene.solver.broadphaseType, "sap3_axis");
  ASSERT_EQ(b.scene.materials.size(), 1u);
  EXPECT_EQ(b.scene.materials[0].id, "engine_default");
  EXPECT_DOUBLE_EQ(b.scene.materials[0].roughness, 0.55);
  ASSERT_EQ(b.scene.terrainTextures.size(), 2u);
  EXPECT_EQ(b.scene.terrainTextures[1].name, "terrain_rock");
  EXPECT_EQ(b.scene.environment.backgroundMode, "rayrai_sky");
}

TEST(Scene, SolverKeysAndAliases) {
  Built b = build(
      "raisim_engine_scene 1\ntime_step 0.001\ngravity 0 0 -1.62\n"
      "solver 40 1e-06 0.3 accurate defaultFriction=0.4 broadphaseType=MBP sleepingEnabled=off\n"
      "environment 0.1 0.2 0.3 0 0 0 0 true true 10 - backgroundMode=Solid fogColor=1,0,0\n");
  ASSERT_TRUE(b.ok) << codes(b.diags);
  EXPECT_DOUBLE_EQ(b.scene.timeStep, 0.001);
  EXPECT_DOUBLE_EQ(b.scene.gravity.z(), -1.62);
  EXPECT_EQ(b.scene.solver.iterations, 40);
  EXPECT_DOUBLE_EQ(b.scene.solver.erp, 0.3);
  EXPECT_DOUBLE_EQ(b.scene.solver.defaultFriction, 0.4);
  EXPECT_EQ(b.scene.solver.broadphaseType, "multi_box_prune");
  EXPECT_FALSE(b.scene.solver.sleepingEnabled);
  EXPECT_EQ(b.scene.environment.backgroundMode, "plain_color");
  EXPECT_EQ(b.scene.environment.fogColor, Eigen::Vector4d(1, 0, 0, 1));
  EXPECT_DOUBLE_EQ(b.scene.environment.background.y(), 0.2);
}

TEST(Scene, ObjectLayoutsAndBodyModes) {
  Built b = build(
      "raisim_engine_scene 1\n"
      "object /World/A cube 1 2 3 1 0 0 0 0.5 0.6 0.7 0.5 1 2 default engine_default false true false - movable true 4 "
      "7\n"
      "object /World/B box 0 0 0 1 0 0 0 1 1 1 0.5 1 1 default engine_default true false false - bogus true 1 1\n"
      "object /World/C box 0 0 0 1 0 0 0 1 1 1 0.5 1 1 default engine_default true true\n"
      "object /World/D sphere 0 0 0 1 0 0 0 2 1 1 0.25 1 3 default engine_default\n"
      "object /World/E plane 0 0 -0.5 1 0 0 0 10 10 1 0.5 1 0 default engine_default false true false - dynamic "
      "true 1 1\n"
      "object /World/F box 0 0 0 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false - dynamic false 1 1\n");
  ASSERT_TRUE(b.ok) << codes(b.diags);
  const auto& o = b.scene.objects;
  ASSERT_EQ(o.size(), 6u);
  EXPECT_EQ(o[0].primitive, "box");
  EXPECT_EQ(o[0].bodyMode, BodyMode::Dynamic);
  EXPECT_EQ(o[0].collisionGroup, 4u);
  EXPECT_EQ(o[0].collisionMask, 7u);
  EXPECT_EQ(o[0].world.position, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(o[0].id, "object_/World/A");
  EXPECT_EQ(o[1].bodyMode, BodyMode::VisualOnly);  // unknown #21, #17 visualOnly=true
  EXPECT_EQ(o[2].bodyMode, BodyMode::Static);      // 19 fields: fixed=true
  EXPECT_EQ(o[3].bodyMode, BodyMode::Dynamic);     // 17 fields
  EXPECT_DOUBLE_EQ(o[3].physicsRadius(), 0.5);
  EXPECT_EQ(o[4].primitive, "ground");
  EXPECT_EQ(o[4].bodyMode, BodyMode::Static);  // a ground is always static
  EXPECT_EQ(o[5].bodyMode, BodyMode::VisualOnly);  // collidable=false
  EXPECT_EQ(o[0].positionToken, 2);
}

TEST(Scene, ParentedToNonGroupInheritsTransform) {
  std::string text =
      "raisim_engine_scene 1\n"
      "group /World id=folder_world parentId=-\n"
      "object /World/Base box 1 0 0 0.7071067811865476 0 0 0.7071067811865476 1 1 1 0.5 1 1 default engine_default "
      "false true false - static true 1 1 id=base parentGroupId=folder_world\n"
      "object /World/Base/Top box 1 0 0 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false - dynamic "
      "true 1 1 parentGroupId=base\n";
  Built b = build(text);
  ASSERT_TRUE(b.ok);
  const Object& top = b.scene.objects[1];
  EXPECT_NEAR(top.world.position.x(), 1, 1e-12);  // base yaws 90 degrees: +x becomes +y
  EXPECT_NEAR(top.world.position.y(), 1, 1e-12);
  EXPECT_EQ(top.local.position, Eigen::Vector3d(1, 0, 0));
  Built flat = build(text + "scene_graph inheritedTransforms=false\n");
  EXPECT_EQ(flat.scene.objects[1].world.position, Eigen::Vector3d(1, 0, 0));
}

TEST(Scene, AssetPathsResolveAgainstSceneDirThenAssetRoot) {
  SceneOptions opt;
  opt.sceneDir = "/scenes";
  opt.exists = [](const std::string& p) { return p == "/scenes/near.obj"; };
  Built b = build(
      "raisim_engine_scene 2\nasset_root assets\n"
      "object /World/A mesh 0 0 0 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false near.obj static "
      "true 1 1 collisionMeshPath=far.stl\n",
      opt);
  ASSERT_TRUE(b.ok);
  EXPECT_EQ(b.scene.objects[0].meshPath, "/scenes/near.obj");
  EXPECT_EQ(b.scene.objects[0].collisionMeshPath, "/scenes/assets/far.stl");
}

TEST(Scene, BadNumbersAreErrorsWithLocation) {
  Built b = build(
      "raisim_engine_scene 1\n"
      "object /World/A box 0 0 zz 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false - dynamic true 1 1\n");
  EXPECT_FALSE(b.ok);
  ASSERT_EQ(b.diags.size(), 1u);
  EXPECT_EQ(b.diags[0].code, "RS2001");  // the validator's code for it
  EXPECT_EQ(b.diags[0].line, 2u);
  EXPECT_EQ(b.diags[0].column, 25u);
}

TEST(Scene, TerrainSamplesAndLayers) {
  Built b = build(
      "raisim_engine_scene 1\n"
      "terrain_region /World/T 3 2 4 2 1 1 0.5 heights=0,1,2,3,4,5 texturePrimary=0,0,0,1,1,1\n"
      "terrain_splat_layer /World/T slot=1 weights=1,1,1,0,0,0\n");
  ASSERT_TRUE(b.ok) << codes(b.diags);
  const Terrain& t = b.scene.terrains.at(0);
  EXPECT_EQ(t.samplePosition(2, 1), Eigen::Vector3d(3, 2, 5.5));
  EXPECT_EQ(t.samplePosition(0, 0), Eigen::Vector3d(-1, 0, 0.5));
  ASSERT_EQ(t.splatLayers.size(), 1u);
  EXPECT_EQ(t.splatLayers[0].weights.size(), 6u);
}

TEST(Scene, HugeTerrainIsRefusedBeforeParsing) {
  Built b = build("raisim_engine_scene 1\nterrain_region /World/T 16384 16384 4 2 0 0 0 heights=1\n");
  EXPECT_FALSE(b.ok);
  EXPECT_EQ(codes(b.diags), "RS4002 ");
  EXPECT_TRUE(b.scene.terrains.empty());
  Built axis = build("raisim_engine_scene 1\nterrain_region /World/T 1 20000 4 2 0 0 0 heights=1\n");
  EXPECT_EQ(codes(axis.diags), "RS4001 RS4001 ");
  Built wrong = build("raisim_engine_scene 1\nterrain_region /World/T 2 2 4 2 0 0 0 heights=1,2,3\n");
  EXPECT_EQ(codes(wrong.diags), "RS4003 ");
}

TEST(Scene, CompoundsWiresAndSkippedRecords) {
  Built b = build(
      "raisim_engine_scene 1\n"
      "compound /World/C 0 0 1 1 0 0 0 1 1 1 2 dynamic true true id=c1 centerOfMass=0,0,0.1\n"
      "compound_child c1 box 0 0 0 1 0 0 0 1 1 1 size=1,1,1\n"
      "compound_child /World/C sphere 0 0 1 1 0 0 0 1 1 1 radius=0.2\n"
      "wire /World/W soft c1 /World/C 2 stiffness=50\n"
      "sensor /World/S imu - 0 0 0 1 0 0 0\n"
      "granular /World/G sand 0 0 0 1 0 0 0 1 1 1\n");
  ASSERT_TRUE(b.ok) << codes(b.diags);
  ASSERT_EQ(b.scene.compounds.size(), 1u);
  EXPECT_EQ(b.scene.compounds[0].children.size(), 2u);
  EXPECT_TRUE(b.scene.compounds[0].hasCenterOfMass);
  EXPECT_DOUBLE_EQ(b.scene.compounds[0].children[1].radius, 0.2);
  ASSERT_EQ(b.scene.wires.size(), 1u);
  EXPECT_EQ(b.scene.wires[0].kind, "compliant");
  EXPECT_DOUBLE_EQ(b.scene.wires[0].stiffness, 50);
  EXPECT_TRUE(b.scene.skipped.empty());
  ASSERT_EQ(b.scene.granulars.size(), 1u);
  EXPECT_EQ(b.scene.granulars[0].recordIndex, 6);
  EXPECT_EQ(b.scene.granulars[0].kind, "sand");
  ASSERT_EQ(b.scene.sensors.size(), 1u);
  EXPECT_EQ(b.scene.sensors[0].kind, "imu");
  EXPECT_EQ(b.scene.sensors[0].mount.kind, Mount::Kind::World);
}

TEST(Scene, SensorsAndCamerasRideOnTheirBodies) {
  Built b = build(
      "raisim_engine_scene 1\n"
      "object /World/Box box 1 2 3 0.7071068 0 0 0.7071068 1 1 1 0 0 1 default default false true false - dynamic "
      "true 1 18446744073709551615 id=box semanticClass=crate instanceId=7\n"
      "sensor /World/Box/Cam spinning_lidar box 1 0 0 1 0 0 0 parentLink=- lidarChannels=8\n"
      "sensor /World/Free camera - 0 0 5 1 0 0 0 calibrationFx=500 noiseSeed=42 outputPath=cam.png\n"
      "camera /World/Box/View 0 0 1 1 0 0 0 60 0.1 100 64 48 depth true parentGroupId=box outputPath=out.png\n");
  ASSERT_TRUE(b.ok) << codes(b.diags);
  ASSERT_EQ(b.scene.sensors.size(), 2u);
  const Sensor& lidar = b.scene.sensors[0];
  EXPECT_EQ(lidar.kind, "lidar");  // spinning_lidar is RaiSim's name
  EXPECT_EQ(lidar.mount.kind, Mount::Kind::Object);
  EXPECT_EQ(lidar.mount.index, 0);
  EXPECT_TRUE(lidar.mount.link.empty());
  EXPECT_EQ(lidar.params.lidarChannels, 8);
  EXPECT_EQ(lidar.params.lidarSamples, 1024);  // the schema's default
  EXPECT_DOUBLE_EQ(lidar.params.lidarMaxPitch, 15);
  // The box is turned 90 degrees about z: its local +x is world +y.
  EXPECT_TRUE(lidar.world.position.isApprox(Eigen::Vector3d(1, 3, 3), 1e-6)) << lidar.world.position.transpose();
  const Sensor& free = b.scene.sensors[1];
  EXPECT_EQ(free.kind, "rgb");
  EXPECT_EQ(free.mount.kind, Mount::Kind::World);
  EXPECT_DOUBLE_EQ(free.params.fx, 500);
  EXPECT_EQ(free.params.noiseSeed, 42u);
  EXPECT_EQ(free.outputPath, "cam.png");
  ASSERT_EQ(b.scene.cameras.size(), 1u);
  EXPECT_EQ(b.scene.cameras[0].mount.kind, Mount::Kind::Object);
  EXPECT_EQ(b.scene.cameras[0].outputPath, "out.png");
  EXPECT_EQ(b.scene.objects[0].semanticClass, "crate");
  EXPECT_EQ(b.scene.objects[0].instanceId, 7);
  EXPECT_FALSE(b.scene.objects[0].segmentationColor);
}

TEST(Scene, LightsCamerasInstances) {
  Built b = build(
      "raisim_engine_scene 1\n"
      "light /World/L 0 0 -2 3 type=sun\n"
      "camera /World/Cam 1 2 3 1 0 0 0 200 0.1 100 640 480 rgb true\n"
      "instanced_visual /World/I sphere instances=1,2,3,1,0,0,0,2,2,2;0,0,0,1,0,0,0,1,1,1\n");
  ASSERT_TRUE(b.ok) << codes(b.diags);
  EXPECT_EQ(b.scene.lights[0].type, "directional");
  EXPECT_EQ(b.scene.lights[0].direction, Eigen::Vector3d(0, 0, -1));
  EXPECT_EQ(b.scene.lights[0].position, Eigen::Vector3d(0, 0, 3));
  EXPECT_DOUBLE_EQ(b.scene.lights[0].coneAngle, 30);
  EXPECT_DOUBLE_EQ(b.scene.cameras[0].verticalFov, 175);
  ASSERT_EQ(b.scene.instancedVisuals[0].instances.size(), 2u);
  EXPECT_EQ(b.scene.instancedVisuals[0].instances[0].scale, Eigen::Vector3d(2, 2, 2));
}

TEST(Scene, CorpusScenesBuild) {
  fs::path dir = fs::path(RSCENE_SHARED_DIR) / "corpus";
  auto files = test::scenesIn(dir);
  if (files.empty()) GTEST_SKIP() << "../shared/corpus is absent";
  for (const fs::path& f : files) {
    LoadResult r = parse(test::readAll(f));
    ASSERT_TRUE(r.ok()) << f;
    Scene s;
    Diagnostics ds;
    SceneOptions opt;
    opt.sceneDir = f.parent_path().string();
    EXPECT_TRUE(buildScene(r.document, opt, s, ds)) << f << ": " << (ds.empty() ? "" : ds[0].message);
    EXPECT_FALSE(s.objects.empty() && s.materials.size() < 2 && s.lights.empty()) << f;
  }
}

namespace {

// An object line: a 1 x 1 x 1 static box at `position` (a "x y z" text),
// unrotated unless `orientation` says otherwise, under `parent`.
std::string boxLine(const std::string& path, const std::string& id, const std::string& position,
                    const std::string& parent, const std::string& orientation = "1 0 0 0") {
  return "object " + path + " box " + position + " " + orientation +
         " 1 1 1 0.5 1 1 default engine_default false true false - static true 1 1 id=" + id +
         " parentGroupId=" + parent + "\n";
}

}  // namespace

// Issue 10, item 8: transforms stopped inheriting, and a hidden group was
// no longer seen, past 64 levels.  At depth 100 both must still hold.
TEST(Scene, TransformsInheritAtDepth100) {
  std::string text = "raisim_engine_scene 2\ngroup /World id=w parentId=-\n";
  // A base yawed 90 degrees at (1, 0, 0), then 100 boxes each 1 m along
  // its parent's +x, which the yaw turns into world +y.
  text += boxLine("/World/b0", "b0", "1 0 0", "w", "0.7071067811865476 0 0 0.7071067811865476");
  for (int i = 1; i <= 100; ++i)
    text += boxLine("/World/b" + std::to_string(i), "b" + std::to_string(i), "1 0 0", "b" + std::to_string(i - 1));
  Built b = build(text);
  ASSERT_TRUE(b.ok) << codes(b.diags);
  ASSERT_EQ(b.scene.objects.size(), 101u);
  const Object& leaf = b.scene.objects.back();
  EXPECT_NEAR(leaf.world.position.x(), 1, 1e-9);
  EXPECT_NEAR(leaf.world.position.y(), 100, 1e-9);
  EXPECT_NEAR(leaf.world.position.z(), 0, 1e-9);
  EXPECT_NEAR(std::abs(leaf.world.orientation.w()), 0.7071067811865476, 1e-9);
  const Object& mid = b.scene.objects[50];
  EXPECT_NEAR(mid.world.position.y(), 50, 1e-9);
}

TEST(Scene, HiddenGroupSeenAtDepth100) {
  // g0 (hidden) > g1 > ... > g99 > leaf: the leaf is 100 levels under g0.
  // A second chain of the same depth under a visible group stays visible.
  std::string text = "raisim_engine_scene 2\n";
  for (const char* chain : {"h", "v"}) {
    std::string c = chain;
    text += "group /" + c + "0 id=" + c + "0 parentId=-" + (c == "h" ? " visible=false" : "") + "\n";
    for (int i = 1; i < 100; ++i)
      text += "group /" + c + std::to_string(i) + " id=" + c + std::to_string(i) + " parentId=" + c +
              std::to_string(i - 1) + "\n";
    text += boxLine("/" + c + "leaf", c + "leaf", "0 0 0", c + "99");
  }
  Built b = build(text);
  ASSERT_TRUE(b.ok) << codes(b.diags);
  ASSERT_EQ(b.scene.objects.size(), 2u);
  EXPECT_TRUE(b.scene.objects[0].hiddenByGroup);
  EXPECT_FALSE(b.scene.objects[1].hiddenByGroup);
}

TEST(Scene, ParentCyclesResolveWithoutHanging) {
  // a <- b <- a: lib/core reports the cycle; the scene model must still
  // come back, with finite poses, and a hidden group inside a cycle hides
  // every member and what hangs below them.
  std::string text = "raisim_engine_scene 2\n";
  text += boxLine("/a", "a", "1 0 0", "b");
  text += boxLine("/b", "b", "1 0 0", "a");
  text += boxLine("/c", "c", "1 0 0", "b");
  text += "group /g id=g parentId=k visible=false\ngroup /k id=k parentId=g\n";
  text += boxLine("/d", "d", "0 0 0", "k");
  Built b = build(text);
  ASSERT_EQ(b.scene.objects.size(), 4u);
  for (const Object& o : b.scene.objects) EXPECT_TRUE(o.world.position.allFinite()) << o.path;
  EXPECT_FALSE(b.scene.objects[0].hiddenByGroup);
  EXPECT_TRUE(b.scene.objects[3].hiddenByGroup);
  // c hangs below the cycle: it inherits from b, which keeps one level.
  EXPECT_NEAR(b.scene.objects[2].world.position.x(), 2, 1e-12);
}
