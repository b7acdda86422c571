#include "robot/check.hpp"

#include "core/codes.hpp"
#include "scene/validate.hpp"

#include <map>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "core/suggest.hpp"
#include "robot/ik.hpp"
#include "robot/instance.hpp"
#include "robot/sensors.hpp"
#include "scene/reader.hpp"
#include "scene/sensor_check.hpp"

namespace rscene::robot {
namespace {

// A robot whose model was read, by its articulated record.
struct Checked {
  const Articulated* record = nullptr;
  std::shared_ptr<const Model> model;
  Coordinates coordinates;
};

class RobotChecker {
 public:
  RobotChecker(const Document& doc, const Scene& scene, const RobotCheckOptions& options, ModelCache& cache,
               std::vector<SceneFinding>& out)
      : doc_(doc), scene_(scene), options_(options), cache_(cache), out_(out) {}

  void run() {
    for (const Articulated& a : scene_.articulated) used_.insert(a.resource);
    for (const Sensor& s : scene_.sensors) sensorAt_[s.recordIndex] = &s;
    for (const Articulated& a : scene_.articulated) articulated(a);
    if (options_.checkFiles) unusedResources();
    sensors();
    wires();
  }

 private:
  std::uint32_t lineOf(int recordIndex) const {
    return recordIndex >= 0 ? doc_.records[static_cast<std::size_t>(recordIndex)].line : 0;
  }

  // Findings in the scene are listed at their line; findings in a robot
  // file at `anchor`, the record that named the file.
  void take(Diagnostics& found, std::uint32_t anchor) {
    for (Diagnostic& d : found) out_.push_back({d.file.empty() ? d.line : anchor, std::move(d)});
    found.clear();
  }

  void articulated(const Articulated& a) {
    Diagnostics found;
    std::size_t enabled = 0;
    for (const ArticulatedIk& ik : a.ik) {
      if (!ik.enabled) continue;  // knobs of a target nobody solves are not used
      RecordReader r(doc_, static_cast<std::size_t>(ik.recordIndex), found);
      for (const auto& [field, message] : ikSettingsProblems(ik)) r.error(field, code::kIkSettings, message);
      if (++enabled == kMaxIkTargets + 1)
        r.error("frame", code::kIkSettings,
                "more than " + std::to_string(kMaxIkTargets) + " enabled IK targets on one articulated system");
    }
    take(found, 0);

    // RS3010 already names a resource that does not exist; with
    // --check-files lib/core's RS5001 names a robot file that does not.
    if (a.resource < 0 && a.sourcePath.empty()) return;
    if (options_.checkFiles && !a.sourcePath.empty() && !options_.exists(a.sourcePath)) return;
    if (!options_.checkFiles) sensorSetFindings(a, found);
    RobotInstance instance;
    InstanceOptions io;
    io.reportModel = options_.checkFiles;
    makeInstance(doc_, a, cache_, instance, found, io);
    take(found, lineOf(writtenBy(doc_, a, "sourcePath").record));
    if (!instance.model) return;

    const Model& model = *instance.model;
    for (const ArticulatedIk& ik : a.ik) {
      if (frameLink(model, ik.frame) >= 0) continue;
      RecordReader r(doc_, static_cast<std::size_t>(ik.recordIndex), found);
      r.error("frame", code::kUnknownFrame,
              "frame '" + ik.frame + "' is no joint or link of the model '" + model.name + "'" +
                  (ik.enabled ? "" : " (the target is disabled)"),
              frameHint(model, ik.frame), ik.enabled ? Severity::Error : Severity::Warning);
    }
    if (options_.checkFiles && options_.readMesh) collisionMeshes(a, model, found);
    take(found, 0);
    robots_[a.recordIndex] = {&a, instance.model, instance.coordinates};
  }

