// One list of every sensor (lib/robot/sensors.cpp): collectSensors over
// records and robots' sensor sets, restPoses, sensorPose.  Poses are
// checked against closed forms worked out by hand, not against our own
// forward kinematics; RS7045 is one finding whoever reports it.
#include "robot/sensors.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "core/loader.hpp"
#include "robot/check.hpp"
#include "robot/load.hpp"
#include "scene/validate.hpp"

namespace rscene::robot {
namespace {

namespace fs = std::filesystem;

// A fixed-base arm: `world` - fixed - `base` - revolute about z, 1 m up -
// `arm`; `arm` carries the sensor set `tip.xml` (an IMU 0.5 m out on x).
const char* const kArm = R"(<robot name="arm">
  <link name="world"/>
  <link name="base"/>
  <link name="arm" sensor="tip.xml"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="arm"/>
    <origin xyz="0 0 1"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
</robot>
)";
const char* const kTip = R"(<sensor_set name="tip">
  <link>
    <sensor name="imu" type="imu" update_rate="100"><origin xyz="0.5 0 0"/></sensor>
  </link>
</sensor_set>
)";

std::string exact(double v) {
  std::ostringstream s;
  s << std::setprecision(17) << v;
  return s.str();
}

class SensorsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "rscene-sensors-XXXXXX").string();
    std::vector<char> buf(pattern.begin(), pattern.end());
    buf.push_back('\0');
    dir_ = ::mkdtemp(buf.data());
    std::ofstream(dir_ + "/arm.urdf") << kArm;
    std::ofstream(dir_ + "/tip.xml") << kTip;
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  // The scene: the arm at (2, 0, 0) with its shoulder at `angle`, a box,
  // and `sensors` (records).
  void build(double angle, const std::string& sensors) {
    text_ =
        "raisim_engine_scene 2\n"
        "articulated_resource arm Arm " +
        dir_ +
        "/arm.urdf\n"
        "articulated /World/Arm arm 2 0 0 1 0 0 0 true true id=robot generalizedCoordinate=" +
        exact(angle) +
        "\n"
        "object /World/Box box 0 0 5 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false - dynamic "
        "true 1 18446744073709551615 id=box\n" +
        sensors;
    LoadResult loaded = parse(text_);
    ASSERT_TRUE(loaded.ok());
    doc_ = std::move(loaded.document);
    scene_ = Scene{};
    Diagnostics d;
    ASSERT_TRUE(buildScene(doc_, SceneOptions{}, scene_, d));
    ASSERT_EQ(scene_.articulated.size(), 1u);
    models_ = {cache_.get(scene_.articulated[0].sourcePath, LoadOptions{}, d)};
    ASSERT_TRUE(models_[0]) << (d.empty() ? "" : d[0].message);
  }

  std::string dir_, text_;
  Document doc_;
  Scene scene_;
  ModelCache cache_;
  std::vector<std::shared_ptr<const Model>> models_;
};

const std::string kOnArm = "sensor /World/Cam rgb robot 1 0 0 1 0 0 0 parentLink=arm\n";

TEST_F(SensorsTest, RecordsFirstThenTheRobotsSets) {
  build(0, kOnArm + "sensor /World/Free lidar - 0 0 3 1 0 0 0\nsensor /World/OnBox imu box 0 0 1 1 0 0 0\n");
  Diagnostics d;
  std::vector<SensorSpec> all = collectSensors(doc_, scene_, models_, d);
  EXPECT_TRUE(d.empty());
  ASSERT_EQ(all.size(), 4u);
  EXPECT_EQ(all[0].name, "/World/Cam");
  EXPECT_EQ(all[0].kind, SensorKind::Rgb);
  EXPECT_EQ(all[0].mount.kind, Mount::Kind::Articulated);
  EXPECT_EQ(all[0].link, models_[0]->findLink("arm"));
  EXPECT_EQ(all[0].robotRecord, scene_.articulated[0].recordIndex);
  EXPECT_EQ(all[1].kind, SensorKind::Lidar);
  EXPECT_EQ(all[1].mount.kind, Mount::Kind::World);
  EXPECT_EQ(all[2].mount.kind, Mount::Kind::Object);
  // The URDF's set: named by robot, link (the set) and sensor.
  EXPECT_EQ(all[3].name, "/World/Arm/arm/imu");
  EXPECT_EQ(all[3].kind, SensorKind::Imu);
  EXPECT_EQ(all[3].recordIndex, -1);
  EXPECT_EQ(all[3].line, 3);
  EXPECT_EQ(all[3].file, dir_ + "/tip.xml");
  EXPECT_DOUBLE_EQ(all[3].params.updateRate, 100);
}

// The shoulder turns the arm about z through (2, 0, 1): a point p out on
// the arm is at (2, 0, 1) + Rz(angle) p.
Eigen::Vector3d onArm(double angle, const Eigen::Vector3d& p) {
  return Eigen::Vector3d(2, 0, 1) + Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()) * p;
}

