#include "sim/granular_material.hpp"

#include <algorithm>
#include <cmath>

namespace rscene::sim {
namespace {

// Above this a value is hostile rather than physical (1e12 N/m, kg/m^3 ...)
// and would only overflow the arithmetic of the stability bound.
constexpr double kHuge = 1e12;

}  // namespace

bool granularMaterial(const Granular& g, GranularMaterial& m, std::vector<GranularFinding>& findings) {
  bool ok = true;
  auto check = [&](const char* key, double v, bool positive) {
    if (std::isfinite(v) && (positive ? v > 0 : v >= 0) && v <= kHuge) return v;
    findings.push_back({true, "RS7088", key,
                        "granular " + g.path + ": " + key + " must be " + (positive ? "positive" : "non-negative") +
                            ", finite and at most 1e12"});
    ok = false;
    return 0.0;
  };
  m.density = check("density", g.density, true);
  m.kn = check("normalStiffness", g.normalStiffness, true);
  m.cn = check("normalDamping", g.normalDamping, false);
  m.kt = check("tangentialStiffness", g.tangentialStiffness, false);
  m.ct = check("tangentialDamping", g.tangentialDamping, false);
  m.friction = check("friction", g.friction, false);
  m.rollingFriction = check("rollingFriction", g.rollingFriction, false);
  m.cohesionStiffness = check("cohesionStiffness", g.cohesionStiffness, false);
  m.cohesionMaxDistance = check("cohesionMaxDistance", g.cohesionMaxDistance, false);
  if (m.kt == 0) m.kt = 2.0 / 7.0 * m.kn;
  if (g.normalContactModel == "hertz") {
    m.hertz = true;
  } else if (g.normalContactModel == "linear") {
    m.hertz = false;
  } else {
    findings.push_back({true, "RS7088", "normalContactModel",
                        "granular " + g.path + ": normalContactModel '" + g.normalContactModel +
                            "' is neither hertz nor linear"});
    ok = false;
  }
  return ok;
}

double granularMaxSubstep(const GranularMaterial& m, double minMass) {
  const double pairMass = minMass / 2;
  // Critical step of the damped oscillator x'' = -(k x + c x') / mass under
  // explicit (semi-implicit Euler) integration.
  auto critical = [](double k, double c, double mass) {
    if (!(k > 0)) return mass > 0 && c > 0 ? 2 * mass / c : INFINITY;
    double w = std::sqrt(k / mass), z = c / (2 * std::sqrt(k * mass));
    return 2 / w * (std::sqrt(1 + z * z) - z);
  };
  // Hertz: dF/dd = 1.5 kn sqrt(d / Reff), taken at d = kHertzOverlap Reff.
  double kNormal = m.hertz ? 1.5 * m.kn * std::sqrt(kHertzOverlap) : m.kn;
  // A tangential force at the contact point moves it as a mass of m / 3.5
  // would (translation 1/m plus rotation r^2 / (2/5 m r^2)).
  double normal = critical(kNormal, m.cn, pairMass);
  double tangential = critical(3.5 * m.kt, 3.5 * m.ct, pairMass);
  // Cohesion is an undamped spring of cohesionStiffness across the gap: as
  // stiff a mode as the normal one when kc is as large (a bed at the edge of
  // stability without it gains energy and flies apart with it).
  double cohesion = m.cohesionStiffness > 0 && m.cohesionMaxDistance > 0 ? critical(m.cohesionStiffness, 0, pairMass)
                                                                         : INFINITY;
  return kStableFraction * std::min({normal, tangential, cohesion});
}

}  // namespace rscene::sim
