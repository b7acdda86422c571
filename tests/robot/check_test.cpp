// Robot checks of rscene-validate (robot/check.hpp) on the walker fixture
// (tests/data/robots/check/walker.urdf: floating base, L_HIP L_KNEE R_HIP
// R_KNEE, fixed feet L_FOOT R_FOOT; 11 coordinates, 10 velocities, 5 bodies).
#include "robot/check.hpp"

#include <gtest/gtest.h>

#include "core/loader.hpp"

namespace rscene::robot {
namespace {

const std::string kDir = std::string(RSCENE_TEST_DATA) + "/robots/check";

const std::string kResource = "raisim_engine_scene 1\narticulated_resource walker_res Walker walker.urdf\n";
const std::string kBox =
    "object /World/Box box 1 0 0.5 1 0 0 0 0.2 0.2 0.2 0.5 1 1 default - false true false - dynamic true 1 "
    "18446744073709551615 id=box\n";

std::string walker(const std::string& extra = "",
                   const std::string& q = "0,0,0.5,1,0,0,0,0.3,-0.6,0.3,-0.6") {
  return "articulated /World/Walker walker_res 0 0 0.5 1 0 0 0 true true id=walker generalizedCoordinate=" + q +
         extra + "\n";
}

struct Checked {
  LoadResult loaded;
  Scene scene;
  std::vector<SceneFinding> found;

