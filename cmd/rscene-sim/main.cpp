// rscene-sim: steps a scene's physics in Bullet and writes the scene back
// with the simulated poses (and optionally a trajectory).
#include <sys/statvfs.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <ctime>
#include <cstdio>
#include <optional>
#include <iostream>
#include <nlohmann/json.hpp>

#include "common/batch.hpp"
#include "common/cli.hpp"
#include "core/loader.hpp"
#include "core/scene_pattern.hpp"
#include "scene/scene.hpp"
#include "robot/load.hpp"
#include "robot/trajectory_format.hpp"
#include "core/writer.hpp"
#include "sensor_files.hpp"
#include "sim/limits.hpp"
#include "sim/prepare.hpp"
#include "sim/run.hpp"
#include "sim/sensor_recorder.hpp"
#include "sim/world.hpp"

namespace {

using namespace rscene;
using Clock = std::chrono::steady_clock;

volatile std::sig_atomic_t gInterrupted = 0;  // the stop signal's number (cli::stopOnInterrupt)

struct Options {
  std::vector<std::string> files;
  std::string output = "-", stdinName, baseDir, trajectory, trajectoryFormat = "jsonl";
  std::string sensors, imuFormat = "csv", pcdEncoding = "binary";
  double duration = 1;
  long long steps = -1;
  long long every = 1;
  long long maxSteps = static_cast<long long>(sim::kDefaultMaxSteps);
  long long maxPairs = static_cast<long long>(sim::kDefaultMaxPairs);
  bool untilRest = false, report = false, allowMissing = false;
  std::vector<std::string> pdGains;
};

double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

// One scene's operand and outputs (the patterns of a batch expanded).
struct SceneJob {
  std::string file = "-", output = "-", trajectory, sensors;
};

// What the scenes of one run share: meshes and robot files are read once.
// Only what was read from disk: each scene builds its own model and world.
struct Shared {
  asset::AssetCache assets;
  robot::ModelCache models;
};

// Simulates one scene as rscene-sim always has: diagnostics printed, the
// outputs written atomically, a failed or interrupted run leaving none of
// its own.  Returns the exit status (kInterrupted when a stop signal
// stopped it: the caller ends by the signal); `report` gets the --report object of
// a run that succeeded; `batch` (several scenes) takes the step progress.
int simulate(const Options& base, const SceneJob& job, Shared& shared, nlohmann::json* report,
             cli::BatchProgress* batch) {
  Options opt = base;  // the per-scene paths below
  opt.output = job.output;
  opt.trajectory = job.trajectory;
  opt.sensors = job.sensors;
  bool color = cli::colorFor(2);
  Clock::time_point start = Clock::now();
  cli::Input in;
  if (!cli::readInput(job.file, opt.stdinName, in)) return cli::kTrouble;
  LoadResult loaded = parse(std::move(in.text));
  Clock::time_point parsedAt = Clock::now();
  Document& doc = loaded.document;
  auto print = [&](Diagnostics ds) {
    cli::hintStdinPaths(in, opt.baseDir, ds);
    cli::printDiagnostics(ds, in.display, doc.buffer(), color);
  };
  if (!loaded.ok()) return print(loaded.diagnostics), cli::kTrouble;

  sim::PrepareOptions po;
  po.scene.sceneDir = in.path.empty() ? "." : directoryOf(in.path);
  po.scene.project = cli::projectPlace(in, opt.baseDir);
  po.scene.baseDir = opt.baseDir;
  po.allowMissingAssets = opt.allowMissing;
  if (opt.steps >= 0) po.steps = static_cast<std::uint64_t>(opt.steps);
  po.duration = opt.duration;
  po.maxSteps = static_cast<std::uint64_t>(opt.maxSteps);
  po.maxPairs = static_cast<std::uint64_t>(opt.maxPairs);
  po.pdGains = opt.pdGains;
  po.recordSensors = !opt.sensors.empty();
  po.imuFormat = opt.imuFormat == "jsonl" ? sim::ImuFormat::Jsonl : sim::ImuFormat::Csv;
  po.models = &shared.models;
  Diagnostics ds = loaded.diagnostics;
  asset::AssetCache& assets = shared.assets;
  sim::Prepared prepared;
  std::string usage;
  bool ok = sim::prepareSimulation(doc, po, assets, prepared, ds, usage);
  if (!usage.empty()) {
    cli::error(usage);
    return cli::kTrouble;
  }
  print(ds);
  if (!ok) return cli::kTrouble;
  const Scene& scene = prepared.scene;
  const std::vector<sim::RecordedSensor>& sensors = prepared.sensors;
  std::unique_ptr<sim::World>& world = prepared.world;
  const std::uint64_t total = prepared.steps;
  simcmd::SensorFiles files(opt.sensors, sensors,
                            opt.pcdEncoding == "ascii" ? sim::PcdEncoding::Ascii : sim::PcdEncoding::Binary);
  if (!opt.sensors.empty() && !files.prepare({{"-o", opt.output}, {"--trajectory", opt.trajectory}})) {
    files.discard();  // the folders it made before refusing
    return cli::kTrouble;
  }
  // What the LiDAR scans will take on disk, said before the run (RS7094).
  if (!opt.sensors.empty()) {
    struct statvfs fsInfo {};
    double freeBytes = ::statvfs(opt.sensors.c_str(), &fsInfo) == 0
                           ? static_cast<double>(fsInfo.f_bavail) * static_cast<double>(fsInfo.f_frsize)
                           : -1;
    if (auto w = sim::lidarOutputWarning(doc, sensors, total, world->timeStep(),
                                         opt.pcdEncoding == "ascii" ? sim::PcdEncoding::Ascii : sim::PcdEncoding::Binary,
                                         freeBytes))
      print(Diagnostics{*w});
  }
  std::unique_ptr<sim::SensorRecorder> recorder;
  if (!sensors.empty()) recorder = std::make_unique<sim::SensorRecorder>(scene, *world, sensors);
  bool sensorsFailed = false;  // a sensor file could not be written, or a reading was not finite (printed)
  auto record = [&] {
    if (recorder && !recorder->sample(files)) {
      sensorsFailed = true;
      Diagnostics fault;
      recorder->faultDiagnostic(doc, fault);
      print(fault);
    }
    return !sensorsFailed;
  };
  Clock::time_point loadedAt = Clock::now();
  std::clock_t loadedCpu = std::clock();

  // The stepping loop is the library's (sim/run.hpp): trajectory frames
  // streamed, every state checked before it is written anywhere.
  auto format = opt.trajectoryFormat == "csv" ? robot::TrajectoryFormat::Csv : robot::TrajectoryFormat::Jsonl;
  const robot::TrajectoryWriter lines(format, world->robotStates());
  sim::RunOptions ro;
  ro.steps = total;
  ro.every = static_cast<std::uint64_t>(opt.every);
  ro.untilRest = opt.untilRest;
  ro.maxPairs = po.maxPairs;
  ro.interrupted = &gInterrupted;
  ro.sample = record;
  if (batch && batch->terminal()) {
    ro.progress = [batch](std::uint64_t n, std::uint64_t of) { batch->step(n, of); };
    ro.progressDone = [batch] { batch->stepsDone(); };
  } else if (!batch && isatty(2)) {
    ro.progress = [](std::uint64_t n, std::uint64_t of) {
      std::cerr << "\r" << cli::toolName() << ": step " << n << "/" << of << std::flush;
    };
    ro.progressDone = [] { std::cerr << "\r\033[K" << std::flush; };
  }
  sim::RunResult result;
  // A failed run cancels the trajectory (no file is left at its path) and
  // writes no scene; the failure printed is the one line about it.
  auto withTrajectory = [&] {
    auto run = [&](Sink* s) {
      // SIGINT stops the loop even inside the writes of the trajectory and
      // sensor files: the run then cancels them.
      cli::InterruptibleScope interruptible;
      result = sim::runWorld(*world, doc, ro, s, &lines);
      // Stepping done: a stop signal now waits until the sensor files and
      // scan folders are in place (it would otherwise end the tool inside
      // the trajectory's rename, leaving the temporary scan folders).
      if (result.ok() && recorder) files.holdStops();
      if (result.failure) print(Diagnostics{*result.failure});
      return result.ok();
    };
    return opt.trajectory.empty()
               ? run(nullptr)
               : cli::writeOutput(opt.trajectory, [&](Sink& s) { return run(&s); }, cli::Cancel::Quiet);
  };
  bool simulated = recorder ? files.run(withTrajectory, &gInterrupted) : withTrajectory();
  if (!simulated || gInterrupted) {
    files.discard();  // a failed or interrupted run leaves no sensor files
    return gInterrupted ? cli::kInterrupted : cli::kTrouble;  // the caller ends by the signal
  }
  // What the first step found about the start (RS7013) before what
  // happened later: each group in line order, printed apart.
  Diagnostics starts;
  for (const sim::StartOverlap& o : world->startOverlaps()) starts.push_back(sim::startOverlapWarning(doc, o));
  print(starts);
  Diagnostics departures;
  for (const sim::Departure& d : world->departures()) departures.push_back(sim::departureWarning(doc, d));
  // Bodies still deep in contact (RS7002): the run ended before the solver
  // pushed them out, whether --until-rest ran out of time or no rest was asked.
  if (!result.rested)
    if (std::vector<sim::DeepContact> deep = world->deepContacts(); !deep.empty())
      departures.push_back(sim::notAtRestWarning(doc, deep, world->time(), opt.untilRest));
  print(departures);
  Clock::time_point steppedAt = Clock::now();
  std::clock_t steppedCpu = std::clock();

  world->writeBack(doc);
  // Deformables keep their start pose in the scene written (RS7079): said
  // once, naming them, with the way to draw the simulated cloth.
  if (auto w = sim::deformablesAtStartPose(doc, prepared.scene)) print(Diagnostics{*w});
  if (!cli::writeOutput(opt.output, [&](Sink& s) { writeCanonical(doc, s); return true; })) return cli::kTrouble;
  Clock::time_point writtenAt = Clock::now();
  if (report) {
    sim::RunTimes t;
    t.wall = seconds(start, Clock::now());
    t.parse = seconds(start, parsedAt);
    t.build = seconds(parsedAt, loadedAt);
    t.step = seconds(loadedAt, steppedAt);
    t.stepCpu = double(steppedCpu - loadedCpu) / CLOCKS_PER_SEC;
    t.write = seconds(steppedAt, writtenAt);
    *report = sim::runReport(*world, result, t, sensors.size(), recorder ? recorder->scans() : 0,
                             recorder ? recorder->scanSeconds() : 0.0);
  }
  return cli::kSuccess;
}

// The outputs of the scene `file`: the patterns expanded ({stem} of `-` is
// that of --stdin-filename, else "stdin").
bool expandOutputs(const Options& opt, const std::string& file, SceneJob& job) {
  job.file = file;
  const std::string& named = file == "-" && !opt.stdinName.empty() ? opt.stdinName : file;
  return cli::scenePath("-o", opt.output, named, job.output) &&
         cli::scenePath("--trajectory", opt.trajectory, named, job.trajectory) &&
         cli::scenePath("--sensors", opt.sensors, named, job.sensors);
}

// One scene: the operand and outputs as given (today's rscene-sim); a
// pattern names the one scene's outputs too.
int runOne(const Options& opt) {
  SceneJob job;
  if (!expandOutputs(opt, opt.files.empty() ? "-" : opt.files[0], job)) return cli::kTrouble;
  // The folders of outputs named by a pattern are made, as in a batch.
  std::vector<cli::NamedOutput> patterned;
  if (hasSceneFields(opt.output)) patterned.push_back({"-o", job.output});
  if (hasSceneFields(opt.trajectory)) patterned.push_back({"--trajectory", job.trajectory});
  if (!cli::makeOutputFolders(patterned)) return cli::kTrouble;
  // -o may write the scene back; --trajectory must not replace it.
  cli::SceneOutputs self{job.file, job.file == "-" ? "" : job.file, {{"-o", job.output}, {"--trajectory", job.trajectory}}, {}};
  if (!cli::checkInputsKept({self}, "-o")) return cli::kTrouble;
  // With --sensors, SensorFiles::prepare() checks them once the sensors'
  // folders are known (an output inside a LiDAR's folder-to-be is refused
  // as that, not as a file in a missing folder).
  if (job.sensors.empty() && !cli::checkOutputs({{"-o", job.output}, {"--trajectory", job.trajectory}}))
    return cli::kTrouble;
  cli::stopOnInterrupt(&gInterrupted);
  Shared shared;
  nlohmann::json report;
  int rc = simulate(opt, job, shared, opt.report ? &report : nullptr, nullptr);
  if (rc == cli::kInterrupted) return cli::endBySignal(gInterrupted);
  if (rc == cli::kSuccess && opt.report) std::cerr << report.dump() << '\n';
  return rc;
}

// Several scenes (rscene-sim(1), BATCHES): every output named by a
// pattern and checked before any work; a scene that fails does not stop
// the others; a stop signal stops the batch.
int runBatch(const Options& opt) {
  cli::Operands operands = cli::expandOperands(opt.files);
  const std::vector<std::string>& files = operands.files;
  const std::size_t n = files.size();
  if (!cli::requireScenePattern("-o", opt.output, n) ||
      (!opt.trajectory.empty() && !cli::requireScenePattern("--trajectory", opt.trajectory, n)) ||
      (!opt.sensors.empty() && !cli::requireScenePattern("--sensors", opt.sensors, n)))
    return cli::kTrouble;
  if (std::count(files.begin(), files.end(), std::string("-")) > 1) {
    cli::error("standard input (-) is named more than once");
    return cli::kTrouble;
  }
  std::vector<SceneJob> jobs(n);
  std::vector<cli::SceneOutputs> outputs(n);
  for (std::size_t i = 0; i < n; ++i) {
    SceneJob& job = jobs[i];
    if (!expandOutputs(opt, files[i], job)) return cli::kTrouble;
    outputs[i].scene = job.file != "-" ? job.file : opt.stdinName.empty() ? "<stdin>" : opt.stdinName;
    if (job.file != "-") outputs[i].file = job.file;
    // (Inside a scene, SensorFiles::prepare() also checks them against its
    // sensors' folders, as a single run does.)
    outputs[i].outputs = {{"-o", job.output}, {"--trajectory", job.trajectory}};
    if (!job.sensors.empty()) outputs[i].folders = {{"--sensors", job.sensors}};
  }
  if (!cli::checkBatchOutputs(outputs, {{"-o", opt.output}, {"--trajectory", opt.trajectory}, {"--sensors", opt.sensors}},
                              "-o"))
    return cli::kTrouble;
  cli::stopOnInterrupt(&gInterrupted);
  Shared shared;
  cli::BatchProgress progress(n);
  std::vector<std::string> failed;
  std::size_t done = 0;
  for (std::size_t i = 0; i < n && !gInterrupted; ++i) {
    progress.scene(i);
    cli::batchReached(done + failed.size(), n);
    nlohmann::json report;
    int rc = simulate(opt, jobs[i], shared, opt.report ? &report : nullptr, &progress);
    if (rc == cli::kInterrupted) break;  // its outputs discarded; the scenes before it stay written
    if (rc == cli::kSuccess)
      ++done;
    else
      failed.push_back(outputs[i].scene);
    if (!opt.report) continue;
    nlohmann::json line = nlohmann::json::object();
    line["scene"] = outputs[i].scene;
    line["status"] = rc;
    if (rc == cli::kSuccess) line.update(report);
    else line["error"] = progress.firstError();
    std::cerr << line.dump() << '\n';
  }
  progress.clear();
  cli::batchReached(n, n);
  if (gInterrupted) {
    cli::batchStopped(done + failed.size(), n);
    return cli::endBySignal(gInterrupted);
  }
  std::size_t unread = operands.ok ? 0 : 1;  // an unreadable folder or project (expandOperands said which)
  cli::batchSummary(n, done, failed, unread, "simulated");
  return failed.empty() && !unread ? cli::kSuccess : cli::kTrouble;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Simulate the physics of a .rscene scene in Bullet and write the scene back."};
  cli::setup(app, "rscene-sim");
  Options opt;
  app.add_option("files", opt.files,
                 "Scene files, or folders and projects to simulate every *.rscene of; none or - reads standard input")
      ->type_name("FILE");
  cli::addOutputOption(app, opt.output,
                       "Write the simulated scene to FILE (atomically) instead of standard output; with several "
                       "scenes a pattern naming each: {stem} (file name without .rscene), {dir} (its folder)");
  auto* duration = app.add_option("--duration", opt.duration, "Simulate S seconds (default 1)")->type_name("S")
                       ->check(cli::seconds());
  app.add_option("--steps", opt.steps, "Simulate N time steps")->type_name("N")->check(cli::count(0))
      ->excludes(duration);
  app.add_option("--max-steps", opt.maxSteps, "Refuse a run of more than N time steps (default 10000000)")
      ->type_name("N")->check(cli::count(0));
  app.add_option("--max-pairs", opt.maxPairs,
                 "Stop when more than N body pairs overlap, 0 for no limit (default 100000)")
      ->type_name("N")->check(cli::count(0));
  app.add_option("--trajectory", opt.trajectory, "Write body states to FILE as they are simulated")
      ->type_name("FILE");
  app.add_option("--every", opt.every, "Write a trajectory line every K steps (default 1)")->type_name("K")
      ->check(cli::count(1));
  app.add_option("--trajectory-format", opt.trajectoryFormat, "Trajectory format: jsonl (default) or csv")
      ->type_name("FORMAT")->check(CLI::IsMember({"jsonl", "csv"}));
  app.add_flag("--until-rest", opt.untilRest, "Stop early once every dynamic body sleeps (--duration is the cap)");
  app.add_flag("--report", opt.report, "Print a JSON summary of the run on standard error");
  app.add_option("--pd-gains", opt.pdGains,
                 "Hold every robot joint at its initial position by PD: KP,KD for all joints, JOINT=KP,KD for one "
                 "(repeatable)")
      ->type_name("GAINS")->allow_extra_args(false);
  app.add_flag("--allow-missing-assets", opt.allowMissing,
               "Leave out a body whose collision mesh is missing or unreadable and warn, instead of failing");
  app.add_option("--sensors", opt.sensors,
                 "Record every enabled lidar and imu sensor into DIR (created if missing): IMU readings as CSV or JSON "
                 "Lines, LiDAR scans as PCD files with an index")
      ->type_name("DIR")
      ->check([](const std::string& dir) { return dir.empty() ? std::string("DIR is empty: name a folder") : std::string(); });
  app.add_option("--imu-format", opt.imuFormat,
                 "IMU files: csv (default) or jsonl; an outputPath ending in .csv or .jsonl picks its own")
      ->type_name("FORMAT")->check(CLI::IsMember({"csv", "jsonl"}));
  app.add_option("--pcd-encoding", opt.pcdEncoding, "LiDAR scans' PCD data: binary (default) or ascii")
      ->type_name("ENCODING")->check(CLI::IsMember({"binary", "ascii"}));
  cli::addStdinFilename(app, opt.stdinName, true);
  cli::addBaseDir(app, opt.baseDir, "Resolve relative asset paths against DIR instead of the scene's folder");
  if (int rc = cli::parseArgs(app, argc, argv); rc >= 0) return rc;
  return cli::isBatch(opt.files, hasSceneFields(opt.output)) ? runBatch(opt) : runOne(opt);
}
