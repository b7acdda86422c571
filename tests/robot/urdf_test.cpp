// URDF loading (lib/robot/urdf.cpp, urdf_tree.cpp, robot_paths.cpp,
// load.cpp): hand-written fixtures under tests/data/robots/urdf/ for every
// element and every error or warning (lines asserted), file trees built in
// a temporary directory for package:// and module search, and the real
// robots of ../shared/corpus/robots (skipped when absent).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "core/io.hpp"
#include "robot/instance.hpp"
#include "robot/kinematics.hpp"
#include "robot/load.hpp"
#include "robot/robot_paths.hpp"
#include "scene/scene.hpp"

namespace rscene::robot {
namespace {

namespace fs = std::filesystem;

const std::string kFixtures = std::string(RSCENE_TEST_DATA) + "/robots/urdf/";
const std::string kRobots = std::string(RSCENE_SHARED_DIR) + "/corpus/robots/";
// RaiSim's joint order of ANYmal C, and of our quadruped built like it.
const std::vector<std::string> kAnymalJoints = {"LF_HAA", "LF_HFE", "LF_KFE", "RF_HAA", "RF_HFE", "RF_KFE",
                                                "LH_HAA", "LH_HFE", "LH_KFE", "RH_HAA", "RH_HFE", "RH_KFE"};

bool load(const std::string& path, Model& m, Diagnostics& d, const LoadOptions& o = {}) {
  return loadModel(path, o, m, d);
}

// "CODE:line" of every diagnostic, for exact comparisons.
std::vector<std::string> codesAndLines(const Diagnostics& ds) {
  std::vector<std::string> out;
  for (const Diagnostic& d : ds) out.push_back(d.code + ":" + std::to_string(d.line));
  return out;
}

std::string messages(const Diagnostics& ds) {
  std::string out;
  for (const Diagnostic& d : ds) out += d.file + ":" + std::to_string(d.line) + ": " + d.message + " [" + d.code + "]\n";
  return out;
}

// A scratch directory removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "rscene-urdf-XXXXXX").string();
    std::vector<char> buf(pattern.begin(), pattern.end());
    buf.push_back('\0');
    path_ = ::mkdtemp(buf.data());
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string path() const { return path_; }
  std::string write(const std::string& rel, const std::string& text) const {
    fs::path p = fs::path(path_) / rel;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p.string();
  }

 private:
  std::string path_;
};

const std::string kOneMeshRobot = R"(<robot name="m">
  <link name="base">
    <collision>
      <geometry>
        <mesh filename="package://pkg/meshes/part.stl" scale="2"/>
      </geometry>
    </collision>
  </link>
</robot>
)";

// ---------------------------------------------------------------------------
// Elements

