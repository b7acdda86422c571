// Sensor-record checks (scene/sensor_check.hpp): every bound fires on a
// record that breaks it, at the field, and not on the same record kept
// within it; checkScene() (what sim and render run) and rscene-validate
// report each condition once, with the same code at the same line:col.
#include "scene/sensor_check.hpp"

#include <gtest/gtest.h>

#include "core/loader.hpp"
#include "scene/check.hpp"
#include "scene/validate.hpp"

namespace rscene {
namespace {

const std::string H = "raisim_engine_scene 2\n";
const std::string kRobot =
    "articulated_resource arm Arm arm.urdf\n"
    "articulated /World/Arm arm 0 0 0 1 0 0 0 true true id=robot\n";
const std::string kBox =
    "object /World/Box box 0 0 1 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false - dynamic true 1 "
    "18446744073709551615 id=box\n";

std::string sensor(const std::string& kind, const std::string& keys, const std::string& parent = "-") {
  return "sensor /World/S " + kind + " " + parent + " 0 0 1 1 0 0 0" + (keys.empty() ? "" : " " + keys) + "\n";
}

// checkScene's findings, as sim and render get them (a full scene build).
Diagnostics checked(const std::string& text) {
  LoadResult loaded = parse(text);
  EXPECT_TRUE(loaded.ok());
  Scene scene;
  Diagnostics d;
  buildScene(loaded.document, SceneOptions{}, scene, d);
  d.clear();  // the build's own findings are not what is tested here
  checkScene(loaded.document, scene, SceneCheckOptions{}, d);
  return d;
}

Diagnostics validated(const std::string& text) {
  Document doc;
  return validateScene(text, CheckOptions{}, doc);
}

std::string describe(const Diagnostics& ds) {
  std::string s;
  for (const Diagnostic& d : ds)
    s += d.code + " " + std::to_string(d.line) + ":" + std::to_string(d.column) + " " + d.message + "\n";
  return s;
}

// "CODE line:col" of the findings with codes RS2007, RS4012 or RS706x.
std::vector<std::string> sensorFindings(const Diagnostics& ds) {
  std::vector<std::string> out;
  for (const Diagnostic& d : ds)
    if (d.code == "RS2007" || d.code == "RS4012" || d.code.rfind("RS706", 0) == 0)
      out.push_back(d.code + " " + std::to_string(d.line) + ":" + std::to_string(d.column));
  return out;
}

struct Case {
  const char* code;
  const char* field;  // where the caret must be
  std::string bad, good;
};

std::string at(const std::string& text, const char* field) {
  // Column of `field=` (or of the kind for "kind") on the last line.
  std::size_t lineStart = text.rfind('\n', text.size() - 2) + 1;
  std::string line = text.substr(lineStart);
  std::size_t col = std::string(field) == "kind" ? line.find(' ', 7) + 1
                                                 : line.find(std::string(field) + "=") + std::string(field).size() + 1;
  return std::to_string(col + 1);
}

TEST(SensorCheck, EachBoundFiresAtItsFieldAndNotWithinIt) {
  const std::vector<Case> cases = {
      {"RS2007", "kind", sensor("sonar", ""), sensor("lidar", "")},
      {"RS7064", "width", sensor("rgb", "width=0"), sensor("rgb", "width=1")},
      {"RS7064", "height", sensor("depth", "height=16385"), sensor("depth", "height=16384")},
      {"RS7064", "verticalFov", sensor("rgb", "verticalFov=180"), sensor("rgb", "verticalFov=179.9")},
      {"RS7064", "verticalFov", sensor("rgb", "verticalFov=0"), sensor("rgb", "verticalFov=0.1")},
      {"RS7064", "horizontalFov", sensor("segmentation", "horizontalFov=-1"),
       sensor("segmentation", "horizontalFov=0")},
      // lib/core's near/far code, for every kind (validate's core check says it of any sensor).
      {"RS4012", "nearPlane", sensor("rgb_depth", "nearPlane=0"), sensor("rgb_depth", "nearPlane=0.001")},
      {"RS4012", "farPlane", sensor("imu", "nearPlane=2 farPlane=2"), sensor("imu", "nearPlane=2 farPlane=2.5")},
      {"RS7064", "farPlane", sensor("rgb", "farPlane=2e12"), sensor("rgb", "farPlane=1e12")},
      {"RS7065", "calibrationFx", sensor("rgb", "calibrationFx=500 calibrationFy=500 calibrationCx=320"),
       sensor("rgb", "calibrationFx=500 calibrationFy=500 calibrationCx=320 calibrationCy=240")},
      {"RS7065", "calibrationFy", sensor("depth", "calibrationFx=500 calibrationFy=0 calibrationCx=0 calibrationCy=0"),
       sensor("depth", "calibrationFx=500 calibrationFy=1 calibrationCx=0 calibrationCy=0")},
      {"RS7066", "lidarSamples", sensor("lidar", "lidarChannels=64 lidarSamples=65537"),
       sensor("lidar", "lidarChannels=64 lidarSamples=65536")},
      {"RS7066", "lidarChannels", sensor("spinning_lidar", "lidarChannels=0"),
       sensor("spinning_lidar", "lidarChannels=1")},
      {"RS7066", "lidarMinRange", sensor("lidar", "lidarMinRange=-0.1"), sensor("lidar", "lidarMinRange=0")},
      {"RS7066", "lidarMaxRange", sensor("lidar", "lidarMinRange=5 lidarMaxRange=5"),
       sensor("lidar", "lidarMinRange=5 lidarMaxRange=5.01")},
      {"RS7066", "lidarVerticalFov", sensor("lidar", "lidarVerticalFov=181"), sensor("lidar", "lidarVerticalFov=0")},
      {"RS7067", "updateRate", sensor("imu", "updateRate=-1"), sensor("imu", "updateRate=0")},
      {"RS7067", "updateRate", sensor("imu", "updateRate=1000001"), sensor("imu", "updateRate=1e6")},
      {"RS7067", "noiseStddev", sensor("depth", "noiseStddev=-0.01"), sensor("depth", "noiseStddev=0.01")},
      {"RS7067", "noiseMean", sensor("lidar", "noiseMean=-2e12"), sensor("lidar", "noiseMean=-2")},
      {"RS7068", "parentLink", H + kBox + sensor("imu", "parentLink=base", "box"),
       H + kRobot + sensor("imu", "parentLink=base", "robot")},
      {"RS7068", "parentLink", sensor("imu", "parentLink=base"), sensor("imu", "parentLink=-")},
      {"RS7069", "outputPath", sensor("rgb", "outputPath=/tmp/x.png"), sensor("rgb", "outputPath=out/x.png")},
      {"RS7069", "outputPath", sensor("rgb", "outputPath=a/../../x.png"), sensor("rgb", "outputPath=a/..x.png")},
  };
  for (const Case& c : cases) {
    std::string bad = c.bad.rfind(H, 0) == 0 ? c.bad : H + c.bad;
    std::string good = c.good.rfind(H, 0) == 0 ? c.good : H + c.good;
    SCOPED_TRACE(bad);
    std::string line = std::to_string(std::count(bad.begin(), bad.end(), '\n'));
    std::vector<std::string> want = {std::string(c.code) + " " + line + ":" + at(bad, c.field)};
    Diagnostics sim = checked(bad);
    EXPECT_EQ(sensorFindings(sim), want) << describe(sim);
    // validate: the same finding, once (RS2007 is lib/core's own, at the same place).
    Diagnostics v = validated(bad);
    EXPECT_EQ(sensorFindings(v), want) << describe(v);
    EXPECT_TRUE(sensorFindings(checked(good)).empty()) << describe(checked(good));
    EXPECT_TRUE(sensorFindings(validated(good)).empty()) << describe(validated(good));
  }
}

TEST(SensorCheck, SeverityAndRefusal) {
  // Warnings (kind, parentLink) do not fail checkScene; bounds do.
  for (const std::string& warning : {sensor("sonar", ""), sensor("imu", "parentLink=base")}) {
    LoadResult loaded = parse(H + warning);
    Scene scene;
    Diagnostics d;
    buildScene(loaded.document, SceneOptions{}, scene, d);
    EXPECT_TRUE(checkScene(loaded.document, scene, SceneCheckOptions{}, d)) << describe(d);
    ASSERT_EQ(sensorFindings(d).size(), 1u);
    EXPECT_EQ(d.back().severity, Severity::Warning);
  }
  LoadResult loaded = parse(H + sensor("rgb", "width=0"));
  Scene scene;
  Diagnostics d;
  buildScene(loaded.document, SceneOptions{}, scene, d);
  EXPECT_FALSE(checkScene(loaded.document, scene, SceneCheckOptions{}, d));
}

TEST(SensorCheck, KindDecidesWhichNumbersCount) {
  // An IMU has no image and a camera no LiDAR: their fields are not read.
  EXPECT_TRUE(sensorFindings(checked(H + sensor("imu", "width=0 lidarChannels=0"))).empty());
  EXPECT_TRUE(sensorFindings(checked(H + sensor("rgb", "lidarChannels=0 lidarMinRange=-1"))).empty());
  // The defaults of the schema pass every bound, for every kind.
  for (const char* kind : {"rgb", "depth", "segmentation", "rgb_depth", "imu", "lidar", "force_torque"})
    EXPECT_TRUE(sensorFindings(checked(H + sensor(kind, ""))).empty()) << kind;
}

TEST(SensorCheck, MessagesNameTheValueAndTheBound) {
  Diagnostics d = checked(H + sensor("lidar", "lidarChannels=100000 lidarSamples=100000"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].message, "lidar scan of 100000 x 100000 rays is more than 4194304 rays");
  d = checked(H + sensor("rgb", "calibrationCx=1 calibrationFx=2"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].message, "calibration given in part: calibrationFy, calibrationCy missing");
  EXPECT_EQ(d[0].field, "calibrationFx");         // the first of the four that is written
  // Four zeros: Engine 2's "not calibrated", no finding.
  EXPECT_TRUE(checked(H + sensor("rgb", "calibrationFx=0 calibrationFy=0 calibrationCx=0 calibrationCy=0")).empty());
  d = checked(H + sensor("rgb", "width=99999"));  // the scene model keeps 0; the message the value written
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].message, "image width is 99999, outside 1..16384");
}

