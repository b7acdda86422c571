#include "robot/sensor_set.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <set>

#include "core/assets.hpp"
#include "core/schema.hpp"
#include "robot/load.hpp"
#include "robot/xml_file.hpp"
#include "scene/limits.hpp"
#include "scene/sensor_check.hpp"

namespace rscene::robot {
namespace {

using tinyxml2::XMLElement;
constexpr double kPi = 3.14159265358979323846;
constexpr double kDegrees = 180.0 / kPi;

std::string join(const std::string& dir, const std::string& rest) {
  namespace fs = std::filesystem;
  if (dir.empty() || dir == ".") return fs::path(rest).lexically_normal().string();
  return (fs::path(dir) / rest).lexically_normal().string();
}

// The sensor record's default of `field` (the schema table holds it once).
double recordDefault(const char* field) {
  const KindDef* kind = Schema::get().kind("sensor");
  const FieldDef* f = kind ? kind->key(field) : nullptr;
  double v = 0;
  if (f && f->defaultValue) parseXmlNumber(*f->defaultValue, v);
  return v;
}

// A value quoted in a message, cut short: an attribute can be megabytes.
std::string shown(const char* text) {
  std::string_view v(text);
  return v.size() <= 60 ? std::string(v) : std::string(v.substr(0, 60)) + "...";
}

// One <sensor> element read into a SensorDef.
class SensorReader {
 public:
  SensorReader(const SensorSetFile& set, Diagnostics& diagnostics) : set_(set), diagnostics_(diagnostics) {}

  // False after an error; `skipped` when the sensor is left out with a warning.
  bool read(const XMLElement* e, SensorDef& out, bool& skipped);

 private:
  void report(Severity s, const char* code, const XMLElement* e, std::string message) {
    diagnostics_.push_back(robotDiagnostic(s, code, set_.path, e ? e->GetLineNum() : 0, std::move(message)));
    if (s == Severity::Error) ok_ = false;
  }
  void fail(const char* code, const XMLElement* e, std::string message) {
    report(Severity::Error, code, e, who_ + std::move(message));
  }

  // Numbers of attribute `attr` of `e`: nothing when absent, `count` when
  // present, else an RS7061 error (an unexpanded template too: a number
  // that is not there cannot be bounded).
  bool numbers(const XMLElement* e, const char* attr, std::size_t count, std::vector<double>& out) {
    out.clear();
    const char* text = e ? e->Attribute(attr) : nullptr;
    if (!text) return false;
    if (!parseXmlNumbers(text, out) || out.size() != count) {
      fail(code::kBadSensorSet, e,
           "<" + std::string(e->Name()) + " " + attr + "> is '" + shown(text) + "', not " + std::to_string(count) +
               (count == 1 ? " finite number" : " finite numbers"));
      out.clear();
      return false;
    }
    return true;
  }
  bool number(const XMLElement* e, const char* attr, double& out) {
    std::vector<double> v;
    if (!numbers(e, attr, 1, v)) return false;
    out = v[0];
    return true;
  }
  // An integer count (image side, samples): as a double first, so that a
  // hostile 1e30 is a number out of bounds, not a parse error.
  bool count(const XMLElement* e, const char* attr, std::int64_t& out) {
    double v = 0;
    if (!number(e, attr, v)) return false;
    if (v != std::floor(v)) {
      fail(code::kBadSensorSet, e, "<" + std::string(e->Name()) + " " + attr + "> is not a whole number");
      return false;
    }
    out = v >= 9e18 ? INT64_MAX : v <= -9e18 ? INT64_MIN : static_cast<std::int64_t>(v);
    return true;
  }
  void origin(const XMLElement* parent, Pose& out) {
    const XMLElement* o = parent->FirstChildElement("origin");
    if (!o) return;
    std::vector<double> xyz, rpy;
    if (numbers(o, "xyz", 3, xyz)) out.position = {xyz[0], xyz[1], xyz[2]};
    if (numbers(o, "rpy", 3, rpy)) out.orientation = rpyToQuaternion(rpy[0], rpy[1], rpy[2]);
    if (!(out.position.lpNorm<Eigen::Infinity>() <= kMaxLength))
      fail(code::kBadSensorSet, o, "<origin xyz> is beyond 1e12 m");
  }
  void camera(const XMLElement* e, SensorValues& v);
  void lidar(const XMLElement* e, SensorValues& v);
  void noise(const XMLElement* e, SensorValues& v);