TEST(Urdf, ReadsEveryElementOfTheTwoLinkArm) {
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load(kFixtures + "two_link.urdf", m, d)) << messages(d);
  EXPECT_TRUE(d.empty()) << messages(d);
  EXPECT_EQ(m.name, "two_link");
  EXPECT_FALSE(m.floatingBase);  // root link `world`
  EXPECT_EQ(m.links[static_cast<std::size_t>(m.root)].name, "world");
  ASSERT_EQ(m.links.size(), 5u);
  ASSERT_EQ(m.joints.size(), 4u);

  const Link& base = m.links[static_cast<std::size_t>(m.findLink("base"))];
  EXPECT_EQ(base.line, 13);
  EXPECT_DOUBLE_EQ(base.inertial.mass, 2);
  EXPECT_DOUBLE_EQ(base.inertial.origin.position.z(), 0.05);
  Eigen::Matrix3d inertia;
  inertia << 0.1, 0.01, 0.02, 0.01, 0.2, 0.03, 0.02, 0.03, 0.3;
  EXPECT_TRUE(base.inertial.inertia.isApprox(inertia));
  ASSERT_EQ(base.visuals.size(), 1u);
  const Visual& body = base.visuals[0];
  EXPECT_EQ(body.name, "body");
  EXPECT_EQ(body.line, 19);
  EXPECT_EQ(body.geometry.kind, GeometryKind::Box);
  EXPECT_TRUE(body.geometry.size.isApprox(Eigen::Vector3d(0.2, 0.3, 0.1)));
  EXPECT_EQ(body.materialName, "blue");
  ASSERT_TRUE(body.color.has_value());  // the top-level material by name
  EXPECT_TRUE(body.color->isApprox(Eigen::Vector4d(0, 0, 1, 1)));
  ASSERT_EQ(base.collisions.size(), 1u);
  EXPECT_EQ(base.collisions[0].geometry.kind, GeometryKind::Capsule);
  EXPECT_DOUBLE_EQ(base.collisions[0].geometry.length, 0.4);  // RaiSim's height: between sphere centres
  EXPECT_DOUBLE_EQ(base.collisions[0].geometry.radius, 0.05);

  const Link& arm = m.links[static_cast<std::size_t>(m.findLink("arm"))];
  ASSERT_EQ(arm.visuals.size(), 1u);
  EXPECT_EQ(arm.visuals[0].geometry.kind, GeometryKind::Cylinder);
  EXPECT_DOUBLE_EQ(arm.visuals[0].geometry.length, 0.5);
  ASSERT_TRUE(arm.visuals[0].color.has_value());  // inline colour
  EXPECT_TRUE(arm.visuals[0].color->isApprox(Eigen::Vector4d(1, 0.5, 0, 0.5)));
  ASSERT_EQ(arm.collisions.size(), 1u);
  EXPECT_EQ(arm.collisions[0].geometry.kind, GeometryKind::Sphere);
  EXPECT_DOUBLE_EQ(arm.collisions[0].origin.position.z(), -0.25);

  const Joint& shoulder = m.joints[static_cast<std::size_t>(m.findJoint("shoulder"))];
  EXPECT_EQ(shoulder.type, JointType::Revolute);
  EXPECT_EQ(shoulder.line, 32);
  EXPECT_TRUE(shoulder.axis.isApprox(Eigen::Vector3d::UnitY()));  // normalised
  EXPECT_TRUE(shoulder.hasLimits);
  EXPECT_DOUBLE_EQ(shoulder.lower, -1.5);
  EXPECT_DOUBLE_EQ(shoulder.upper, 1.5);
  EXPECT_DOUBLE_EQ(shoulder.effort, 30);
  EXPECT_DOUBLE_EQ(shoulder.velocity, 4);
  EXPECT_DOUBLE_EQ(shoulder.damping, 0.5);
  EXPECT_DOUBLE_EQ(shoulder.friction, 0.1);
  EXPECT_DOUBLE_EQ(shoulder.rotorInertia, 0.002);
  EXPECT_DOUBLE_EQ(shoulder.stiffness, 3);
  EXPECT_EQ(shoulder.springMount, std::vector<double>{0.25});

  const Joint& slide = m.joints[static_cast<std::size_t>(m.findJoint("slide"))];
  EXPECT_EQ(slide.type, JointType::Prismatic);
  EXPECT_TRUE(slide.axis.isApprox(-Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(slide.hasLimits);
  const Joint& spin = m.joints[static_cast<std::size_t>(m.findJoint("spin"))];
  EXPECT_EQ(spin.type, JointType::Continuous);
  EXPECT_FALSE(spin.hasLimits);  // a continuous joint's <limit> has no position bounds
  EXPECT_TRUE(spin.axis.isApprox(Eigen::Vector3d::UnitX()));  // URDF's default axis
  EXPECT_DOUBLE_EQ(spin.effort, 5);

  Coordinates c;
  ASSERT_TRUE(makeCoordinates(m, {}, c).empty());
  EXPECT_EQ(c.coordinateDim, 3);  // fixed base: joints only
  EXPECT_DOUBLE_EQ(m.totalMass(), 3);
}

TEST(Urdf, RollPitchYawIsFixedAxisZYX) {
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load(kFixtures + "two_link.urdf", m, d));
  const Joint& shoulder = m.joints[static_cast<std::size_t>(m.findJoint("shoulder"))];
  // rpy="0.1 0.2 0.3": roll about x first, then pitch about the fixed y,
  // then yaw about the fixed z, written out as matrices.
  double r = 0.1, p = 0.2, y = 0.3;
  Eigen::Matrix3d rx, ry, rz;
  rx << 1, 0, 0, 0, std::cos(r), -std::sin(r), 0, std::sin(r), std::cos(r);
  ry << std::cos(p), 0, std::sin(p), 0, 1, 0, -std::sin(p), 0, std::cos(p);
  rz << std::cos(y), -std::sin(y), 0, std::sin(y), std::cos(y), 0, 0, 0, 1;
  EXPECT_TRUE(shoulder.origin.orientation.toRotationMatrix().isApprox(rz * ry * rx, 1e-12));
  EXPECT_TRUE(shoulder.origin.position.isApprox(Eigen::Vector3d(0.1, 0, 0)));
}

TEST(Urdf, SkipsWhatCannotBeUsedWithWarningsAndKeepsTheRobot) {
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load(kFixtures + "skipped.urdf", m, d)) << messages(d);
  EXPECT_EQ(codesAndLines(d), (std::vector<std::string>{"RS7031:4", "RS7031:9", "RS7031:13", "RS7031:18",
                                                         "RS7031:23", "RS7031:33", "RS7031:40", "RS7031:42",
                                                         "RS7031:45", "RS7031:48", "RS7031:54"}))
      << messages(d);
  for (const Diagnostic& x : d) {
    EXPECT_EQ(x.severity, Severity::Warning);
    EXPECT_EQ(x.file, kFixtures + "skipped.urdf");
  }
  EXPECT_NE(d[1].message.find("${base_mass}"), std::string::npos) << d[1].message;
  EXPECT_NE(d[3].message.find("<heightfield>"), std::string::npos) << d[3].message;
  EXPECT_NE(d[5].message.find("meshes/not_here.stl"), std::string::npos) << d[5].message;
  const Link& base = m.links[static_cast<std::size_t>(m.findLink("base"))];
  EXPECT_EQ(base.inertial.mass, 0);   // the xacro mass skipped the inertial
  EXPECT_TRUE(base.visuals.empty());  // all three visuals skipped
  ASSERT_EQ(base.collisions.size(), 1u);
  EXPECT_EQ(base.collisions[0].line, 26);
  const Joint& j = m.joints[0];
  EXPECT_TRUE(j.origin.position.isZero());  // the xacro origin ignored
  EXPECT_TRUE(j.axis.isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_EQ(m.links[static_cast<std::size_t>(m.findLink("leg"))].sensorSet, "imu_set.xml");
  ASSERT_EQ(m.sensors.size(), 1u);  // from sensors/imu_set.xml
  EXPECT_EQ(m.sensors[0].link, m.findLink("leg"));
  EXPECT_FALSE(m.joints[static_cast<std::size_t>(m.findJoint("k"))].hasLimits);  // lower above upper: dropped
  EXPECT_TRUE(m.floatingBase);
}

struct ErrorCase {
  const char* file;
  const char* code;
  int line;
  const char* words;  // a piece of the message
};

