#include "scene/deformable_check.hpp"

#include "core/text.hpp"
#include "scene/limits.hpp"

namespace rscene {
namespace {

constexpr double kMaxCoordinate = kMaxLength;  // m, as for every other body (scene/limits.hpp)

std::string num(double x) { return roundedNumber(x, 6); }

}  // namespace

bool checkDeformableRecord(const Deformable& r, std::string& error, std::string& field) {
  auto fail = [&](const char* f, std::string message) {
    field = f;
    error = std::move(message);
    return false;
  };
  if (r.kind != "cloth" && r.kind != "mass_spring" && r.kind != "fem")
    return fail("kind", "kind '" + r.kind + "' is not one of cloth, mass_spring, fem");
  if (!(r.totalMass > 0 && r.totalMass <= 1e12))
    return fail("totalMass", "totalMass " + num(r.totalMass) + " is not in (0, 1e12] kg");
  const double big = 1e30;
  struct Range {
    const char* key;
    double value, lo, hi;
  };
  for (const Range& k : {Range{"distanceCompliance", r.distanceCompliance, -big, big},
                         Range{"distanceStiffness", r.distanceStiffness, -big, big},
                         Range{"bendCompliance", r.bendCompliance, -big, big},
                         Range{"bendStiffness", r.bendStiffness, -big, big},
                         Range{"youngsModulus", r.youngsModulus, 0, kMaxYoungsModulus},
                         Range{"thickness", r.thickness, 0, kMaxThickness},
                         Range{"damping", r.damping, 0, 1}, Range{"collisionRadius", r.collisionRadius, 0, 1e6},
                         Range{"particleSpacing", r.particleSpacing, 0, 1e6}})
    if (!(k.value >= k.lo && k.value <= k.hi))
      return fail(k.key, std::string(k.key) + " " + num(k.value) + " is not in [" + num(k.lo) + ", " + num(k.hi) + "]");
  // Validated as RaiSim does, not used: no volumetric Poisson model.
  if (!(r.poissonRatio > -1 && r.poissonRatio < 0.5))
    return fail("poissonRatio", "poissonRatio " + num(r.poissonRatio) + " is not in (-1, 0.5)");
  if (r.distanceCompliance < 0 && !(r.distanceStiffness > 0))
    return fail("distanceStiffness", "distanceCompliance is negative (use 1/distanceStiffness) but distanceStiffness " +
                                         num(r.distanceStiffness) + " is not positive");
  if (r.youngsModulus > 0 && !(r.thickness > 0))
    return fail("thickness", "youngsModulus > 0 derives each edge's area from thickness, which is 0");
  // Physical ranges: a sheet thinner than a micrometre or a modulus below
  // 1 Pa is no material; its edges' compliance L / (E A) would be so large
  // that the cloth has no stretch resistance left and tears apart
  // (thickness=1e-300 threw a pinned cloth 35 km).
  if (r.thickness > 0 && r.thickness < kMinThickness)
    return fail("thickness", "thickness " + num(r.thickness) + " m is not 0 or in [" + num(kMinThickness) + ", " +
                                 num(kMaxThickness) + "] m");
  if (r.youngsModulus > 0 && r.youngsModulus < kMinYoungsModulus)
    return fail("youngsModulus", "youngsModulus " + num(r.youngsModulus) + " Pa is not 0 or in [" +
                                     num(kMinYoungsModulus) + ", " + num(kMaxYoungsModulus) + "] Pa");
  if (r.iterations < 0 || r.iterations > kMaxDeformableIterations)
    return fail("iterations", "iterations " + std::to_string(r.iterations) + " is not in [0, " +
                                  std::to_string(kMaxDeformableIterations) + "]");
  if (r.substeps < 1 || r.substeps > kMaxDeformableSubsteps)
    return fail("substeps", "substeps " + std::to_string(r.substeps) + " is not in [1, " +
                                std::to_string(kMaxDeformableSubsteps) + "]");
  if (!r.scale.allFinite() || r.scale.cwiseAbs().maxCoeff() > kMaxCoordinate)
    return fail("scale", "scale is not finite");
  // As written (a check needs no world pose); the placed particles are
  // bounded again once placed (deformable_model.hpp).
  if (!r.local.position.allFinite() || r.local.position.cwiseAbs().maxCoeff() > kMaxCoordinate)
    return fail("position", "position is beyond 1e12 m");
  if ((deformableFilled(r) || r.kind == "fem") && !(r.particleSpacing > 0))
    return fail("particleSpacing", "particleSpacing must be positive for a filled or fem body");
  return true;
}

}  // namespace rscene