  // --check-files: every collision mesh reads, or rscene-sim refuses the
  // robot (RS7007 at the record's resource field, sim's words).  A mesh
  // that was not found is the loader's RS5001 in the robot file.
  void collisionMeshes(const Articulated& a, const Model& model, Diagnostics& found) {
    for (const Link& link : model.links)
      for (const Collision& c : link.collisions) {
        if (c.geometry.kind != GeometryKind::Mesh) continue;
        std::string why;
        if (options_.readMesh(c.geometry.meshPath, why)) continue;
        RecordReader(doc_, static_cast<std::size_t>(a.recordIndex), found)
            .error("resource", rscene::scene_code::kBadMesh,
                   "body '" + a.path + "': link '" + link.name + "': cannot read mesh '" + c.geometry.meshPath +
                       "': " + why);
        return;  // sim stops at the first
      }
  }

  // What is wrong inside a robot's sensor-set files is said without
  // --check-files too: sim and render refuse those numbers (RS7061,
  // RS7064-RS7067 ...) when they load the robot, so validate must not call
  // the scene clean.  A robot or sensor-set file that is missing (RS7060)
  // or a robot file that does not load stays --check-files' matter.  Runs
  // before makeInstance: the cache gives a model's findings to its first
  // request only.
  void sensorSetFindings(const Articulated& a, Diagnostics& found) {
    Diagnostics load;
    cache_.get(a.sourcePath, loadOptionsOf(a), load);
    for (Diagnostic& d : load)
      if (!d.file.empty() && d.code.rfind("RS706", 0) == 0 && d.code != rs::RS7060) found.push_back(std::move(d));
  }

  // --check-files reads a resource no articulated record instantiates too,
  // as written (its directory and modules, scale 1).
  void unusedResources() {
    Diagnostics found;
    for (std::size_t i = 0; i < scene_.articulatedResources.size(); ++i) {
      const ArticulatedResource& res = scene_.articulatedResources[i];
      if (used_.count(static_cast<int>(i)) || res.path.empty() || !options_.exists(res.path)) continue;
      LoadOptions lo;
      lo.resourceDirectory = res.resourceDirectory;
      lo.modules = res.modules;
      cache_.get(res.path, lo, found);
      take(found, lineOf(res.recordIndex));
    }
  }

  // The checked robot of an articulated record (the record a wire end or
  // a sensor mount resolved to in the scene model: one rule, by id then by
  // path); nullptr when its model was not read.
  const Checked* robotAt(int recordIndex) const {
    auto it = robots_.find(recordIndex);
    return it == robots_.end() ? nullptr : &it->second;
  }

  // The record of the articulated system `ref` names: by id, then by path
  // (the scene model's rule); -1 when none.
  int articulatedNamed(const std::string& ref) const {
    if (ref.empty()) return -1;
    for (const Articulated& a : scene_.articulated)
      if (a.id == ref) return a.recordIndex;
    for (const Articulated& a : scene_.articulated)
      if (a.path == ref) return a.recordIndex;
    return -1;
  }

  void sensors() {
    if (robots_.empty()) return;
    // Where rscene-sim --sensors would write the LiDARs and IMUs of the
    // robots' sensor sets (scene/sensor_check.hpp's rule, an IMU's default
    // .csv), to compare with what the sensor records write.
    SensorOutputs urdf;
    std::unordered_map<std::string, const SensorDef*> byName;
    for (const auto& [index, robot] : robots_)
      for (const SensorDef& d : robot.model->sensors) {
        if (d.kind != "lidar" && d.kind != "imu") continue;
        std::string name = robot.record->path + "/" + d.set + "/" + d.name;
        if (!byName.emplace(name, &d).second) continue;
        urdf.add(sensorOutput(name, "", d.kind == "lidar", ".csv"), name);
      }
    Diagnostics found;
    for (std::size_t i = 1; i < doc_.records.size(); ++i) {
      const Record& rec = doc_.records[i];
      if (!rec.kind || rec.kind->tag != "sensor") continue;
      RecordReader r(doc_, i, found);
      if (!byName.empty()) sameOutput(r, i, urdf, byName);
      std::string link = r.str("parentLink");
      if (link.empty() || link == "-") continue;
      // The robot the sensor rides on: Sensor::mount where the model read
      // sensors, else (validate's bodies-only build) the same rule, an id
      // first, then a path.
      const Checked* robot = nullptr;
      if (auto sensor = sensorAt_.find(static_cast<int>(i)); sensor != sensorAt_.end()) {
        const Mount& m = sensor->second->mount;
        if (m.kind == Mount::Kind::Articulated)
          robot = robotAt(scene_.articulated[static_cast<std::size_t>(m.index)].recordIndex);
      } else {
        robot = robotAt(articulatedNamed(r.str("parentObject")));
      }
      if (!robot || robot->model->findLink(link) >= 0) continue;
      reportUnknownSensorLink(doc_, static_cast<int>(i), *robot->model, link, robot->record->path, found);
    }
    take(found, 0);
  }

