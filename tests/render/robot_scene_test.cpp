// Articulated records in the prepared render scene: the robot file loaded
// through lib/robot, the record's state read by robot::makeInstance, one
// drawable per visual element at its link's pose; visible=false, hidden
// groups, scale= and the errors a robot gives.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "asset/cache.hpp"
#include "core/loader.hpp"
#include "render/render_scene.hpp"

using namespace rscene;
using namespace rscene::render;

namespace {

// A two-link arm fixed to the world: a red 0.6 m box at the base, a green
// 0.4 m box 1 m up the arm (joint j1 about x); `arm` replaces the green
// box's geometry.
std::string armUrdf(const std::string& arm = R"(<box size="0.4 0.4 0.4"/>)") {
  return R"(<robot name="arm">
  <material name="red"><color rgba="0.9 0.05 0.05 1"/></material>
  <link name="world"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="base">
    <visual><geometry><box size="0.6 0.6 0.6"/></geometry><material name="red"/></visual>
  </link>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="1 0 0"/>
    <limit lower="-3" upper="3" effort="10" velocity="1"/>
  </joint>
  <link name="arm">
    <visual>
      <origin xyz="0 0 1"/>
      <geometry>)" + arm + R"(</geometry>
      <material name="green"><color rgba="0.05 0.9 0.05 1"/></material>
    </visual>
  </link>
</robot>
)";
}

// The same arm with a floating base (no `world` link).
std::string floatingUrdf() {
  std::string u = armUrdf();
  u.erase(u.find("  <link name=\"world\"/>"), std::string("  <link name=\"world\"/>\n").size());
  std::size_t j = u.find("  <joint name=\"fix\"");
  u.erase(j, u.find('\n', j) - j + 1);
  return u;
}

class RobotScene : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("rscene_robot_scene_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
    write("arm.urdf", armUrdf());
    write("floating.urdf", floatingUrdf());
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }

  struct Built {
    bool ok = false;
    RenderScene scene;
    Diagnostics diags;
  };

  // A scene with the arm's resources and `body` (articulated records).
  Built build(const std::string& body) {
    Built b;
    LoadResult loaded = parse("raisim_engine_scene 2\n"
                              "articulated_resource arm_res Arm arm.urdf\n"
                              "articulated_resource float_res Floating floating.urdf\n" +
                              body);
    EXPECT_TRUE(loaded.ok());
    SceneOptions so;
    so.sceneDir = dir_.string();
    b.ok = buildRenderScene(loaded.document, so, b.scene, b.diags);
    return b;
  }

  std::filesystem::path dir_;
};

std::string arm(const std::string& at, const std::string& keys = "", const std::string& flags = "true true") {
  return "articulated /World/Arm arm_res " + at + " 1 0 0 0 " + flags + " id=arm " + keys + "\n";
}

}  // namespace

TEST_F(RobotScene, EveryVisualAtItsLinkPose) {
  Built b = build(arm("5 0 0"));
  ASSERT_TRUE(b.ok) << (b.diags.empty() ? "" : b.diags[0].message);
  EXPECT_EQ(b.scene.robots, 1u);
  ASSERT_EQ(b.scene.drawables.size(), 2u);
  const Drawable& base = b.scene.drawables[0];
  const Drawable& tip = b.scene.drawables[1];
  EXPECT_EQ(base.shape, Shape::Box);
  EXPECT_TRUE(base.world.translation().isApprox(Eigen::Vector3d(5, 0, 0)));
  EXPECT_TRUE(tip.world.translation().isApprox(Eigen::Vector3d(5, 0, 1)));
  EXPECT_NEAR(tip.bounds.sizes().z(), 0.4, 1e-9);
  // Their URDF colours, not the default material.
  const RenderMaterial& red = b.scene.materials[std::size_t(base.material)];
  EXPECT_NEAR(red.color.x(), 0.9f, 1e-6);
  EXPECT_FALSE(red.isDefault);
  EXPECT_NEAR(b.scene.materials[std::size_t(tip.material)].color.y(), 0.9f, 1e-6);
  // Framing: the scene's bounds hold both links.
  EXPECT_TRUE(b.scene.bounds.contains(Eigen::Vector3d(5, 0, 1.15)));
  EXPECT_TRUE(b.scene.bounds.contains(Eigen::Vector3d(5, 0, -0.25)));
}

TEST_F(RobotScene, GeneralizedCoordinateTurnsTheJoint) {
  Built b = build(arm("5 0 0", "generalizedCoordinate=1.5707963267948966"));
  ASSERT_TRUE(b.ok);
  ASSERT_EQ(b.scene.drawables.size(), 2u);
  EXPECT_TRUE(b.scene.drawables[1].world.translation().isApprox(Eigen::Vector3d(5, -1, 0), 1e-9));
}