TEST(Urdf, ErrorsNameTheFileAndLine) {
  const ErrorCase cases[] = {
      // At the end tag that does not match (tinyxml2 names the line of <visual>).
      {"bad_xml.urdf", "RS7030", 4, "(mismatched element: </link> does not close <visual> (opened at line 3))"},
      {"unknown_link.urdf", "RS7032", 8, "child link 'c' that does not exist"},
      {"two_parents.urdf", "RS7032", 13, "link 'c' has two parent joints: 'ac' (line 9) and 'bc'"},
      {"cycle.urdf", "RS7032", 9, "closes a cycle"},
      {"two_roots.urdf", "RS7032", 3, "two root links, 'a' (line 2) and 'b'"},
      {"floating_below.urdf", "RS7032", 4, "floating joint 'free'"},
      {"missing_collision_mesh.urdf", "RS5001", 5, "collision mesh 'package://nowhere/meshes/hull.stl' not found"},
      {"bad_values.urdf", "RS7030", 4, "<mass value> is 'heavy', not 1 finite number"},
  };
  for (const ErrorCase& c : cases) {
    SCOPED_TRACE(c.file);
    Model m;
    Diagnostics d;
    EXPECT_FALSE(load(kFixtures + c.file, m, d));
    ASSERT_FALSE(d.empty());
    const Diagnostic& first = d.front();
    EXPECT_EQ(first.severity, Severity::Error);
    EXPECT_EQ(first.code, c.code) << messages(d);
    EXPECT_EQ(first.line, static_cast<std::uint32_t>(c.line)) << messages(d);
    EXPECT_EQ(first.file, kFixtures + c.file);
    EXPECT_NE(first.message.find(c.words), std::string::npos) << first.message;
  }
}

TEST(Urdf, EveryErrorOfAFileIsReported) {
  Model m;
  Diagnostics d;
  EXPECT_FALSE(load(kFixtures + "bad_values.urdf", m, d));
  // The bad mass and the unsupported joint type, both in one run.
  EXPECT_EQ(codesAndLines(d), (std::vector<std::string>{"RS7030:4", "RS7030:8"})) << messages(d);
  EXPECT_NE(d[1].message.find("type 'planar'"), std::string::npos) << d[1].message;
}

TEST(Urdf, DuplicateNamesAreErrorsNamingTheFirst) {
  Model m;
  Diagnostics d;
  EXPECT_FALSE(load(kFixtures + "duplicates.urdf", m, d));
  // The second joint `j` is a duplicate even though the first one named a
  // link that does not exist (found by fuzzing: it once read past the end).
  EXPECT_EQ(codesAndLines(d), (std::vector<std::string>{"RS7032:4", "RS7032:5", "RS7032:9"})) << messages(d);
  EXPECT_NE(d[0].message.find("link 'a' declared twice (first at line 2)"), std::string::npos) << d[0].message;
  EXPECT_NE(d[2].message.find("joint 'j' declared twice (first at line 5)"), std::string::npos) << d[2].message;
}

TEST(Urdf, FloatingJointFromWorldMakesAFloatingBase) {
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load(kFixtures + "floating_root.urdf", m, d)) << messages(d);
  EXPECT_TRUE(m.floatingBase);
  EXPECT_EQ(m.links[static_cast<std::size_t>(m.root)].name, "base");
  EXPECT_EQ(m.findLink("world"), -1);
  EXPECT_EQ(m.findJoint("free"), -1);
  Coordinates c;
  makeCoordinates(m, {}, c);
  EXPECT_EQ(c.coordinateDim, 8);
  EXPECT_EQ(c.velocityDim, 7);
  EXPECT_DOUBLE_EQ(m.totalMass(), 3);
}

TEST(Urdf, LongChainNeedsNoRecursion) {
  // 20 000 links, each one joint below the last: read, checked and walked
  // with explicit stacks, so depth costs no call stack.
  TempDir t;
  std::ostringstream text;
  text << "<robot name=\"chain\">\n<link name=\"l0\"/>\n";
  const int n = 20000;
  for (int i = 1; i < n; ++i)
    text << "<link name=\"l" << i << "\"/><joint name=\"j" << i << "\" type=\"revolute\"><parent link=\"l"
         << i - 1 << "\"/><child link=\"l" << i << "\"/><origin xyz=\"0 0 -0.1\"/></joint>\n";
  text << "</robot>\n";
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load(t.write("chain.urdf", text.str()), m, d)) << messages(d);
  Coordinates c;
  makeCoordinates(m, {}, c);
  EXPECT_EQ(c.coordinateDim, 7 + n - 1);
  Eigen::VectorXd q = neutralCoordinate(m, c, Pose{});
  EXPECT_NEAR(linkPoses(m, c, Pose{}, q).back().position.z(), -0.1 * (n - 1), 1e-6);
}

TEST(Urdf, FloatingJointFromAWorldWithOtherChildrenIsAnError) {
  TempDir t;
  Model m;
  Diagnostics d;
  EXPECT_FALSE(load(t.write("w.urdf", R"(<robot name="w">
  <link name="world"/>
  <link name="a"/>
  <link name="b"/>
  <joint name="free" type="floating"><parent link="world"/><child link="a"/></joint>
  <joint name="bolt" type="fixed"><parent link="world"/><child link="b"/></joint>
</robot>
)"),
                    m, d));
  EXPECT_EQ(codesAndLines(d), std::vector<std::string>{"RS7032:5"}) << messages(d);
}

TEST(Urdf, NotARobotFile) {
  TempDir t;
  Model m;
  Diagnostics d;
  EXPECT_FALSE(load(t.write("x.xml", "<scene>\n</scene>\n"), m, d));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].code, "RS7030");
  EXPECT_NE(d[0].message.find("<scene>"), std::string::npos);
  d.clear();
  EXPECT_FALSE(load(t.path() + "/absent.urdf", m, d));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].code, "RS5001");
  EXPECT_NE(d[0].message.find("does not exist"), std::string::npos);
}

