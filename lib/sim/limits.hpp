// What rscene-sim refuses so that a run stays bounded in time and memory
// and never writes a value it cannot stand behind (README "Resource
// limits", rscene-sim(1) LIMITS):
//  - up front: a time_step that is not finite or below kMinTimeStep; a
//    dynamic body whose mass is not a finite normal double (1/mass must be
//    finite); a body whose pose is not finite or whose orientation does not
//    normalise to a unit quaternion; a run of more steps than the cap;
//  - while stepping: a body whose state is no longer finite (World reports
//    it, nonFiniteError() words it).
// Kept apart from checkPhysics() (check.cpp): those refusals belong to the
// scene view, these to the simulator's own limits.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "core/scene.hpp"
#include "sim/world.hpp"

namespace rscene::sim {

namespace limit_code {
inline constexpr const char* kBadMassValue = "RS7020";  // dynamic mass below the smallest normal double, or infinite
inline constexpr const char* kBadPose = "RS7021";       // pose not finite, orientation not normalisable
inline constexpr const char* kBadTimeStep = "RS7022";   // time_step not finite or below kMinTimeStep
inline constexpr const char* kTooManySteps = "RS7023";  // run longer than --max-steps
inline constexpr const char* kNonFinite = "RS7024";     // a body's state stopped being finite while stepping
inline constexpr const char* kTooManyPairs = "RS7025";  // more overlapping pairs than --max-pairs
}  // namespace limit_code

// Smallest time_step simulated: one simulated second is then 10^9 steps,
// already 100 times the default step cap.
inline constexpr double kMinTimeStep = 1e-9;
// Default cap on the steps of one run (--max-steps): a few minutes for a
// small scene (about 10^5 steps per second for a dozen bodies).
inline constexpr std::uint64_t kDefaultMaxSteps = 10'000'000;
// Default cap on overlapping body pairs (--max-pairs, WorldOptions::maxPairs).
// A pair of touching boxes costs about 8.5 KB (pair, collision algorithm,
// contact manifold): about 850 MB at the cap, some 12,000 bodies in one
// dense pile; 450 boxes in one spot already make 100,000 pairs.
inline constexpr std::uint64_t kDefaultMaxPairs = 100'000;

// The up-front refusals above (all but the step count), each an error at
// the record's field.  Returns false when it added an error.
bool checkLimits(const Document& doc, const Scene& scene, Diagnostics& diagnostics);

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

// The error for a world that met more overlapping pairs than its cap, at
// the record World::pairOverflow() names.
Diagnostic tooManyPairs(const Document& doc, int recordIndex, std::uint64_t step, std::uint64_t maxPairs);

}  // namespace rscene::sim