TEST_F(SensorsTest, ASensorOnALinkMovesWithTheJoint) {
  for (double angle : {0.0, 1.2}) {
    SCOPED_TRACE(angle);
    build(angle, kOnArm);
    Diagnostics d;
    std::vector<SensorSpec> all = collectSensors(doc_, scene_, models_, d);
    ASSERT_EQ(all.size(), 2u);
    BodyPoses poses = restPoses(scene_, models_);
    Pose cam = sensorPose(all[0], scene_, poses);
    Pose imu = sensorPose(all[1], scene_, poses);
    EXPECT_TRUE(cam.position.isApprox(onArm(angle, {1, 0, 0}), 1e-12)) << cam.position.transpose();
    EXPECT_TRUE(imu.position.isApprox(onArm(angle, {0.5, 0, 0}), 1e-12)) << imu.position.transpose();
    // Looking along the arm: +x of the sensor is the arm's direction.
    Eigen::Vector3d forward = cam.orientation * Eigen::Vector3d::UnitX();
    EXPECT_TRUE(forward.isApprox(Eigen::Vector3d(std::cos(angle), std::sin(angle), 0), 1e-12));
  }
}

TEST_F(SensorsTest, BodyPosesMoveSensorsOnObjectsAndRobots) {
  build(0, kOnArm + "sensor /World/OnBox imu box 0 0 1 1 0 0 0\nsensor /World/Free lidar - 0 0 3 1 0 0 0\n");
  Diagnostics d;
  std::vector<SensorSpec> all = collectSensors(doc_, scene_, models_, d);
  BodyPoses poses = restPoses(scene_, models_);
  EXPECT_TRUE(sensorPose(all[1], scene_, poses).position.isApprox(Eigen::Vector3d(0, 0, 6)));  // box at z 5, +1
  EXPECT_TRUE(sensorPose(all[2], scene_, poses).position.isApprox(Eigen::Vector3d(0, 0, 3)));  // the world
  // The box fell to z 0.5 and turned half round z; the robot's links as at 90 degrees.
  poses.objects[0].position = {0, 0, 0.5};
  poses.objects[0].orientation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(sensorPose(all[1], scene_, poses).position.isApprox(Eigen::Vector3d(0, 0, 1.5)));
  build(M_PI / 2, kOnArm);
  BodyPoses turned = restPoses(scene_, models_);
  EXPECT_TRUE(sensorPose(all[0], scene_, turned).position.isApprox(onArm(M_PI / 2, {1, 0, 0}), 1e-12));
  // Without link poses (a robot not loaded), on the robot's record pose.
  turned.robotLinks[0].clear();
  EXPECT_TRUE(sensorPose(all[0], scene_, turned).position.isApprox(Eigen::Vector3d(3, 0, 0), 1e-12))
      << sensorPose(all[0], scene_, turned).position.transpose();
}

TEST_F(SensorsTest, RestPosesFollowTheRecordsCoordinate) {
  build(0.4, "");
  BodyPoses poses = restPoses(scene_, models_);
  ASSERT_EQ(poses.robotLinks.size(), 1u);
  const std::vector<Pose>& links = poses.robotLinks[0];
  ASSERT_EQ(links.size(), models_[0]->links.size());
  const Pose& arm = links[static_cast<std::size_t>(models_[0]->findLink("arm"))];
  EXPECT_TRUE(arm.position.isApprox(Eigen::Vector3d(2, 0, 1)));
  EXPECT_TRUE(arm.orientation.isApprox(Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ())), 1e-12));
  ASSERT_EQ(poses.objects.size(), 1u);
  EXPECT_TRUE(poses.objects[0].position.isApprox(Eigen::Vector3d(0, 0, 5)));
  // A robot whose model did not load has no link poses.
  std::vector<std::shared_ptr<const Model>> none = {nullptr};
  EXPECT_TRUE(restPoses(scene_, none).robotLinks[0].empty());
}

TEST_F(SensorsTest, AnUnknownParentLinkIsOneFindingWhoeverAsks) {
  const std::string bad = "sensor /World/Cam rgb robot 1 0 0 1 0 0 0 parentLink=shoulder\n";
  build(0, bad);
  Diagnostics d;
  std::vector<SensorSpec> all = collectSensors(doc_, scene_, models_, d);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].code, "RS7045");
  EXPECT_EQ(d[0].line, 5u);
  EXPECT_EQ(d[0].field, "parentLink");
  EXPECT_EQ(d[0].message, "parentLink 'shoulder' is no link of the model 'arm' of '/World/Arm'");
  EXPECT_EQ(d[0].hint, "'shoulder' is a joint; its child link is 'arm'");
  EXPECT_EQ(all[0].link, models_[0]->root);  // left on the root
  // rscene-validate's robot check: the same finding, once.
  ModelCache cache;
  Document doc;
  CollectDiagnostics found;
  validateScene(text_, CheckOptions{}, doc, found,
                [&](const Document& dd, const Scene& s, std::vector<SceneFinding>& out) {
                  checkRobots(dd, s, RobotCheckOptions{}, cache, out);
                });
  int count = 0;
  for (const Diagnostic& x : found.all)
    if (x.code == "RS7045") {
      ++count;
      EXPECT_EQ(x.message, d[0].message);
      EXPECT_EQ(x.column, d[0].column);
    }
  EXPECT_EQ(count, 1);
}

