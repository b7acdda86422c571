// Reading rscene-sim trajectories back (lib/robot/trajectory_read): frames
// grouped by time in both formats, every malformed line refused at its
// line and column, and frames turned into body and link poses.
#include "robot/trajectory_read.hpp"
#include "trajectory_read_util.hpp"

#include <gtest/gtest.h>

#include <sstream>

namespace rscene::robot {
namespace {

using test::Read;
using test::readAll;

std::string jsonLine(double t, const std::string& path, double x, const std::string& extra = "") {
  std::ostringstream s;
  s << "{\"time\":" << t << ",\"path\":\"" << path << "\",\"position\":[" << x
    << ",0,1],\"quaternion\":[1,0,0,0],\"linearVelocity\":[0,0,0],\"angularVelocity\":[0,0,0]" << extra << "}\n";
  return s.str();
}

// The one error of a failed read: its code, line and column.
void expectError(const Read& r, const char* code, std::uint32_t line, std::uint32_t column) {
  ASSERT_TRUE(r.failed);
  ASSERT_EQ(r.diags.size(), 1u);
  EXPECT_EQ(r.diags[0].code, code);
  EXPECT_EQ(r.diags[0].file, "t.jsonl");
  EXPECT_EQ(r.diags[0].line, line) << r.diags[0].message;
  EXPECT_EQ(r.diags[0].column, column) << r.diags[0].message;
}

TEST(TrajectoryRead, JsonLinesWithTheSameTimeAreOneFrame) {
  Read r = readAll(jsonLine(0, "/a", 1) + jsonLine(0, "/b", 2) + "\n" + jsonLine(0.5, "/a", 3) +
                   jsonLine(0.5, "/b", 4) + jsonLine(1, "/a", 5));
  ASSERT_FALSE(r.failed) << r.diags[0].message;
  ASSERT_EQ(r.frames.size(), 3u);
  EXPECT_EQ(r.frames[0].entries.size(), 2u);
  EXPECT_EQ(r.frames[1].entries.size(), 2u);
  EXPECT_EQ(r.frames[2].entries.size(), 1u);
  EXPECT_EQ(r.frames[1].time, 0.5);
  EXPECT_EQ(r.frames[2].index, 2u);
  EXPECT_EQ(r.frames[1].entries[1].path, "/b");
  EXPECT_EQ(r.frames[1].entries[1].pose.position.x(), 4);
  EXPECT_EQ(r.frames[1].entries[1].line, 5u);  // the blank line counts
}

TEST(TrajectoryRead, JointPositionsByName) {
  Read r = readAll(jsonLine(0, "/robot", 0, ",\"jointPositions\":{\"j1\":0.5,\"j2\":-1},\"jointVelocities\":{}"));
  ASSERT_EQ(r.frames.size(), 1u);
  const auto& joints = r.frames[0].entries[0].joints;
  ASSERT_EQ(joints.size(), 2u);
  EXPECT_EQ(joints[0].name, "j1");
  EXPECT_EQ(joints[0].value, 0.5);
  EXPECT_EQ(joints[1].value, -1);
}

TEST(TrajectoryRead, CsvWithJointColumnsQuotedPathsAndCrlf) {
  Read r = readAll(
      "time,path,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,q.j1,u.j1,\"q.a,b\"\r\n"
      "0,/box,1,2,3,1,0,0,0,0,0,0,0,0,0,,,\r\n"
      "0,\"/r,\"\"x\"\"\",0,0,0,0,0,0,1,0,0,0,0,0,0,0.25,9,-2\r\n"
      "0.1,/box,4,5,6,1,0,0,0,0,0,0,0,0,0,,,\r\n");
  ASSERT_FALSE(r.failed) << r.diags[0].message;
  ASSERT_EQ(r.frames.size(), 2u);
  const TrajectoryEntry& robot = r.frames[0].entries[1];
  EXPECT_EQ(robot.path, "/r,\"x\"");
  EXPECT_NEAR(robot.pose.orientation.z(), 1, 1e-12);
  ASSERT_EQ(robot.joints.size(), 2u);  // q.j1 and q.a,b; not the velocity
  EXPECT_EQ(robot.joints[0].name, "j1");
  EXPECT_EQ(robot.joints[1].name, "a,b");
  EXPECT_EQ(robot.joints[1].value, -2);
  EXPECT_TRUE(r.frames[0].entries[0].joints.empty());  // empty cells: another robot's joints
  EXPECT_EQ(r.frames[1].entries[0].pose.position.z(), 6);
}

TEST(TrajectoryRead, QuaternionsAreNormalised) {
  Read r = readAll("{\"time\":0,\"path\":\"/a\",\"position\":[0,0,0],\"quaternion\":[2,0,0,0]}\n");
  ASSERT_EQ(r.frames.size(), 1u);
  EXPECT_DOUBLE_EQ(r.frames[0].entries[0].pose.orientation.w(), 1);
}

TEST(TrajectoryRead, MalformedLinesAreErrorsAtTheirLineAndColumn) {
  // Cut off: at the end of the line, where parsing stopped.
  expectError(readAll(jsonLine(0, "/a", 1) + "{\"time\":0,\n"), code::kTrajectorySyntax, 2, 11);
  std::string cut = "{\"time\":0,\"path\":\"/a\",\"position\":[1,2";
  expectError(readAll(cut + "\n"), code::kTrajectorySyntax, 1, static_cast<std::uint32_t>(cut.size() + 1));
  Read missingComma = readAll("{\"time\":0 \"path\":\"/a\"}\n");
  expectError(missingComma, code::kTrajectorySyntax, 1, 11);  // at the unexpected "path"
  EXPECT_NE(missingComma.diags[0].message.find("malformed JSON: object"), std::string::npos)
      << missingComma.diags[0].message;
  std::string noPosition = "{\"time\":0,\"path\":\"/a\",\"quaternion\":[1,0,0,0]}\n";
  expectError(readAll(noPosition), code::kTrajectorySyntax, 1, 1);
  std::string shortPosition = "{\"time\":0,\"path\":\"/a\",\"position\":[1,2],\"quaternion\":[1,0,0,0]}\n";
  expectError(readAll(shortPosition), code::kTrajectorySyntax, 1, 23);
  std::string zeroQuaternion = "{\"time\":0,\"path\":\"/a\",\"position\":[1,2,3],\"quaternion\":[0,0,0,0]}\n";
  expectError(readAll(zeroQuaternion), code::kTrajectorySyntax, 1, 42);
  std::string huge = "{\"time\":0,\"path\":\"/a\",\"position\":[1e300,2,3],\"quaternion\":[1,0,0,0]}\n";
  expectError(readAll(huge), code::kTrajectorySyntax, 1, 23);
  std::string textJoint = jsonLine(0, "/r", 0, ",\"jointPositions\":{\"j\":\"x\"}");
  expectError(readAll(textJoint), code::kTrajectorySyntax, 1,
              static_cast<std::uint32_t>(textJoint.find("\"joint") + 1));
  expectError(readAll("[1,2,3]\n"), code::kTrajectorySyntax, 1, 1);
  expectError(readAll("hello\n"), code::kTrajectorySyntax, 1, 1);
}

TEST(TrajectoryRead, ADuplicateKeyIsAnErrorAtItsSecondUse) {
  std::string twice = jsonLine(0, "/a", 1, ",\"time\":5");
  Read r = readAll(twice);
  expectError(r, code::kTrajectorySyntax, 1, static_cast<std::uint32_t>(twice.rfind("\"time\"") + 1));
  EXPECT_EQ(r.diags[0].message, "\"time\" twice in one object (which one is meant?)");
  std::string joint = jsonLine(0, "/r", 0, ",\"jointPositions\":{\"j\":1,\"k\":0,\"j\":2}");
  expectError(readAll(joint), code::kTrajectorySyntax, 1, static_cast<std::uint32_t>(joint.rfind("\"j\"") + 1));
  // The same key in two different objects is no duplicate; nor a value equal to a key.
  std::string fine = jsonLine(0, "/time", 0, ",\"jointPositions\":{\"time\":1}");
  Read ok = readAll(fine);
  EXPECT_FALSE(ok.failed) << (ok.diags.empty() ? "" : ok.diags[0].message);
  EXPECT_EQ(ok.frames.size(), 1u);
}

// A stream whose reads throw, as libstdc++'s filebuf does for a directory.
struct ThrowingBuf : std::streambuf {
  int_type underflow() override { throw std::ios_base::failure("read error"); }
};

TEST(TrajectoryRead, AStreamThatThrowsIsAnErrorNotAnException) {
  ThrowingBuf buf;
  std::istream in(&buf);
  TrajectoryReader r(in, "t.jsonl");
  TrajectoryFrame f;
  Diagnostics d;
  EXPECT_FALSE(r.next(f, d));
  EXPECT_TRUE(r.failed());
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].code, code::kTrajectorySyntax);
  EXPECT_NE(d[0].message.find("cannot read the trajectory"), std::string::npos) << d[0].message;
}