TEST(Urdf, RefusesDirectoriesDevicesFifosAndFilesOverTheCap) {
  TempDir t;
  Model m;
  for (const std::string& path : {t.path(), std::string("/dev/zero")}) {
    Diagnostics d;
    EXPECT_FALSE(load(path, m, d));
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(d[0].code, "RS5001") << path;
  }
  std::string fifo = t.path() + "/pipe.urdf";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  Diagnostics d;
  EXPECT_FALSE(load(fifo, m, d));  // returns at once: a FIFO is never opened for reading
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NE(d[0].message.find("FIFO"), std::string::npos) << d[0].message;

  LoadOptions small;
  small.maxFileBytes = 100;
  d.clear();
  EXPECT_FALSE(load(kFixtures + "two_link.urdf", m, d, small));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].code, "RS7030");
  EXPECT_NE(d[0].message.find("larger than"), std::string::npos) << d[0].message;
}

TEST(Urdf, MjcfRootGoesToTheMjcfLoader) {
  TempDir t;
  Model m;
  Diagnostics d;
  // Whatever the MJCF loader decides, it is asked: the URDF reader would
  // say "not <robot>".
  load(t.write("m.xml", "<mujoco model=\"x\">\n  <worldbody/>\n</mujoco>\n"), m, d);
  for (const Diagnostic& x : d) EXPECT_EQ(x.message.find("not <robot>"), std::string::npos) << x.message;
}

// ---------------------------------------------------------------------------
// Paths

TEST(UrdfPaths, PackageResolvesAgainstTheResourceDirectoryFirst) {
  TempDir t;
  std::string urdf = t.write("ws/pkg/urdf/robot.urdf", kOneMeshRobot);
  std::string inPackage = t.write("ws/pkg/meshes/part.stl", "solid x\nendsolid x\n");
  std::string inResources = t.write("res/meshes/part.stl", "solid x\nendsolid x\n");
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load(urdf, m, d)) << messages(d);
  // No resource directory: walking up from urdf/ finds pkg/meshes/part.stl.
  EXPECT_EQ(fs::path(m.links[0].collisions[0].geometry.meshPath), fs::path(inPackage));
  EXPECT_TRUE(m.links[0].collisions[0].geometry.meshScale.isApprox(Eigen::Vector3d::Constant(2)));
  LoadOptions o;
  o.resourceDirectory = t.path() + "/res";
  ASSERT_TRUE(load(urdf, m, d, o)) << messages(d);
  EXPECT_EQ(fs::path(m.links[0].collisions[0].geometry.meshPath), fs::path(inResources));
}

TEST(UrdfPaths, PackageNameFolderFoundWalkingUp) {
  TempDir t;
  std::string urdf = t.write("ws/src/robots/urdf/robot.urdf", kOneMeshRobot);
  // A workspace layout: ws/src/pkg/meshes, found as DIR/NAME/REST from ws/src.
  std::string mesh = t.write("ws/src/pkg/meshes/part.stl", "solid x\nendsolid x\n");
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load(urdf, m, d)) << messages(d);
  EXPECT_EQ(fs::path(m.links[0].collisions[0].geometry.meshPath), fs::path(mesh));
}

TEST(UrdfPaths, CandidatesInRaiSimOrder) {
  RobotPaths p{"/res", "/a/b"};
  EXPECT_EQ(meshCandidates(p, "/a/b", "package://pkg/m/x.dae"),
            (std::vector<std::string>{"/res/m/x.dae", "/res/pkg/m/x.dae", "/a/b/m/x.dae", "/a/b/pkg/m/x.dae",
                                      "/a/m/x.dae", "/a/pkg/m/x.dae", "/m/x.dae", "/pkg/m/x.dae"}));
  EXPECT_EQ(meshCandidates(p, "/a/b", "../meshes/x.stl"),
            (std::vector<std::string>{"/a/meshes/x.stl", "/meshes/x.stl"}));
  EXPECT_EQ(meshCandidates(p, "/a/b", "/abs/x.stl"), std::vector<std::string>{"/abs/x.stl"});
  EXPECT_EQ(meshCandidates(p, "/a/b", "file:///abs/x.stl"), std::vector<std::string>{"/abs/x.stl"});
  EXPECT_EQ(moduleCandidates(p, "cam.xml"),
            (std::vector<std::string>{"/res/cam.xml", "/res/modules/cam.xml", "/modules/cam.xml",
                                      "/res/module/cam.xml", "/module/cam.xml"}));
  EXPECT_EQ(moduleCandidates(RobotPaths{"", "/a/b"}, "cam.xml").front(), "/a/b/cam.xml");
  EXPECT_EQ(moduleCandidates(p, "/abs/cam.xml"), std::vector<std::string>{"/abs/cam.xml"});
}

TEST(UrdfPaths, TextureOfANamedMaterialResolvesLikeAMesh) {
  TempDir t;
  std::string urdf = t.write("pkg/urdf/r.urdf", R"(<robot name="t">
  <link name="base">
    <visual>
      <geometry><box size="1 1 1"/></geometry>
      <material name="skin"/>
    </visual>
    <visual>
      <geometry><box size="1 1 1"/></geometry>
      <material name="gone"/>
    </visual>
  </link>
  <material name="skin">
    <texture filename="package://pkg/textures/skin.png"/>
  </material>
  <material name="gone">
    <texture filename="textures/gone.png"/>
  </material>
</robot>
)");
  std::string png = t.write("pkg/textures/skin.png", "not really a png");
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load(urdf, m, d)) << messages(d);
  EXPECT_EQ(fs::path(m.links[0].visuals[0].texture), fs::path(png));
  EXPECT_TRUE(m.links[0].visuals[1].texture.empty());
  EXPECT_EQ(codesAndLines(d), std::vector<std::string>{"RS7031:15"}) << messages(d);  // the material's line
}

// ---------------------------------------------------------------------------
// Modules

