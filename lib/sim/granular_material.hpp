// The contact law of one granular record (RaiSim's GranularSystem::Material)
// and the time step it can afford.  The forms, chosen where RaiSim's
// documentation leaves them open, are in rscene-sim(1) "Granular media":
//   normal, linear   fn = kn d - cn vn
//   normal, Hertz    fn = kn d sqrt(d / Reff) - cn vn   (kn keeps N/m, and
//                    for d < Reff it is softer than linear, as RaiSim says)
//   both clamped at 0: damping never pulls grains together.
//   tangential       Cundall-Strack spring kt xi + dashpot ct, |ft| <= mu fn;
//                    kt = 0 in the record means 2/7 kn (the ratio that gives
//                    a solid sphere the same normal and tangential frequency)
//   rolling          a spring kr = kt Reff^2 on the relative rolling angle,
//                    |M| <= mur Reff fn (elastic-plastic, with history)
//   cohesion         attraction kc g for a surface gap 0 < g <= gmax
#pragma once
#include <string>
#include <vector>

#include "scene/visual_records.hpp"
#include "sim/granular_body.hpp"

namespace rscene::sim {

struct GranularMaterial {
  double density = 0;
  double kn = 0, cn = 0, kt = 0, ct = 0;
  double friction = 0, rollingFriction = 0;
  double cohesionStiffness = 0, cohesionMaxDistance = 0;
  bool hertz = true;
};

// The record's material, or findings (RS7088 at the key) when a value is
// out of range: not finite, negative, a zero density or stiffness, an
// unknown normalContactModel.
bool granularMaterial(const Granular& record, GranularMaterial& out, std::vector<GranularFinding>& findings);

// The largest substep the explicit integrator stays stable and accurate
// with for grains of mass `minMass` (the lightest): kStableFraction of the
// critical step 2/w (sqrt(1 + z^2) - z) of the stiffest mode, the normal
// (kn; Hertz: its tangent stiffness at an overlap of kHertzOverlap x
// Reff) or tangential one (kt with rotation: 3.5 kt), of a pair (mass m/2).
double granularMaxSubstep(const GranularMaterial& m, double minMass);

// The margin below the pair's critical step for a grain's several
// contacts at once: 0.6, which RaiSim's own example material (radius
// 0.02, normalStiffness 5e4, tangentialStiffness 2.5e4) meets in its 2
// substeps of a 1 ms step (it runs at 0.56).
inline constexpr double kStableFraction = 0.6;

// The Hertz overlap, as a fraction of Reff, at which the stability bound
// takes the stiffness: 5 %, deeper than a usable bed sinks into itself.
inline constexpr double kHertzOverlap = 0.05;

}  // namespace rscene::sim
