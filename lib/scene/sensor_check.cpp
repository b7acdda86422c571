#include "scene/sensor_check.hpp"

#include <cmath>
#include <unordered_set>

#include "core/schema.hpp"
#include "core/text.hpp"
#include "scene/limits.hpp"
#include "scene/reader.hpp"

namespace rscene {
namespace {

std::string num(double v) {
  std::string s;
  appendNumber(s, v);
  return s;
}

// Checks of one sensor's numbers, each adding at most one problem.
class Bounds {
 public:
  explicit Bounds(std::vector<SensorProblem>& out) : out_(out) {}

  void add(const char* code, const char* field, std::string message) {
    out_.push_back({code, field, std::move(message)});
  }

  // A field of view in (0, 180) degrees; 0 allowed when `zeroIsUnset`.
  void fov(const char* field, const char* what, double v, bool zeroIsUnset) {
    if (zeroIsUnset && v == 0) return;
    if (!(v > 0 && v < 180))
      add(sensor_code::kImage, field, std::string(what) + " is " + num(v) + " degrees, outside (0, 180)");
  }

  void side(const char* field, const char* what, std::int64_t v) {
    if (v < 1 || v > kMaxCameraSide)
      add(sensor_code::kImage, field,
          std::string(what) + " is " + std::to_string(v) + ", outside 1.." + std::to_string(kMaxCameraSide));
  }

  // A non-negative number no larger than kMaxLength.
  void magnitude(const char* code, const char* field, const char* what, double v) {
    if (!(v >= 0 && v <= kMaxLength)) add(code, field, std::string(what) + " is " + num(v) + ", outside 0..1e12");
  }