TEST(TrajectoryRead, CsvErrorsPointAtTheField) {
  const std::string header = "time,path,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
  expectError(readAll(header + "0,/a,nan,0,0,1,0,0,0,0,0,0,0,0,0\n"), code::kTrajectorySyntax, 2, 6);
  expectError(readAll(header + "0,/a,0,0,0,1,0,0,0,0,0,0,0,0\n"), code::kTrajectorySyntax, 2, 29);
  expectError(readAll(header + "0,/a,0,0,0,1,0,0,0,0,0,0,0,0,0,7\n"), code::kTrajectorySyntax, 2, 32);
  expectError(readAll(header + "0,\"/a,0,0,0,1,0,0,0,0,0,0,0,0,0\n"), code::kTrajectorySyntax, 2, 3);
  expectError(readAll("time,path,x\n"), code::kTrajectorySyntax, 1, 11);
  expectError(readAll(header.substr(0, header.size() - 1) + ",speed\n0,/a,0,0,0,1,0,0,0,0,0,0,0,0,0,1\n"),
              code::kTrajectorySyntax, 1, 50);
  expectError(readAll(header), code::kTrajectorySyntax, 1, 0);  // a header and no line
}

TEST(TrajectoryRead, FrameLevelErrors) {
  // Time going back: a second trajectory appended to a first.
  expectError(readAll(jsonLine(1, "/a", 0) + jsonLine(0, "/a", 0)), code::kTrajectorySyntax, 2, 1);
  // Times as the file wrote them: -1 and 0.25, not -1.000000 and 0.250000.
  Read back = readAll(jsonLine(0.25, "/a", 0) + jsonLine(-1, "/a", 0));
  expectError(back, code::kTrajectorySyntax, 2, 1);
  EXPECT_NE(back.diags[0].message.find("time -1 is before the previous frame's 0.25 "), std::string::npos)
      << back.diags[0].message;
  // The same body twice at one time.
  Read twice = readAll(jsonLine(0, "/a", 0) + jsonLine(0, "/a", 0));
  expectError(twice, code::kTrajectorySyntax, 2, 18);
  EXPECT_NE(twice.diags[0].message.find("first on line 1"), std::string::npos);
  expectError(readAll(""), code::kTrajectorySyntax, 0, 0);
  expectError(readAll("\n  \n"), code::kTrajectorySyntax, 2, 0);
}

