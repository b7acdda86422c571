#include "sim/run.hpp"

#include <chrono>

#include "sim/limits.hpp"

namespace rscene::sim {
namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

}  // namespace

RunResult runWorld(World& world, const Document& doc, const RunOptions& options, Sink* trajectory,
                   const robot::TrajectoryWriter* lines) {
  RunResult result;
  Clock::time_point start = Clock::now();
  const bool traj = trajectory && lines;
  const std::uint64_t every = options.every ? options.every : 1;
  auto interrupted = [&] { return options.interrupted && *options.interrupted; };
  // After every step (and before the first) every body's state is checked.
  auto healthy = [&] {
    if (auto bad = world.nonFinite()) result.failure = nonFiniteError(doc, *bad);
    else if (auto stopped = world.particleFailure()) result.failure = particleError(doc, *stopped);
    else if (auto record = world.pairOverflow())
      result.failure = tooManyPairs(doc, *record, world.steps(), options.maxPairs);
    return !result.failure;
  };
  auto sample = [&] {
    if (options.sample && !options.sample()) result.sampleFailed = true;
    return !result.sampleFailed;
  };
  constexpr std::size_t kChunk = 1 << 16;
  std::string buffer;
  auto frame = [&] {
    lines->append(buffer, world.time(), world.states(), world.robotStates(), world.particleStates());
    if (buffer.size() >= kChunk) trajectory->write(buffer), buffer.clear();
  };
  if (traj) buffer = lines->header();
  bool good = !options.checkStart || (healthy() && sample());
  if (good && traj) frame();
  Clock::time_point lastProgress = start;
  while (good && world.steps() < options.steps && !interrupted()) {
    world.step();
    if (!healthy() || !sample()) break;
    result.contacts += world.contactCount();
    std::uint64_t n = world.steps();
    if (traj && n % every == 0) frame();
    if (options.untilRest && world.atRest()) {
      result.rested = true;
      break;
    }
    if (options.progress && (n & 255) == 0 && seconds(lastProgress, Clock::now()) > 0.25) {
      lastProgress = Clock::now();
      options.progress(n, options.steps);
    }
  }
  if (options.progressDone) options.progressDone();
  result.interrupted = interrupted();
  // What sim writes, sim reads: grains the scene model would refuse stop
  // the run before anything is written.
  if (result.ok())
    if (auto unwritable = world.particlesUnwritable()) result.failure = particleError(doc, *unwritable);
  result.stepSeconds = seconds(start, Clock::now());
  if (result.ok() && traj) trajectory->write(buffer);
  return result;
}

nlohmann::json runReport(const World& world, const RunResult& result, const RunTimes& times, std::size_t sensors,
                         std::uint64_t lidarScans, double lidarScanSeconds) {
  auto steps = world.steps();
  nlohmann::json r = {{"steps", steps},
                      {"simulatedTime", world.time()},
                      {"wallTime", times.wall},
                      {"loadTime", times.parse + times.build},
                      {"parseTime", times.parse},
                      {"buildTime", times.build},
                      {"stepTime", times.step},
                      {"stepCpuTime", times.stepCpu},
                      {"writeTime", times.write},
                      {"stepsPerSecond", times.step > 0 ? steps / times.step : 0.0},
                      {"realtimeFactor", times.wall > 0 ? world.time() / times.wall : 0.0},
                      {"bodies", world.bodyCount()},
                      {"robots", world.robotCount()},
                      {"particleSystems", world.particleSystems().systems()},
                      {"particles", world.particleSystems().particles()},
                      {"particleStepTime", world.particleSystems().stepSeconds()},
                      {"leftWorld", world.departures().size()},
                      {"contactsPerStep", steps ? result.contacts / steps : 0.0},
                      {"sensors", sensors},
                      {"lidarScans", lidarScans},
                      {"lidarScanTime", lidarScanSeconds},
                      {"atRest", result.rested || world.atRest()}};
  // Where the granular solvers' time went (rscene-sim(1), Granular media).
  GranularStats gs = world.particleSystems().granularStats();
  double granularTime = gs.neighbourSeconds + gs.contactSeconds + gs.surfaceSeconds + gs.integrateSeconds;
  r["granular"] = {{"substepsPerStep", gs.substepsPerStep},
                   {"particleSubsteps", gs.particleSubsteps},
                   {"particleSubstepsPerSecond", granularTime > 0 ? gs.particleSubsteps / granularTime : 0.0},
                   {"neighbourTime", gs.neighbourSeconds},
                   {"neighbourBuilds", gs.neighbourBuilds},
                   {"contactTime", gs.contactSeconds},
                   {"surfaceTime", gs.surfaceSeconds},
                   {"integrationTime", gs.integrateSeconds},
                   {"contacts", gs.contacts},
                   {"surfaceContacts", gs.surfaceContacts},
                   {"maxPenetration", gs.maxPenetration}};
  return r;
}

}  // namespace rscene::sim
