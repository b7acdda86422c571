// The granular record's checks and the substeps it needs; the solver is
// granular_dem.cpp.
#include "sim/granular_body.hpp"

#include <cmath>
#include <limits>

#include "core/text.hpp"
#include "sim/granular_dem.hpp"
#include "sim/granular_pairs.hpp"

namespace rscene::sim {
namespace {

// Coordinates past this are hostile, not a scene (and would lose every
// digit of a grain's radius).
constexpr double kMaxCoordinate = 1e9;
// Largest over smallest radius of one record (polydisperse sand spans 2 to 5).
constexpr double kMaxRadiusRatio = 10;

std::string number(double v) { return roundedNumber(v, 3); }  // a message, not data
std::string seconds(double s) { return number(s) + " s"; }

bool finiteVector(const Eigen::Vector3d& v, double limit) { return v.allFinite() && v.cwiseAbs().maxCoeff() <= limit; }

// Grains whose centres are closer than half the sum of their radii start
// so deep in each other that the first substep throws them apart (and
// grains written at one point would make every pair a contact).
bool deepOverlap(const std::vector<Eigen::Vector3d>& x, const std::vector<double>& r, double rMax, std::size_t& a,
                 std::size_t& b) {
  GranularPairs pairs;
  pairs.build(x, r, rMax, 0);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    std::size_t i = pairs.i[k], j = pairs.j[k];
    double limit = 0.5 * (r[i] + r[j]);
    if ((x[i] - x[j]).squaredNorm() < limit * limit) {
      a = i, b = j;
      return true;
    }
  }
  return false;
}

}  // namespace

std::unique_ptr<GranularBody> GranularBody::create(const Granular& g, double worldTimeStep,
                                                   std::vector<GranularFinding>& findings) {
  const std::size_t before = findings.size();
  auto failed = [&] {
    for (std::size_t k = before; k < findings.size(); ++k)
      if (findings[k].error) return true;
    return false;
  };
  GranularMaterial material;
  granularMaterial(g, material, findings);
  if (g.substeps < 1 || g.substeps > kMaxSubsteps)
    findings.push_back({true, "RS7088", "substeps",
                        "granular " + g.path + ": substeps must be between 1 and " + std::to_string(kMaxSubsteps)});
  for (auto [key, v] : {std::pair{"velocity", g.velocity}, std::pair{"angularVelocity", g.angularVelocity}})
    if (!finiteVector(v, kMaxCoordinate))
      findings.push_back({true, "RS7088", key, "granular " + g.path + ": " + key + " must be finite and at most 1e9"});
  if (failed()) return nullptr;

  GranularParticles particles;
  std::string error = granularParticles(g, kMaxParticles, particles.positions, particles.radii);
  if (!error.empty()) {
    findings.push_back({true, "RS7082", g.positions.empty() ? "maxParticles" : "positions", error});
    return nullptr;
  }
  const char* radiusKey = g.radii.empty() ? "radius" : "radii";
  for (std::size_t k = 0; k < particles.radii.size(); ++k) {
    double r = particles.radii[k];
    if (!(r > 0) || !(r <= kMaxCoordinate)) {
      findings.push_back({true, "RS7088", radiusKey,
                          "granular " + g.path + ": particle " + std::to_string(k) +
                              " has a radius that is not positive and finite"});
      return nullptr;
    }
    if (!finiteVector(particles.positions[k], kMaxCoordinate)) {
      findings.push_back({true, "RS7088", "positions",
                          "granular " + g.path + ": particle " + std::to_string(k) +
                              " has a position that is not finite or past 1e9"});
      return nullptr;
    }
  }

  // Positions, velocity and angular velocity are in the record's frame.
  const Eigen::Quaterniond& q = g.world.orientation;
  for (Eigen::Vector3d& x : particles.positions) x = g.world.position + q * x;
  particles.velocity = g.fixed ? Eigen::Vector3d::Zero() : Eigen::Vector3d(q * g.velocity);
  particles.angularVelocity = g.fixed ? Eigen::Vector3d::Zero() : Eigen::Vector3d(q * g.angularVelocity);
  particles.fixed = g.fixed;

  int substeps = static_cast<int>(g.substeps);
  double maxSubstep = std::numeric_limits<double>::infinity();
  if (!particles.radii.empty()) {
    double rMin = INFINITY, rMax = 0;
    for (double r : particles.radii) rMin = std::min(rMin, r), rMax = std::max(rMax, r);
    // The neighbour grid's cells are sized by the largest grain: past this
    // ratio a cell holds thousands of the smallest and the search turns
    // quadratic (a hang, for a bed of a million).
    if (rMax > kMaxRadiusRatio * rMin) {
      findings.push_back({true, "RS7088", radiusKey,
                          "granular " + g.path + ": radii from " + number(rMin) + " to " + number(rMax) +
                              " m span more than a factor of " + number(kMaxRadiusRatio)});
      return nullptr;
    }
    std::size_t a = 0, b = 0;
    if (deepOverlap(particles.positions, particles.radii, rMax, a, b)) {
      findings.push_back({true, "RS7089", g.positions.empty() ? "spacing" : "positions",
                          "granular " + g.path + ": particles " + std::to_string(a) + " and " + std::to_string(b) +
                              " overlap by more than half their radii (spacing at least 2 x radius keeps a box "
                              "fill apart)"});
      return nullptr;
    }
    const double minMass = material.density * 4.0 / 3.0 * M_PI * rMin * rMin * rMin;
    maxSubstep = granularMaxSubstep(material, minMass);
    // Fixed grains never move: their step cannot go unstable.
    const double needed = g.fixed ? 1 : std::ceil(worldTimeStep / maxSubstep - 1e-9);
    const std::string why = "time_step " + seconds(worldTimeStep) + " against a stable substep of at most " +
                            seconds(maxSubstep) + " (0.6 of the critical step of normalStiffness, normalDamping, "
                            "tangentialStiffness, tangentialDamping and cohesionStiffness for the lightest grain, radius " +
                            number(rMin) + " m)";
    if (!(needed <= kMaxSubsteps)) {
      findings.push_back({true, "RS7087", "normalStiffness",
                          "granular " + g.path + ": stability needs more than " + std::to_string(kMaxSubsteps) +
                              " substeps per world step: " + why +
                              "; lower normalStiffness or normalDamping, raise radius or density, or shorten "
                              "time_step"});
      return nullptr;
    }
    if (needed > substeps) {
      findings.push_back({false, "RS7086", "substeps",
                          "granular " + g.path + ": substeps raised from " + std::to_string(substeps) + " to " +
                              std::to_string(static_cast<int>(needed)) + " for stability (" + why + "), " +
                              number(std::round(needed / substeps * 10) / 10) +
                              "x the particle time; write substeps=" + std::to_string(static_cast<int>(needed)) +
                              " to accept it, or lower normalStiffness or normalDamping"});
      substeps = static_cast<int>(needed);
    }
  }
  return makeGranularDem(std::move(particles), material, substeps, maxSubstep);
}

}  // namespace rscene::sim
