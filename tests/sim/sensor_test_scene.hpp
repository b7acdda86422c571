// Scenes for the sensor tests (lidar_sensor_test.cpp, imu_sensor_test.cpp):
// scene text in, a simulated world and its sensors out.
#pragma once
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "asset/cache.hpp"
#include "core/loader.hpp"
#include "robot/sensors.hpp"
#include "scene/scene.hpp"
#include "sim/sensor_recorder.hpp"
#include "sim/world.hpp"

namespace rscene::sim::test {

// An object line of the 25-field layout; `size` is "sx sy sz".
inline std::string object(const std::string& path, const std::string& prim, const Eigen::Vector3d& at,
                          const std::string& size, double radius, double height, double mass, const std::string& mode,
                          const std::string& extra = "", const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity()) {
  char buf[640];
  std::snprintf(buf, sizeof buf,
                "object %s %s %.17g %.17g %.17g %.17g %.17g %.17g %.17g %s %.17g %.17g %.17g default engine_default "
                "false true false - %s true 1 18446744073709551615 %s\n",
                path.c_str(), prim.c_str(), at.x(), at.y(), at.z(), q.w(), q.x(), q.y(), q.z(), size.c_str(), radius,
                height, mass, mode.c_str(), extra.c_str());
  return buf;
}

inline std::string box(const std::string& path, const Eigen::Vector3d& at, const Eigen::Vector3d& size,
                       const std::string& mode = "static", double mass = 0, const std::string& extra = "") {
  char s[128];
  std::snprintf(s, sizeof s, "%.17g %.17g %.17g", size.x(), size.y(), size.z());
  return object(path, "box", at, s, 0.5, 1, mass, mode, extra);
}

// A closed room: inside [-hx, hx] x [-hy, hy] x [0, 2 hz], walls 0.2 thick.
inline std::string room(double hx, double hy, double hz) {
  const double t = 0.2;
  std::string s;
  s += box("/World/Room/Floor", {0, 0, -t / 2}, {2 * hx + 2 * t, 2 * hy + 2 * t, t});
  s += box("/World/Room/Ceiling", {0, 0, 2 * hz + t / 2}, {2 * hx + 2 * t, 2 * hy + 2 * t, t});
  s += box("/World/Room/East", {hx + t / 2, 0, hz}, {t, 2 * hy, 2 * hz});
  s += box("/World/Room/West", {-hx - t / 2, 0, hz}, {t, 2 * hy, 2 * hz});
  s += box("/World/Room/North", {0, hy + t / 2, hz}, {2 * hx + 2 * t, t, 2 * hz});
  s += box("/World/Room/South", {0, -hy - t / 2, hz}, {2 * hx + 2 * t, t, 2 * hz});
  return s;
}

struct SensorRun {
  Document doc;
  Scene scene;
  Diagnostics diags;
  std::vector<robot::RobotInstance> robots;
  std::unique_ptr<asset::AssetCache> cache;  // before the world, which reads through it
  std::unique_ptr<World> world;
  std::vector<RecordedSensor> sensors;
};

// Builds and simulates `body` (after the header and gravity 0 0 -9.81 unless
// it has a gravity line), with meshes from `fs` when given, and plans its
// sensors.  Robots: `models` (one articulated record per model, /World/R0 ...,
// at `robotAt`).
inline std::unique_ptr<SensorRun> makeSensorRun(const std::string& body, MemoryFileSystem* fs = nullptr,
                                                const std::vector<std::shared_ptr<robot::Model>>& models = {},
                                                const std::string& robotAt = "0 0 0 1 0 0 0") {
  auto r = std::make_unique<SensorRun>();
  std::string text = "raisim_engine_scene 1\n";
  if (body.find("gravity ") == std::string::npos) text += "gravity 0 0 -9.81\n";
  text += body;
  for (std::size_t i = 0; i < models.size(); ++i)
    text += "articulated /World/R" + std::to_string(i) + " res " + robotAt + " true true\n";
  LoadResult loaded = parse(text);
  EXPECT_TRUE(loaded.ok()) << (loaded.diagnostics.empty() ? "" : loaded.diagnostics[0].message);
  r->doc = std::move(loaded.document);
  SceneOptions so;
  if (fs) {
    so.baseDir = "/s";
    so.exists = [fs](const std::string& p) { return fs->exists(p); };
    r->cache = std::make_unique<asset::AssetCache>(*fs);
  }
  EXPECT_TRUE(buildScene(r->doc, so, r->scene, r->diags)) << (r->diags.empty() ? "" : r->diags[0].message);
  r->robots.resize(models.size());
  std::vector<std::shared_ptr<const robot::Model>> loaded_models;
  for (std::size_t i = 0; i < models.size(); ++i) {
    robot::RobotInstance& in = r->robots[i];
    in.record = &r->scene.articulated[i];
    in.model = models[i];
    EXPECT_TRUE(robot::makeCoordinates(*in.model, {}, in.coordinates).empty());
    in.base = in.record->world;
    in.q = robot::neutralCoordinate(*in.model, in.coordinates, in.base);
    in.u = Eigen::VectorXd::Zero(in.coordinates.velocityDim);
    loaded_models.push_back(models[i]);
  }
  WorldOptions wo;
  wo.assets = r->cache.get();
  wo.robots = &r->robots;
  wo.document = &r->doc;
  r->world = World::create(r->scene, r->diags, wo);
  EXPECT_TRUE(r->world) << (r->diags.empty() ? "" : r->diags[0].message);
  std::vector<robot::SensorSpec> all = robot::collectSensors(r->doc, r->scene, loaded_models, r->diags);
  r->sensors = planSensors(r->doc, all, {}, r->diags);
  return r;
}

// Keeps every reading.
struct Collected : SensorOutput {
  struct Scan {
    std::size_t sensor;
    std::uint64_t index;
    double time;
    Pose pose;
    std::vector<Eigen::Vector3f> points;
  };
  std::vector<Scan> scans;
  std::vector<std::pair<std::size_t, ImuReading>> imu;
  bool lidarScan(std::size_t sensor, std::uint64_t index, double time, const Pose& pose,
                 const std::vector<Eigen::Vector3f>& points) override {
    scans.push_back({sensor, index, time, pose, points});
    return true;
  }
  bool imuReading(std::size_t sensor, const ImuReading& r) override {
    imu.emplace_back(sensor, r);
    return true;
  }
};

}  // namespace rscene::sim::test
