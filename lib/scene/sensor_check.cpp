#include "scene/sensor_check.hpp"

#include <cmath>
#include <algorithm>
#include <set>
#include <string_view>
#include <unordered_map>

#include "core/codes.hpp"
#include "core/schema.hpp"
#include "core/text.hpp"
#include "scene/limits.hpp"
#include "scene/reader.hpp"

namespace rscene {
namespace {

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
      add(sensor_code::kImage, field, std::string(what) + " is " + numberText(v) + " degrees, outside (0, 180)");
  }

  void side(const char* field, const char* what, std::int64_t v) {
    if (v < 1 || v > kMaxCameraSide)
      add(sensor_code::kImage, field,
          std::string(what) + " is " + std::to_string(v) + ", outside 1.." + std::to_string(kMaxCameraSide));
  }

  // A non-negative number no larger than kMaxLength.
  void magnitude(const char* code, const char* field, const char* what, double v) {
    if (!(v >= 0 && v <= kMaxLength)) add(code, field, std::string(what) + " is " + numberText(v) + ", outside 0..1e12");
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
  // All four written as 0 is Engine 2's way of writing "not calibrated"
  // (its writer writes every key): the fields of view apply.
  if (values[0] == 0 && values[1] == 0 && values[2] == 0 && values[3] == 0) return;
  for (int i = 0; i < 2; ++i)
    if (!(values[i] > 0 && values[i] <= kMaxLength))
      b.add(sensor_code::kCalibration, kFields[i],
            std::string(i == 0 ? "fx" : "fy") + " is " + numberText(values[i]) + ", outside (0, 1e12] pixels");
  for (int i = 2; i < 4; ++i)
    if (!(std::abs(values[i]) <= kMaxLength))
      b.add(sensor_code::kCalibration, kFields[i],
            std::string(i == 2 ? "cx" : "cy") + " is " + numberText(values[i]) + ", beyond 1e12 pixels");
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
          "lidar vertical field of view is " + numberText(s.lidarVerticalFov) + " degrees, outside 0..180");
  if (!(p.lidarMinRange >= 0 && p.lidarMinRange <= kMaxLength))
    b.add(sensor_code::kLidar, "lidarMinRange", "lidar minimum range is " + numberText(p.lidarMinRange) + ", outside 0..1e12");
  else if (!(p.lidarMaxRange > p.lidarMinRange && p.lidarMaxRange <= kMaxLength))
    b.add(sensor_code::kLidar, "lidarMaxRange",
          "lidar maximum range is " + numberText(p.lidarMaxRange) + "; it must be beyond the minimum range (" +
              numberText(p.lidarMinRange) + ") and at most 1e12");
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
    b.add(sensor_code::kClip, "nearPlane", "near plane " + numberText(p.nearPlane) + " is not positive");
  else if (!(p.farPlane > p.nearPlane))
    b.add(sensor_code::kClip, "farPlane",
          "far plane " + numberText(p.farPlane) + " is not beyond the near plane " + numberText(p.nearPlane));
  else if (!(p.farPlane <= kMaxLength))
    b.add(sensor_code::kImage, "farPlane", "far plane " + numberText(p.farPlane) + " is beyond 1e12 m");
  if (isCameraLikeSensor(s.kind)) imageProblems(s, b);
  if (s.kind == "lidar") lidarProblems(s, b);
  if (!(p.updateRate >= 0 && p.updateRate <= kMaxUpdateRate))
    b.add(sensor_code::kRate, "updateRate", "update rate is " + numberText(p.updateRate) + " Hz, outside 0..1e6");
  if (!(std::abs(p.noiseMean) <= kMaxLength))
    b.add(sensor_code::kRate, "noiseMean", "noise mean is " + numberText(p.noiseMean) + ", beyond 1e12");
  b.magnitude(sensor_code::kRate, "noiseStddev", "noise standard deviation", p.noiseStddev);
  if (s.kind == "imu") {
    b.magnitude(sensor_code::kRate, "accelerationLimit", "IMU acceleration limit", p.accelerationLimit);
    b.magnitude(sensor_code::kRate, "angularVelocityLimit", "IMU angular velocity limit", p.angularVelocityLimit);
  }
  return out;
}