TEST(SensorCheck, ProblemsOfValuesAsARobotFileGivesThem) {
  SensorValues v;
  v.kind = "lidar";
  v.lidarChannels = std::int64_t{1} << 40;  // as parsed from a hostile file: no overflow in the product
  v.lidarSamples = std::int64_t{1} << 40;
  v.params.lidarMinRange = 0.1;
  v.params.lidarMaxRange = 100;
  v.params.nearPlane = 0.05;  // every kind carries near and far
  v.params.farPlane = 100;
  std::vector<SensorProblem> p = sensorProblems(v);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_STREQ(p[0].code, "RS7066");
  v.kind = "imu";
  v.params.accelerationLimit = -1;
  p = sensorProblems(v);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_STREQ(p[0].field, "accelerationLimit");
}

TEST(SensorCheck, OutputPathRule) {
  EXPECT_EQ(outputPathProblem(""), "");
  EXPECT_EQ(outputPathProblem("-"), "");
  EXPECT_EQ(outputPathProblem("a/b.png"), "");
  EXPECT_EQ(outputPathProblem("..png"), "");
  EXPECT_EQ(outputPathProblem("/a.png"), "is absolute");
  EXPECT_EQ(outputPathProblem(".."), "has a '..' part");
  EXPECT_EQ(outputPathProblem("a/.."), "has a '..' part");
  EXPECT_EQ(outputPathProblem("../a"), "has a '..' part");
  EXPECT_EQ(outputPathProblem("a\\..\\x.png"), "has a '..' part");
  EXPECT_EQ(outputPathProblem("C:x.png"), "is absolute");
}

