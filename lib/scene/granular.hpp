// What a granular record means for a simulator, decided once in the scene
// model: its contact law (RaiSim's GranularSystem::Material), its grains
// (explicit or the box fill, placed by the record's world pose) and the
// substeps a world step needs.  checkScene() reports the same findings
// (rscene-validate), rscene-sim builds its solver from the setup, and
// rscene-render draws the same grains, so the three give one verdict.
//
// The forms, chosen where RaiSim's documentation leaves them open, are in
// rscene-sim(1) "Granular media":
//   normal, linear   fn = kn d - cn vn
//   normal, Hertz    fn = kn d sqrt(d / Reff) - cn vn   (kn keeps N/m, and
//                    for d < Reff it is softer than linear, as RaiSim says)
//   both clamped at 0: damping never pulls grains together.
//   tangential       Cundall-Strack spring kt xi + dashpot ct, |ft| <= mu fn;
//                    kt = 0 in the record means 2/7 kn (the ratio that gives
//                    a solid sphere the same normal and tangential frequency)
//   rolling          a spring kr = kt Reff^2 on the relative rolling angle,
//                    |M| <= mur Reff fn (elastic-plastic, with history)
//   cohesion         attraction kc g (1 - g / gmax) for a surface gap
//                    0 < g < gmax: slope kc at contact and no jump at the
//                    cut-off (a force that jumps from kc gmax to 0 there
//                    pumps energy into a bed every time a pair crosses it);
//                    gmax at most the smallest grain's radius (RaiSim:
//                    "small relative to particle radius"; cohesion acts at
//                    contact distances, and a longer range makes the pair
//                    list grow with its cube)
#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/codes.hpp"
#include "scene/visual_records.hpp"