const std::string kModule = R"(<?xml version="1.0"?>
<robot>
  <joint name="cam_mount" type="fixed">
    <parent link="base"/>
    <child link="camera"/>
    <origin xyz="0.3 0 0.1"/>
  </joint>
  <link name="camera">
    <inertial>
      <mass value="0.25"/>
    </inertial>
    <visual>
      <geometry><box size="0.1 0.1 ${w}"/></geometry>
    </visual>
  </link>
</robot>
)";

const std::string kBase = R"(<robot name="b">
  <link name="base">
    <inertial>
      <mass value="1"/>
    </inertial>
  </link>
</robot>
)";

TEST(UrdfModules, InsertedAndFoundInRaiSimOrder) {
  TempDir t;
  std::string urdf = t.write("robot/urdf/r.urdf", kBase);
  // Found in BASE/../modules only: the 4th place of the search order.
  std::string module = t.write("robot/modules/cam.xml", kModule);
  LoadOptions o;
  o.modules = {"cam.xml"};
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load(urdf, m, d, o)) << messages(d);
  EXPECT_DOUBLE_EQ(m.totalMass(), 1.25);
  int cam = m.findLink("camera");
  ASSERT_GE(cam, 0);
  EXPECT_EQ(m.links[static_cast<std::size_t>(cam)].file, fs::path(module).lexically_normal().string());
  EXPECT_EQ(m.links[static_cast<std::size_t>(cam)].line, 8);
  EXPECT_TRUE(m.links[static_cast<std::size_t>(m.findLink("base"))].file.empty());
  // The warning inside the module names the module and its line.
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].code, "RS7031");
  EXPECT_EQ(d[0].file, m.links[static_cast<std::size_t>(cam)].file);
  EXPECT_EQ(d[0].line, 13u);

  // An earlier place of the order wins: BASE/modules over BASE/../modules.
  t.write("robot/urdf/modules/cam.xml",  // a fragment with two top-level elements, no <robot>
          "<link name=\"camera\"/>\n<joint name=\"j\" type=\"fixed\"><parent link=\"base\"/>"
          "<child link=\"camera\"/></joint>\n");
  d.clear();
  ASSERT_TRUE(load(urdf, m, d, o)) << messages(d);
  EXPECT_TRUE(d.empty()) << messages(d);
  EXPECT_DOUBLE_EQ(m.totalMass(), 1);
  EXPECT_NE(m.findJoint("j"), -1);
}

TEST(UrdfModules, ResourceDirectoryIsTheBaseWhenGiven) {
  TempDir t;
  std::string urdf = t.write("robot/urdf/r.urdf", kBase);
  t.write("res/module/cam.xml", kModule);
  LoadOptions o;
  o.modules = {"cam.xml"};
  o.resourceDirectory = t.path() + "/res";
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load(urdf, m, d, o)) << messages(d);
  EXPECT_NE(m.findLink("camera"), -1);
}

TEST(UrdfModules, MissingModuleIsAnError) {
  TempDir t;
  std::string urdf = t.write("r.urdf", kBase);
  LoadOptions o;
  o.modules = {"lidar.xml"};
  Model m;
  Diagnostics d;
  EXPECT_FALSE(load(urdf, m, d, o));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].code, "RS7033");
  EXPECT_EQ(d[0].file, urdf);
  EXPECT_NE(d[0].message.find("module 'lidar.xml' not found"), std::string::npos) << d[0].message;
  EXPECT_NE(d[0].message.find("modules/lidar.xml"), std::string::npos) << d[0].message;
}

// ---------------------------------------------------------------------------
// Scale and cache

TEST(UrdfScale, UniformScaleIsExact) {
  Model m, s;
  Diagnostics d;
  ASSERT_TRUE(load(kFixtures + "two_link.urdf", m, d));
  LoadOptions o;
  o.scale = Eigen::Vector3d::Constant(2);
  ASSERT_TRUE(load(kFixtures + "two_link.urdf", s, d, o));
  const Link& a = m.links[static_cast<std::size_t>(m.findLink("base"))];
  const Link& b = s.links[static_cast<std::size_t>(s.findLink("base"))];
  EXPECT_DOUBLE_EQ(b.inertial.mass, 8 * a.inertial.mass);
  EXPECT_TRUE(b.inertial.inertia.isApprox(32 * a.inertial.inertia));  // m r^2: 2^3 * 2^2
  EXPECT_TRUE(b.inertial.origin.position.isApprox(2 * a.inertial.origin.position));
  EXPECT_TRUE(b.visuals[0].geometry.size.isApprox(2 * a.visuals[0].geometry.size));
  EXPECT_DOUBLE_EQ(b.collisions[0].geometry.radius, 2 * a.collisions[0].geometry.radius);
  EXPECT_DOUBLE_EQ(b.collisions[0].geometry.length, 2 * a.collisions[0].geometry.length);
  const Joint& ja = m.joints[static_cast<std::size_t>(m.findJoint("slide"))];
  const Joint& jb = s.joints[static_cast<std::size_t>(s.findJoint("slide"))];
  EXPECT_DOUBLE_EQ(jb.upper, 2 * ja.upper);
  const Joint& sa = m.joints[static_cast<std::size_t>(m.findJoint("shoulder"))];
  const Joint& sb = s.joints[static_cast<std::size_t>(s.findJoint("shoulder"))];
  EXPECT_DOUBLE_EQ(sb.upper, sa.upper);  // angles do not scale
  EXPECT_TRUE(sb.origin.position.isApprox(2 * sa.origin.position));
}