TEST(SensorCheck, CameraOutputPathToo) {
  std::string cam = "camera /World/C 0 0 1 1 0 0 0 50 0.05 50 64 48 rgb true outputPath=../c.png\n";
  std::vector<std::string> want = {"RS7069 2:68"};
  EXPECT_EQ(sensorFindings(checked(H + cam)), want);
  EXPECT_EQ(sensorFindings(validated(H + cam)), want);
}

// "CODE line:col" of every finding.
std::vector<std::string> all(const Diagnostics& ds) {
  std::vector<std::string> out;
  for (const Diagnostic& d : ds) out.push_back(d.code + " " + std::to_string(d.line) + ":" + std::to_string(d.column));
  return out;
}

TEST(SensorCheck, ParentObjectMustNameABody) {
  const std::string kCam = "camera /World/Cam 0 0 1 1 0 0 0 50 0.05 50 64 48 rgb true id=cam_over\n";
  const std::string kGroup = "group /World/G id=g\n";
  const std::string kMaterial = "material steel 0.5 0.5 0.5 1 0 0.5 0 0 0 0 false - - - - - -\n";
  // parentObject's column on the last line: after "sensor /World/S imu ".
  const std::string col = "21";
  struct {
    std::string scene, parent, code;
  } cases[] = {
      {"", "nosuch", "RS3012"},                  // no node at all
      {kMaterial, "steel", "RS3012"},            // a material is no node
      {"articulated_resource arm Arm arm.urdf\n", "arm", "RS3012"},  // nor a resource
      {kCam, "cam_over", "RS7063"},              // a node, but no body
      {kCam, "/World/Cam", "RS7063"},            // by path too
      {kGroup, "g", "RS7063"},
  };
  for (const auto& c : cases) {
    std::string text = H + c.scene + sensor("imu", "", c.parent);
    std::string line = std::to_string(2 + (c.scene.empty() ? 0 : 1));
    std::vector<std::string> want = {c.code + " " + line + ":" + col};
    // sim and render (checkScene) and validate: one finding, same place.
    EXPECT_EQ(all(checked(text)), want) << c.parent;
    EXPECT_EQ(all(validated(text)), want) << c.parent;
  }
  Diagnostics d = checked(H + kCam + sensor("imu", "", "cam_over"));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].message, "'cam_over' is a camera, not a body a sensor can ride on");
  EXPECT_EQ(d[0].severity, Severity::Error);
  // Bodies: an object, a compound, a robot, or none (-).
  EXPECT_TRUE(checked(H + kBox + sensor("imu", "", "box")).empty());
  EXPECT_TRUE(checked(H + kRobot + sensor("imu", "", "robot")).empty());
  EXPECT_TRUE(checked(H + sensor("imu", "", "-")).empty());
  // A sensor on a group is not also told that its parentLink is unused.
  EXPECT_EQ(all(checked(H + kGroup + sensor("imu", "parentLink=x", "g"))), std::vector<std::string>{"RS7063 3:21"});
}

