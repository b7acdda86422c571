// Every sensor of a scene in one list, wherever it was declared: the
// scene's sensor records and the sensor sets of its robots' URDFs
// (RaiSim's <link sensor="FILE">).  rscene-render draws the camera-like
// ones, rscene-sim records the physical ones (LiDAR, IMU); both place them
// with sensorPose() from the current poses of the bodies they ride on, so
// that a sensor on a robot link moves with the link.
//
// Frame convention (Sensors.rst): +x forward, +y left, +z up.  Depth is
// the distance along +x.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "robot/model.hpp"
#include "scene/scene.hpp"

namespace rscene::robot {

enum class SensorKind { Rgb, Depth, Segmentation, RgbDepth, Lidar, Imu, Other };

// The kind of a canonical sensor_kind name (Other for force_torque and names
// the schema does not know).
SensorKind sensorKindOf(const std::string& canonical);
const char* sensorKindName(SensorKind k);  // "rgb", "depth", ..., "other"
inline bool cameraLike(SensorKind k) {
  return k == SensorKind::Rgb || k == SensorKind::Depth || k == SensorKind::Segmentation || k == SensorKind::RgbDepth;
}

struct SensorSpec {
  // The sensor's name in outputs and messages: a sensor record's path, or
  // "<robot path>/<set>/<sensor>" for a sensor of a robot's sensor set.
  std::string name;
  std::string id;  // a sensor record's id; empty for a robot's sensor
  SensorKind kind = SensorKind::Other;
  std::string kindName;  // as the schema canonicalised it (force_torque, ...)
  Mount mount;           // the body it rides on (Scene::objects/compounds/articulated)
  int link = -1;         // Articulated: index into the robot model's links (-1: its root)
  Pose local;            // in the mount's frame (the link's for a robot)
  SensorParams params;
  bool enabled = true;
  std::string outputPath;  // as written; "-" and empty: none
  // Where it was declared, for messages: a sensor record (recordIndex >= 0),
  // else line `line` of the sensor-set file `file`, inside the robot named
  // by the articulated record `robotRecord`.
  int recordIndex = -1;
  int robotRecord = -1;
  std::string file;
  int line = 0;
};

// Current world poses of the bodies sensors ride on.  Objects and compounds
// are indexed like Scene::objects and Scene::compounds; `robotLinks` like
// Scene::articulated, each robot's link poses indexed like its model's
// links (robot::linkPoses), empty when its model was not loaded.
struct BodyPoses {
  std::vector<Pose> objects, compounds;
  std::vector<std::vector<Pose>> robotLinks;
};

// The poses the scene file gives (robots at their record's state, through
// `models`, indexed like Scene::articulated; a null model gets no links).
BodyPoses restPoses(const Scene& scene, const std::vector<std::shared_ptr<const Model>>& models);

// Every sensor: the sensor records in file order, then each robot's sensor
// sets (models indexed like Scene::articulated; null: not loaded, its
// sensors unknown).  A parentLink that names no link of its robot is
// RS7045 at the field (validate's code); the sensor stays on the root.
std::vector<SensorSpec> collectSensors(const Document& doc, const Scene& scene,
                                       const std::vector<std::shared_ptr<const Model>>& models,
                                       Diagnostics& diagnostics);

// RS7045 at `record`'s parentLink field: `link` names no link of `model`,
// the model of the robot `robotPath`, with a hint (the child link of a
// joint of that name, or the closest link name).  The one wording of the
// finding for validate's robot check and collectSensors (sim, render).
void reportUnknownSensorLink(const Document& doc, int record, const Model& model, const std::string& link,
                             const std::string& robotPath, Diagnostics& diagnostics);

// The sensor's world pose (looking along its +x) at `poses`.  A sensor on
// a body `poses` lacks (a robot not loaded) is placed on the body's pose in
// the scene file.
Pose sensorPose(const SensorSpec& sensor, const Scene& scene, const BodyPoses& poses);

}  // namespace rscene::robot
