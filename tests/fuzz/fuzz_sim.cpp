// Feeds arbitrary bytes through rscene-sim's pipeline for a few hundred
// steps: load, buildScene, the missing-mesh skip of --allow-missing-assets,
// checkPhysics (checkScene and the physics checks), sim::World::create,
// the sensors --sensors would record, and 200 steps with their readings
// (grains and deformables step with the bodies).  Mesh files come from an empty in-memory disk, so every mesh is
// missing and the input alone decides what runs; the pair cap is small so
// that a pile of bodies stays fast.
//
// Invariants, besides not crashing: every finding has a registered code;
// a world is built exactly when no error was reported; after each step
// either nonFinite() names a body or every body's state is finite, and
// every sleeping-or-departed flag pair is consistent with the body list;
// every sensor reading handed out is finite (a fault stops the run
// instead).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "asset/cache.hpp"
#include "core/check.hpp"
#include "core/filesystem.hpp"
#include "core/loader.hpp"
#include "scene/scene.hpp"
#include "robot/sensors.hpp"
#include "sim/sensor_recorder.hpp"
#include "sim/world.hpp"

namespace {

[[noreturn]] void fail(const char* invariant, const std::string& detail) {
  std::fprintf(stderr, "fuzz_sim: invariant broken: %s\n%s\n", invariant, detail.c_str());
  std::abort();
}

bool hasError(const rscene::Diagnostics& ds) {
  for (const rscene::Diagnostic& d : ds)
    if (d.severity == rscene::Severity::Error) return true;
  return false;
}

bool finite(const rscene::sim::BodyState& b) {
  return b.position.allFinite() && b.orientation.coeffs().allFinite() && b.linearVelocity.allFinite() &&
         b.angularVelocity.allFinite();
}

// Every reading must be finite: the recorder stops (fault()) before it
// would hand out anything else.
struct CheckedOutput : rscene::sim::SensorOutput {
  bool lidarScan(std::size_t, std::uint64_t, double time, const rscene::Pose& pose,
                 const std::vector<Eigen::Vector3f>& points) override {
    if (!std::isfinite(time) || !pose.position.allFinite() || !pose.orientation.coeffs().allFinite())
      fail("a LiDAR scan's time and pose are finite", std::to_string(time));
    for (const Eigen::Vector3f& p : points)
      if (!p.allFinite()) fail("a LiDAR point is finite", "");
    return true;
  }
  bool imuReading(std::size_t, const rscene::sim::ImuReading& r) override {
    if (!std::isfinite(r.time) || !r.specificForce.allFinite() || !r.angularVelocity.allFinite())
      fail("an IMU reading is finite", std::to_string(r.time));
    return true;
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rscene::LoadResult loaded = rscene::parse(std::string(reinterpret_cast<const char*>(data), size));
  if (!loaded.ok()) return 0;
  const rscene::Document& doc = loaded.document;

  rscene::MemoryFileSystem disk;  // empty: every asset is missing
  rscene::SceneOptions sceneOptions;
  sceneOptions.sceneDir = "/scene";
  sceneOptions.exists = [&disk](const std::string& path) { return disk.exists(path); };
  rscene::asset::AssetCache assets(disk);
  rscene::Scene scene;
  rscene::Diagnostics ds;
  bool ok = rscene::buildScene(doc, sceneOptions, scene, ds);
  if (ok) rscene::sim::skipBodiesWithMissingMeshes(doc, scene, assets, ds);
  ok = ok && rscene::sim::checkPhysics(doc, scene, ds);
  if (ok && hasError(ds)) fail("checks that pass add no error", ds.back().code + ": " + ds.back().message);

  rscene::sim::WorldOptions options;
  options.assets = &assets;
  options.maxPairs = 2000;
  std::unique_ptr<rscene::sim::World> world = ok ? rscene::sim::World::create(scene, ds, options) : nullptr;
  for (const rscene::Diagnostic& d : ds)
    if (!rscene::checkInfo(d.code)) fail("sim codes are registered", d.code + ": " + d.message);
  if (!world) return 0;
  if (hasError(ds)) fail("a world is built only without errors", ds.back().code + ": " + ds.back().message);

  rscene::Diagnostics sensorFindings;
  std::vector<rscene::robot::SensorSpec> all = rscene::robot::collectSensors(doc, scene, {}, sensorFindings);
  std::vector<rscene::sim::RecordedSensor> sensors = rscene::sim::planSensors(doc, all, {}, sensorFindings);
  std::unique_ptr<rscene::sim::SensorRecorder> recorder;
  if (!hasError(sensorFindings) && !sensors.empty())
    recorder = std::make_unique<rscene::sim::SensorRecorder>(scene, *world, sensors, 1);
  CheckedOutput output;
  if (recorder && !recorder->sample(output) && !recorder->fault()) fail("sample() fails only by a fault here", "");

  // A few hundred steps of what the fuzzer makes; a seed with many grains
  // (the reviewers' 64,000-grain bed) gets fewer, so one input stays
  // within libFuzzer's time limit under the sanitizers.
  std::size_t points = 0;
  for (const rscene::sim::ParticleState& p : world->particleStates()) points += p.points ? p.points->size() : 0;
  const int steps = points + static_cast<std::size_t>(world->bodyCount()) > 5000 ? 10 : 200;
  for (int i = 0; i < steps; ++i) {
    world->step();
    if (world->pairOverflow()) return 0;  // rscene-sim stops here (RS7025)
    std::optional<rscene::sim::NonFinite> bad = world->nonFinite();
    std::vector<rscene::sim::BodyState> states = world->states();
    if (static_cast<int>(states.size()) != world->bodyCount())
      fail("states() has one entry per body", std::to_string(states.size()) + " states, " +
                                                  std::to_string(world->bodyCount()) + " bodies");
    if (bad) {
      // rscene-sim reports RS7024 here and writes nothing; the named body
      // must really be one whose state is not finite.
      bool found = false;
      for (const rscene::sim::BodyState& b : states) found = found || (b.recordIndex == bad->recordIndex && !finite(b));
      if (!found) fail("nonFinite() names a non-finite body", bad->path + " (" + bad->what + ")");
      return 0;
    }
    for (const rscene::sim::BodyState& b : states)
      if (!finite(b)) fail("every body is finite unless nonFinite() says otherwise", b.path);
    if (!std::isfinite(world->time())) fail("time stays finite", std::to_string(world->time()));
    if (recorder && !recorder->sample(output)) {
      if (!recorder->fault()) fail("sample() fails only by a fault here", "");
      return 0;  // rscene-sim reports RS7024 here and writes nothing
    }
  }
  return 0;
}
