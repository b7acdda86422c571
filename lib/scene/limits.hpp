// Numbers the scene model refuses because no simulator could stand behind
// the result (issue 10: "nothing non-finite is ever written"):
//   RS7020  a dynamic mass that is not a finite normal double (4.9e-324:
//           its inverse is infinite);
//   RS7021  a body pose that is not finite, or an orientation that does not
//           normalise to a unit quaternion (1e308 1e308 0 0);
//   RS7022  a positive time_step that is not finite or below kMinTimeStep
//           (time_step <= 0 is RS7008).
// checkScene() runs these, so validate, sim and render agree on them.
#pragma once
#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "scene/scene.hpp"

namespace rscene {

// Smallest time_step simulated: one simulated second is then 10^9 steps,
// already 100 times rscene-sim's default step cap.
inline constexpr double kMinTimeStep = 1e-9;

// Appends the refusals above, each an error at the record's field.
// Returns false when it added an error.
bool checkNumericLimits(const Document& doc, const Scene& scene, Diagnostics& diagnostics);

}  // namespace rscene