  Checked(const std::string& text, bool checkFiles = false) {
    loaded = parse(text);
    EXPECT_TRUE(loaded.ok()) << text;
    SceneOptions so;
    so.sceneDir = kDir;
    so.bodiesOnly = true;
    Diagnostics ignored;
    buildScene(loaded.document, so, scene, ignored);
    RobotCheckOptions o;
    o.checkFiles = checkFiles;
    ModelCache cache;
    checkRobots(loaded.document, scene, o, cache, found);
  }
  std::vector<std::string> codes() const {
    std::vector<std::string> c;
    for (const SceneFinding& f : found) c.push_back(f.diagnostic.code);
    return c;
  }
  // The one finding, by value (callers hold it past a temporary Checked).
  Diagnostic only(const char* code) const {
    EXPECT_EQ(codes(), std::vector<std::string>{code});
    return found.empty() ? Diagnostic{} : found[0].diagnostic;
  }
};

TEST(RobotCheck, TheWalkerSceneIsClean) {
  Checked r(kResource + kBox + walker(" generalizedVelocity=0,0,0,0,0,0,1,2,3,4") +
        "articulated_ik /World/Walker L_FOOT 0.05,0.12,0.15\n"
        "articulated_ik /World/Walker L_KNEE 0.05,0.12,0.15\n"  // a joint's frame
        "sensor /World/Walker/Imu imu walker 0 0 0 1 0 0 0 parentLink=base\n"
        "wire /World/Leash stiff walker box 1.5 localIndexA=4 localIndexB=0\n",
        true);
  EXPECT_TRUE(r.found.empty()) << r.found[0].diagnostic.message;
}

TEST(RobotCheck, LengthsAgainstTheModel) {
  Diagnostic q = Checked(kResource + walker("", "0,0,0.5,1,0,0,0,0.3,-0.6")).only("RS7040");
  EXPECT_EQ(q.line, 3u);
  EXPECT_EQ(q.field, "generalizedCoordinate");
  EXPECT_NE(q.message.find("has 9 numbers; the model 'walker' has 11"), std::string::npos) << q.message;
  Checked u(kResource + walker(" generalizedVelocity=0,0,0,0,0,0,0,0,0,0,0"));
  EXPECT_EQ(u.codes(), std::vector<std::string>{"RS7041"});
}

TEST(RobotCheck, AnEmptyListIsNoState) {
  EXPECT_TRUE(Checked(kResource + walker(" generalizedVelocity=-", "-")).found.empty());
  EXPECT_TRUE(Checked(kResource + walker(" generalizedVelocity=", "")).found.empty());
}

TEST(RobotCheck, JointOrderNamesWithDidYouMean) {
  Checked r(kResource + walker(" jointOrder=R_HIP;R_KNEE;L_HIP;L_KNE"));
  ASSERT_EQ(r.codes(), (std::vector<std::string>{"RS7042", "RS7042"}));  // unknown, and L_KNEE left out
  EXPECT_EQ(r.found[0].diagnostic.hint, "did you mean 'L_KNEE'?");
  EXPECT_NE(r.found[1].diagnostic.message.find("leaves out movable joints: L_KNEE"), std::string::npos);
  EXPECT_TRUE(Checked(kResource + walker(" jointOrder=R_HIP;R_KNEE;L_HIP;L_KNEE")).found.empty());
}

TEST(RobotCheck, NonUnitQuaternionIsAWarning) {
  Diagnostic d = Checked(kResource + walker("", "0,0,0.5,2,0,0,0,0.3,-0.6,0.3,-0.6")).only("RS7043");
  EXPECT_EQ(d.severity, Severity::Warning);
  EXPECT_EQ(Checked(kResource + walker("", "0,0,0.5,0,0,0,0,0.3,-0.6,0.3,-0.6")).only("RS7043").severity, Severity::Error);
}

TEST(RobotCheck, IkFramesThatDoNotExist) {
  Checked r(kResource + walker() + "articulated_ik /World/Walker L_FOTO 0,0,0\n" +
        "articulated_ik /World/Walker nowhere 0,0,0 enabled=false\n");
  ASSERT_EQ(r.codes(), (std::vector<std::string>{"RS7044", "RS7044"}));
  const Diagnostic& d = r.found[0].diagnostic;
  EXPECT_EQ(d.line, 4u);
  EXPECT_EQ(d.field, "frame");
  EXPECT_EQ(d.severity, Severity::Error);
  EXPECT_EQ(d.hint, "did you mean 'L_FOOT'?");
  EXPECT_EQ(r.found[1].diagnostic.severity, Severity::Warning);  // disabled: nobody solves it
  EXPECT_EQ(r.found[1].diagnostic.hint, "frames are the model's joint and link names");
}

TEST(RobotCheck, IkKnobsAreCheckedWithoutTheModel) {
  Checked r(kResource + "articulated /World/W walker_res 0 0 0 1 0 0 0 true true sourcePath=nowhere.urdf\n" +
        "articulated_ik /World/W foot 0,0,0 maxIterations=0 inverseMethod=newton\n");
  EXPECT_EQ(r.codes(), (std::vector<std::string>{"RS7048", "RS7048"}));
  EXPECT_EQ(r.found[0].diagnostic.field, "maxIterations");
  EXPECT_EQ(r.found[1].diagnostic.field, "inverseMethod");
}

TEST(RobotCheck, AtMostAThousandEnabledIkTargetsPerRobot) {
  std::string targets;
  for (int i = 0; i < 1001; ++i) targets += "articulated_ik /World/Walker L_FOOT 0,0," + std::to_string(i) + "\n";
  Checked r(kResource + walker() + targets + "articulated_ik /World/Walker L_FOOT 0,0,0 enabled=false\n");
  Diagnostic d = r.only("RS7048");
  EXPECT_EQ(d.line, 4u + 1000u);  // the 1001st
  EXPECT_NE(d.message.find("more than 1000 enabled IK targets"), std::string::npos);
}

TEST(RobotCheck, SensorParentLinkOnTheRobot) {
  Diagnostic d =
      Checked(kResource + walker() + "sensor /World/Walker/Cam rgb walker 0 0 0 1 0 0 0 parentLink=L_THIG\n").only("RS7045");
  EXPECT_EQ(d.field, "parentLink");
  EXPECT_EQ(d.hint, "did you mean 'L_THIGH'?");
  Diagnostic joint =
      Checked(kResource + walker() + "sensor /World/Walker/Cam rgb walker 0 0 0 1 0 0 0 parentLink=L_KNEE\n").only("RS7045");
  EXPECT_EQ(joint.hint, "'L_KNEE' is a joint; its child link is 'L_SHANK'");
  // A sensor on a plain body names no link of a robot.
  EXPECT_TRUE(Checked(kResource + kBox + walker() + "sensor /World/Box/Cam rgb box 0 0 0 1 0 0 0 parentLink=x\n").found.empty());
}

TEST(RobotCheck, WireBodyIndexWithinTheRobotsBodies) {
  Diagnostic d =
      Checked(kResource + kBox + walker() + "wire /World/L stiff box walker 1.5 localIndexA=7 localIndexB=5\n").only("RS7046");
  EXPECT_EQ(d.field, "localIndexB");  // A is the box: its index is not a robot's body
  EXPECT_NE(d.message.find("has bodies 0 to 4"), std::string::npos) << d.message;
}

TEST(RobotCheck, AnUnreadableModelIsLeftToCheckFiles) {
  // Without --check-files: nothing about the file, and no model checks.
  Checked quiet(kResource + "articulated /World/B walker_res 0 0 0 1 0 0 0 true true sourcePath=broken.urdf "
                        "generalizedCoordinate=1,2,3\n");
  EXPECT_TRUE(quiet.found.empty());
  // With it: the findings name the robot file and a line in it, listed at
  // the line of the record that names the file.
  Checked loud(kResource + "articulated /World/B walker_res 0 0 0 1 0 0 0 true true sourcePath=broken.urdf\n", true);
  ASSERT_FALSE(loud.found.empty());
  bool inFile = false;
  for (const SceneFinding& f : loud.found) {
    if (f.diagnostic.file.empty()) continue;
    inFile = true;
    EXPECT_EQ(f.sceneLine, 3u);
    EXPECT_NE(f.diagnostic.file.find("broken.urdf"), std::string::npos);
    EXPECT_GT(f.diagnostic.line, 0u);
    EXPECT_EQ(f.diagnostic.severity, Severity::Error);
  }
  EXPECT_TRUE(inFile);
}

TEST(RobotCheck, AMissingRobotFileIsCoresFinding) {
  // lib/core's RS5001 names the path at the scene's field; not said twice.
  Checked r(kResource + "articulated /World/B walker_res 0 0 0 1 0 0 0 true true sourcePath=nowhere.urdf\n", true);
  EXPECT_TRUE(r.found.empty());
}

TEST(RobotCheck, CheckFilesNamesMissingMeshesInTheRobotFile) {
  Checked r("raisim_engine_scene 1\narticulated_resource m M missing_mesh.urdf\n", true);  // no instance: read as written
  ASSERT_EQ(r.codes(), (std::vector<std::string>{"RS5001", "RS7031"}));
  // A collision mesh is an error (the robot would not collide as written),
  // a visual one a warning (it is drawn without it).
  for (const SceneFinding& f : r.found) {
    EXPECT_EQ(f.sceneLine, 2u);
    EXPECT_NE(f.diagnostic.file.find("missing_mesh.urdf"), std::string::npos);
  }
  EXPECT_EQ(r.found[0].diagnostic.line, 4u);
  EXPECT_NE(r.found[0].diagnostic.message.find("missing.stl"), std::string::npos);
  EXPECT_EQ(r.found[1].diagnostic.line, 5u);
  EXPECT_EQ(r.found[1].diagnostic.severity, Severity::Warning);
}

TEST(RobotCheck, BodyCountIsMovableBodiesAndTheBase) {
  Coordinates c;
  c.joints = {0, 1, 2};
  EXPECT_EQ(bodyCount(c), 4);
}

}  // namespace
}  // namespace rscene::robot