 private:
  std::vector<SensorProblem>& out_;
};

void imageProblems(const SensorValues& s, Bounds& b) {
  const SensorParams& p = s.params;
  b.side("width", "image width", s.width);
  b.side("height", "image height", s.height);
  b.fov("verticalFov", "vertical field of view", p.verticalFov, false);
  b.fov("horizontalFov", "horizontal field of view", p.horizontalFov, true);

  // Intrinsics: all four or none, so that a half-written calibration is
  // not silently mixed with the fields of view.
  static const char* const kFields[4] = {"calibrationFx", "calibrationFy", "calibrationCx", "calibrationCy"};
  int given = 0;
  for (bool g : s.calibrationGiven) given += g;
  if (given == 0) return;
  if (given < 4) {
    std::string missing;
    int first = -1;
    for (int i = 0; i < 4; ++i) {
      if (s.calibrationGiven[static_cast<std::size_t>(i)]) {
        if (first < 0) first = i;
        continue;
      }
      missing += (missing.empty() ? "" : ", ") + std::string(kFields[i]);
    }
    b.add(sensor_code::kCalibration, kFields[first], "calibration given in part: " + missing + " missing");
    return;
  }
  const double values[4] = {p.fx, p.fy, p.cx, p.cy};
  for (int i = 0; i < 2; ++i)
    if (!(values[i] > 0 && values[i] <= kMaxLength))
      b.add(sensor_code::kCalibration, kFields[i],
            std::string(i == 0 ? "fx" : "fy") + " is " + num(values[i]) + ", outside (0, 1e12] pixels");
  for (int i = 2; i < 4; ++i)
    if (!(std::abs(values[i]) <= kMaxLength))
      b.add(sensor_code::kCalibration, kFields[i],
            std::string(i == 2 ? "cx" : "cy") + " is " + num(values[i]) + ", beyond 1e12 pixels");
}

void lidarProblems(const SensorValues& s, Bounds& b) {
  const SensorParams& p = s.params;
  if (s.lidarChannels < 1)
    b.add(sensor_code::kLidar, "lidarChannels", "lidar channels is " + std::to_string(s.lidarChannels) + ", below 1");
  else if (s.lidarSamples < 1)
    b.add(sensor_code::kLidar, "lidarSamples", "lidar samples is " + std::to_string(s.lidarSamples) + ", below 1");
  else if (s.lidarSamples > kMaxLidarRays / s.lidarChannels)  // division: the product may overflow
    b.add(sensor_code::kLidar, "lidarSamples",
          "lidar scan of " + std::to_string(s.lidarChannels) + " x " + std::to_string(s.lidarSamples) +
              " rays is more than " + std::to_string(kMaxLidarRays) + " rays");
  // A single channel scans a plane: a vertical span of 0 is a 2D LiDAR.
  if (!(s.lidarVerticalFov >= 0 && s.lidarVerticalFov <= 180))
    b.add(sensor_code::kLidar, "lidarVerticalFov",
          "lidar vertical field of view is " + num(s.lidarVerticalFov) + " degrees, outside 0..180");
  if (!(p.lidarMinRange >= 0 && p.lidarMinRange <= kMaxLength))
    b.add(sensor_code::kLidar, "lidarMinRange", "lidar minimum range is " + num(p.lidarMinRange) + ", outside 0..1e12");
  else if (!(p.lidarMaxRange > p.lidarMinRange && p.lidarMaxRange <= kMaxLength))
    b.add(sensor_code::kLidar, "lidarMaxRange",
          "lidar maximum range is " + num(p.lidarMaxRange) + "; it must be beyond the minimum range (" +
              num(p.lidarMinRange) + ") and at most 1e12");
}

}  // namespace

bool isCameraLikeSensor(const std::string& k) {
  return k == "rgb" || k == "depth" || k == "segmentation" || k == "rgb_depth";
}

bool isKnownSensorKind(const std::string& k) {
  const EnumDef* e = Schema::get().enumDef("sensor_kind");
  if (!e) return false;
  for (const EnumDef::Value& v : e->values)
    if (v.name == k) return true;
  return false;
}

std::vector<SensorProblem> sensorProblems(const SensorValues& s) {
  std::vector<SensorProblem> out;
  Bounds b(out);
  const SensorParams& p = s.params;
  // Near and far for every kind, in lib/core's words and code: validate's
  // core check says so of any sensor record (and drops this copy).
  if (!(p.nearPlane > 0))
    b.add(sensor_code::kClip, "nearPlane", "near plane " + num(p.nearPlane) + " is not positive");
  else if (!(p.farPlane > p.nearPlane))
    b.add(sensor_code::kClip, "farPlane",
          "far plane " + num(p.farPlane) + " is not beyond the near plane " + num(p.nearPlane));
  else if (!(p.farPlane <= kMaxLength))
    b.add(sensor_code::kImage, "farPlane", "far plane " + num(p.farPlane) + " is beyond 1e12 m");
  if (isCameraLikeSensor(s.kind)) imageProblems(s, b);
  if (s.kind == "lidar") lidarProblems(s, b);
  if (!(p.updateRate >= 0 && p.updateRate <= kMaxUpdateRate))
    b.add(sensor_code::kRate, "updateRate", "update rate is " + num(p.updateRate) + " Hz, outside 0..1e6");
  if (!(std::abs(p.noiseMean) <= kMaxLength))
    b.add(sensor_code::kRate, "noiseMean", "noise mean is " + num(p.noiseMean) + ", beyond 1e12");
  b.magnitude(sensor_code::kRate, "noiseStddev", "noise standard deviation", p.noiseStddev);
  if (s.kind == "imu") {
    b.magnitude(sensor_code::kRate, "accelerationLimit", "IMU acceleration limit", p.accelerationLimit);
    b.magnitude(sensor_code::kRate, "angularVelocityLimit", "IMU angular velocity limit", p.angularVelocityLimit);
  }
  return out;
}

std::string outputPathProblem(const std::string& path) {
  if (path.empty() || path == "-") return {};
  if (path.front() == '/' || path.front() == '\\') return "is absolute";
  if (path.size() >= 2 && path[1] == ':') return "is absolute";  // a Windows drive: C:x, C:/x
  // A '..' part ('/' or '\\' separated) climbs out of the folder outputs are written to.
  std::size_t start = 0;
  while (start <= path.size()) {
    std::size_t end = path.find_first_of("/\\", start);
    if (end == std::string::npos) end = path.size();
    if (path.compare(start, end - start, "..") == 0) return "has a '..' part";
    start = end + 1;
  }
  return {};
}

namespace {

class SensorChecker {
 public:
  SensorChecker(const Document& doc, const Scene& scene, Diagnostics& out) : doc_(doc), scene_(scene), out_(out) {}

