// One run of a world: the stepping loop of rscene-sim, in the library so
// that a batch of scenes (or a Python caller) steps a world the same way.
// The trajectory is streamed as it is made (memory does not grow with the
// steps), sensors are sampled through a callback, and every state is
// checked before it is written anywhere.  No printing: progress goes to a
// callback, the figures of --report to a JSON value.
#pragma once
#include <csignal>
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "core/writer.hpp"
#include "robot/trajectory_format.hpp"
#include "sim/world.hpp"

namespace rscene::sim {

struct RunOptions {
  std::uint64_t steps = 0;   // steps to take (the loop may stop sooner)
  std::uint64_t every = 1;   // a trajectory frame every this many steps (and the first state)
  bool untilRest = false;    // stop at the first step after which World::atRest()
  // false: the state the loop starts from was checked and sampled already
  // (a caller that steps one world in pieces: each piece after the first).
  bool checkStart = true;
  std::uint64_t maxPairs = 0;  // WorldOptions::maxPairs, named in the pair-cap error
  // Set asynchronously (SIGINT) to stop the loop between steps.
  const volatile std::sig_atomic_t* interrupted = nullptr;
  // Called with (steps done, steps) every 256 steps at most every 0.25 s
  // of wall time; empty: none.  done() is called once at the end.
  std::function<void(std::uint64_t, std::uint64_t)> progress;
  std::function<void()> progressDone;
  // Called on the first state and after every step (sensor recording);
  // false stops the run.
  std::function<bool()> sample;
};

struct RunResult {
  // A body whose state is not finite or the pair cap passed (at the
  // record), found before that state was written anywhere.
  std::optional<Diagnostic> failure;
  bool sampleFailed = false;  // RunOptions::sample said false
  bool interrupted = false;
  bool rested = false;   // --until-rest stopped the run
  double contacts = 0;   // summed over the steps
  double stepSeconds = 0;  // wall time of the loop
  bool ok() const { return !failure && !sampleFailed && !interrupted; }
};

// Steps `world` per `options`, writing trajectory frames (header first)
// through `lines` to `trajectory` when both are given; the last chunk is
// written only when the run is ok(), so a caller can cancel the file.
RunResult runWorld(World& world, const Document& doc, const RunOptions& options, Sink* trajectory = nullptr,
                   const robot::TrajectoryWriter* lines = nullptr);

// Wall times of the phases of one run, seconds, and the process's CPU
// time while stepping (as benchmarks judge it: a loaded machine moves it
// far less than wall time).
struct RunTimes {
  double parse = 0, build = 0, step = 0, write = 0, wall = 0, stepCpu = 0;
};

// The --report object (rscene-sim(1), REPORT): steps, times, rates, the
// world's counts, sensors and the granular solvers' figures.
nlohmann::json runReport(const World& world, const RunResult& result, const RunTimes& times, std::size_t sensors,
                         std::uint64_t lidarScans, double lidarScanSeconds);

}  // namespace rscene::sim