TEST(UrdfScale, PerAxisScaleFollowsEachShapesAxes) {
  Model m;
  m.links.resize(1);
  Link& l = m.links[0];
  l.inertial.mass = 6;
  // A 1 x 2 x 3 box of 6 kg, lying along the link's axes.
  double a = 1, b = 2, c = 3;
  l.inertial.inertia = Eigen::Vector3d(b * b + c * c, a * a + c * c, a * a + b * b).asDiagonal();
  l.inertial.inertia *= 6.0 / 12.0;
  Collision box;
  box.geometry.kind = GeometryKind::Box;
  box.geometry.size = {a, b, c};
  box.origin.orientation = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ());  // its x along the link's y
  box.origin.position = {1, 1, 1};
  l.collisions.push_back(box);
  Collision cyl;
  cyl.geometry.kind = GeometryKind::Cylinder;
  cyl.geometry.radius = 1;
  cyl.geometry.length = 1;
  l.collisions.push_back(cyl);
  scaleModel(m, {2, 3, 4});
  EXPECT_DOUBLE_EQ(l.inertial.mass, 6 * 24);
  // The same box stretched to 2 x 6 x 12 at the same density.
  double A = 2, B = 6, C = 12, M = 6 * 24;
  Eigen::Matrix3d expected = Eigen::Vector3d(B * B + C * C, A * A + C * C, A * A + B * B).asDiagonal();
  EXPECT_TRUE(l.inertial.inertia.isApprox(expected * M / 12.0, 1e-12)) << l.inertial.inertia;
  EXPECT_TRUE(l.collisions[0].geometry.size.isApprox(Eigen::Vector3d(3, 4, 12)));  // rotated: x takes sy
  EXPECT_TRUE(l.collisions[0].origin.position.isApprox(Eigen::Vector3d(2, 3, 4)));
  EXPECT_DOUBLE_EQ(l.collisions[1].geometry.length, 4);
  EXPECT_DOUBLE_EQ(l.collisions[1].geometry.radius, std::sqrt(6.0));
}

TEST(UrdfScale, InertiaInARotatedFrameStretchesWithTheLink) {
  // The same 1 x 2 x 3 box, its inertia frame turned 90 degrees about z:
  // its own x lies along the link's y, its own y along the link's -x.
  Model m;
  m.links.resize(1);
  Inertial& in = m.links[0].inertial;
  in.mass = 6;
  auto boxInertia = [](double mass, double a, double b, double c) -> Eigen::Matrix3d {
    return Eigen::Matrix3d(Eigen::Vector3d(b * b + c * c, a * a + c * c, a * a + b * b).asDiagonal()) * mass / 12.0;
  };
  in.inertia = boxInertia(6, 1, 2, 3);
  in.origin.orientation = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ());
  in.origin.position = {1, 2, 3};
  scaleModel(m, {2, 3, 4});
  // Its x side takes the link's y factor (3), its y side the x factor (2).
  EXPECT_TRUE(in.inertia.isApprox(boxInertia(6 * 24, 3, 4, 12), 1e-12)) << in.inertia;
  EXPECT_TRUE(in.origin.position.isApprox(Eigen::Vector3d(2, 6, 12)));
}

TEST(UrdfScale, NonPositiveScaleIsRefused) {
  LoadOptions o;
  o.scale = {1, 0, 1};
  Model m;
  Diagnostics d;
  EXPECT_FALSE(load(kFixtures + "two_link.urdf", m, d, o));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].code, "RS7030");
}

TEST(ModelCache, OneLoadPerKeyAndItsDiagnosticsOnce) {
  ModelCache cache;
  Diagnostics first, second;
  auto a = cache.get(kFixtures + "skipped.urdf", {}, first);
  auto b = cache.get(kFixtures + "skipped.urdf", {}, second);
  ASSERT_TRUE(a);
  EXPECT_EQ(a, b);
  EXPECT_EQ(first.size(), 11u);
  EXPECT_TRUE(second.empty());
  LoadOptions scaled;
  scaled.scale = {2, 2, 2};
  Diagnostics third;
  auto c = cache.get(kFixtures + "skipped.urdf", scaled, third);
  EXPECT_NE(a, c);
  EXPECT_EQ(third.size(), 11u);
  Diagnostics broken1, broken2;
  EXPECT_FALSE(cache.get(kFixtures + "cycle.urdf", {}, broken1));
  EXPECT_FALSE(cache.get(kFixtures + "cycle.urdf", {}, broken2));
  EXPECT_FALSE(broken1.empty());
  EXPECT_TRUE(broken2.empty());
}

// A cache kept across the scenes of a batch (rscene-sim's): each scene
// gets a file's findings once, as it would alone, and the same model.
TEST(ModelCache, NextSceneReportsAFilesFindingsAgainOnce) {
  ModelCache cache;
  Diagnostics warned1, again1, warned2, again2, broken1, broken2;
  auto a = cache.get(kFixtures + "skipped.urdf", {}, warned1);
  cache.get(kFixtures + "skipped.urdf", {}, again1);
  EXPECT_FALSE(cache.get(kFixtures + "cycle.urdf", {}, broken1));
  cache.nextScene();
  auto b = cache.get(kFixtures + "skipped.urdf", {}, warned2);
  cache.get(kFixtures + "skipped.urdf", {}, again2);
  EXPECT_FALSE(cache.get(kFixtures + "cycle.urdf", {}, broken2));
  EXPECT_EQ(a, b);  // loaded once
  EXPECT_EQ(warned1.size(), 11u);
  EXPECT_EQ(warned2.size(), 11u);
  EXPECT_TRUE(again1.empty());
  EXPECT_TRUE(again2.empty());
  ASSERT_FALSE(broken2.empty());
  ASSERT_EQ(broken1.size(), broken2.size());
  EXPECT_EQ(broken1[0].message, broken2[0].message);
}

// ---------------------------------------------------------------------------
// The project's own robot (examples/robots/quadruped), which `make demo`
// simulates and renders without ../shared.