  void run() {
    for (std::size_t i = 1; i < doc_.records.size(); ++i) {
      const Record& rec = doc_.records[i];
      if (!rec.kind) continue;
      // Kinds by pointer: validate runs this over scenes of millions of records.
      if (rec.kind == sensorKind_)
        sensor(i);
      else if (rec.kind == cameraKind_)
        outputPath(RecordReader(doc_, i, out_), "camera");
    }
  }

 private:
  void sensor(std::size_t i) {
    // Values are read with their parse errors left out: the scene build
    // (and lib/core's validator) already reported them.
    Diagnostics ignored;
    RecordReader values(doc_, i, ignored);
    RecordReader r(doc_, i, out_);
    SensorValues s;
    s.kind = values.name("kind");
    if (!isKnownSensorKind(s.kind))
      r.error("kind", sensor_code::kUnknownKind, "unknown sensor_kind '" + s.kind + "'",
              "the sensor is neither rendered nor simulated", Severity::Warning);
    s.width = values.integer("width");
    s.height = values.integer("height");
    s.lidarChannels = values.integer("lidarChannels");
    s.lidarSamples = values.integer("lidarSamples");
    s.lidarVerticalFov = values.number("lidarVerticalFov");
    static const char* const kCalibration[4] = {"calibrationFx", "calibrationFy", "calibrationCx", "calibrationCy"};
    for (std::size_t k = 0; k < 4; ++k) s.calibrationGiven[k] = values.has(kCalibration[k]);
    SensorParams& p = s.params;
    p.verticalFov = values.number("verticalFov");
    p.horizontalFov = values.number("horizontalFov");
    p.nearPlane = values.number("nearPlane");
    p.farPlane = values.number("farPlane");
    p.fx = values.number("calibrationFx");
    p.fy = values.number("calibrationFy");
    p.cx = values.number("calibrationCx");
    p.cy = values.number("calibrationCy");
    p.lidarMinRange = values.number("lidarMinRange");
    p.lidarMaxRange = values.number("lidarMaxRange");
    p.updateRate = values.number("updateRate");
    p.noiseMean = values.number("noiseMean");
    p.noiseStddev = values.number("noiseStddev");
    for (const SensorProblem& problem : sensorProblems(s)) r.error(problem.field, problem.code, problem.message);

    std::string link = values.str("parentLink");
    if (!link.empty() && link != "-") parentLink(r, values.str("parentObject"), link);
    outputPath(r, "sensor");
  }

  // parentLink only means something on a robot.  An unknown parentObject
  // is lib/core's RS3012, not this warning.
  void parentLink(const RecordReader& r, std::string object, const std::string& link) {
    if (object == "-") object.clear();
    if (!object.empty())
      for (const Articulated& a : scene_.articulated)
        if (a.id == object || a.path == object) return;
    std::string what = "no parentObject";
    if (!object.empty()) {
      if (!namesNode(object)) return;
      what = "parentObject '" + object + "', which is not an articulated system";
    }
    r.error("parentLink", sensor_code::kLinkWithoutRobot,
            "parentLink '" + link + "' is not used: the sensor has " + what,
            "name a robot (an articulated record) in parentObject, or remove parentLink", Severity::Warning);
  }

  bool namesNode(const std::string& ref) {
    if (nodes_.empty())  // built on first use: few scenes need it
      for (std::size_t i = 1; i < doc_.records.size(); ++i) {
        const Record& rec = doc_.records[i];
        if (!rec.kind || !rec.kind->isNode()) continue;
        nodes_.insert(nodeId(doc_, rec));
        nodes_.insert(nodePath(doc_, rec));
      }
    return nodes_.count(ref) > 0;
  }

  void outputPath(const RecordReader& r, const char* what) {
    std::string path = r.str("outputPath");
    std::string problem = outputPathProblem(path);
    if (!problem.empty())
      r.error("outputPath", sensor_code::kOutputPath, std::string(what) + " outputPath '" + path + "' " + problem,
              "tools write outputs only inside their output folder: give a relative path without '..'");
  }

  const Document& doc_;
  const Scene& scene_;
  Diagnostics& out_;
  const KindDef* sensorKind_ = Schema::get().kind("sensor");
  const KindDef* cameraKind_ = Schema::get().kind("camera");
  std::unordered_set<std::string> nodes_;
};

}  // namespace

void checkSensors(const Document& doc, const Scene& scene, Diagnostics& diagnostics) {
  SensorChecker(doc, scene, diagnostics).run();
}

}  // namespace rscene
