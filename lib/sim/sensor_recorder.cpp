#include "sim/sensor_recorder.hpp"

#include "scene/mounted_node.hpp"

#include <chrono>
#include <cmath>
#include <map>
#include <optional>

#include "core/text.hpp"
#include "robot/kinematics.hpp"
#include "scene/reader.hpp"
#include "scene/sensor_check.hpp"
#include "sim/sensor_paths.hpp"

namespace rscene::sim {
namespace {

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// A finding about a sensor: at the record's field, or at the sensor's line
// of its robot's sensor-set file.
void report(const Document& doc, const robot::SensorSpec& s, const char* field, const char* code,
            const std::string& message, Severity severity, Diagnostics& ds) {
  if (s.recordIndex >= 0) {
    RecordReader r(doc, static_cast<std::size_t>(s.recordIndex), ds);
    r.error(field, code, message, {}, severity);
    return;
  }
  Diagnostic d;
  d.severity = severity;
  d.code = code;
  d.file = s.file;
  d.line = static_cast<std::uint32_t>(std::max(0, s.line));
  d.message = message;
  ds.push_back(std::move(d));
}

// What is wrong with a sensor's numbers for recording (empty: nothing):
// the bounds of scene/sensor_check.hpp that a checked scene already meets,
// so a scan never allocates past kMaxLidarRays.
struct Bad {
  const char* code = nullptr;
  const char* field = "";
  std::string why;
};
Bad badSetting(const robot::SensorSpec& s) {
  const SensorParams& p = s.params;
  auto finite = [](double v, double lo) { return std::isfinite(v) && v >= lo && v <= 1e12; };
  if (!(std::isfinite(p.updateRate) && p.updateRate >= 0 && p.updateRate <= kMaxUpdateRate))
    return {sensor_code::kRate, "updateRate", "updateRate must be within 0..1e6 Hz"};
  if (!finite(std::abs(p.noiseMean), 0) || !finite(p.noiseStddev, 0))
    return {sensor_code::kRate, "noiseStddev", "noise must be finite, its standard deviation >= 0"};
  if (s.kind == robot::SensorKind::Imu) {
    if (!finite(p.accelerationLimit, 0) || !finite(p.angularVelocityLimit, 0))
      return {sensor_code::kRate, "", "IMU limits must be within 0..1e12"};
    return {};
  }
  if (p.lidarChannels <= 0 || p.lidarSamples <= 0 ||
      std::int64_t(p.lidarChannels) * std::int64_t(p.lidarSamples) > kMaxLidarRays)
    return {sensor_code::kLidar, "lidarChannels",
            "a lidar scan of " + std::to_string(p.lidarChannels) + " x " + std::to_string(p.lidarSamples) +
                " rays is not within 1.." + std::to_string(kMaxLidarRays)};
  if (!(finite(p.lidarMinRange, 0) && finite(p.lidarMaxRange, 0) && p.lidarMaxRange > p.lidarMinRange))
    return {sensor_code::kLidar, "lidarMaxRange", "a lidar needs 0 <= lidarMinRange < lidarMaxRange <= 1e12"};
  if (!(std::isfinite(p.lidarMinPitch) && std::isfinite(p.lidarMaxPitch) && std::abs(p.lidarMinPitch) <= 90 &&
        std::abs(p.lidarMaxPitch) <= 90))
    return {sensor_code::kLidar, "lidarVerticalFov", "a lidar's pitch span must lie within -90..90 degrees"};
  return {};
}

}  // namespace

std::vector<RecordedSensor> planSensors(const Document& doc, const std::vector<robot::SensorSpec>& all,
                                        const SensorPlanOptions& options, Diagnostics& ds) {
  std::vector<RecordedSensor> out;
  SensorOutputs taken;  // place -> the name of the sensor writing it
  std::map<std::string, std::size_t> owner;  // that name -> index into out
  for (const robot::SensorSpec& s : all) {
    if (!s.enabled || robot::cameraLike(s.kind)) continue;
    if (s.kind != robot::SensorKind::Lidar && s.kind != robot::SensorKind::Imu) {
      report(doc, s, "kind", sim_code::kSensorNotRecorded,
             "sensor '" + s.name + "' of kind '" + s.kindName + "' is not recorded (rscene-sim records lidar and imu)",
             Severity::Warning, ds);
      continue;
    }
    if (Bad bad = badSetting(s); bad.code) {
      report(doc, s, bad.field, bad.code, "sensor '" + s.name + "': " + bad.why, Severity::Error, ds);
      continue;
    }
    RecordedSensor r;
    r.spec = s;
    bool folder = s.kind == robot::SensorKind::Lidar;
    bool named = !s.outputPath.empty() && s.outputPath != "-";
    if (named) {
      std::string why;
      if (!safeRelativePath(s.outputPath, why)) {
        report(doc, s, "outputPath", sensor_code::kOutputPath,
               "outputPath '" + s.outputPath + "' of sensor '" + s.name + "' cannot be used: " + why, Severity::Error,
               ds);
        continue;
      }
      // The rule validate applies too (scene/sensor_check.hpp).
      if (std::string problem = sensorOutputProblem(s.outputPath, folder); !problem.empty()) {
        report(doc, s, "outputPath", sensor_code::kOutputPath, "sensor outputPath '" + s.outputPath + "' " + problem,
               Severity::Error, ds);
        continue;
      }
    }
    if (!folder) {
      r.imuFormat = named && endsWith(s.outputPath, ".jsonl") ? ImuFormat::Jsonl
                    : named && endsWith(s.outputPath, ".csv") ? ImuFormat::Csv
                                                              : options.imuFormat;
    } else {
      r.directions = lidarDirections(s.params);
    }
    r.output = sensorOutput(s.name, s.outputPath, folder, r.imuFormat == ImuFormat::Csv ? ".csv" : ".jsonl");
    if (auto* other = taken.clash(r.output)) {
      // At the scene record when one of the two is one: it is the one to
      // rename (a robot's sensor-set file is not the user's to edit).
      const robot::SensorSpec& first = out[owner.at(other->second)].spec;
      bool atFirst = s.recordIndex < 0 && first.recordIndex >= 0;
      const robot::SensorSpec& at = atFirst ? first : s;
      const char* field = !at.outputPath.empty() && at.outputPath != "-" ? "outputPath" : "path";
      auto who = [](const robot::SensorSpec& x) {
        return (x.recordIndex >= 0 ? "the sensor record '" : "the URDF sensor '") + x.name + "'";
      };
      const robot::SensorSpec& rest = atFirst ? s : first;
      std::string atPlace = atFirst ? other->first : r.output, restPlace = atFirst ? r.output : other->first;
      report(doc, at, field, sim_code::kSensorSameOutput, sensorClashMessage(who(at), atPlace, who(rest), restPlace),
             Severity::Error, ds);
      continue;
    }
    taken.add(r.output, s.name);
    owner.emplace(s.name, out.size());
    out.push_back(std::move(r));
  }
  return out;
}

robot::BodyPoses currentPoses(const Scene& scene, const World& world) {
  robot::BodyPoses p;
  std::map<int, Pose*> byRecord;
  for (const Object& o : scene.objects) p.objects.push_back(o.world);
  for (const Compound& c : scene.compounds) p.compounds.push_back(c.world);
  for (std::size_t i = 0; i < scene.objects.size(); ++i) byRecord[scene.objects[i].recordIndex] = &p.objects[i];
  for (std::size_t i = 0; i < scene.compounds.size(); ++i) byRecord[scene.compounds[i].recordIndex] = &p.compounds[i];
  for (const BodyState& b : world.states())
    if (auto it = byRecord.find(b.recordIndex); it != byRecord.end()) *it->second = Pose{b.position, b.orientation};
  p.robotLinks.resize(scene.articulated.size());
  std::map<int, std::size_t> robotOf;
  for (std::size_t i = 0; i < scene.articulated.size(); ++i) robotOf[scene.articulated[i].recordIndex] = i;
  for (const RobotState& r : world.robotStates()) {
    auto it = robotOf.find(r.recordIndex);
    if (it == robotOf.end() || !r.instance || !r.instance->model) continue;
    p.robotLinks[it->second] = robot::linkPoses(*r.instance->model, r.instance->coordinates, r.instance->base, r.q);
  }
  return p;
}

struct SensorRecorder::State {
  double period = 0;           // 1 / updateRate; 0: every step
  std::uint64_t nextSlot = 0;  // the multiple of period the next reading waits for
  std::uint64_t readings = 0;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // an IMU's point, at the last step
  const btCollisionObject* exclude = nullptr;          // a LiDAR's own body
};

namespace {

// The name the world knows the mounted node by: its id (the world looks
// names up as the scene model does, an id first, so an id names one node),
// else its path; nullptr for the world.
const std::string* mountPath(const Scene& scene, const Mount& m) {
  MountedNode n = mountedNode(scene, m);
  if (!n.id) return nullptr;
  return n.id->empty() ? n.path : n.id;
}

}  // namespace

SensorRecorder::SensorRecorder(const Scene& scene, const World& world, std::vector<RecordedSensor> sensors, int threads)
    : scene_(scene), world_(world), sensors_(std::move(sensors)), states_(sensors_.size()), threads_(threads) {
  bool lidar = false;
  for (std::size_t i = 0; i < sensors_.size(); ++i) {
    const robot::SensorSpec& s = sensors_[i].spec;
    State& st = states_[i];
    st.period = s.params.updateRate > 0 ? 1 / s.params.updateRate : 0;
    if (s.kind != robot::SensorKind::Lidar) continue;
    lidar = true;
    if (const std::string* path = mountPath(scene, s.mount))
      st.exclude = s.mount.kind == Mount::Kind::Articulated ? world.robotCollisionObject(*path, s.link)
                                                            : world.collisionObject(*path);
  }
  if (lidar) geometry_ = std::make_unique<RayGeometry>(world);
}

SensorRecorder::~SensorRecorder() = default;

bool SensorRecorder::due(State& s, double time, bool first) const {
  if (s.period == 0) return true;
  // Slots are multiples of the period; a step that passes several takes
  // one reading (never more than one a step).
  double tolerance = 1e-9 * std::max(1.0, time);
  if (!first && time + tolerance < double(s.nextSlot) * s.period) return false;
  s.nextSlot = static_cast<std::uint64_t>(std::floor((time + tolerance) / s.period)) + 1;
  return true;
}

bool SensorRecorder::finite(std::size_t sensor, double time, const Pose& pose, const Eigen::Vector3d* a,
                            const Eigen::Vector3d* b) {
  bool ok = pose.position.allFinite() && pose.orientation.coeffs().allFinite() && (!a || a->allFinite()) &&
            (!b || b->allFinite());
  if (!ok) fault_ = Fault{sensor, time};
  return ok;
}

void SensorRecorder::faultDiagnostic(const Document& doc, Diagnostics& diagnostics) const {
  if (!fault_) return;
  const robot::SensorSpec& s = sensors_[fault_->sensor].spec;
  std::string time;
  appendNumber(time, fault_->time);
  reportAt(&doc, s.recordIndex, "position", rs::RS7024,
           "sensor '" + s.name + "' has a reading that is not finite at time " + time +
               " s: the body it rides on left the range a pose may have; nothing of it is written",
           diagnostics, Severity::Error, "look for a body thrown away or a spring too stiff for the time step");
}

bool SensorRecorder::sample(SensorOutput& out) {
  if (sensors_.empty()) return true;
  const double time = world_.time(), dt = world_.timeStep();
  const bool first = world_.steps() == 0;
  static const robot::BodyPoses kScenePoses;  // empty: robot::sensorPose falls back to the scene's poses
  bool geometryFresh = first;
  for (std::size_t i = 0; i < sensors_.size(); ++i) {
    const RecordedSensor& r = sensors_[i];
    const robot::SensorSpec& s = r.spec;
    State& st = states_[i];
    // Where its body is now: asked of the world for just that body (the
    // whole currentPoses() every step would cost more than the step).
    Pose pose = robot::sensorPose(s, scene_, kScenePoses);
    const std::string* path = mountPath(scene_, s.mount);
    if (path) {
      std::optional<Pose> body =
          s.mount.kind == Mount::Kind::Articulated ? world_.robotLinkPose(*path, s.link) : world_.bodyPose(*path);
      if (body) pose = *body * s.local;
    }
    if (s.kind == robot::SensorKind::Imu) {
      Eigen::Vector3d v = Eigen::Vector3d::Zero(), w = Eigen::Vector3d::Zero();
      if (path) {
        bool known = s.mount.kind == Mount::Kind::Articulated
                         ? world_.robotPointVelocity(*path, s.link, pose.position, v, w)
                         : world_.pointVelocity(*path, pose.position, v, w);
        if (!known) v.setZero(), w.setZero();  // a body not simulated (visual only) stays put
      }
      if (first) {
        st.velocity = v;
        st.nextSlot = 1;  // slot 0 (time 0) has no acceleration yet: the first reading waits for 1/r
        continue;
      }
      if (due(st, time, false)) {
        ImuReading reading = imuReading(time, pose, st.velocity, v, w, scene_.gravity, dt, s.params, st.readings++);
        if (!finite(i, time, pose, &reading.specificForce, &reading.angularVelocity) || !out.imuReading(i, reading))
          return false;
      }
      st.velocity = v;
      continue;
    }
    if (!due(st, time, first)) continue;
    if (!finite(i, time, pose)) return false;
    auto start = std::chrono::steady_clock::now();
    if (!geometryFresh) geometry_->update(world_), geometryFresh = true;
    LidarScanOptions o;
    o.exclude = st.exclude;
    o.scanIndex = st.readings;
    o.threads = threads_;
    std::vector<Eigen::Vector3f> points = scanLidar(*geometry_, pose, s.params, r.directions, o);
    scanSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++scans_;
    if (!out.lidarScan(i, st.readings++, time, pose, points)) return false;
  }
  return true;
}

}  // namespace rscene::sim
