// URDF sensor sets (lib/robot/sensor_set.cpp and the <link sensor=> hook
// of urdf.cpp): ANYmal C's real sets from ../shared/corpus (skipped when
// absent), RaiSim's search order, and every error and bound on files
// written into a scratch directory.
#include "robot/sensor_set.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "robot/load.hpp"

namespace rscene::robot {
namespace {

namespace fs = std::filesystem;
const std::string kAnymal = std::string(RSCENE_SHARED_DIR) + "/corpus/robots/anymal_c/urdf/anymal_sensored.urdf";
constexpr double kDeg = 180.0 / 3.14159265358979323846;

std::string messages(const Diagnostics& ds) {
  std::string out;
  for (const Diagnostic& d : ds)
    out += d.file + ":" + std::to_string(d.line) + ": " + d.message + " [" + d.code + "]\n";
  return out;
}

class Scratch {
 public:
  Scratch() {
    std::string pattern = (fs::temp_directory_path() / "rscene-sensorset-XXXXXX").string();
    std::vector<char> buf(pattern.begin(), pattern.end());
    buf.push_back('\0');
    path_ = ::mkdtemp(buf.data());
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string write(const std::string& rel, const std::string& text) const {
    fs::path p = fs::path(path_) / rel;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p.string();
  }
  std::string path(const std::string& rel) const { return (fs::path(path_) / rel).lexically_normal().string(); }

 private:
  std::string path_;
};

// A robot of one link `cam` (line 3) that names `set`.
std::string robotNaming(const std::string& set) {
  return "<robot name=\"r\">\n  <link name=\"base\"/>\n  <link name=\"cam\" sensor=\"" + set +
         "\"/>\n  <joint name=\"j\" type=\"fixed\"><parent link=\"base\"/><child link=\"cam\"/>"
         "<origin xyz=\"1 0 0\"/></joint>\n</robot>\n";
}

// A sensor set with one sensor element `sensor` (starting on line 4).
std::string setWith(const std::string& sensor, const std::string& origin = "<origin xyz=\"0 0 0.5\"/>") {
  return "<?xml version=\"1.0\"?>\n<sensor_set name=\"s\">\n  " + origin + "\n" + sensor + "\n</sensor_set>\n";
}

struct Loaded {
  bool ok = false;
  Model model;
  Diagnostics diagnostics;
};

Loaded loadRobot(const std::string& urdf, const LoadOptions& o = {}) {
  Loaded l;
  l.ok = loadModel(urdf, o, l.model, l.diagnostics);
  return l;
}

// ---------------------------------------------------------------------------
// ANYmal C

const SensorDef* find(const Model& m, const std::string& set, const std::string& name) {
  for (const SensorDef& d : m.sensors)
    if (d.set == set && d.name == name) return &d;
  return nullptr;
}

TEST(SensorSetCorpus, AnymalCHasEightSensorsOnTheRightLinksAtTheRightOrigins) {
  if (!fs::exists(kAnymal)) GTEST_SKIP() << "../shared/corpus is absent";
  Loaded l = loadRobot(kAnymal);
  ASSERT_TRUE(l.ok) << messages(l.diagnostics);
  const Model& m = l.model;
  ASSERT_EQ(m.sensors.size(), 8u);
  const std::string front = "depth_camera_front_camera_parent", rear = "depth_camera_rear_camera_parent";
  struct Want {
    std::string set, name, kind;
    Eigen::Vector3d origin;  // set origin + sensor origin (no rotations in these files)
  };
  const std::vector<Want> want = {
      {"lidar_link", "lidar", "lidar", {0.006253, -0.011775, 0.049645 + 0.008}},
      {"lidar_link", "imu", "imu", {0.006253, -0.011775, 0.049645 + 0.008}},
      {front, "color", "rgb", {0, -0.046, 0.004 + 0.015}},
      {front, "depth", "depth", {0, -0.03, 0.004 + 0.015}},
      {front, "imu", "imu", {0, 0, 0.015}},
      {rear, "color", "rgb", {0, -0.046, 0.004 + 0.015}},
      {rear, "depth", "depth", {0, -0.03, 0.004 + 0.015}},
      {rear, "imu", "imu", {0, 0, 0.015}},
  };
  for (std::size_t i = 0; i < want.size(); ++i) {
    const SensorDef& d = m.sensors[i];  // in link order, then file order
    SCOPED_TRACE(want[i].set + "/" + want[i].name);
    EXPECT_EQ(d.set, want[i].set);
    EXPECT_EQ(d.name, want[i].name);
    EXPECT_EQ(d.kind, want[i].kind);
    ASSERT_GE(d.link, 0);
    EXPECT_EQ(m.links[static_cast<std::size_t>(d.link)].name, want[i].set);
    EXPECT_TRUE(d.origin.position.isApprox(want[i].origin, 1e-12)) << d.origin.position.transpose();
    EXPECT_TRUE(d.origin.orientation.isApprox(Eigen::Quaterniond::Identity()));
    EXPECT_NE(d.file.find(d.set == "lidar_link" ? "sensors/ouster1-64.xml" : "sensors/realsense435.xml"),
              std::string::npos);
  }
  const SensorDef& color = *find(m, front, "color");
  EXPECT_EQ(color.params.width, 640);
  EXPECT_EQ(color.params.height, 480);
  EXPECT_NEAR(color.params.horizontalFov, 1.047 * kDeg, 1e-9);
  // Square pixels: tan(v/2) = tan(h/2) * 480/640.
  EXPECT_NEAR(std::tan(color.params.verticalFov / kDeg / 2), std::tan(1.047 / 2) * 0.75, 1e-12);
  EXPECT_DOUBLE_EQ(color.params.nearPlane, 0.1);
  EXPECT_DOUBLE_EQ(color.params.farPlane, 100);
  EXPECT_DOUBLE_EQ(color.params.noiseStddev, 0.007);
  EXPECT_DOUBLE_EQ(color.params.updateRate, 20);  // the attribute, not <update_rate>60
  EXPECT_EQ(color.line, 23);
  const SensorDef& lidar = *find(m, "lidar_link", "lidar");
  EXPECT_EQ(lidar.params.lidarChannels, 64);
  EXPECT_EQ(lidar.params.lidarSamples, 512);
  EXPECT_NEAR(lidar.params.lidarMinPitch, -0.2897247 * kDeg, 1e-9);
  EXPECT_NEAR(lidar.params.lidarMaxPitch, 0.2897247 * kDeg, 1e-9);
  EXPECT_DOUBLE_EQ(lidar.params.lidarMinRange, 0.8);
  EXPECT_DOUBLE_EQ(lidar.params.lidarMaxRange, 40);
  EXPECT_DOUBLE_EQ(lidar.params.lidarSpinRate, 10);
  EXPECT_TRUE(lidar.params.lidarClockwise);
  EXPECT_DOUBLE_EQ(lidar.params.updateRate, 100);
  const SensorDef& imu = *find(m, "lidar_link", "imu");
  EXPECT_DOUBLE_EQ(imu.params.accelerationLimit, 50);
  EXPECT_DOUBLE_EQ(imu.params.angularVelocityLimit, 40);
  EXPECT_DOUBLE_EQ(imu.params.updateRate, 10);
  EXPECT_DOUBLE_EQ(find(m, rear, "imu")->params.updateRate, 200);
}

TEST(SensorSetCorpus, TheSetsBodiesJoinTheirLinks) {
  if (!fs::exists(kAnymal)) GTEST_SKIP() << "../shared/corpus is absent";
  Loaded l = loadRobot(kAnymal);
  ASSERT_TRUE(l.ok) << messages(l.diagnostics);
  // The ouster's mesh (package://ouster_description/...) is not in the
  // corpus: one warning, in the set's file, said once.
  ASSERT_EQ(l.diagnostics.size(), 1u) << messages(l.diagnostics);
  EXPECT_EQ(l.diagnostics[0].code, "RS7031");
  EXPECT_NE(l.diagnostics[0].file.find("ouster1-64.xml"), std::string::npos);
  EXPECT_EQ(l.diagnostics[0].line, 35);
  const Model& m = l.model;
  const Link& lidar = m.links[static_cast<std::size_t>(m.findLink("lidar_link"))];
  ASSERT_EQ(lidar.visuals.size(), 1u);  // the box; the mesh was not found
  EXPECT_EQ(lidar.visuals[0].geometry.kind, GeometryKind::Box);
  EXPECT_TRUE(lidar.visuals[0].origin.position.isApprox(Eigen::Vector3d(0, 0, 0.008)));
  ASSERT_EQ(lidar.collisions.size(), 2u);
  EXPECT_EQ(lidar.collisions[1].geometry.kind, GeometryKind::Cylinder);
  EXPECT_TRUE(lidar.collisions[1].origin.position.isApprox(Eigen::Vector3d(0, 0, 0.0785 + 0.008)));
  EXPECT_DOUBLE_EQ(lidar.inertial.mass, 0.33);
  EXPECT_TRUE(lidar.inertial.origin.position.isApprox(Eigen::Vector3d(0, 0, 0.0785 + 0.008)));
  const Link& cam = m.links[static_cast<std::size_t>(m.findLink("depth_camera_front_camera_parent"))];
  ASSERT_EQ(cam.visuals.size(), 1u);  // model://realsense_camera/meshes/realsense.dae, found beside urdf/
  EXPECT_TRUE(fs::is_regular_file(cam.visuals[0].geometry.meshPath));
  EXPECT_TRUE(cam.visuals[0].geometry.meshScale.isApprox(Eigen::Vector3d::Constant(0.001)));
  EXPECT_DOUBLE_EQ(cam.inertial.mass, 0.061575);
}

// ---------------------------------------------------------------------------
// Search order and errors

TEST(SensorSet, SearchOrderIsRaiSims) {
  EXPECT_EQ(sensorSetCandidates("/r/urdf", "s.xml"),
            (std::vector<std::string>{"/r/urdf/s.xml", "/r/urdf/sensor/s.xml", "/r/urdf/sensors/s.xml", "/r/s.xml",
                                      "/r/sensors/s.xml"}));
  EXPECT_EQ(sensorSetCandidates("/r/urdf", "/abs/s.xml"), std::vector<std::string>{"/abs/s.xml"});
  // The first place that has the file wins.
  Scratch dir;
  std::string urdf = dir.write("urdf/r.urdf", robotNaming("s.xml"));
  dir.write("sensors/s.xml", setWith("<sensor name=\"far\" type=\"imu\"/>"));
  Loaded l = loadRobot(urdf);
  ASSERT_TRUE(l.ok) << messages(l.diagnostics);
  ASSERT_EQ(l.model.sensors.size(), 1u);
  EXPECT_EQ(l.model.sensors[0].name, "far");
  dir.write("urdf/sensor/s.xml", setWith("<sensor name=\"near\" type=\"imu\"/>"));
  l = loadRobot(urdf);
  ASSERT_EQ(l.model.sensors.size(), 1u);
  EXPECT_EQ(l.model.sensors[0].name, "near");
}

TEST(SensorSet, NotFoundListsThePlacesSearchedAtTheLinksLine) {
  Scratch dir;
  std::string urdf = dir.write("urdf/r.urdf", robotNaming("gone.xml"));
  Loaded l = loadRobot(urdf);
  EXPECT_FALSE(l.ok);
  ASSERT_EQ(l.diagnostics.size(), 1u) << messages(l.diagnostics);
  const Diagnostic& d = l.diagnostics[0];
  EXPECT_EQ(d.code, "RS7060");
  EXPECT_EQ(d.file, urdf);
  EXPECT_EQ(d.line, 3u);
  EXPECT_NE(d.message.find(dir.path("urdf/sensors/gone.xml")), std::string::npos) << d.message;
  EXPECT_NE(d.message.find(dir.path("sensors/gone.xml")), std::string::npos) << d.message;
}

// One finding (code and line in the set's file) for each broken set.
TEST(SensorSet, EachProblemIsReportedInTheSetFileAtItsLine) {
  struct Case {
    std::string set;
    std::string code;
    unsigned line;
    bool loads;  // a warning leaves the robot loadable
  };
  const std::vector<Case> cases = {
      {"<sensor_set name=\"s\">\n<sensor name=\"a\"\n</sensor_set>\n", "RS7061", 2,
       false},  // not well-formed: the element left open
      {"<robot name=\"s\"/>\n", "RS7061", 1, false},
      {setWith("<sensor type=\"imu\"/>"), "RS7061", 4, false},
      {setWith("<sensor name=\"a\" type=\"imu\" update_rate=\"fast\"/>"), "RS7061", 4, false},
      {setWith("<sensor name=\"a\" type=\"rgb\">\n<camera horizontal_fov=\"1\"><image width=\"64.5\" height=\"48\"/>"
               "</camera></sensor>"),
       "RS7061", 5, false},
      {setWith("<sensor name=\"a\" type=\"imu\"/>", "<origin xyz=\"0 0\"/>"), "RS7061", 3, false},
      {setWith("<sensor name=\"a\" type=\"sonar\"/>"), "RS7062", 4, true},
      {setWith("<sensor name=\"a\" type=\"imu\"/>\n<sensor name=\"a\" type=\"imu\"/>"), "RS7062", 5, true},
      {setWith("<sensor name=\"a\" type=\"depth\">\n<camera><noise type=\"uniform\"/></camera></sensor>"), "RS7062", 5,
       true},
      // The record's bounds, with the record's codes, at the element that wrote the number.
      {setWith("<sensor name=\"a\" type=\"rgb\">\n<camera horizontal_fov=\"1\">\n<image width=\"0\" height=\"48\"/>"
               "</camera></sensor>"),
       "RS7064", 6, false},
      {setWith("<sensor name=\"a\" type=\"rgb\">\n<camera>\n<image width=\"1e30\" height=\"48\"/></camera></sensor>"),
       "RS7064", 6, false},
      {setWith("<sensor name=\"a\" type=\"depth\">\n<camera horizontal_fov=\"3.2\"/></sensor>"), "RS7064", 5, false},
      {setWith("<sensor name=\"a\" type=\"depth\">\n<camera>\n<clip near=\"2\" far=\"1\"/></camera></sensor>"),
       "RS4012", 6, false},
      {setWith("<sensor name=\"a\" type=\"spinning_lidar\">\n<yaw samples=\"1000000\"/>\n<pitch samples=\"1000000\" "
               "min_angle=\"-0.1\" max_angle=\"0.1\"/></sensor>"),
       "RS7066", 5, false},
      {setWith("<sensor name=\"a\" type=\"spinning_lidar\">\n<pitch samples=\"16\" min_angle=\"0.1\" "
               "max_angle=\"-0.1\"/></sensor>"),
       "RS7066", 5, false},
      {setWith("<sensor name=\"a\" type=\"spinning_lidar\">\n<range min=\"5\" max=\"1\"/></sensor>"), "RS7066", 5,
       false},
      {setWith("<sensor name=\"a\" type=\"imu\" update_rate=\"-1\"/>"), "RS7067", 4, false},
      {setWith("<sensor name=\"a\" type=\"imu\">\n<limit acc_limit=\"-5\"/></sensor>"), "RS7067", 5, false},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.set);
    Scratch dir;
    std::string urdf = dir.write("r.urdf", robotNaming("s.xml"));
    std::string set = dir.write("s.xml", c.set);
    Loaded l = loadRobot(urdf);
    EXPECT_EQ(l.ok, c.loads) << messages(l.diagnostics);
    ASSERT_EQ(l.diagnostics.size(), 1u) << messages(l.diagnostics);
    EXPECT_EQ(l.diagnostics[0].code, c.code) << messages(l.diagnostics);
    EXPECT_EQ(l.diagnostics[0].file, set);
    EXPECT_EQ(l.diagnostics[0].line, c.line) << messages(l.diagnostics);
    EXPECT_EQ(l.diagnostics[0].severity, c.loads ? Severity::Warning : Severity::Error);
  }
}

TEST(SensorSet, TwoLinksNamingOneBrokenFileHearOfItOnce) {
  Scratch dir;
  std::string urdf = dir.write("r.urdf",
                               "<robot name=\"r\">\n  <link name=\"base\" sensor=\"s.xml\"/>\n"
                               "  <link name=\"cam\" sensor=\"s.xml\"/>\n  <joint name=\"j\" type=\"fixed\">"
                               "<parent link=\"base\"/><child link=\"cam\"/></joint>\n</robot>\n");
  dir.write("s.xml", setWith("<sensor name=\"a\" type=\"sonar\"/>"));
  Loaded l = loadRobot(urdf);
  ASSERT_TRUE(l.ok);
  EXPECT_EQ(l.diagnostics.size(), 1u) << messages(l.diagnostics);
}

TEST(SensorSet, AnEmptySensorAttributeIsAWarning) {
  Scratch dir;
  std::string urdf = dir.write("r.urdf", robotNaming(""));
  Loaded l = loadRobot(urdf);
  ASSERT_TRUE(l.ok);
  ASSERT_EQ(l.diagnostics.size(), 1u) << messages(l.diagnostics);
  EXPECT_EQ(l.diagnostics[0].code, "RS7062");
  EXPECT_EQ(l.diagnostics[0].line, 3u);
  EXPECT_TRUE(l.model.sensors.empty());
}

// ---------------------------------------------------------------------------
// Values

TEST(SensorSet, DefaultsAreTheSensorRecordsAndOriginsCompose) {
  Scratch dir;
  std::string urdf = dir.write("r.urdf", robotNaming("s.xml"));
  dir.write("s.xml",
            setWith("<sensor name=\"c\" type=\"camera\">\n<origin xyz=\"1 0 0\" rpy=\"0 0 1.5707963267948966\"/>"
                    "\n</sensor>\n<sensor name=\"l\" type=\"lidar\"><update_rate>15</update_rate></sensor>",
                    "<origin xyz=\"0 0 0.5\" rpy=\"0 0 1.5707963267948966\"/>"));
  Loaded l = loadRobot(urdf);
  ASSERT_TRUE(l.ok) << messages(l.diagnostics);
  EXPECT_TRUE(l.diagnostics.empty()) << messages(l.diagnostics);
  ASSERT_EQ(l.model.sensors.size(), 2u);
  const SensorDef& c = l.model.sensors[0];
  EXPECT_EQ(c.kind, "rgb");  // RaiSim's alias, canonical
  EXPECT_EQ(c.set, "cam");
  EXPECT_EQ(c.link, l.model.findLink("cam"));
  // The set turned 90 degrees about z: the sensor's x offset lands on y.
  EXPECT_TRUE(c.origin.position.isApprox(Eigen::Vector3d(0, 1, 0.5), 1e-12)) << c.origin.position.transpose();
  EXPECT_TRUE((c.origin.orientation * Eigen::Vector3d::UnitX()).isApprox(-Eigen::Vector3d::UnitX(), 1e-12));
  // No <camera>: the sensor record's schema defaults.
  EXPECT_EQ(c.params.width, 640);
  EXPECT_EQ(c.params.height, 480);
  EXPECT_DOUBLE_EQ(c.params.verticalFov, 60);
  EXPECT_DOUBLE_EQ(c.params.nearPlane, 0.05);
  EXPECT_DOUBLE_EQ(c.params.farPlane, 100);
  const SensorDef& lidar = l.model.sensors[1];
  EXPECT_EQ(lidar.params.lidarChannels, 16);
  EXPECT_EQ(lidar.params.lidarSamples, 1024);
  EXPECT_DOUBLE_EQ(lidar.params.lidarMaxPitch - lidar.params.lidarMinPitch, 30);
  EXPECT_DOUBLE_EQ(lidar.params.updateRate, 15);  // the element, when no attribute
  EXPECT_FALSE(lidar.params.lidarClockwise);
}

TEST(SensorSet, ScalingTheRobotMovesItsSensors) {
  Scratch dir;
  std::string urdf = dir.write("r.urdf", robotNaming("s.xml"));
  dir.write("s.xml", setWith("<sensor name=\"i\" type=\"imu\"><origin xyz=\"1 2 3\"/></sensor>"));
  LoadOptions o;
  o.scale = {2, 2, 2};
  Loaded l = loadRobot(urdf, o);
  ASSERT_TRUE(l.ok) << messages(l.diagnostics);
  ASSERT_EQ(l.model.sensors.size(), 1u);
  EXPECT_TRUE(l.model.sensors[0].origin.position.isApprox(Eigen::Vector3d(2, 4, 7)));  // (1, 2, 3.5) x 2
}

TEST(SensorSet, CombinedInertialIsTheTwoBodiesAsOne) {
  // Two 1 kg points (zero own inertia) 2 m apart on x: 2 kg at the middle,
  // Iyy = Izz = 2 x 1 kg x (1 m)^2, Ixx = 0.
  Inertial a, b;
  a.mass = 1;
  a.origin.position = {-1, 0, 0};
  b.mass = 1;
  b.origin.position = {1, 0, 0};
  b.origin.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()));  // a point: no matter
  combineInertial(a, b);
  EXPECT_DOUBLE_EQ(a.mass, 2);
  EXPECT_TRUE(a.origin.position.isZero());
  EXPECT_TRUE(a.inertia.isApprox(Eigen::Vector3d(0, 2, 2).asDiagonal().toDenseMatrix()));
  // A massless link takes the other as it is, axes included.
  Inertial empty;
  combineInertial(empty, b);
  EXPECT_DOUBLE_EQ(empty.mass, 1);
  EXPECT_TRUE(empty.origin.orientation.isApprox(b.origin.orientation));
}

}  // namespace
}  // namespace rscene::robot
