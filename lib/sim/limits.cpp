// The simulator's own limits (limits.hpp).
#include "sim/limits.hpp"

#include <cfloat>
#include <cmath>
#include <cstdio>

#include "core/scene_reader.hpp"

namespace rscene::sim {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// What is wrong with a pose for Bullet, and the field to point at; empty
// when nothing is.  The scene view normalises orientations, so a quaternion
// whose norm overflowed (1e308 1e308 0 0) arrives here as zero or NaN.
std::pair<std::string, const char*> poseProblem(const Pose& p) {
  if (!p.position.allFinite()) return {"position is not finite", "position"};
  const Eigen::Vector4d q = p.orientation.coeffs();
  if (!q.allFinite() || !(std::abs(q.norm() - 1) < 1e-6))
    return {"orientation does not normalise to a unit quaternion", "orientation"};
  return {};
}

// A dynamic mass Bullet can invert: a finite normal double (not 4.9e-324,
// whose inverse is infinite).  mass <= 0 is checkPhysics()'s RS7002.
bool badMass(double mass) { return mass > 0 && !(mass >= DBL_MIN && mass <= DBL_MAX); }

const char* kMassHint = "a dynamic mass must lie between 2.2250738585072014e-308 and 1.7976931348623157e+308 kg";

}  // namespace

bool checkLimits(const Document& doc, const Scene& scene, Diagnostics& diagnostics) {
  std::size_t before = diagnostics.size();
  for (std::size_t i = 1; i < doc.records.size(); ++i) {
    const Record& rec = doc.records[i];
    if (!rec.kind || rec.kind->tag != "time_step") continue;
    RecordReader r(doc, i, diagnostics);
    double dt = r.number("dt", scene.timeStep);
    if (!(std::isfinite(dt) && dt >= kMinTimeStep))  // dt <= 0 included: the tool refuses it too
      r.error("dt", limit_code::kBadTimeStep,
              "time_step " + number(dt) + " is below the smallest simulated step, " + number(kMinTimeStep) + " s",
              "a smaller step would need more than 10^9 steps per simulated second");
  }
  for (const Object& o : scene.objects) {
    if (o.bodyMode == BodyMode::VisualOnly) continue;
    RecordReader r(doc, static_cast<std::size_t>(o.recordIndex), diagnostics);
    if (o.bodyMode == BodyMode::Dynamic && badMass(o.mass))
      r.error("mass", limit_code::kBadMassValue, "dynamic body '" + o.path + "' has mass " + number(o.mass) +
                                                     ", which cannot be simulated", kMassHint);
    if (o.primitive == "ground" || o.primitive == "half_space") continue;  // only position.z is used
    auto [problem, field] = poseProblem(o.world);
    if (!problem.empty()) r.error(field, limit_code::kBadPose, "body '" + o.path + "': " + problem);
  }
  for (const Compound& c : scene.compounds) {
    if (c.bodyMode == BodyMode::VisualOnly) continue;
    RecordReader r(doc, static_cast<std::size_t>(c.recordIndex), diagnostics);
    if (c.bodyMode == BodyMode::Dynamic && badMass(c.mass))
      r.error("mass", limit_code::kBadMassValue, "dynamic compound '" + c.path + "' has mass " + number(c.mass) +
                                                     ", which cannot be simulated", kMassHint);
    auto [problem, field] = poseProblem(c.world);
    if (!problem.empty()) r.error(field, limit_code::kBadPose, "compound '" + c.path + "': " + problem);
    for (const CompoundChild& ch : c.children) {
      auto [childProblem, childField] = poseProblem(ch.local);
      if (childProblem.empty()) continue;
      RecordReader cr(doc, static_cast<std::size_t>(ch.recordIndex), diagnostics);
      cr.error(childField, limit_code::kBadPose, "child of compound '" + c.path + "': " + childProblem);
    }
  }
  for (std::size_t i = before; i < diagnostics.size(); ++i)
    if (diagnostics[i].severity == Severity::Error) return false;
  return true;
}

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
  d.message = "the " + bad.what + " of body '" + bad.path + "' is no longer finite " + at +
              "; the simulation stopped and nothing was written";
  d.hint = "look for extreme masses, sizes, speeds or time steps";
  return d;
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

}  // namespace rscene::sim