TEST_F(RobotScene, FloatingBaseStandsAtItsCoordinate) {
  Built b = build("articulated /World/F float_res 9 9 9 1 0 0 0 true true generalizedCoordinate=1,2,3,1,0,0,0,0\n");
  ASSERT_TRUE(b.ok);
  ASSERT_EQ(b.scene.drawables.size(), 2u);
  EXPECT_TRUE(b.scene.drawables[0].world.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  // Without a coordinate: the record's pose.
  Built r = build("articulated /World/F float_res 9 8 7 1 0 0 0 true true\n");
  ASSERT_TRUE(r.ok);
  EXPECT_TRUE(r.scene.drawables[0].world.translation().isApprox(Eigen::Vector3d(9, 8, 7)));
}

TEST_F(RobotScene, InvisibleAndHiddenGroupsDrawNothing) {
  Built off = build(arm("5 0 0", "", "false true"));
  ASSERT_TRUE(off.ok);
  EXPECT_TRUE(off.scene.drawables.empty());
  EXPECT_EQ(off.scene.robots, 0u);
  Built hidden = build("group /World id=w parentId=- visible=false\n" + arm("5 0 0", "parentGroupId=w"));
  ASSERT_TRUE(hidden.ok);
  EXPECT_TRUE(hidden.scene.drawables.empty());
}

TEST_F(RobotScene, ScaleScalesTheModel) {
  Built b = build(arm("5 0 0", "scale=2,2,2"));
  ASSERT_TRUE(b.ok);
  ASSERT_EQ(b.scene.drawables.size(), 2u);
  EXPECT_TRUE(b.scene.drawables[1].world.translation().isApprox(Eigen::Vector3d(5, 0, 2)));
  EXPECT_NEAR(b.scene.drawables[1].bounds.sizes().z(), 0.8, 1e-9);
}

TEST_F(RobotScene, SixteenRobotsLoadTheFileOnce) {
  std::string body;
  for (int i = 0; i < 16; ++i)
    body += "articulated /World/Arm" + std::to_string(i) + " arm_res " + std::to_string(i) + " 0 0 1 0 0 0 true true\n";
  Built b = build(body);
  ASSERT_TRUE(b.ok);
  EXPECT_EQ(b.scene.robots, 16u);
  EXPECT_EQ(b.scene.drawables.size(), 32u);
  // One material per URDF colour, however many robots.
  EXPECT_EQ(b.scene.materials.size(), 3u);  // the engine default, red, green
}

TEST_F(RobotScene, WrongCoordinateLengthIsAnError) {
  Built b = build(arm("5 0 0", "generalizedCoordinate=0,0"));
  EXPECT_FALSE(b.ok);
  ASSERT_FALSE(b.diags.empty());
  EXPECT_EQ(b.diags[0].code, "RS7040");
  EXPECT_EQ(b.diags[0].line, 4u);
}

TEST_F(RobotScene, MissingRobotFileIsAnError) {
  Built b = build("articulated_resource gone_res Gone gone.urdf\narticulated /World/G gone_res 0 0 0 1 0 0 0 true true\n");
  EXPECT_FALSE(b.ok);
  ASSERT_FALSE(b.diags.empty());
  EXPECT_EQ(b.diags[0].code, "RS5001");
  EXPECT_EQ(b.diags[0].line, 4u);  // the resource's path, where validate --check-files reports it
  EXPECT_TRUE(b.diags[0].file.empty());
  EXPECT_EQ(b.diags[0].message, "robot file '" + (dir_ / "gone.urdf").string() + "' does not exist");
  EXPECT_EQ(b.scene.robots, 0u);
}

TEST_F(RobotScene, ModelWithoutVisualsWarns) {
  write("bare.urdf", R"(<robot name="bare"><link name="world"/>
  <joint name="f" type="fixed"><parent link="world"/><child link="b"/></joint>
  <link name="b"><collision><geometry><sphere radius="0.1"/></geometry></collision></link></robot>
)");
  Built b = build("articulated_resource bare_res Bare bare.urdf\narticulated /World/B bare_res 0 0 0 1 0 0 0 true true\n");
  EXPECT_TRUE(b.ok);
  ASSERT_EQ(b.diags.size(), 1u);
  EXPECT_EQ(b.diags[0].severity, Severity::Warning);
  EXPECT_EQ(b.diags[0].code, "RS9030");
  EXPECT_EQ(b.diags[0].message, "articulated system '/World/B' draws nothing: its model 'bare' has no visual elements");
  EXPECT_EQ(b.diags[0].line, 5u);
}

TEST_F(RobotScene, AnymalStandsOnTheGroundWithItsTexturedMeshes) {
  std::filesystem::path urdf = std::filesystem::path(RSCENE_SHARED_DIR) / "corpus/robots/anymal_c/urdf/anymal.urdf";
  if (!std::filesystem::exists(urdf)) GTEST_SKIP() << "no ../shared corpus";
  LoadResult loaded = parse("raisim_engine_scene 2\narticulated_resource anymal ANYmal " + urdf.string() +
                            "\narticulated /World/A anymal 0 0 0.54 1 0 0 0 true true generalizedCoordinate=0,0,0.54,1,"
                            "0,0,0,0.03,0.4,-0.8,-0.03,0.4,-0.8,0.03,-0.4,0.8,-0.03,-0.4,0.8\n");
  ASSERT_TRUE(loaded.ok());
  asset::AssetCache assets;
  RenderScene scene;
  Diagnostics diags;
  ASSERT_TRUE(buildRenderScene(loaded.document, {}, scene, diags, {}, &assets));
  EXPECT_TRUE(diags.empty()) << diags[0].message;
  // 46 visual elements, 45 of them COLLADA meshes.
  EXPECT_EQ(scene.drawables.size(), 46u);
  // Standing: the feet reach the ground (the pose leaves them 1.7 cm in it,
  // where the simulation settles them), the lidar's antenna 0.82 m up, the
  // body about 1.05 m long and 0.7 m wide.  A COLLADA file turned to y-up
  // (assimp's default) or a wrong joint axis shows here.
  EXPECT_NEAR(scene.bounds.min().z(), -0.017, 0.01);
  EXPECT_NEAR(scene.bounds.max().z(), 0.82, 0.02);
  EXPECT_NEAR(scene.bounds.sizes().x(), 1.05, 0.03);
  EXPECT_NEAR(scene.bounds.sizes().y(), 0.71, 0.03);
  // Every mesh with its JPEG (or PNG) texture and a UV per vertex: the
  // texture paths assimp gives resolve relative to the mesh file.
  int meshes = 0, textured = 0;
  for (const Drawable& d : scene.drawables) {
    if (d.shape != Shape::Mesh) continue;
    ++meshes;
    std::string err;
    auto m = assets.mesh(d.meshPath, asset::MeshContent::Surface, &err);
    ASSERT_TRUE(m) << err;
    EXPECT_TRUE(m->warnings.empty()) << m->warnings[0];
    bool any = false;
    for (const asset::MeshPart& p : m->parts) any = any || (p.material.texture && p.uvs.size() == p.vertexCount() * 2);
    textured += any;
  }
  EXPECT_EQ(meshes, 45);
  EXPECT_EQ(textured, meshes);
}

TEST_F(RobotScene, MjcfGeomsInTheirRgba) {
  // MuJoCo's compiler turns fromto into a capsule of half-length 0.5 along
  // the segment; the model gives its full length between the sphere centres.
  write("rod.xml", R"(<mujoco model="rod"><worldbody>
  <body name="rod" pos="0 0 1">
    <geom type="capsule" fromto="0 0 0 0 0 1" size="0.1" rgba="0.1 0.2 0.9 1"/>
    <geom type="box" pos="0.5 0 0" size="0.1 0.2 0.3"/>
  </body></worldbody></mujoco>
)");
  Built b = build("articulated_resource rod_res Rod rod.xml\narticulated /World/Rod rod_res 2 0 0 1 0 0 0 true true\n");
  ASSERT_TRUE(b.ok) << (b.diags.empty() ? "" : b.diags[0].message);
  ASSERT_EQ(b.scene.drawables.size(), 2u);
  const Drawable& rod = b.scene.drawables[0];
  EXPECT_EQ(rod.shape, Shape::Capsule);
  EXPECT_NEAR(rod.capsuleRadius, 0.1, 1e-9);
  EXPECT_NEAR(rod.capsuleHeight, 1.0, 1e-9);
  EXPECT_NEAR(rod.bounds.min().z(), 0.9, 1e-6);  // from z = 1 (the body) - 0.1 to 2 + 0.1, at x = 2
  EXPECT_NEAR(rod.bounds.max().z(), 2.1, 1e-6);
  EXPECT_NEAR(rod.bounds.center().x(), 2.0, 1e-6);
  EXPECT_NEAR(b.scene.materials[std::size_t(rod.material)].color.z(), 0.9f, 1e-6);
  // A box's MJCF half sizes become full sides.
  EXPECT_NEAR(b.scene.drawables[1].bounds.sizes().z(), 0.6, 1e-6);
}

// Trajectories move drawables through their attachments (poseScene): a
// robot's visuals follow their links, a dynamic object its body, a static
// one stays; each record is one segmentation legend entry.
TEST_F(RobotScene, DrawablesFollowTheirBodiesAndLinks) {
  Built b = build(arm("5 0 0") +
                  "object /World/Crate box 0 0 1 1 0 0 0 1 1 1 0 0 1 default engine_default false true false - dynamic true "
                  "1 18446744073709551615 id=crate semanticClass=crate\n"
                  "object /World/Wall box 0 3 1 1 0 0 0 1 1 1 0 0 1 default engine_default false true true - static true "
                  "1 18446744073709551615 id=wall segmentationColor=1,0,0\n");
  ASSERT_TRUE(b.ok) << (b.diags.empty() ? "" : b.diags[0].message);
  ASSERT_EQ(b.scene.drawables.size(), 4u);  // crate, wall, the arm's two links
  const Drawable& crate = b.scene.drawables[0];
  const Drawable& wall = b.scene.drawables[1];
  EXPECT_EQ(crate.attachment.kind, Mount::Kind::Object);
  EXPECT_EQ(wall.attachment.kind, Mount::Kind::World);  // static: never moves
  EXPECT_EQ(b.scene.drawables[3].attachment.kind, Mount::Kind::Articulated);
  EXPECT_EQ(b.scene.drawables[3].attachment.link, 2);  // world, base, arm
  // Legend: the wall's written red; the crate's from its class; one entry
  // for both links of the arm.
  ASSERT_EQ(b.scene.segments.size(), 3u);
  const Segment& wallSeg = b.scene.segments[std::size_t(wall.segment)];
  EXPECT_EQ(wallSeg.rgb[0], 255);
  EXPECT_EQ(wallSeg.rgb[1], 0);
  EXPECT_EQ(b.scene.drawables[2].segment, b.scene.drawables[3].segment);
  EXPECT_EQ(b.scene.segments[std::size_t(b.scene.drawables[3].segment)].path, "/World/Arm");
  std::uint8_t again[3];
  segmentColor(std::nullopt, -1, "crate", "/elsewhere", again);  // the class decides, not the path
  const Segment& crateSeg = b.scene.segments[std::size_t(crate.segment)];
  EXPECT_EQ(std::vector<int>(again, again + 3), std::vector<int>(crateSeg.rgb, crateSeg.rgb + 3));
  EXPECT_TRUE(crateSeg.rgb[0] >= 32 && crateSeg.rgb[1] >= 32 && crateSeg.rgb[2] >= 32);
  // Instance ids count within a class: instance 1 of two classes differ,
  // of one class agree wherever the record is.
  std::uint8_t box1[3], person1[3], box1b[3];
  segmentColor(std::nullopt, 1, "box", "/a", box1);
  segmentColor(std::nullopt, 1, "person", "/a", person1);
  segmentColor(std::nullopt, 1, "box", "/b", box1b);
  EXPECT_NE(std::vector<int>(box1, box1 + 3), std::vector<int>(person1, person1 + 3));
  EXPECT_EQ(std::vector<int>(box1, box1 + 3), std::vector<int>(box1b, box1b + 3));
  // Move the crate up 2 m and turn the arm's link half a turn about x.
  std::vector<Pose> objects = {Pose{Eigen::Vector3d(0, 0, 3), Eigen::Quaterniond::Identity()}, Pose{}};
  std::vector<std::vector<Pose>> links(1);
  links[0] = {Pose{}, Pose{Eigen::Vector3d(5, 0, 0), Eigen::Quaterniond::Identity()},
              Pose{Eigen::Vector3d(5, 0, 0), Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()))}};
  BodyPoseView view{&objects, nullptr, &links};
  poseScene(b.scene, view);
  EXPECT_TRUE(crate.world.translation().isApprox(Eigen::Vector3d(0, 0, 3))) << crate.world.translation().transpose();
  EXPECT_NEAR(crate.bounds.min().z(), 2.5, 1e-9);
  EXPECT_TRUE(wall.world.translation().isApprox(Eigen::Vector3d(0, 3, 1)));
  // The green box, 1 m up the arm, is now 1 m below the joint.
  EXPECT_TRUE(b.scene.drawables[3].world.translation().isApprox(Eigen::Vector3d(5, 0, -1), 1e-9))
      << b.scene.drawables[3].world.translation().transpose();
  EXPECT_TRUE(b.scene.bounds.contains(Eigen::Vector3d(5, 0, -1)));
}