namespace rscene {

namespace particle_code {
inline constexpr const char* kDeformableMesh = rs::RS7080;  // a deformable's mesh is not a usable OBJ surface
inline constexpr const char* kDeformable = rs::RS7081;      // a deformable record that cannot be simulated
inline constexpr const char* kGranular = rs::RS7082;        // a granular record whose grains cannot be made
inline constexpr const char* kSubstepsRaised = rs::RS7086;  // warning: substeps raised for stability
inline constexpr const char* kTooStiff = rs::RS7087;        // stability needs more than kMaxGranularSubsteps
inline constexpr const char* kGranularValue = rs::RS7088;   // a granular value out of range
inline constexpr const char* kOverlap = rs::RS7089;         // grains overlapping by more than half their radii
inline constexpr const char* kEnergy = rs::RS7083;          // sim: energy grew, the solver is unstable
inline constexpr const char* kLeftBounds = rs::RS7084;      // sim: grains past 1e9 m or settled into a refused state
inline constexpr const char* kTooManyGrainPairs = rs::RS7085;  // sim: pair list past its cap
inline constexpr const char* kStartsInside = rs::RS7091;  // grains starting inside the ground or a body
inline constexpr const char* kCohesionTooStrong = rs::RS7092;  // cohesion well deeper than the contact spring holds
inline constexpr const char* kGranularWork = rs::RS7093;  // sim: the run's solver work (refusal or warning)
}  // namespace particle_code

// A finding of a particle record's check: an error refuses the record, a
// warning does not.  The caller reports it at the record's `field`.
struct ParticleFinding {
  bool error = true;
  const char* code = "";
  std::string field;  // the record's key at fault, "" for the record
  std::string message;
};

// Most particles one granular record may have whatever its maxParticles.
inline constexpr std::uint64_t kMaxGranularParticles = 2'000'000;
// Most substeps per world step stability may ask for; past it the record
// is refused (RS7087) naming the keys that would make it affordable.
inline constexpr int kMaxGranularSubsteps = 1000;
// Fastest a granular record's grains may start (m/s, RS7088): `velocity`,
// and `angularVelocity` times the largest radius (a grain's surface
// speed).  Ten times a rifle bullet; at 1e9 a grain would leave the
// 1e9 m world in a second of simulated time (RS7084).
inline constexpr double kMaxGranularSpeed = 1e4;
// The margin below the pair's critical step for a grain's several
// contacts at once: 0.6, which RaiSim's own example material (radius
// 0.02, normalStiffness 5e4, tangentialStiffness 2.5e4) meets in its 2
// substeps of a 1 ms step (it runs at 0.56).
inline constexpr double kStableFraction = 0.6;
// The Hertz overlap, as a fraction of Reff, at which the stability bound
// takes the stiffness: 5 %, deeper than a usable bed sinks into itself.
inline constexpr double kHertzOverlap = 0.05;
// Grain coordinates (and record velocities) past this are hostile, not a
// scene; a run whose grains get past it stops (RS7084) rather than write them.
inline constexpr double kMaxGranularCoordinate = 1e9;
// The granular solver's candidate pairs (grains within the contact range,
// the cohesion range and a skin) are at most this many per grain, plus
// kGranularPairSlack: about 3.6 KB a grain.  Equal grains that do not
// overlap by more than half their radii have at most 9 per grain with
// the longest cohesion range allowed (one radius); past the cap the grains
// are pressed into each other and the run stops (RS7085).
inline constexpr std::size_t kMaxGranularPairsPerGrain = 32;
inline constexpr std::size_t kGranularPairSlack = 4096;

struct GranularMaterial {
  double density = 0;
  double kn = 0, cn = 0, kt = 0, ct = 0;
  double friction = 0, rollingFriction = 0;
  double cohesionStiffness = 0, cohesionMaxDistance = 0;
  bool hertz = true;
};

// The record's material, or findings (RS7088 at the key) when a value is
// out of range: not finite, negative, a zero density or stiffness, an
// unknown normalContactModel (the schema's enumeration).
bool granularMaterial(const Granular& record, GranularMaterial& out, std::vector<ParticleFinding>& findings);

// The largest substep the explicit integrator stays stable and accurate
// with for grains of mass `minMass` (the lightest): kStableFraction of the
// critical step 2/w (sqrt(1 + z^2) - z) of the stiffest mode, the normal
// (kn; Hertz: its tangent stiffness at an overlap of kHertzOverlap x
// Reff) or tangential one (kt with rotation: 3.5 kt), of a pair (mass m/2).
// `limiting`, when given, gets the record key of the mode that sets it
// (normalStiffness, tangentialStiffness or cohesionStiffness).
double granularMaxSubstep(const GranularMaterial& m, double minMass, const char** limiting = nullptr);

// Energy stored in the normal spring of a contact at overlap `depth`
// (linear 1/2 kn d^2, Hertz 2/5 kn d^2 sqrt(d / Reff)).
double granularNormalEnergy(const GranularMaterial& m, double depth, double reff);

// The overlap, as a fraction of the smallest radius, whose normal-spring
// energy the cohesion well must not exceed (RS7092): a quarter.  A pair
// falling from cohesionMaxDistance into contact stops within it, and a
// grain pulled by 16 such wells at once (linear) still stops short of the
// deep overlap RS7089 refuses (half the sum of the radii).
inline constexpr double kCohesionOverlapFraction = 0.25;

// The deepest a grain of `radius` may start inside the ground or another
// body (RS7091): where its normal spring holds the energy of lifting the
// grain by its own radius against 9.81 m/s^2 (what the solver's energy
// check lets pass for each grain), and never more than half the radius.
// A bed settled on the ground is far inside it.
double granularStartDepthTolerance(const GranularMaterial& m, double radius);

// Grains that start deeper inside a surface than granularStartDepthTolerance().
struct GranularStartDepth {
  std::size_t count = 0;  // grains past the tolerance
  std::size_t worst = 0;  // the one furthest past it
  double depth = 0;       // its depth, m
  double tolerance = 0;   // its tolerance, m
  Eigen::Vector3d at = Eigen::Vector3d::Zero();  // its centre, world
};
// The finding (RS7091) for `deep` (count > 0), at the key that placed the
// grains (positions, or boxMin for a box fill); `inside` names what they
// start in ("the ground", "the ground or another body").
// `advise`: end with where to place the grains (not for a settled bed).
ParticleFinding granularStartDepthFinding(const Granular& record, const GranularStartDepth& deep,
                                          const std::string& inside, bool advise = true);

// A granular record ready to simulate.
struct GranularSetup {
  GranularMaterial material;
  std::vector<Eigen::Vector3d> positions;  // world (the record's world pose applied)
  std::vector<double> radii;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero(), angularVelocity = Eigen::Vector3d::Zero();  // world, all grains
  bool fixed = false;
  int substeps = 1;        // what stability asks for, at least the record's
  double maxSubstep = 0;   // s; infinity for an empty bed
};

// Checks the record against a world step of `worldTimeStep` and builds its
// grains: findings RS7082 (grains that cannot be made: past maxParticles or
// kMaxGranularParticles, radii that do not match), RS7088 (a value out of
// range), RS7089 (a deep overlap at the start), RS7087 (too stiff to
// afford), and the warning RS7086 (substeps raised).  std::nullopt when a
// finding is an error.  `world` false: the grains stay in the record's
// frame (a check needs no world pose).
std::optional<GranularSetup> granularSetup(const Granular& record, double worldTimeStep,
                                           std::vector<ParticleFinding>& findings, bool world = true);

// The grains of a setup in world coordinates against horizontal ground
// planes at `heights` (normal +z, as the simulator builds them).
GranularStartDepth granularGroundDepth(const GranularSetup& worldSetup, const std::vector<double>& heights);

}  // namespace rscene
