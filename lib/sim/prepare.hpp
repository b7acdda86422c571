// Everything rscene-sim does with a scene before its first step, in the
// library so that a batch of scenes (or a Python caller) prepares each one
// the same way: lib/core's verdict (as rscene-validate gives it), the
// scene model, --allow-missing-assets, the physics checks, the step
// count, the robots and their PD gains, the sensors to record (or, when
// none are, their mounts), and the world.  Nothing is printed.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "asset/cache.hpp"
#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "scene/scene.hpp"
#include "sim/imu.hpp"
#include "sim/sensor_recorder.hpp"
#include "sim/world.hpp"

namespace rscene::sim {

struct PrepareOptions {
  SceneOptions scene;                    // the scene's folder, --base-dir
  bool allowMissingAssets = false;       // --allow-missing-assets
  std::optional<std::uint64_t> steps;    // --steps; else duration / time_step
  double duration = 1;                   // --duration, seconds
  std::uint64_t maxSteps = 0;            // --max-steps
  std::uint64_t maxPairs = 0;            // --max-pairs (WorldOptions::maxPairs)
  std::vector<std::string> pdGains;      // --pd-gains, as written
  bool recordSensors = false;            // --sensors: plan what to record
  ImuFormat imuFormat = ImuFormat::Csv;  // --imu-format
  // Robot files loaded once for a batch of scenes (rscene-sim's several
  // operands); null: loaded for this scene only.  Meshes are shared
  // through the AssetCache passed to prepareSimulation().
  robot::ModelCache* models = nullptr;
};

// A scene made ready to step.  Not movable: the world points into the
// scene and the robots.
struct Prepared {
  Prepared() = default;
  Prepared(const Prepared&) = delete;
  Prepared& operator=(const Prepared&) = delete;

  Scene scene;
  std::vector<robot::RobotInstance> robots;
  std::vector<RecordedSensor> sensors;  // with recordSensors
  std::uint64_t steps = 0;
  std::unique_ptr<World> world;  // last: destroyed first
};

// Prepares `doc` into `out`, reading files through `assets` (one cache for
// the run).  False after an error, added to `diagnostics` at its record;
// warnings are added too.  A --pd-gains value that does not parse, or that
// names a joint no robot has, is a usage error: false with `usageError`
// set and nothing added.
bool prepareSimulation(const Document& doc, const PrepareOptions& options, asset::AssetCache& assets, Prepared& out,
                       Diagnostics& diagnostics, std::string& usageError);

}  // namespace rscene::sim