TEST(SensorCheck, AValueThatDoesNotParseIsOneFinding) {
  // Each field, written so that it does not parse: only its RS2xxx, never a
  // bound judged on the default that replaced it (fx=nan was "fx is 0").
  const std::string kCalibration = "calibrationFx=500 calibrationFy=500 calibrationCx=320 calibrationCy=240";
  struct {
    const char* kind;
    std::string keys;
  } cases[] = {
      {"rgb", "width=abc"},         {"rgb", "height=1.5"},          {"rgb", "verticalFov=nan"},
      {"rgb", "horizontalFov=x"},   {"rgb", "nearPlane=nan"},       {"rgb", "farPlane=nan"},
      {"lidar", "lidarChannels=q"}, {"lidar", "lidarSamples=nan"},  {"lidar", "lidarVerticalFov=nan"},
      {"lidar", "lidarMinRange=x"}, {"lidar", "lidarMaxRange=nan"}, {"imu", "updateRate=nan"},
      {"imu", "noiseMean=nan"},     {"imu", "noiseStddev=nan"},
  };
  for (const auto& c : cases) {
    std::string text = H + sensor(c.kind, c.keys);
    EXPECT_TRUE(checked(text).empty()) << c.keys << "\n" << describe(checked(text));
    Diagnostics v = validated(text);
    ASSERT_EQ(v.size(), 1u) << c.keys << "\n" << describe(v);
    EXPECT_EQ(v[0].code.substr(0, 3), "RS2") << c.keys;
  }
  for (const char* field : {"calibrationFx", "calibrationFy", "calibrationCx", "calibrationCy"}) {
    std::string keys;
    for (const char* f : {"calibrationFx", "calibrationFy", "calibrationCx", "calibrationCy"})
      keys += std::string(keys.empty() ? "" : " ") + f + "=" + (f == std::string(field) ? "nan" : "500");
    EXPECT_TRUE(checked(H + sensor("rgb", keys)).empty()) << keys;
    EXPECT_EQ(all(validated(H + sensor("rgb", keys))).size(), 1u) << describe(validated(H + sensor("rgb", keys)));
  }
  // The others still judged: a bad width beside a nan fx.
  EXPECT_EQ(all(checked(H + sensor("rgb", "width=0 calibrationFx=nan " + kCalibration.substr(18)))),
            std::vector<std::string>{"RS7064 2:43"});
}