TEST(UrdfExample, QuadrupedIsAPlausibleRobot) {
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load(std::string(RSCENE_SOURCE_DIR) + "/examples/robots/quadruped/quadruped.urdf", m, d));
  EXPECT_TRUE(d.empty()) << messages(d);
  EXPECT_TRUE(m.floatingBase);
  EXPECT_NEAR(m.totalMass(), 15.2, 1e-9);
  Coordinates c;
  makeCoordinates(m, {}, c);
  std::vector<std::string> order;
  for (int j : c.joints) {
    const Joint& joint = m.joints[static_cast<std::size_t>(j)];
    order.push_back(joint.name);
    EXPECT_EQ(joint.type, JointType::Revolute);
    EXPECT_TRUE(joint.hasLimits);
    EXPECT_GT(joint.damping, 0);
  }
  EXPECT_EQ(order, kAnymalJoints);
  for (const Link& l : m.links) {
    SCOPED_TRACE(l.name);
    EXPECT_GT(l.inertial.mass, 0);
    EXPECT_FALSE(l.visuals.empty());
    EXPECT_FALSE(l.collisions.empty());
    for (const Visual& v : l.visuals) EXPECT_TRUE(v.color.has_value());
    // A physical inertia: positive principal moments, each at most the sum
    // of the other two.
    Eigen::Vector3d p = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(l.inertial.inertia).eigenvalues();
    EXPECT_GT(p.minCoeff(), 0);
    EXPECT_LE(p[2], p[0] + p[1] + 1e-12);
  }
}

TEST(UrdfExample, RobotCellStandsTheQuadrupedOnTheGround) {
  std::string path = std::string(RSCENE_SOURCE_DIR) + "/examples/robot_cell.rscene";
  Document doc;
  std::string error;
  ASSERT_TRUE(loadFile(path, doc, &error)) << error;
  Scene scene;
  Diagnostics d;
  SceneOptions options;
  options.sceneDir = std::string(RSCENE_SOURCE_DIR) + "/examples";
  ASSERT_TRUE(buildScene(doc, options, scene, d)) << messages(d);
  ASSERT_EQ(scene.articulated.size(), 1u);
  ModelCache cache;
  RobotInstance robot;
  ASSERT_TRUE(makeInstance(doc, scene.articulated[0], cache, robot, d)) << messages(d);
  EXPECT_FALSE(hasErrors(d)) << messages(d);
  // Every foot sphere's lowest point within 1 mm of the ground (z = 0),
  // and nothing else of the robot below it.
  std::vector<Pose> poses = linkPoses(robot);
  double lowestOther = 1e9;
  for (std::size_t i = 0; i < robot.model->links.size(); ++i) {
    const Link& l = robot.model->links[i];
    for (const Collision& k : l.collisions) {
      double z = (poses[i] * k.origin).position.z();
      if (l.name.find("_FOOT") != std::string::npos) {
        EXPECT_NEAR(z - k.geometry.radius, 0, 1e-3) << l.name;
      } else {
        lowestOther = std::min(lowestOther, z);
      }
    }
  }
  EXPECT_GT(lowestOther, 0.05);
}

// ---------------------------------------------------------------------------
// The robots of ../shared/corpus

bool haveCorpus() { return fs::exists(kRobots + "anymal_c/urdf/anymal.urdf"); }


void expectAnymal(const std::string& file, double mass, std::size_t links, bool hasMeshes = true) {
  SCOPED_TRACE(file);
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load(kRobots + "anymal_c/urdf/" + file, m, d)) << messages(d);
  EXPECT_FALSE(hasErrors(d));
  EXPECT_TRUE(m.floatingBase);
  EXPECT_EQ(m.links[static_cast<std::size_t>(m.root)].name, "base");
  EXPECT_EQ(m.links.size(), links);
  // Total mass: the sum of the file's <mass value> entries (worked out
  // with a separate XML reader).
  EXPECT_NEAR(m.totalMass(), mass, 1e-9);
  Coordinates c;
  ASSERT_TRUE(makeCoordinates(m, {}, c).empty());
  std::vector<std::string> order;
  for (int j : c.joints) {
    order.push_back(m.joints[static_cast<std::size_t>(j)].name);
    EXPECT_EQ(m.joints[static_cast<std::size_t>(j)].type, JointType::Revolute);
  }
  EXPECT_EQ(order, kAnymalJoints);
  EXPECT_EQ(c.coordinateDim, 19);
  EXPECT_EQ(c.velocityDim, 18);
  // Every mesh left in the model exists.
  int meshes = 0;
  for (const Link& l : m.links) {
    for (const Visual& v : l.visuals) {
      if (v.geometry.kind != GeometryKind::Mesh) continue;
      ++meshes;
      EXPECT_TRUE(fs::is_regular_file(v.geometry.meshPath)) << v.geometry.meshPath;
    }
    for (const Collision& k : l.collisions) {
      if (k.geometry.kind != GeometryKind::Mesh) continue;
      EXPECT_TRUE(fs::is_regular_file(k.geometry.meshPath)) << k.geometry.meshPath;
    }
  }
  EXPECT_EQ(meshes > 0, hasMeshes);
  // The standing pose puts the feet on the ground: the foot spheres'
  // lowest points within 3 cm of z = 0 with the base at 0.54.
  Eigen::VectorXd q(19);
  q << 0, 0, 0.54, 1, 0, 0, 0, 0.03, 0.4, -0.8, -0.03, 0.4, -0.8, 0.03, -0.4, 0.8, -0.03, -0.4, 0.8;
  std::vector<Pose> poses = linkPoses(m, c, Pose{}, q);
  for (const char* foot : {"LF_FOOT", "RF_FOOT", "LH_FOOT", "RH_FOOT"}) {
    int f = m.findLink(foot);
    ASSERT_GE(f, 0) << foot;
    const Link& link = m.links[static_cast<std::size_t>(f)];
    double lowest = 1e9;
    for (const Collision& k : link.collisions)
      if (k.geometry.kind == GeometryKind::Sphere)
        lowest = std::min(lowest, (poses[static_cast<std::size_t>(f)] * k.origin).position.z() - k.geometry.radius);
    ASSERT_LT(lowest, 1e9) << foot << " has no sphere";
    EXPECT_NEAR(lowest, 0, 0.03) << foot;
  }
}

