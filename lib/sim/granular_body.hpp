// One granular record simulated as RaiSim's GranularSystem does
// (../shared/spec/raisim/GranularMedia.rst): spherical grains with a
// discrete-element contact model (linear or Hertz normal force with
// damping, tangential springs with history capped by Coulomb friction,
// rolling friction, short-range cohesion), explicit integration in the
// record's substeps, contacts with the rigid world through a SurfaceQuery
// with the reaction applied back to dynamic bodies.  rscene-sim(1) has the
// key-by-key mapping.
#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "scene/granular.hpp"
#include "scene/visual_records.hpp"
#include "sim/surface_query.hpp"

namespace rscene::sim {

// What create() found (scene/granular.hpp): an error refuses the record,
// a warning does not.
using GranularFinding = ParticleFinding;

// Where a granular body's time went, for rscene-sim --report.
struct GranularStats {
  int substepsPerStep = 0;            // what stability asked for (>= the record's substeps)
  std::uint64_t particleSubsteps = 0; // dynamic and fixed particles times substeps, so far
  std::uint64_t neighbourBuilds = 0;  // pair-list rebuilds (grid + sort + history merge)
  std::size_t pairs = 0;              // candidate pairs in the list now
  std::size_t contacts = 0;           // touching pairs at the last substep
  std::size_t surfaceContacts = 0;    // grain-surface contacts at the last substep
  double neighbourSeconds = 0, contactSeconds = 0, surfaceSeconds = 0, integrateSeconds = 0;
  double maxPenetration = 0;          // deepest overlap at the last substep, m
};

// Why a granular body stopped (scene/granular.hpp's particle_code: RS7083
// energy, RS7084 bounds, RS7085 pairs): reported at the record's `field`
// ("" for the record).  A stopped body steps no more.
struct GranularFailure {
  const char* code = "";
  std::string field;
  std::string message;
  std::string hint;
};

class GranularBody {
 public:
  static constexpr std::uint64_t kMaxParticles = kMaxGranularParticles;
  static constexpr int kMaxSubsteps = kMaxGranularSubsteps;

  // The solver for the record's granularSetup() (the scene model's one
  // decision: grains placed by the record's world pose, material, the
  // substeps a world step of `worldTimeStep` needs), whose findings are
  // appended.  nullptr when a finding is an error.
  static std::unique_ptr<GranularBody> create(const Granular& record, double worldTimeStep,
                                              std::vector<GranularFinding>& findings);
  virtual ~GranularBody() = default;

  virtual void step(double dt, const Eigen::Vector3d& gravity, SurfaceQuery& surfaces) = 0;

  virtual const std::vector<Eigen::Vector3d>& positions() const = 0;  // world
  virtual const std::vector<Eigen::Vector3d>& velocities() const = 0; // world
  virtual const std::vector<double>& radii() const = 0;
  virtual double totalMass() const = 0;
  virtual double maxSpeed() const = 0;
  virtual bool finite() const = 0;
  virtual const GranularStats& stats() const = 0;
  virtual const std::optional<GranularFailure>& failure() const = 0;
  virtual const GranularMaterial& material() const = 0;
  virtual bool fixed() const = 0;
  // Candidate pairs in the neighbour list (built when the body is made):
  // with the grains and the substeps, the solver's work per step.
  virtual std::size_t candidatePairs() const = 0;
};

}  // namespace rscene::sim