  // An enabled LiDAR or IMU record that would write where a sensor of a
  // robot's sensor set writes (the same file, or one inside the other's
  // folder): rscene-sim --sensors refuses it (RS7070).  Said at the
  // record, the one to rename.  Paths it refuses otherwise are
  // scene/sensor_check's findings.
  void sameOutput(const RecordReader& r, std::size_t index, const SensorOutputs& urdf,
                  const std::unordered_map<std::string, const SensorDef*>& byName) {
    Diagnostics ignored;
    RecordReader values(doc_, index, ignored);
    std::string kind = values.name("kind");
    if ((kind != "lidar" && kind != "imu") || !values.flag("enabled")) return;
    bool folder = kind == "lidar";
    std::string outputPath = values.str("outputPath");
    if (!outputPathProblem(outputPath).empty() || !sensorOutputProblem(outputPath, folder).empty()) return;
    std::string path = nodePath(doc_, r.record());
    std::string place = sensorOutput(path, outputPath, folder, ".csv");
    auto* other = urdf.clash(place);
    if (!other) return;
    const SensorDef& d = *byName.at(other->second);
    bool named = !outputPath.empty() && outputPath != "-";
    r.error(named ? "outputPath" : "path", sensor_code::kSameOutput,
            sensorClashMessage("the sensor record '" + path + "'", place,
                               "the URDF sensor '" + d.name + "' of the sensor set on link '" + d.set + "' (" + d.file +
                                   ":" + std::to_string(d.line) + ")",
                               other->first),
            "rename the record or give it an outputPath: rscene-sim --sensors would write both there");
  }

  void wires() {
    if (robots_.empty()) return;
    Diagnostics found;
    for (const Wire& w : scene_.wires) {
      RecordReader r(doc_, static_cast<std::size_t>(w.recordIndex), found);
      auto end = [&](WireEnd kind, int record, int index, const char* field) {
        if (kind != WireEnd::Articulated) return;
        const Checked* robot = robotAt(record);
        if (!robot) return;
        int bodies = bodyCount(robot->coordinates);
        if (index >= 0 && index < bodies) return;
        r.error(field, code::kWireBody,
                std::string(field) + " is " + std::to_string(index) + "; '" + robot->record->path + "' has bodies 0 to " +
                    std::to_string(bodies - 1),
                "RaiSim's body index: the base is 0, then one body per movable joint in joint order");
      };
      end(w.endA, w.recordA, w.localIndexA, "localIndexA");
      end(w.endB, w.recordB, w.localIndexB, "localIndexB");
    }
    take(found, 0);
  }

  const Document& doc_;
  const Scene& scene_;
  const RobotCheckOptions& options_;
  ModelCache& cache_;
  std::vector<SceneFinding>& out_;
  std::map<int, Checked> robots_;  // by articulated record index
  std::unordered_map<int, const Sensor*> sensorAt_;  // by record index
  std::unordered_set<int> used_;  // resources some articulated record instantiates
};

}  // namespace

int bodyCount(const Coordinates& c) { return static_cast<int>(c.joints.size()) + 1; }

void checkRobots(const Document& doc, const Scene& scene, const RobotCheckOptions& options, ModelCache& cache,
                 std::vector<SceneFinding>& out) {
  RobotChecker(doc, scene, options, cache, out).run();
}

bool checkDocument(const Document& doc, const std::string& sceneDir, Diagnostics& out) {
  return rscene::checkDocument(doc, sceneDir, out, [&](const Document& d, const Scene& s, std::vector<SceneFinding>& found) {
    ModelCache models;
    checkRobots(d, s, RobotCheckOptions{}, models, found);
  });
}

}  // namespace rscene::robot