TEST(UrdfCorpus, AnymalC) {
  if (!haveCorpus()) GTEST_SKIP() << "../shared/corpus is absent";
  expectAnymal("anymal.urdf", 52.13485, 78);
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load(kRobots + "anymal_c/urdf/anymal.urdf", m, d));
  EXPECT_TRUE(d.empty()) << messages(d);  // nothing in it is skipped
  int meshes = 0;
  for (const Link& l : m.links)
    for (const Visual& v : l.visuals) meshes += v.geometry.kind == GeometryKind::Mesh;
  EXPECT_EQ(meshes, 45);  // every <mesh> of the file, resolved through package://
}

TEST(UrdfCorpus, AnymalCSensoredKeepsItsSensorSets) {
  if (!haveCorpus()) GTEST_SKIP() << "../shared/corpus is absent";
  // The sensor sets' bodies join their links: the ouster's 0.33 kg and two
  // realsenses of 0.061575 kg (tests/robot/sensor_set_test.cpp).
  expectAnymal("anymal_sensored.urdf", 52.13485 + 0.33 + 2 * 0.061575, 79);
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load(kRobots + "anymal_c/urdf/anymal_sensored.urdf", m, d));
  EXPECT_EQ(m.links[static_cast<std::size_t>(m.findLink("lidar_link"))].sensorSet, "ouster1-64.xml");
  EXPECT_EQ(m.links[static_cast<std::size_t>(m.findLink("depth_camera_front_camera_parent"))].sensorSet,
            "realsense435.xml");
}

TEST(UrdfCorpus, AnymalCNoLimitLoadsPastGazeboAndMissingVisualMeshes) {
  if (!haveCorpus()) GTEST_SKIP() << "../shared/corpus is absent";
  expectAnymal("anymal_c_nolimit.urdf", 41.709183258, 62, false);
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load(kRobots + "anymal_c/urdf/anymal_c_nolimit.urdf", m, d));
  // 8 <gazebo> blocks, and three visual meshes named relative to urdf/
  // that live in meshes/ (RaiSim never reads visual meshes, so it loads
  // this robot too).
  int gazebo = 0;
  std::vector<int> meshLines;
  for (const Diagnostic& x : d) {
    EXPECT_EQ(x.code, "RS7031");
    if (x.message.find("<gazebo>") != std::string::npos) ++gazebo;
    if (x.message.find("visual mesh") != std::string::npos) meshLines.push_back(static_cast<int>(x.line));
  }
  EXPECT_EQ(gazebo, 8);
  EXPECT_EQ(meshLines, (std::vector<int>{230, 312, 418}));
  for (const Joint& j : m.joints) EXPECT_FALSE(j.hasLimits) << j.name;
}

TEST(UrdfCorpus, ChainsWithSphericalJointsAndSprings) {
  if (!haveCorpus()) GTEST_SKIP() << "../shared/corpus is absent";
  for (const char* file : {"robot.urdf", "robot_limit.urdf", "robot_short.urdf", "robot_springed.urdf",
                           "robot_springed_10.urdf", "robot_springed_20.urdf", "robot_springed_30.urdf"}) {
    SCOPED_TRACE(file);
    Model m;
    Diagnostics d;
    ASSERT_TRUE(load(kRobots + "chain/" + file, m, d)) << messages(d);
    EXPECT_TRUE(d.empty()) << messages(d);
    EXPECT_FALSE(m.floatingBase);
    Coordinates c;
    makeCoordinates(m, {}, c);
    int spherical = 0;
    for (int j : c.joints)
      if (m.joints[static_cast<std::size_t>(j)].type == JointType::Spherical) {
        ++spherical;
        EXPECT_EQ(m.joints[static_cast<std::size_t>(j)].coordinateDim(), 4);
      }
    EXPECT_GT(spherical, 0);
    EXPECT_EQ(c.coordinateDim, 4 * spherical + (static_cast<int>(c.joints.size()) - spherical));
  }
  Model m;
  Diagnostics d;
  ASSERT_TRUE(load(kRobots + "chain/robot_springed.urdf", m, d));
  const Joint& j = m.joints[static_cast<std::size_t>(m.findJoint("link1Tolink2"))];
  EXPECT_EQ(j.type, JointType::Spherical);
  EXPECT_DOUBLE_EQ(j.rotorInertia, 0.0001);
  EXPECT_DOUBLE_EQ(j.stiffness, 500);
  EXPECT_DOUBLE_EQ(j.damping, 3);
  ASSERT_EQ(j.springMount.size(), 4u);
  EXPECT_NEAR(j.springMount[0], std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(j.springMount[2], std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(Eigen::Vector4d(j.springMount.data()).norm(), 1, 1e-12);
  Model limited;
  ASSERT_TRUE(load(kRobots + "chain/robot_short.urdf", limited, d));
  int withLimits = 0;
  for (const Joint& x : limited.joints)
    if (x.hasLimits) {
      ++withLimits;
      EXPECT_EQ(x.type, JointType::Spherical);
      EXPECT_DOUBLE_EQ(x.lower, 1);  // <limit lower="1"/>, kept as written
    }
  EXPECT_EQ(withLimits, 3);
}

}  // namespace
}  // namespace rscene::robot