// rscene-validate's findings with its robot check (no --check-files
// unless asked).
Diagnostics validatedWithRobots(const std::string& text, bool checkFiles = false) {
  ModelCache cache;
  Document doc;
  CollectDiagnostics found;
  CheckOptions co;
  co.checkFiles = checkFiles;
  RobotCheckOptions ro;
  ro.checkFiles = checkFiles;
  validateScene(text, co, doc, found, [&](const Document& dd, const Scene& s, std::vector<SceneFinding>& out) {
    checkRobots(dd, s, ro, cache, out);
  });
  return std::move(found.all);
}

std::vector<std::string> codes(const Diagnostics& ds) {
  std::vector<std::string> out;
  for (const Diagnostic& d : ds) out.push_back(d.code);
  return out;
}

TEST_F(SensorsTest, SensorSetNumbersAreValidateFindingsWithoutCheckFiles) {
  // What sim and render refuse when they load the robot, validate says
  // without --check-files, in the set file at the sensor's line.
  build(0, "");  // (a bad set fails the robot's load: the scene text first)
  std::ofstream(dir_ + "/tip.xml") << R"(<sensor_set name="tip">
  <link>
    <sensor name="imu" type="imu" update_rate="2e6"><origin xyz="0.5 0 0"/></sensor>
  </link>
</sensor_set>
)";
  Diagnostics d = validatedWithRobots(text_);
  ASSERT_EQ(codes(d), std::vector<std::string>{"RS7067"});
  EXPECT_EQ(d[0].file, dir_ + "/tip.xml");
  EXPECT_EQ(d[0].line, 3u);
  EXPECT_EQ(d[0].severity, Severity::Error);
  // A value that is no number: RS7061, likewise.
  std::ofstream(dir_ + "/tip.xml") << R"(<sensor_set name="tip">
  <link>
    <sensor name="imu" type="imu" update_rate="nan"/>
  </link>
</sensor_set>
)";
  EXPECT_EQ(codes(validatedWithRobots(text_)), std::vector<std::string>{"RS7061"});
}

TEST_F(SensorsTest, AMissingSensorSetStaysACheckFilesFinding) {
  build(0, "");
  fs::remove(dir_ + "/tip.xml");
  EXPECT_TRUE(validatedWithRobots(text_).empty());
  EXPECT_EQ(codes(validatedWithRobots(text_, true)), std::vector<std::string>{"RS7060"});
}

TEST_F(SensorsTest, ARecordNamedAsARobotsSensorIsRS7070AtTheRecord) {
  // The tip set is named by its link, "arm": its IMU is /World/Arm/arm/imu.
  build(0, "sensor /World/Arm/arm/imu imu - 0 0 0 1 0 0 0\nsensor /World/Arm/arm/imu2 imu - 0 0 0 1 0 0 0\n");
  Diagnostics d = validatedWithRobots(text_);
  ASSERT_EQ(codes(d), std::vector<std::string>{"RS7070"});
  EXPECT_EQ(d[0].file, "");
  EXPECT_EQ(d[0].line, 5u);
  EXPECT_EQ(d[0].column, 8u);  // the record's path: the one to rename
  EXPECT_EQ(d[0].message, "the sensor record '/World/Arm/arm/imu' and the URDF sensor 'imu' of the sensor set on link "
                          "'arm' (" + dir_ + "/tip.xml:3) would both write 'World+Arm+arm+imu.csv'");
}

// Compared by what rscene-sim --sensors writes, not by name: a LiDAR record
// with the IMU's name writes a folder beside the IMU's file; an outputPath
// equal to the IMU's default file collides.
TEST_F(SensorsTest, ARecordClashesWithARobotsSensorByWhatItWrites) {
  build(0, "sensor /World/Arm/arm/imu lidar - 0 0 0 1 0 0 0\n");
  EXPECT_TRUE(validatedWithRobots(text_).empty()) << codes(validatedWithRobots(text_)).size();
  build(0, "sensor /World/Other imu - 0 0 0 1 0 0 0 outputPath=./World+Arm+arm+imu.csv\n");
  Diagnostics d = validatedWithRobots(text_);
  ASSERT_EQ(codes(d), std::vector<std::string>{"RS7070"});
  EXPECT_EQ(d[0].column, 52u);  // at the outputPath
  build(0, "sensor /World/Other imu - 0 0 0 1 0 0 0 outputPath=World+Arm+arm+imu.csv enabled=false\n");
  EXPECT_TRUE(validatedWithRobots(text_).empty());
}

}  // namespace
}  // namespace rscene::robot
