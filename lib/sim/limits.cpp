// The simulator's own limits (limits.hpp).
#include "sim/limits.hpp"

#include <cmath>
#include <cstdio>

#include "scene/reader.hpp"

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

}  // namespace rscene::sim