TEST(TrajectoryRead, MemoryIsBoundedByTheLimits) {
  TrajectoryLimits small;
  small.maxLineBytes = 64;
  Read longLine = readAll(jsonLine(0, std::string(100, 'x'), 0), small);
  expectError(longLine, code::kTrajectorySyntax, 1, 1);
  // An endless line of one byte is refused after maxLineBytes, not read whole.
  Read endless = readAll(std::string(1000, '{'), small);
  expectError(endless, code::kTrajectorySyntax, 1, 1);
  TrajectoryLimits fewLines;
  fewLines.maxEntriesPerFrame = 2;
  expectError(readAll(jsonLine(0, "/a", 0) + jsonLine(0, "/b", 0) + jsonLine(0, "/c", 0), fewLines),
              code::kTrajectorySyntax, 3, 1);
}

// A robot: base --revolute j1 about x--> arm, 1 m above the base.
std::shared_ptr<Model> armModel(bool floating) {
  auto m = std::make_shared<Model>();
  m->name = "arm";
  m->floatingBase = floating;
  m->links.resize(2);
  m->links[0].name = "base";
  m->links[1].name = "arm";
  Joint j;
  j.name = "j1";
  j.type = JointType::Revolute;
  j.parentLink = 0;
  j.childLink = 1;
  j.origin.position = {0, 0, 1};
  j.axis = Eigen::Vector3d::UnitX();
  m->joints.push_back(j);
  m->links[0].childJoints.push_back(0);
  m->links[1].parentJoint = 0;
  return m;
}