TEST(SensorOutputRule, WhatASensorWritesAndWhatCollides) {
  EXPECT_EQ(normalizedSensorOutput("./a//b/."), "a/b");
  EXPECT_EQ(normalizedSensorOutput("."), "");
  EXPECT_EQ(sensorOutputProblem(".", true), "names the --sensors folder itself");
  EXPECT_EQ(sensorOutputProblem("./", false), "names the --sensors folder itself");
  EXPECT_EQ(sensorOutputProblem("sub/", false), "ends in '/', but an IMU writes a file");
  EXPECT_EQ(sensorOutputProblem("sub/.", false), "ends in '/', but an IMU writes a file");
  EXPECT_EQ(sensorOutputProblem("sub/", true), "");  // a LiDAR's folder
  EXPECT_EQ(sensorOutputProblem("a.b", false), "");
  EXPECT_EQ(sensorOutput("/World/Imu", "", false, ".csv"), "World+Imu.csv");
  EXPECT_EQ(sensorOutput("/World/L", "", true, ".csv"), "World+L");
  EXPECT_EQ(sensorOutput("/World/L", "scans/", true, ".csv"), "scans");
  SensorOutputs o;
  o.add("x", "L");
  o.add("World+Robot+lidar", "R");
  EXPECT_NE(o.clash("x"), nullptr);
  EXPECT_NE(o.clash("x/scans.csv"), nullptr);             // inside the folder x
  EXPECT_EQ(o.clash("x.csv"), nullptr);                   // beside it
  EXPECT_EQ(o.clash("World+Robot+lidar.csv"), nullptr);   // an IMU named like the LiDAR
  EXPECT_EQ(o.clash("xy"), nullptr);
  o.add("deep/a/b", "D");
  ASSERT_NE(o.clash("deep"), nullptr);  // a file where a folder of another sensor is
  EXPECT_EQ(o.clash("deep")->second, "D");
}

