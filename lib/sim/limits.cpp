// The simulator's own limits (limits.hpp).
#include "sim/limits.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "scene/reader.hpp"
#include "sim/particle_systems.hpp"

namespace rscene::sim {

std::optional<std::uint64_t> stepsFor(double duration, double timeStep, std::uint64_t maxSteps) {
  double q = duration / timeStep;
  // Compared as doubles first: converting a quotient beyond the integer
  // range (1e300 / 0.001, or anything over 5e-324) would be undefined.
  if (!(q >= 0) || !(q < static_cast<double>(maxSteps) + 0.5)) return std::nullopt;
  return static_cast<std::uint64_t>(std::llround(q));
}

Diagnostic tooManySteps(const Document& doc, const std::string& what, std::uint64_t maxSteps) {
  std::string message = what + ", more than the limit of " + std::to_string(maxSteps) + " steps";
  const char* hint = "raise the limit with --max-steps N, or simulate less time";
  Diagnostics found;
  for (std::size_t i = doc.records.size(); i-- > 1;) {  // the last time_step record is the one in force
    const Record& rec = doc.records[i];
    if (!rec.kind || rec.kind->tag != "time_step") continue;
    RecordReader(doc, i, found).error("dt", limit_code::kTooManySteps, message, hint);
    return found.back();
  }
  Diagnostic d;
  d.code = limit_code::kTooManySteps;
  d.message = std::move(message);
  d.hint = hint;
  return d;
}

Diagnostic nonFiniteError(const Document& doc, const NonFinite& bad) {
  Diagnostic d;
  d.code = limit_code::kNonFinite;
  if (bad.recordIndex >= 0 && static_cast<std::size_t>(bad.recordIndex) < doc.records.size()) {
    const Record& r = doc.records[static_cast<std::size_t>(bad.recordIndex)];
    d.line = r.line;
    d.column = 1;
    d.tag = std::string(doc.tag(r));
  }
  char at[96];
  std::snprintf(at, sizeof at, "at step %llu (t = %.6g s)", static_cast<unsigned long long>(bad.step), bad.time);
  if (bad.diverged && !bad.cause.empty()) {
    d.message = "deformable '" + bad.path + "' diverged " + at + ": " + bad.cause +
                "; the simulation stopped and nothing was written";
    d.hint = "a constraint too stiff or a triangle too thin for the time step (youngsModulus with a tiny thickness, "
             "compliance near 0 with few iterations), or a start inside another body: raise substeps, "
             "thickness or compliance, or shorten time_step";
    return d;
  }
  if (bad.diverged) {
    d.message = "the state of articulated system '" + bad.path + "' diverged " + at +
                " (a joint reached 1e6 rad/s or m/s, or the base went past 1e12 m); the simulation stopped and "
                "nothing was written";
    d.hint = "springs or --pd-gains too stiff for the time step: a shorter time_step or smaller gains keep it stable";
    return d;
  }
  d.message = "the " + bad.what + " of body '" + bad.path + "' is no longer finite " + at +
              "; the simulation stopped and nothing was written";
  d.hint = "look for extreme masses, sizes, speeds or time steps";
  return d;
}

Diagnostic particleError(const Document& doc, const ParticleFailure& bad) {
  const GranularFailure& f = bad.failure;
  Diagnostics found;
  reportAt(&doc, bad.recordIndex, f.field, f.code, f.message, found, Severity::Error, f.hint);
  return found.back();
}

Diagnostic tooManyPairs(const Document& doc, int recordIndex, std::uint64_t step, std::uint64_t maxPairs) {
  Diagnostic d;
  d.code = limit_code::kTooManyPairs;
  if (recordIndex >= 0 && static_cast<std::size_t>(recordIndex) < doc.records.size()) {
    const Record& r = doc.records[static_cast<std::size_t>(recordIndex)];
    d.line = r.line;
    d.column = 1;
    d.tag = std::string(doc.tag(r));
  }
  d.message = "more than " + std::to_string(maxPairs) + " overlapping body pairs at step " + std::to_string(step) +
              ", this body in one of them; the simulation stopped and nothing was written";
  d.hint = "raise the limit with --max-pairs N (each pair costs about 8.5 KB), or spread the bodies out";
  return d;
}

namespace {

// Seconds of one core for `work` updates, in words ("about 8.3 h").
std::string coreTime(double work, double rate = kDeformableUpdatesPerSecond) {
  const double s = work / rate;
  char text[64];
  if (s < 120) std::snprintf(text, sizeof text, "about %.2g s", s);
  else if (s < 7200) std::snprintf(text, sizeof text, "about %.2g min", s / 60);
  else if (s < 172800) std::snprintf(text, sizeof text, "about %.2g h", s / 3600);
  else std::snprintf(text, sizeof text, "about %.2g days", s / 86400);
  return text;
}

std::string sci(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

}  // namespace

bool checkDeformableWork(const Document& doc, const World& world, std::uint64_t steps, Diagnostics& ds) {
  std::vector<ParticleSystems::DeformableCost> costs = world.particleSystems().deformableCosts();
  if (costs.empty()) return true;
  double perStep = 0;
  const ParticleSystems::DeformableCost* top = &costs.front();
  for (const auto& c : costs) {
    perStep += c.workPerStep;
    if (c.workPerStep > top->workPerStep) top = &c;
  }
  const double total = perStep * static_cast<double>(steps);
  if (!(total > kDeformableWorkWarning)) return true;
  const bool refused = total > kMaxDeformableWorkPerRun;
  // Like with like: the run's work against the per-run limit; the
  // per-step figures say where it comes from.
  std::string message = "the deformables' solver work for this run is " + sci(perStep) + " updates a step x " +
                        std::to_string(steps) + " steps = " + sci(total) +
                        " updates (iterations x substeps x (constraints + particles) x steps), " + coreTime(total) +
                        " of one core; deformable '" + top->path + "' takes " + sci(top->workPerStep) +
                        " updates a step";
  if (refused)
    message += "; the run's " + sci(total) + " updates are more than the limit of " +
               sci(kMaxDeformableWorkPerRun) + " updates a run (" + coreTime(kMaxDeformableWorkPerRun) +
               "); nothing was simulated";
  reportAt(&doc, top->recordIndex, "iterations", refused ? rs::RS7075 : rs::RS7076, message, ds,
           refused ? Severity::Error : Severity::Warning,
           "lower iterations or substeps, use a coarser mesh, or simulate fewer steps (--steps, --duration)");
  return !refused;
}

std::uint64_t lidarScansInRun(const RecordedSensor& lidar, std::uint64_t steps, double timeStep) {
  const double rate = lidar.spec.params.updateRate;
  const double samples = static_cast<double>(steps) + 1;  // time 0, then after each step
  if (!(rate > 0)) return steps + 1;
  double scans = std::floor(static_cast<double>(steps) * timeStep * rate * (1 + 1e-9)) + 1;
  return static_cast<std::uint64_t>(std::min(scans, samples));
}

double lidarScanBytes(const RecordedSensor& lidar, PcdEncoding encoding) {
  const double point = encoding == PcdEncoding::Binary ? 12 : kAsciiPcdPointBytes;
  return static_cast<double>(lidar.directions.size()) * point + kPcdHeaderBytes;
}

namespace {

// "37.5 GiB", "512 MiB".
std::string bytesText(double b) {
  char text[48];
  if (b >= 1024.0 * 1024 * 1024 * 1024) std::snprintf(text, sizeof text, "%.3g TiB", b / (1024.0 * 1024 * 1024 * 1024));
  else if (b >= 1024.0 * 1024 * 1024) std::snprintf(text, sizeof text, "%.3g GiB", b / (1024.0 * 1024 * 1024));
  else if (b >= 1024.0 * 1024) std::snprintf(text, sizeof text, "%.3g MiB", b / (1024.0 * 1024));
  else std::snprintf(text, sizeof text, "%.3g KiB", b / 1024);
  return text;
}

}  // namespace

std::optional<Diagnostic> lidarOutputWarning(const Document& doc, const std::vector<RecordedSensor>& sensors,
                                             std::uint64_t steps, double timeStep, PcdEncoding encoding,
                                             double freeBytes) {
  double total = 0, most = -1;
  const RecordedSensor* top = nullptr;
  int lidars = 0;
  for (const RecordedSensor& s : sensors) {
    if (s.spec.kind != robot::SensorKind::Lidar) continue;
    ++lidars;
    const double bytes = lidarScanBytes(s, encoding) * static_cast<double>(lidarScansInRun(s, steps, timeStep));
    total += bytes;
    if (bytes > most) most = bytes, top = &s;
  }
  if (!top || !(total > kLidarOutputWarning)) return std::nullopt;
  const bool binary = encoding == PcdEncoding::Binary;
  const std::uint64_t scans = lidarScansInRun(*top, steps, timeStep);
  std::string message = "the LiDAR scans of this run would write up to " + bytesText(total) +
                        ", more than 1 GiB: LiDAR '" + top->spec.name + "' takes " +
                        std::to_string(top->directions.size()) + " points a scan x " +
                        (binary ? "12 bytes (binary PCD)" : "about 32 bytes (ascii PCD)") + " = " +
                        bytesText(lidarScanBytes(*top, encoding)) + " a scan, x " + std::to_string(scans) +
                        " scans = " + bytesText(most) + " (every ray a return)";
  if (lidars > 1) message += std::string("; the other LiDAR") + (lidars > 2 ? "s" : "") + " the rest";
  if (freeBytes >= 0 && total > freeBytes)
    message += "; the file system of --sensors has " + bytesText(freeBytes) +
               " free, and the run stops when it is full (the earlier scans stay)";
  std::string hint = "fewer lidarChannels or lidarSamples, a lower updateRate, or a shorter run (--steps, --duration)";
  if (!binary) hint += "; --pcd-encoding binary writes 12 bytes a point";
  const bool record = top->spec.recordIndex >= 0;
  Diagnostics ds;
  reportAt(&doc, record ? top->spec.recordIndex : top->spec.robotRecord, record ? "lidarSamples" : "", rs::RS7094,
           message, ds, Severity::Warning, hint);
  return ds.back();
}

bool checkGranularWork(const Document& doc, const World& world, std::uint64_t steps, Diagnostics& ds) {
  std::vector<ParticleSystems::GranularCost> costs = world.particleSystems().granularCosts();
  if (costs.empty()) return true;
  double perStep = 0;
  const ParticleSystems::GranularCost* top = &costs.front();
  for (const auto& c : costs) {
    perStep += c.workPerStep;
    if (c.workPerStep > top->workPerStep) top = &c;
  }
  const double total = perStep * static_cast<double>(steps);
  if (!(total > kGranularWorkWarning)) return true;
  const bool refused = total > kMaxGranularWorkPerRun;
  const double rate = kGranularUpdatesPerSecond;
  std::string message = "the granular solver's work for this run is " + sci(perStep) + " updates a step (" +
                        coreTime(perStep, rate) + " of one core a step) x " + std::to_string(steps) + " steps = " +
                        sci(total) + " updates (substeps x (grains + candidate pairs) x steps), " +
                        coreTime(total, rate) + " of one core for the run; granular " + top->path + ": " +
                        std::to_string(top->grains) + " grains and " + std::to_string(top->pairs) +
                        " candidate pairs in " + std::to_string(top->substeps) + " substeps a step";
  if (refused)
    message += "; more than the limit of " + sci(kMaxGranularWorkPerRun) + " updates a run (" +
               coreTime(kMaxGranularWorkPerRun, rate) + "), so nothing was simulated";
  else
    message += "; more than " + sci(kGranularWorkWarning) + " updates a run (" + coreTime(kGranularWorkWarning, rate) +
               ")";
  reportAt(&doc, top->recordIndex, "substeps", particle_code::kGranularWork, message, ds,
           refused ? Severity::Error : Severity::Warning,
           "lower substeps (or the stiffness that raised them), use fewer or larger grains, or simulate fewer steps "
           "(--steps, --duration)");
  return !refused;
}

std::optional<Diagnostic> deformablesAtStartPose(const Document& doc, const Scene& scene) {
  if (scene.deformables.empty()) return std::nullopt;
  std::string names;
  for (const Deformable& d : scene.deformables) names += (names.empty() ? "'" : ", '") + d.path + "'";
  Diagnostics ds;
  const bool one = scene.deformables.size() == 1;
  reportAt(&doc, scene.deformables.front().recordIndex, "", rs::RS7079,
           std::string(one ? "deformable " : "deformables ") + names + (one ? " is" : " are") +
               " written back at the start pose: the format has no key for a deformed state, so a renderer of this "
               "scene draws " + (one ? "it" : "them") + " undeformed while the other bodies have moved",
           ds, Severity::Warning,
           "to draw the simulated particles, write them with rscene-sim --trajectory t.jsonl and draw with "
           "rscene-render --trajectory t.jsonl");
  return ds.back();
}

}  // namespace rscene::sim