struct PoserScene {
  Scene scene;
  std::vector<std::shared_ptr<const Model>> models;
  PoserScene() {
    scene.objects.resize(1);
    scene.objects[0].path = "/World/Box";
    scene.compounds.resize(1);
    scene.compounds[0].path = "/World/Cart";
    scene.articulated.resize(1);
    scene.articulated[0].path = "/World/Arm";
    models.push_back(armModel(true));
  }
};

TEST(TrajectoryPoser, BodiesAndRobotLinksTakeTheFramesPoses) {
  PoserScene s;
  TrajectoryPoser poser(s.scene, s.models);
  Read r = readAll(jsonLine(0, "/World/Box", 2) + jsonLine(0, "/World/Cart", 3) +
                   jsonLine(0, "/World/Arm", 5, ",\"jointPositions\":{\"j1\":1.5707963267948966}"));
  ASSERT_EQ(r.frames.size(), 1u);
  BodyPoses poses = restPoses(s.scene, s.models);
  Diagnostics d;
  ASSERT_TRUE(poser.apply(r.frames[0], "t.jsonl", poses, d));
  EXPECT_EQ(poses.objects[0].position, Eigen::Vector3d(2, 0, 1));
  EXPECT_EQ(poses.compounds[0].position, Eigen::Vector3d(3, 0, 1));
  ASSERT_EQ(poses.robotLinks[0].size(), 2u);
  EXPECT_TRUE(poses.robotLinks[0][0].position.isApprox(Eigen::Vector3d(5, 0, 1)));
  // The arm turned a quarter about x: its +y now points up.
  EXPECT_TRUE((poses.robotLinks[0][1].orientation * Eigen::Vector3d::UnitY()).isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(poses.robotLinks[0][1].position.isApprox(Eigen::Vector3d(5, 0, 2)));
}

TEST(TrajectoryPoser, UnknownBodyOrJointIsAnErrorNamingIt) {
  PoserScene s;
  TrajectoryPoser poser(s.scene, s.models);
  BodyPoses poses = restPoses(s.scene, s.models);
  Read r = readAll(jsonLine(0, "/World/Box", 2) + jsonLine(0, "/World/Ghost", 2));
  Diagnostics d;
  EXPECT_FALSE(poser.apply(r.frames[0], "t.jsonl", poses, d));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].code, code::kTrajectoryTarget);
  EXPECT_EQ(d[0].line, 2u);
  EXPECT_EQ(d[0].column, 18u);
  EXPECT_NE(d[0].message.find("'/World/Ghost'"), std::string::npos);

  std::string bad = jsonLine(0, "/World/Arm", 0, ",\"jointPositions\":{\"elbow\":1}");
  Read j = readAll(bad);
  d.clear();
  EXPECT_FALSE(poser.apply(j.frames[0], "t.jsonl", poses, d));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NE(d[0].message.find("joint 'elbow'"), std::string::npos);
  EXPECT_EQ(d[0].column, static_cast<std::uint32_t>(bad.find("\"jointPositions") + 1));

  // A robot's line without one of its movable joints: cut or edited, not
  // what rscene-sim writes; the joint is named at jointPositions.
  std::string cut = jsonLine(0, "/World/Arm", 0, ",\"jointPositions\":{}");
  Read c = readAll(cut);
  d.clear();
  EXPECT_FALSE(poser.apply(c.frames[0], "t.jsonl", poses, d));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].code, code::kTrajectoryTarget);
  EXPECT_NE(d[0].message.find("leaves out joint 'j1'"), std::string::npos) << d[0].message;
  // No jointPositions at all: the error points at the path.
  d.clear();
  EXPECT_FALSE(poser.apply(readAll(jsonLine(0, "/World/Arm", 0)).frames[0], "t.jsonl", poses, d));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].column, 18u);

  Read body = readAll(jsonLine(0, "/World/Box", 0, ",\"jointPositions\":{\"j1\":1}"));
  d.clear();
  EXPECT_FALSE(poser.apply(body.frames[0], "t.jsonl", poses, d));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NE(d[0].message.find("not a robot"), std::string::npos);
}

}  // namespace
}  // namespace rscene::robot
