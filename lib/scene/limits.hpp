// Numbers the scene model refuses because no simulator could stand behind
// the result (issue 10: "nothing non-finite is ever written"):
//   RS7020  a dynamic mass outside [DBL_MIN, kMaxMass] (4.9e-324: its
//           inverse is infinite; above kMaxMass Bullet takes the body for an
//           immovable one and it falls through what it lands on);
//   RS7021  a body pose that is not finite, farther than kMaxLength from
//           its frame's origin, or an orientation that does not normalise to
//           a unit quaternion (1e308 1e308 0 0);
//   RS7022  a positive time_step that is not finite or outside
//           [kMinTimeStep, kMaxTimeStep] (time_step <= 0 is RS7008);
//   RS7026  a size, wire attachment or length, terrain size, centre or
//           height, or gravity larger than kMaxLength (a local pose of at
//           most kMaxLength at every level keeps every world pose finite,
//           however deep the parent chain);
//   RS7027  a coefficient (wire stiffness/damping/compliance, friction,
//           restitution) negative or above kMaxCoefficient, or solver
//           iterations outside 0..kMaxSolverIterations;
//   RS7028  a camera width or height outside 0..kMaxCameraSide;
//   RS7090  a dynamic body's custom inertia diagonal that is not positive
//           and finite or above kMaxInertia (Bullet inverts each moment);
//   RS4011  (lib/core's code, in its words) a wire with a negative length.
// checkScene() runs these, so validate, sim and render agree on them.
#pragma once
#include <cstdint>
#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "scene/scene.hpp"

namespace rscene {

// Smallest time_step simulated: one simulated second is then 10^9 steps,
// already 100 times rscene-sim's default step cap.
inline constexpr double kMinTimeStep = 1e-9;
// Longest time_step simulated: a step of more than a second resolves no
// contact (a body falls 5 m in it), and 1e300 overflows positions at once.
inline constexpr double kMaxTimeStep = 1;
// Largest dynamic mass.  Bullet treats a body whose inverse mass is near
// its epsilon (DBL_EPSILON, about 1/4.5e15 kg) as immovable: measured, a
// 1 m box of 8e15 kg falls through the ground; 1e15 kg rests on it at every
// size from 1 cm to 1 km.
inline constexpr double kMaxMass = 1e15;
// Largest principal moment of a custom inertia (kg m^2): like kMaxMass,
// Bullet inverts it, and a larger one makes the body's rotation immovable.
inline constexpr double kMaxInertia = 1e15;
// Largest length, coordinate or acceleration (m, m/s^2): at 1e12 m a double
// resolves 0.2 mm, and products of two such values (inertia, energy)
// stay far from overflow.
inline constexpr double kMaxLength = 1e12;
// Largest coefficient (wire stiffness, damping, compliance; friction and
// restitution): with lengths within kMaxLength, forces stay within 1e27.
inline constexpr double kMaxCoefficient = 1e15;
// Most solver iterations per step: Bullet runs each one over every
// contact, so 2^31 iterations never finish a step.  RaiSim's scenes use
// tens to hundreds.
inline constexpr std::int64_t kMaxSolverIterations = 10000;
// Largest camera image side (rscene-render draws at most 16384 per side).
inline constexpr std::int64_t kMaxCameraSide = 16384;

// Appends the refusals above, each an error at the record's field.
// Returns false when it added an error.
bool checkNumericLimits(const Document& doc, const Scene& scene, Diagnostics& diagnostics);

}  // namespace rscene