std::string outputPathProblem(const std::string& path) {
  if (path.empty() || path == "-") return {};
  // %00 decodes to a NUL the file system would cut the name at: two
  // records would write one file.
  if (path.find('\0') != std::string::npos) return "contains a NUL byte";
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

std::string imageExtensionProblem(const std::string& file) {
  std::size_t start = file.find_last_of('/');
  start = start == std::string::npos ? 0 : start + 1;
  std::size_t dot = file.find_last_of('.');
  if (dot == std::string::npos || dot <= start) return {};
  std::string extension = file.substr(dot + 1);
  std::string lower = extension;
  for (char& c : lower) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  // Only names that promise another format are refused: a name such as
  // "pipe.out" or "frame.tmp" promises nothing, and a FIFO or a temporary
  // name must stay writable.
  static const char* const kOther[] = {"jpg", "jpeg", "jpe", "jp2", "bmp", "gif", "tif", "tiff", "webp", "exr",
                                       "ppm", "pgm", "pbm", "pnm", "pfm", "hdr", "tga", "npy", "npz", "json",
                                       "csv", "pcd", "rgb", "depth", "segmentation"};
  if (std::find(std::begin(kOther), std::end(kOther), lower) == std::end(kOther)) return {};
  return "'" + file + "' ends in ." + extension +
         ", but rscene-render writes PNG images only (a depth image's float .npy and a segmentation's .json legend "
         "are written beside the image, under its name with .npy or .json)";
}

std::string sensorFileName(const std::string& path) {
  std::string out;
  bool componentStart = true;
  for (std::size_t i = !path.empty() && path[0] == '/' ? 1 : 0; i < path.size(); ++i) {
    unsigned char c = static_cast<unsigned char>(path[i]);
    bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
                 (c == '.' && !componentStart);
    componentStart = c == '/';
    if (c == '/') {
      out += '+';
    } else if (plain) {
      out += static_cast<char>(c);
    } else {
      static const char* const kHex = "0123456789ABCDEF";
      out += '%';
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  return out.empty() ? "%2F" : out;  // the path "/" alone (never a sensor's, but total)
}

std::string normalizedSensorOutput(const std::string& path) {
  std::string out;
  std::size_t start = 0;
  while (start <= path.size()) {
    std::size_t end = path.find('/', start);
    if (end == std::string::npos) end = path.size();
    std::string_view part(path.data() + start, end - start);
    if (!part.empty() && part != ".") {
      if (!out.empty()) out += '/';
      out += part;
    }
    start = end + 1;
  }
  return out;
}

std::string sensorOutputProblem(const std::string& path, bool folder) {
  if (path.empty() || path == "-") return {};
  if (normalizedSensorOutput(path).empty()) return "names the --sensors folder itself";
  if (!folder) {
    std::string_view last(path);
    while (!last.empty() && last.back() == '.' && (last.size() == 1 || last[last.size() - 2] == '/'))
      last.remove_suffix(1);
    if (!last.empty() && last.back() == '/') return "ends in '/', but an IMU writes a file";
  }
  return {};
}

std::string sensorOutput(const std::string& name, const std::string& outputPath, bool folder,
                         const std::string& imuExtension) {
  if (!outputPath.empty() && outputPath != "-") return normalizedSensorOutput(outputPath);
  return sensorFileName(name) + (folder ? "" : imuExtension);
}

const std::pair<const std::string, std::string>* SensorOutputs::clash(const std::string& place) const {
  if (auto it = places_.find(place); it != places_.end()) return &*it;
  // An earlier place that is a folder above this one.
  for (std::size_t slash = place.find('/'); slash != std::string::npos; slash = place.find('/', slash + 1))
    if (auto it = places_.find(place.substr(0, slash)); it != places_.end()) return &*it;
  // An earlier place inside this one.
  auto it = places_.lower_bound(place + '/');
  if (it != places_.end() && it->first.compare(0, place.size() + 1, place + '/') == 0) return &*it;
  return nullptr;
}

std::string sensorClashMessage(const std::string& self, const std::string& place, const std::string& other,
                               const std::string& otherPlace) {
  if (place == otherPlace) return self + " and " + other + " would both write '" + place + "'";
  if (place.size() > otherPlace.size())
    return self + " would write '" + place + "', inside '" + otherPlace + "' of " + other;
  return self + " would write '" + place + "', and " + other + " '" + otherPlace + "' inside it";
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
        camera(i);
    }
  }

 private:
  // Fields judged together: a value that did not parse (already an RS2xxx
  // error where it is written) silences every bound that reads it, so the
  // default it was replaced by never shows up as a second finding.
  static bool judgedWithBad(const char* field, const std::set<std::string_view>& bad) {
    static const std::vector<std::vector<std::string_view>> kTogether = {
        {"nearPlane", "farPlane"},
        {"lidarMinRange", "lidarMaxRange"},
        {"lidarChannels", "lidarSamples"},
        {"calibrationFx", "calibrationFy", "calibrationCx", "calibrationCy"}};
    if (bad.count(field)) return true;
    for (const auto& group : kTogether) {
      if (std::find(group.begin(), group.end(), field) == group.end()) continue;
      for (std::string_view f : group)
        if (bad.count(f)) return true;
    }
    return false;
  }

  void camera(std::size_t i) {
    RecordReader r(doc_, i, out_);
    outputPath(r, "camera", true);
    Diagnostics ignored;  // values that do not parse are RS2xxx errors already
    RecordReader values(doc_, i, ignored);
    std::size_t before = ignored.size();
    double scale = values.number("orthoScale");
    if (ignored.size() != before || values.name("projection") != "orthographic") return;
    if (!(std::isfinite(scale) && scale > 0 && scale <= kMaxLength))
      r.error("orthoScale", sensor_code::kOrthoScale,
              "orthoScale is " + numberText(scale) + " under an orthographic projection; it must be within (0, 1e12]",
              "the height of the view in metres");
  }

  void sensor(std::size_t i) {
    // Values are read with their parse errors left out: the scene build
    // (and lib/core's validator) already reported them.  Which fields did
    // not parse is remembered, to say nothing more about them.
    Diagnostics ignored;
    RecordReader values(doc_, i, ignored);
    RecordReader r(doc_, i, out_);
    std::set<std::string_view> bad;
    auto read = [&](const char* field, auto get) {
      std::size_t before = ignored.size();
      auto v = get(field);
      if (ignored.size() != before) bad.insert(field);
      return v;
    };
    auto number = [&](const char* f) { return read(f, [&](const char* g) { return values.number(g); }); };
    auto integer = [&](const char* f) { return read(f, [&](const char* g) { return values.integer(g); }); };
    SensorValues s;
    s.kind = values.name("kind");
    if (!isKnownSensorKind(s.kind))
      r.error("kind", sensor_code::kUnknownKind, "unknown sensor_kind '" + s.kind + "'",
              "the sensor is neither rendered nor simulated", Severity::Warning);
    s.width = integer("width");
    s.height = integer("height");
    s.lidarChannels = integer("lidarChannels");
    s.lidarSamples = integer("lidarSamples");
    s.lidarVerticalFov = number("lidarVerticalFov");
    static const char* const kCalibration[4] = {"calibrationFx", "calibrationFy", "calibrationCx", "calibrationCy"};
    for (std::size_t k = 0; k < 4; ++k) s.calibrationGiven[k] = values.has(kCalibration[k]);
    SensorParams& p = s.params;
    p.verticalFov = number("verticalFov");
    p.horizontalFov = number("horizontalFov");
    p.nearPlane = number("nearPlane");
    p.farPlane = number("farPlane");
    p.fx = number("calibrationFx");
    p.fy = number("calibrationFy");
    p.cx = number("calibrationCx");
    p.cy = number("calibrationCy");
    p.lidarMinRange = number("lidarMinRange");
    p.lidarMaxRange = number("lidarMaxRange");
    p.updateRate = number("updateRate");
    p.noiseMean = number("noiseMean");
    p.noiseStddev = number("noiseStddev");
    for (const SensorProblem& problem : sensorProblems(s))
      if (!judgedWithBad(problem.field, bad)) r.error(problem.field, problem.code, problem.message);
    if (s.kind == "lidar" && s.lidarVerticalFov == 0 && s.lidarChannels > 1 && !bad.count("lidarVerticalFov"))
      r.error("lidarVerticalFov", sensor_code::kFlatLidar,
              "lidarVerticalFov is 0 with " + std::to_string(s.lidarChannels) +
                  " channels: every ring scans the same plane",
              "give the vertical span in degrees, or lidarChannels=1 for a 2D LiDAR", Severity::Warning);
    if (!isCameraLikeSensor(s.kind) && isKnownSensorKind(s.kind) && values.flag("segmentation"))
      r.error("segmentation", sensor_code::kSegmentationUnused,
              "segmentation=true on a " + s.kind + " sensor is not used: only camera-like kinds draw images",
              "remove it, or use kind segmentation", Severity::Warning);

    std::string object = values.str("parentObject");
    if (object == "-") object.clear();
    bool onBody = object.empty() || mount(r, object);
    std::string link = values.str("parentLink");
    if (onBody && !link.empty() && link != "-") parentLink(r, object, link);
    bool problem = outputPath(r, "sensor", isCameraLikeSensor(s.kind));
    if (!values.flag("enabled")) return;
    if (s.kind == "lidar" || s.kind == "imu") {
      if (!problem) recorded(r, s.kind == "lidar", values.str("outputPath"));
    } else {
      sameOutput(r, values.str("outputPath"));
    }
  }

  // Where rscene-sim --sensors would write this LiDAR or IMU (an unnamed
  // IMU's default .csv), refused as sim refuses it: RS7069 for a place it
  // cannot use, RS7070 for one that collides with an earlier sensor's.
  void recorded(const RecordReader& r, bool folder, const std::string& outputPath) {
    if (std::string why = sensorOutputProblem(outputPath, folder); !why.empty()) {
      r.error("outputPath", sensor_code::kOutputPath, "sensor outputPath '" + outputPath + "' " + why,
              folder ? "a LiDAR's outputPath is a folder under --sensors DIR" : "name a file under --sensors DIR");
      return;
    }
    std::string self = nodePath(doc_, r.record());
    std::string place = sensorOutput(self, outputPath, folder, ".csv");
    bool named = !outputPath.empty() && outputPath != "-";
    if (auto* other = recorded_.clash(place)) {
      r.error(named ? "outputPath" : "path", sensor_code::kSameOutput,
              sensorClashMessage("sensor '" + self + "'", place, "sensor '" + other->second + "'", other->first),
              "give each sensor its own outputPath (a LiDAR's is a folder)");
      return;
    }
    recorded_.add(place, self);
  }

  // What parentObject names must be a body the sensor can ride on: an
  // object, a compound or an articulated system.  Without this the scene
  // model leaves the sensor at its folder's frame (the world origin) and
  // sim and render would use it there without a word.  A name of no node
  // is lib/core's RS3012, said here too for sim and render (validate
  // drops this copy: core reports it at the same field).  False when the
  // name is not a body.
  bool mount(const RecordReader& r, const std::string& object) {
    int target = nodeNamed(object);
    if (target < 0) {
      r.error("parentObject", rs::RS3012, "body '" + object + "' does not exist", "name a node by its id or path");
      return false;
    }
    const std::string& tag = doc_.records[static_cast<std::size_t>(target)].kind->tag;
    if (tag == "object" || tag == "compound" || tag == "articulated") return true;
    std::string what = tag.find_first_of("aeiou") == 0 ? "an " + tag : "a " + tag;
    r.error("parentObject", sensor_code::kNotABody, "'" + object + "' is " + what + ", not a body a sensor can ride on",
            "name an object, a compound or an articulated system, or write - for a sensor fixed in the world");
    return false;
  }

  // parentLink only means something on a robot.
  void parentLink(const RecordReader& r, const std::string& object, const std::string& link) {
    if (!object.empty())
      for (const Articulated& a : scene_.articulated)
        if (a.id == object || a.path == object) return;
    std::string what = "no parentObject";
    if (!object.empty()) what = "parentObject '" + object + "', which is not an articulated system";
    r.error("parentLink", sensor_code::kLinkWithoutRobot,
            "parentLink '" + link + "' is not used: the sensor has " + what,
            "name a robot (an articulated record) in parentObject, or remove parentLink", Severity::Warning);
  }

  // Two enabled sensor records writing one outputPath (rscene-sim's
  // RS7070, said of the scene so that validate and render say it too).
  void sameOutput(const RecordReader& r, const std::string& path) {
    if (path.empty() || path == "-") return;
    std::string self = nodePath(doc_, r.record());
    auto [it, fresh] = outputs_.emplace(path, self);
    if (fresh) return;
    r.error("outputPath", sensor_code::kSameOutput,
            "sensors '" + it->second + "' and '" + self + "' would both write '" + path + "'",
            "give each sensor its own outputPath");
  }

  // The record a node reference names (by id first, then by path, the
  // first of a name, as the scene model resolves it), or -1.
  int nodeNamed(const std::string& ref) {
    if (!indexed_) {  // built on first use: few scenes need it
      indexed_ = true;
      for (std::size_t i = 1; i < doc_.records.size(); ++i) {
        const Record& rec = doc_.records[i];
        if (!rec.kind || !rec.kind->isNode()) continue;
        std::string id = nodeId(doc_, rec), path = nodePath(doc_, rec);
        if (!id.empty()) byId_.emplace(id, static_cast<int>(i));
        if (!path.empty()) byPath_.emplace(path, static_cast<int>(i));
      }
    }
    if (auto it = byId_.find(ref); it != byId_.end()) return it->second;
    if (auto it = byPath_.find(ref); it != byPath_.end()) return it->second;
    return -1;
  }

  // False when the outputPath is refused (said here).  `image`: the path
  // names the PNG rscene-render writes (a camera, a camera-like sensor).
  bool outputPath(const RecordReader& r, const char* what, bool image) {
    std::string path = r.str("outputPath");
    std::string problem = outputPathProblem(path);
    if (problem.empty() && image && path != "-" && !path.empty()) {
      std::string_view last(path);
      if (std::size_t slash = last.find_last_of("/\\"); slash != std::string_view::npos) last.remove_prefix(slash + 1);
      if (last.empty() || last == "." || last == "..")
        problem = "names a folder, but a view's image is a file";
      else if (std::string why = imageExtensionProblem(path); !why.empty())
        problem = why.substr(why.find("' ends in") + 2);
    }
    if (problem.empty()) return false;
    // Shown as written: a NUL byte spelled %00, not a raw byte on a terminal.
    std::string shown;
    for (char c : path) shown += c == '\0' ? std::string("%00") : std::string(1, c);
    r.error("outputPath", sensor_code::kOutputPath, std::string(what) + " outputPath '" + shown + "' " + problem,
            image ? "name a .png file (or no extension) inside the output folder, without '..'"
                  : "tools write outputs only inside their output folder: give a relative path without '..'");
    return true;
  }

  const Document& doc_;
  const Scene& scene_;
  Diagnostics& out_;
  const KindDef* sensorKind_ = Schema::get().kind("sensor");
  const KindDef* cameraKind_ = Schema::get().kind("camera");
  bool indexed_ = false;
  std::unordered_map<std::string, int> byId_, byPath_;
  std::unordered_map<std::string, std::string> outputs_;  // outputPath -> the first sensor writing it
  SensorOutputs recorded_;  // what the enabled LiDARs and IMUs would write under rscene-sim --sensors
};

}  // namespace

void checkSensors(const Document& doc, const Scene& scene, Diagnostics& diagnostics) {
  SensorChecker(doc, scene, diagnostics).run();
}

}  // namespace rscene
