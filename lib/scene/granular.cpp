// The granular record's one decision: material, grains, substeps
// (granular.hpp).  Moved here from lib/sim so that rscene-validate runs the
// same rules rscene-sim builds its solver from.
#include "scene/granular.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/text.hpp"
#include "scene/neighbour_grid.hpp"

namespace rscene {
namespace {

// Above this a value is hostile rather than physical (1e12 N/m, kg/m^3 ...)
// and would only overflow the arithmetic of the stability bound.
constexpr double kHuge = 1e12;
// Coordinates past this are hostile, not a scene (and would lose every
// digit of a grain's radius).
constexpr double kMaxCoordinate = kMaxGranularCoordinate;
// Largest over smallest radius of one record (polydisperse sand spans 2 to 5).
constexpr double kMaxRadiusRatio = 10;

using namespace particle_code;

std::string number(double v) { return roundedNumber(v, 3); }  // a message, not data
std::string exact(double v) { return numberText(v); }          // a value as the user wrote it
std::string seconds(double s) { return number(s) + " s"; }

bool finiteVector(const Eigen::Vector3d& v, double limit) { return v.allFinite() && v.cwiseAbs().maxCoeff() <= limit; }

// Grains whose centres are closer than half the sum of their radii start
// so deep in each other that the first substep throws them apart (and
// grains written at one point would make every pair a contact).
bool deepOverlap(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& r, double rMax, std::size_t& a,
                 std::size_t& b) {
  NeighbourGrid grid;
  std::vector<std::uint32_t> is, js;
  // Touching pairs of grains that do not overlap that deep are a dozen per
  // grain: past the solver's cap some must (grains written at one point
  // would otherwise list every pair before the first is looked at).
  const std::size_t cap = kMaxGranularPairsPerGrain * x.size() + kGranularPairSlack;
  const bool all = grid.pairs(x, r, rMax, 0, is, js, cap);
  for (std::size_t k = 0; k < is.size(); ++k) {
    std::size_t i = is[k], j = js[k];
    double limit = 0.5 * (r[i] + r[j]);
    if ((x[i] - x[j]).squaredNorm() < limit * limit) {
      a = i, b = j;
      return true;
    }
  }
  if (!all) a = b = 0;  // crowded: no one pair to name
  return !all;
}

}  // namespace

bool granularMaterial(const Granular& g, GranularMaterial& m, std::vector<ParticleFinding>& findings) {
  bool ok = true;
  auto check = [&](const char* key, double v, bool positive) {
    if (std::isfinite(v) && (positive ? v > 0 : v >= 0) && v <= kHuge) return v;
    findings.push_back({true, kGranularValue, key,
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
  // The schema's granular_contact_model enumeration: the reader refused
  // any other name (RS2006) and left the default.
  m.hertz = g.normalContactModel != "linear";
  return ok;
}

double granularMaxSubstep(const GranularMaterial& m, double minMass, const char** limiting) {
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
  // stability without it gains energy and flies apart with it).  A pair,
  // like the normal mode: a grain's cohesion partners are its contact
  // neighbours, whose several springs at once kStableFraction covers for
  // both (tests/sim/granular_test.cpp runs a bed held by cohesion alone at
  // the step this gives).
  double cohesion = m.cohesionStiffness > 0 && m.cohesionMaxDistance > 0 ? critical(m.cohesionStiffness, 0, pairMass)
                                                                         : INFINITY;
  const double least = std::min({normal, tangential, cohesion});
  if (limiting)
    *limiting = least == cohesion ? "cohesionStiffness" : least == tangential ? "tangentialStiffness" : "normalStiffness";
  return kStableFraction * least;
}

double granularNormalEnergy(const GranularMaterial& m, double depth, double reff) {
  if (!(depth > 0)) return 0;
  return m.hertz ? 0.4 * m.kn * depth * depth * std::sqrt(depth / reff) : 0.5 * m.kn * depth * depth;
}

double granularStartDepthTolerance(const GranularMaterial& m, double r) {
  // A grain against a surface: Reff is its radius (the solver's rule).
  const double lift = m.density * 4.0 / 3.0 * M_PI * r * r * r * 9.81 * r;
  double d = m.hertz ? std::pow(lift * std::sqrt(r) / (0.4 * m.kn), 0.4) : std::sqrt(2 * lift / m.kn);
  if (!(d < 0.5 * r)) d = 0.5 * r;
  return d;
}

ParticleFinding granularStartDepthFinding(const Granular& g, const GranularStartDepth& deep, const std::string& inside,
                                          bool advise) {
  auto mm = [](double v) { return v < 0.1 ? roundedNumber(v * 1000, 3) + " mm" : roundedNumber(v, 3) + " m"; };
  const Eigen::Vector3d& at = deep.at;
  const bool one = deep.count == 1;
  return {true, kStartsInside, g.positions.empty() ? "boxMin" : "positions",
          "granular " + g.path + ": " + std::to_string(deep.count) + (one ? " grain starts" : " grains start") +
              " inside " + inside +
              (one ? " deeper than its contact spring holds without throwing it"
                   : " deeper than their contact springs hold without throwing them") +
              "; the deepest, grain " +
              std::to_string(deep.worst) + " at (" + roundedNumber(at.x(), 6) + ", " + roundedNumber(at.y(), 6) + ", " +
              roundedNumber(at.z(), 6) + "), by " + mm(deep.depth) + " (at most " + mm(deep.tolerance) +
              ": where its spring holds the energy of lifting it by its radius)" +
              (advise ? "; place the grains clear of the ground and the bodies (centres at least a radius above the "
                        "ground)"
                      : "")};
}

GranularStartDepth granularGroundDepth(const GranularSetup& s, const std::vector<double>& heights) {
  GranularStartDepth out;
  if (heights.empty()) return out;
  double worstExcess = 0;
  for (std::size_t i = 0; i < s.positions.size(); ++i) {
    const double r = s.radii[i];
    double depth = -INFINITY;
    for (double h : heights) depth = std::max(depth, r - (s.positions[i].z() - h));
    const double tol = granularStartDepthTolerance(s.material, r);
    if (!(depth > tol * (1 + 1e-9))) continue;
    ++out.count;
    if (depth - tol > worstExcess) {
      worstExcess = depth - tol;
      out.worst = i, out.depth = depth, out.tolerance = tol, out.at = s.positions[i];
    }
  }
  return out;
}

std::optional<GranularSetup> granularSetup(const Granular& g, double worldTimeStep,
                                           std::vector<ParticleFinding>& findings, bool world) {
  const std::size_t before = findings.size();
  auto failed = [&] {
    for (std::size_t k = before; k < findings.size(); ++k)
      if (findings[k].error) return true;
    return false;
  };
  GranularSetup s;
  granularMaterial(g, s.material, findings);
  if (g.substeps < 1 || g.substeps > kMaxGranularSubsteps)
    findings.push_back({true, kGranularValue, "substeps",
                        "granular " + g.path + ": substeps must be between 1 and " +
                            std::to_string(kMaxGranularSubsteps)});
  for (auto [key, v] : {std::pair{"velocity", g.velocity}, std::pair{"angularVelocity", g.angularVelocity}})
    if (!finiteVector(v, kMaxCoordinate))
      findings.push_back({true, kGranularValue, key, "granular " + g.path + ": " + key + " must be finite and at most 1e9"});
  if (finiteVector(g.velocity, kMaxCoordinate) && !(g.velocity.norm() <= kMaxGranularSpeed))
    findings.push_back({true, kGranularValue, "velocity",
                        "granular " + g.path + ": velocity " + number(g.velocity.norm()) + " m/s is past " +
                            number(kMaxGranularSpeed) + " m/s, the fastest grains may start"});
  if (failed()) return std::nullopt;

  if (g.positions.empty()) {
    // The box fill's own numbers first, each at its key.
    for (auto [key, v] : {std::pair{"radius", g.radius}, std::pair{"spacing", g.spacing}})
      if (!(v > 0) || !std::isfinite(v)) {
        findings.push_back({true, kGranular, key,
                            "granular " + g.path + " fills its box with " + key + " " + exact(v) +
                                ": it must be positive and finite"});
        return std::nullopt;
      }
  }
  std::string error = granularParticles(g, kMaxGranularParticles, s.positions, s.radii);
  if (!error.empty()) {
    // A box fill's count is weighed against its maxParticles (README).
    findings.push_back({true, kGranular,
                        !g.positions.empty() ? (error.find(" radii for ") != std::string::npos ? "radii" : "positions")
                                             : "maxParticles",
                        error});
    return std::nullopt;
  }
  const char* radiusKey = g.radii.empty() ? "radius" : "radii";
  for (std::size_t k = 0; k < s.radii.size(); ++k) {
    double r = s.radii[k];
    if (!(r > 0) || !(r <= kMaxCoordinate)) {
      findings.push_back({true, kGranularValue, radiusKey,
                          "granular " + g.path + ": particle " + std::to_string(k) +
                              " has a radius that is not positive and finite"});
      return std::nullopt;
    }
    if (!finiteVector(s.positions[k], kMaxCoordinate)) {
      findings.push_back({true, kGranularValue, "positions",
                          "granular " + g.path + ": particle " + std::to_string(k) +
                              " has a position that is not finite or past 1e9"});
      return std::nullopt;
    }
  }

  // Where the record's pose (and its parents') puts the grains: a grain
  // past 1e9 m is a position error, at the pose, whatever else it meets
  // there (at 1e300 every grain rounds to one point: not an overlap).
  for (std::size_t k = 0; k < s.positions.size(); ++k) {
    const Eigen::Vector3d w = g.world.position + g.world.orientation * s.positions[k];
    if (!finiteVector(w, kMaxCoordinate)) {
      findings.push_back({true, kGranularValue, "position",
                          "granular " + g.path + ": its pose puts particle " + std::to_string(k) + " at " +
                              exact(w.cwiseAbs().maxCoeff()) + " m, past 1e9 m"});
      return std::nullopt;
    }
  }

  s.fixed = g.fixed;
  s.substeps = static_cast<int>(g.substeps);
  s.maxSubstep = std::numeric_limits<double>::infinity();
  if (!s.radii.empty()) {
    double rMin = INFINITY, rMax = 0;
    for (double r : s.radii) rMin = std::min(rMin, r), rMax = std::max(rMax, r);
    // The neighbour grid's cells are sized by the largest grain: past this
    // ratio a cell holds thousands of the smallest and the search turns
    // quadratic (a hang, for a bed of a million).
    if (rMax > kMaxRadiusRatio * rMin) {
      findings.push_back({true, kGranularValue, radiusKey,
                          "granular " + g.path + ": radii from " + number(rMin) + " to " + number(rMax) +
                              " m span more than a factor of " + number(kMaxRadiusRatio)});
      return std::nullopt;
    }
    // A spin whose surface speed is past the bound: the grains' velocity
    // at their contacts.
    if (g.angularVelocity.norm() * rMax > kMaxGranularSpeed) {
      findings.push_back({true, kGranularValue, "angularVelocity",
                          "granular " + g.path + ": angularVelocity " + number(g.angularVelocity.norm()) +
                              " rad/s spins its largest grain (radius " + number(rMax) + " m) at " +
                              number(g.angularVelocity.norm() * rMax) + " m/s at its surface, past " +
                              number(kMaxGranularSpeed) + " m/s"});
      return std::nullopt;
    }
    // Cohesion acts at contact distances: RaiSim keeps its range "small
    // relative to particle radius".  At most the smallest radius, a grain's
    // cohesion partners are its neighbours (9 pairs a grain at most), not
    // the whole bed (cohesionMaxDistance=100 listed every pair).
    if (s.material.cohesionStiffness > 0 && s.material.cohesionMaxDistance > rMin) {
      findings.push_back({true, kGranularValue, "cohesionMaxDistance",
                          "granular " + g.path + ": cohesionMaxDistance " + exact(g.cohesionMaxDistance) +
                              " m is more than the smallest grain radius " + exact(rMin) +
                              " m: cohesion acts at contact distances (a surface gap of at most one radius), "
                              "and a longer range makes every grain pull on grains it does not touch"});
      return std::nullopt;
    }
    // Cohesion stronger than the contact repulsion: a pair falling from
    // cohesionMaxDistance into contact gains the well's depth,
    // integral of kc g (1 - g / gmax) = kc gmax^2 / 6, and only the normal
    // spring stops it.  When that spring needs more than a quarter of the
    // smallest radius to take it, grains pulled by their neighbours fall
    // through each other and are thrown out again.
    if (s.material.cohesionStiffness > 0 && s.material.cohesionMaxDistance > 0) {
      const double well = s.material.cohesionStiffness * s.material.cohesionMaxDistance *
                          s.material.cohesionMaxDistance / 6;
      const double overlap = kCohesionOverlapFraction * rMin;
      const double spring = granularNormalEnergy(s.material, overlap, rMin / 2);
      if (!(well <= spring)) {
        // The largest cohesionStiffness the rule lets pass for this range.
        const double most = 6 * spring / (s.material.cohesionMaxDistance * s.material.cohesionMaxDistance);
        findings.push_back({true, kCohesionTooStrong, "cohesionStiffness",
                            "granular " + g.path + ": cohesion stronger than the contact repulsion: its well, " +
                                "cohesionStiffness x cohesionMaxDistance^2 / 6 = " + number(well) +
                                " J, is more than the normal spring holds at an overlap of a quarter of the "
                                "smallest radius (" + number(spring) + " J at " + number(overlap) +
                                " m), so grains it pulls together fall through each other; at this "
                                "cohesionMaxDistance cohesionStiffness may be at most " + number(most) +
                                " (or raise normalStiffness, or shorten cohesionMaxDistance)"});
        return std::nullopt;
      }
    }
    std::size_t a = 0, b = 0;
    if (deepOverlap(s.positions, s.radii, rMax, a, b)) {
      findings.push_back({true, kOverlap, g.positions.empty() ? "spacing" : "positions",
                          "granular " + g.path + ": " +
                              (a == b ? "more than " + std::to_string(kMaxGranularPairsPerGrain) +
                                            " touching pairs per grain: grains" 
                                      : "particles " + std::to_string(a) + " and " + std::to_string(b)) +
                              " overlap by more than half their radii" +
                              (g.positions.empty() ? " (spacing at least 2 x radius keeps a box fill apart)"
                                                   : std::string())});
      return std::nullopt;
    }
    const double minMass = s.material.density * 4.0 / 3.0 * M_PI * rMin * rMin * rMin;
    const char* limiting = "normalStiffness";
    s.maxSubstep = granularMaxSubstep(s.material, minMass, &limiting);
    // kt = 0 in the record is 2/7 of normalStiffness: that is the key to change.
    std::string cause = limiting;
    if (cause == "tangentialStiffness" && !(g.tangentialStiffness > 0)) cause = "normalStiffness";
    const std::string lower = cause == "cohesionStiffness" ? "lower cohesionStiffness"
                              : cause == "tangentialStiffness" ? "lower tangentialStiffness or tangentialDamping"
                                                               : "lower normalStiffness or normalDamping";
    // Fixed grains never move: their step cannot go unstable.
    const double needed = g.fixed ? 1 : std::ceil(worldTimeStep / s.maxSubstep - 1e-9);
    const std::string why = "time_step " + seconds(worldTimeStep) + " against a stable substep of at most " +
                            seconds(s.maxSubstep) + " (0.6 of the critical step of " + cause +
                            " for the lightest grain, radius " + number(rMin) + " m)";
    if (!(needed <= kMaxGranularSubsteps)) {
      findings.push_back({true, kTooStiff, cause,
                          "granular " + g.path + ": stability needs more than " +
                              std::to_string(kMaxGranularSubsteps) + " substeps per world step: " + why + "; " +
                              lower + ", raise radius or density, or shorten time_step"});
      return std::nullopt;
    }
    if (needed > s.substeps) {
      findings.push_back({false, kSubstepsRaised, "substeps",
                          "granular " + g.path + ": substeps raised from " + std::to_string(s.substeps) + " to " +
                              std::to_string(static_cast<int>(needed)) + " for stability (" + why + "), " +
                              number(std::round(needed / s.substeps * 10) / 10) +
                              "x the particle time; write substeps=" + std::to_string(static_cast<int>(needed)) +
                              " to accept it, or " + lower});
      s.substeps = static_cast<int>(needed);
    }
  }
  if (world) {
    // Positions, velocity and angular velocity are in the record's frame.
    const Eigen::Quaterniond& q = g.world.orientation;
    for (Eigen::Vector3d& x : s.positions) x = g.world.position + q * x;
    s.velocity = g.fixed ? Eigen::Vector3d::Zero() : Eigen::Vector3d(q * g.velocity);
    s.angularVelocity = g.fixed ? Eigen::Vector3d::Zero() : Eigen::Vector3d(q * g.angularVelocity);
  }
  return s;
}

}  // namespace rscene