  const SensorSetFile& set_;
  Diagnostics& diagnostics_;
  bool ok_ = true;
  std::string who_;  // "sensor 'NAME' of sensor set 'SET': "
  // Where each record field was written, for the bounds' messages.
  std::map<std::string, const XMLElement*> at_;
};

void SensorReader::camera(const XMLElement* e, SensorValues& v) {
  SensorParams& p = v.params;
  v.width = static_cast<std::int64_t>(recordDefault("width"));
  v.height = static_cast<std::int64_t>(recordDefault("height"));
  double verticalFov = recordDefault("verticalFov");
  const XMLElement* cam = e->FirstChildElement("camera");
  if (!cam) cam = e;  // image and clip written directly in the sensor
  double hfov = 0;
  bool haveHfov = number(cam, "horizontal_fov", hfov);
  if (const XMLElement* image = cam->FirstChildElement("image")) {
    count(image, "width", v.width);
    count(image, "height", v.height);
    at_["width"] = at_["height"] = image;
  }
  if (const XMLElement* clip = cam->FirstChildElement("clip")) {
    number(clip, "near", p.nearPlane);
    number(clip, "far", p.farPlane);
    at_["nearPlane"] = at_["farPlane"] = clip;
  }
  at_["verticalFov"] = at_["horizontalFov"] = cam;
  if (haveHfov) {
    // RaiSim's cameras are given by their horizontal field of view; the
    // vertical one follows from the image's aspect (square pixels).
    p.horizontalFov = hfov * kDegrees;
    double aspect = v.width > 0 && v.height > 0 ? double(v.height) / double(v.width) : 1;
    // (An hfov out of bounds is reported by itself; the vertical one keeps the default.)
    p.verticalFov = hfov > 0 && hfov < kPi ? 2 * std::atan(std::tan(hfov / 2) * aspect) * kDegrees : verticalFov;
  } else {
    p.verticalFov = verticalFov;
  }
  noise(cam, v);
}

void SensorReader::lidar(const XMLElement* e, SensorValues& v) {
  SensorParams& p = v.params;
  v.lidarChannels = static_cast<std::int64_t>(recordDefault("lidarChannels"));
  v.lidarSamples = static_cast<std::int64_t>(recordDefault("lidarSamples"));
  p.lidarMaxPitch = recordDefault("lidarVerticalFov") / 2;
  p.lidarMinPitch = -p.lidarMaxPitch;
  p.lidarMinRange = recordDefault("lidarMinRange");
  p.lidarMaxRange = recordDefault("lidarMaxRange");
  if (const XMLElement* yaw = e->FirstChildElement("yaw")) {
    count(yaw, "samples", v.lidarSamples);
    at_["lidarSamples"] = yaw;
  }
  if (const XMLElement* pitch = e->FirstChildElement("pitch")) {
    count(pitch, "samples", v.lidarChannels);
    double lo = 0, hi = 0;
    if (number(pitch, "min_angle", lo)) p.lidarMinPitch = lo * kDegrees;
    if (number(pitch, "max_angle", hi)) p.lidarMaxPitch = hi * kDegrees;
    at_["lidarChannels"] = at_["lidarVerticalFov"] = pitch;
    if (ok_ && !(p.lidarMinPitch >= -90 && p.lidarMaxPitch <= 90 && p.lidarMinPitch <= p.lidarMaxPitch))
      fail(sensor_code::kLidar, pitch, "<pitch min_angle max_angle> must satisfy -pi/2 <= min <= max <= pi/2");
  }
  if (const XMLElement* spin = e->FirstChildElement("spin")) {
    const char* direction = spin->Attribute("direction");
    // RaiSim: "everything other than clockwise is counter-clockwise".
    p.lidarClockwise = direction && std::string(direction) == "clockwise";
    if (number(spin, "rate", p.lidarSpinRate) && !(p.lidarSpinRate >= 0 && p.lidarSpinRate <= kMaxUpdateRate))
      fail(sensor_code::kRate, spin, "<spin rate> is outside 0..1e6 Hz");
  }
  if (const XMLElement* range = e->FirstChildElement("range")) {
    number(range, "min", p.lidarMinRange);
    number(range, "max", p.lidarMaxRange);
    at_["lidarMinRange"] = at_["lidarMaxRange"] = range;
  }
  v.lidarVerticalFov = p.lidarMaxPitch - p.lidarMinPitch;
  noise(e, v);
}

void SensorReader::noise(const XMLElement* e, SensorValues& v) {
  const XMLElement* n = e->FirstChildElement("noise");
  if (!n) return;
  at_["noiseMean"] = at_["noiseStddev"] = n;
  const char* type = n->Attribute("type");
  if (type && std::string(type) != "gaussian")
    report(Severity::Warning, code::kSensorSkipped, n,
           who_ + "noise type '" + shown(type) + "' is read as gaussian (the only noise the tools add)");
  number(n, "mean", v.params.noiseMean);
  number(n, "stddev", v.params.noiseStddev);
}

bool SensorReader::read(const XMLElement* e, SensorDef& out, bool& skipped) {
  skipped = false;
  const char* name = e->Attribute("name");
  const char* type = e->Attribute("type");
  if (!name || !*name || !type || !*type) {
    report(Severity::Error, code::kBadSensorSet, e,
           std::string("<sensor> without a ") + (!name || !*name ? "name" : "type") + " in sensor set '" + set_.name +
               "'");
    return false;
  }
  who_ = "sensor '" + std::string(name) + "' of sensor set '" + set_.name + "': ";
  const EnumDef* kinds = Schema::get().enumDef("sensor_kind");
  std::optional<std::string_view> canonical = kinds ? kinds->canonical(type) : std::nullopt;
  std::string kind = canonical ? std::string(*canonical) : std::string();
  if (kind.empty() || kind == "force_torque") {
    report(Severity::Warning, code::kSensorSkipped, e,
           who_ + "type '" + shown(type) + "' is not one the tools read (rgb, depth, imu, spinning_lidar); skipped");
    skipped = true;
    return true;
  }
  SensorValues v;
  v.kind = kind;
  at_.clear();
  at_["updateRate"] = e;
  if (!number(e, "update_rate", v.params.updateRate))
    if (const XMLElement* rate = e->FirstChildElement("update_rate"); rate && rate->GetText()) {
      at_["updateRate"] = rate;
      if (!parseXmlNumber(rate->GetText(), v.params.updateRate))
        fail(code::kBadSensorSet, rate, "<update_rate> is '" + shown(rate->GetText()) + "', not a finite number");
    }
  Pose local;
  origin(e, local);
  // Every kind carries near and far, as a sensor record does (a camera's <clip> sets them).
  v.params.nearPlane = recordDefault("nearPlane");
  v.params.farPlane = recordDefault("farPlane");
  if (isCameraLikeSensor(kind)) camera(e, v);
  if (kind == "lidar") lidar(e, v);
  if (kind == "imu") {
    if (const XMLElement* limit = e->FirstChildElement("limit")) {
      number(limit, "acc_limit", v.params.accelerationLimit);
      number(limit, "ang_vel_limit", v.params.angularVelocityLimit);
      at_["accelerationLimit"] = at_["angularVelocityLimit"] = limit;
    }
    noise(e, v);
  }
  if (!ok_) return false;
  // The record's bounds, with the record's codes, at the element that wrote
  // the number (the <sensor> for a default out of bounds: none is).
  for (const SensorProblem& problem : sensorProblems(v)) {
    auto where = at_.find(problem.field);
    fail(problem.code, where != at_.end() ? where->second : e, problem.message);
  }
  if (!ok_) return false;

  v.params.width = static_cast<int>(v.width);
  v.params.height = static_cast<int>(v.height);
  v.params.lidarChannels = static_cast<int>(v.lidarChannels);
  v.params.lidarSamples = static_cast<int>(v.lidarSamples);
  out = SensorDef{};
  out.name = name;
  out.kind = kind;
  out.origin = set_.origin * local;
  out.params = v.params;
  out.file = set_.path;
  out.line = e->GetLineNum();
  return true;
}

}  // namespace

std::vector<std::string> sensorSetCandidates(const std::string& dir, const std::string& file) {
  if (!file.empty() && file.front() == '/') return {file};
  return {join(dir, file), join(dir, "sensor/" + file), join(dir, "sensors/" + file), join(dir, "../" + file),
          join(dir, "../sensors/" + file)};
}

bool openSensorSet(const FileSystem& files, const std::string& urdfDirectory, const std::string& file, const std::string& urdfFile, int line,
                   std::size_t maxBytes, SensorSetFile& out, Diagnostics& diagnostics) {
  std::vector<std::string> tried = sensorSetCandidates(urdfDirectory, file);
  for (const std::string& c : tried)
    if (files.stat(c).kind == FileKind::Regular) {
      out.path = c;
      break;
    }
  if (out.path.empty()) {
    std::string list;
    for (const std::string& c : tried) list += (list.empty() ? "" : ", ") + c;
    diagnostics.push_back(robotDiagnostic(Severity::Error, code::kNoSensorSet, urdfFile, line,
                                          "sensor set '" + file + "' not found (tried " + list + ")"));
    return false;
  }
  if (!readXmlFile(files, out.path, maxBytes, out.doc, diagnostics, "sensor set file", code::kBadSensorSet)) return false;
  const XMLElement* root = out.doc.RootElement();
  if (!root || std::string(root->Name()) != "sensor_set") {
    diagnostics.push_back(robotDiagnostic(
        Severity::Error, code::kBadSensorSet, out.path, root ? root->GetLineNum() : 0,
        "sensor set file's root element is <" + std::string(root ? root->Name() : "") + ">, not <sensor_set>"));
    return false;
  }
  if (const char* name = root->Attribute("name")) out.name = name;
  out.body = root->FirstChildElement("link");
  if (const XMLElement* o = root->FirstChildElement("origin")) {
    std::vector<double> xyz, rpy;
    for (auto [attr, values] : {std::pair{"xyz", &xyz}, std::pair{"rpy", &rpy}}) {
      const char* text = o->Attribute(attr);
      if (text && (!parseXmlNumbers(text, *values) || values->size() != 3)) {
        diagnostics.push_back(robotDiagnostic(Severity::Error, code::kBadSensorSet, out.path, o->GetLineNum(),
                                              "<origin " + std::string(attr) + "> of sensor set '" + out.name +
                                                  "' is '" + shown(text) + "', not 3 finite numbers"));
        return false;
      }
    }
    if (xyz.size() == 3) out.origin.position = {xyz[0], xyz[1], xyz[2]};
    if (rpy.size() == 3) out.origin.orientation = rpyToQuaternion(rpy[0], rpy[1], rpy[2]);
    if (!(out.origin.position.lpNorm<Eigen::Infinity>() <= kMaxLength)) {
      diagnostics.push_back(robotDiagnostic(Severity::Error, code::kBadSensorSet, out.path, o->GetLineNum(),
                                            "<origin xyz> of sensor set '" + out.name + "' is beyond 1e12 m"));
      return false;
    }
  }
  return true;
}

bool readSensors(const SensorSetFile& set, const std::string& linkName, std::vector<SensorDef>& out,
                 Diagnostics& diagnostics) {
  const XMLElement* root = set.doc.RootElement();
  bool ok = true;
  std::set<std::string> names;
  for (const XMLElement* parent : {root, set.body}) {
    if (!parent) continue;
    for (const XMLElement* e = parent->FirstChildElement("sensor"); e; e = e->NextSiblingElement("sensor")) {
      SensorReader reader(set, diagnostics);
      SensorDef def;
      bool skipped = false;
      if (!reader.read(e, def, skipped)) {
        ok = false;
        continue;
      }
      if (skipped) continue;
      if (!names.insert(def.name).second) {
        // RaiSim finds a set's sensors by name: a second one of a name
        // could never be asked for.
        diagnostics.push_back(
            robotDiagnostic(Severity::Warning, code::kSensorSkipped, set.path, e->GetLineNum(),
                            "sensor set '" + set.name + "' has a second sensor named '" + def.name + "'; skipped"));
        continue;
      }
      def.set = linkName;
      out.push_back(std::move(def));
    }
  }
  return ok;
}

void combineInertial(Inertial& into, const Inertial& extra) {
  if (!(extra.mass > 0)) return;
  if (!(into.mass > 0)) {
    into = extra;
    return;
  }
  double mass = into.mass + extra.mass;
  Eigen::Vector3d com = (into.mass * into.origin.position + extra.mass * extra.origin.position) / mass;
  // Both inertias about `com`, in the link's axes, then in `into`'s axes.
  auto shifted = [&](const Inertial& in) {
    Eigen::Matrix3d r = in.origin.orientation.toRotationMatrix();
    Eigen::Matrix3d linkAxes = r * in.inertia * r.transpose();
    Eigen::Vector3d d = in.origin.position - com;
    return Eigen::Matrix3d(linkAxes + in.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose()));
  };
  Eigen::Matrix3d total = shifted(into) + shifted(extra);
  Eigen::Matrix3d r = into.origin.orientation.toRotationMatrix();
  into.inertia = r.transpose() * total * r;
  into.mass = mass;
  into.origin.position = com;
}

}  // namespace rscene::robot
