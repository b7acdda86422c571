// What rscene-sim refuses so that a run stays bounded in time and memory
// and never writes a value it cannot stand behind (README "Resource
// limits", rscene-sim(1) LIMITS):
//  - up front: a run of more steps than the cap (the numbers no simulator
//    can stand behind, RS7020-RS7022, are the scene model's:
//    scene/limits.hpp, run by checkScene() in every tool);
//  - while stepping: a body whose state is no longer finite (World reports
//    it, nonFiniteError() words it), more overlapping pairs than the cap.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "core/codes.hpp"
#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "scene/scene.hpp"
#include "sim/pcd.hpp"
#include "sim/sensor_recorder.hpp"
#include "sim/world.hpp"

namespace rscene::sim {

namespace limit_code {
inline constexpr const char* kTooManySteps = rs::RS7023;  // run longer than --max-steps
inline constexpr const char* kNonFinite = rs::RS7024;     // a body's state stopped being finite while stepping
inline constexpr const char* kTooManyPairs = rs::RS7025;  // more overlapping pairs than --max-pairs
}  // namespace limit_code

// Default cap on the steps of one run (--max-steps): a few minutes for a
// small scene (about 10^5 steps per second for a dozen bodies).
inline constexpr std::uint64_t kDefaultMaxSteps = 10'000'000;
// Default cap on overlapping body pairs (--max-pairs, WorldOptions::maxPairs).
// A pair of touching boxes costs about 8.5 KB (pair, collision algorithm,
// contact manifold): about 850 MB at the cap, some 12,000 bodies in one
// dense pile; 448 boxes in one spot already make more than 100,000 pairs.
inline constexpr std::uint64_t kDefaultMaxPairs = 100'000;

// The deformables' solver work of one run, in updates (iterations x
// substeps x (constraints + particles) x steps, summed over the
// deformables): past kMaxDeformableWorkPerRun the run is refused before
// its first step (RS7075), past kDeformableWorkWarning the expected cost is
// a warning (RS7076).  One core does about kDeformableUpdatesPerSecond.
inline constexpr double kDeformableUpdatesPerSecond = 5e7;
inline constexpr double kMaxDeformableWorkPerRun = 3e10;  // about 10 minutes of one core
inline constexpr double kDeformableWorkWarning = 5e8;     // about 10 s

// The granular solver's work of one run, in updates (substeps x (grains
// + candidate pairs) x steps, summed over the granular records): past
// kMaxGranularWorkPerRun the run is refused before its first step, past
// kGranularWorkWarning the expected cost is a warning (both RS7093, with
// the figures a step and a run).  One core does about
// kGranularUpdatesPerSecond, as for the deformables (CPU time: a packed
// bed of 11,774 grains and 33,669 candidate pairs 5.3e7 a second, a loose
// one of 95,220 grains 1.2e8: its pairs are mostly out of reach).
inline constexpr double kGranularUpdatesPerSecond = 5e7;
inline constexpr double kMaxGranularWorkPerRun = 3e10;  // about 10 minutes of one core
inline constexpr double kGranularWorkWarning = 5e8;     // about 10 s

// Steps of a run of `duration` seconds at `timeStep`: round(duration /
// timeStep), computed without overflow or undefined conversion.  nullopt
// when that is more than maxSteps (a non-finite quotient included).
std::optional<std::uint64_t> stepsFor(double duration, double timeStep, std::uint64_t maxSteps);

// The error for a run of more than maxSteps steps, at the time_step record
// when the file has one.  `what` says how the count came about
// ("--duration 1 at time_step 1e-12 is 1e+12 steps").
Diagnostic tooManySteps(const Document& doc, const std::string& what, std::uint64_t maxSteps);

// The error for World::nonFinite(), at the body's record.
Diagnostic nonFiniteError(const Document& doc, const NonFinite& bad);

// The error for a particle system that stopped the run, at its record's field.
Diagnostic particleError(const Document& doc, const ParticleFailure& bad);

// The error for a world that met more overlapping pairs than its cap, at
// the record World::pairOverflow() names.
Diagnostic tooManyPairs(const Document& doc, int recordIndex, std::uint64_t step, std::uint64_t maxPairs);

// The per-run cap on the deformables' work (above) for a run of `steps`
// steps of `world`: false after an error at the costliest deformable's
// iterations (RS7075); a warning there (RS7076) for a run past the warning
// threshold.
bool checkDeformableWork(const Document& doc, const World& world, std::uint64_t steps, Diagnostics& diagnostics);

// Bytes the LiDAR scans of a run write, at most (every ray a return):
// rays x bytes a point (12 binary, kAsciiPcdPointBytes as text) plus
// a header, for each scan the run takes (one at time 0, then one an
// update period; every step at updateRate 0).  Past kLidarOutputWarning
// (1 GiB) rscene-sim warns before the first step (RS7094), at the costliest
// LiDAR's lidarSamples (its robot's record for a sensor-set LiDAR).  No
// refusal: a write that fails (a full disk) stops the run, which then
// leaves the earlier run's scans as they were.
inline constexpr double kLidarOutputWarning = 1024.0 * 1024 * 1024;
inline constexpr double kAsciiPcdPointBytes = 32;  // "x y z\n", shortest round-trip floats, typical
inline constexpr double kPcdHeaderBytes = 300;
std::uint64_t lidarScansInRun(const RecordedSensor& lidar, std::uint64_t steps, double timeStep);
double lidarScanBytes(const RecordedSensor& lidar, PcdEncoding encoding);
// `freeBytes`: room left where the scans go (< 0: unknown), named when the
// estimate is past it.
std::optional<Diagnostic> lidarOutputWarning(const Document& doc, const std::vector<RecordedSensor>& sensors,
                                             std::uint64_t steps, double timeStep, PcdEncoding encoding,
                                             double freeBytes);

// The per-run cap on the granular solver's work (above) for a run of
// `steps` steps of `world`: false after an error at the costliest granular
// record's substeps (RS7093); a warning there (RS7093) past the warning
// threshold.
bool checkGranularWork(const Document& doc, const World& world, std::uint64_t steps, Diagnostics& diagnostics);

// The warning (RS7079, once, at the first deformable record, naming them
// all) for a scene written back with deformables: the format has no key
// for a deformed state, so they stay at their start pose; nullopt when the
// scene has none.
std::optional<Diagnostic> deformablesAtStartPose(const Document& doc, const Scene& scene);

}  // namespace rscene::sim