TEST(SensorCheck, SensorOutputsSimWouldRefuseAreRefusedAtTheRecord) {
  auto codesOf = [](const std::string& lines) { return all(checked(H + lines)); };
  EXPECT_EQ(codesOf("sensor /World/I imu - 0 0 1 1 0 0 0 outputPath=.\n"), std::vector<std::string>{"RS7069 2:48"});
  EXPECT_EQ(codesOf("sensor /World/I imu - 0 0 1 1 0 0 0 outputPath=sub/\n"), std::vector<std::string>{"RS7069 2:48"});
  EXPECT_TRUE(codesOf("sensor /World/L lidar - 0 0 1 1 0 0 0 outputPath=sub/\n").empty());
  EXPECT_EQ(codesOf("sensor /World/I imu - 0 0 1 1 0 0 0 outputPath=x/scans.csv\n"
                    "sensor /World/L lidar - 0 0 1 1 0 0 0 outputPath=x\n"),
            std::vector<std::string>{"RS7070 3:50"});
  EXPECT_EQ(codesOf("sensor /World/I imu - 0 0 1 1 0 0 0 outputPath=x\n"
                    "sensor /World/L lidar - 0 0 1 1 0 0 0 outputPath=x/y\n"),
            std::vector<std::string>{"RS7070 3:50"});
  // An IMU named like a LiDAR writes a file beside the LiDAR's folder.
  EXPECT_TRUE(codesOf("sensor /World/L lidar - 0 0 1 1 0 0 0\nsensor /World/I imu - 0 0 1 1 0 0 0 outputPath=World+L.csv\n")
                  .empty());
  // Without an outputPath the clash is said at the record's path.
  EXPECT_EQ(codesOf("sensor /World/I imu - 0 0 1 1 0 0 0 outputPath=World+J.csv\nsensor /World/J imu - 0 0 1 1 0 0 0\n"),
            std::vector<std::string>{"RS7070 3:8"});
}

TEST(SensorCheck, OrthoScaleFlatLidarAndUnusedSegmentation) {
  const std::string cam = "camera /World/C 0 0 5 1 0 0 0 45 0.05 50 64 48 rgb true ";
  auto codesOf = [](const std::string& lines) { return all(checked(H + lines)); };
  EXPECT_EQ(codesOf(cam + "projection=orthographic orthoScale=0\n"), std::vector<std::string>{"RS7074 2:92"});
  EXPECT_EQ(codesOf(cam + "projection=orthographic orthoScale=1e300\n"), std::vector<std::string>{"RS7074 2:92"});
  EXPECT_TRUE(codesOf(cam + "projection=orthographic orthoScale=4\n").empty());
  EXPECT_TRUE(codesOf(cam + "orthoScale=-6\n").empty());  // perspective: not used
  EXPECT_EQ(codesOf("sensor /World/L lidar - 0 0 1 1 0 0 0 lidarVerticalFov=0 lidarChannels=2\n"),
            std::vector<std::string>{"RS7072 2:56"});
  EXPECT_TRUE(codesOf("sensor /World/L lidar - 0 0 1 1 0 0 0 lidarVerticalFov=0 lidarChannels=1\n").empty());
  EXPECT_EQ(codesOf("sensor /World/I imu - 0 0 1 1 0 0 0 segmentation=true\n"),
            std::vector<std::string>{"RS7073 2:50"});
  EXPECT_TRUE(codesOf("sensor /World/S rgb - 0 0 1 1 0 0 0 segmentation=true\n").empty());
  Diagnostics d = checked(H + "sensor /World/I imu - 0 0 1 1 0 0 0 segmentation=true\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].severity, Severity::Warning);
}

TEST(SensorCheck, TwoEnabledSensorsWithOneOutputPath) {
  std::string text = H + "sensor /World/A imu - 0 0 1 1 0 0 0 outputPath=a.csv\n" +
                     "sensor /World/B imu - 0 0 1 1 0 0 0 enabled=false outputPath=a.csv\n" +
                     "sensor /World/C lidar - 0 0 1 1 0 0 0 outputPath=a.csv\n";
  std::vector<std::string> want = {"RS7070 4:50"};  // the second enabled one, at its outputPath
  EXPECT_EQ(all(checked(text)), want) << describe(checked(text));
  EXPECT_EQ(all(validated(text)), want);
  EXPECT_EQ(checked(text)[0].message, "sensor '/World/C' and sensor '/World/A' would both write 'a.csv'");
  EXPECT_TRUE(checked(H + "sensor /World/A imu - 0 0 1 1 0 0 0 outputPath=a.csv\n" +
                      "sensor /World/C lidar - 0 0 1 1 0 0 0 outputPath=c\n")
                  .empty());
}

}  // namespace
}  // namespace rscene
