// The deformable and granular records of a scene, simulated beside the
// rigid world (World owns one): built from the scene, stepped once per
// world step before Bullet (their contact reactions are forces on Bullet's
// bodies for that step), reported per step (trajectory, rest, finiteness)
// and written back (granular records get explicit positions and radii).
#pragma once
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "asset/cache.hpp"
#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "robot/trajectory_format.hpp"
#include "scene/scene.hpp"
#include "sim/deformable_body.hpp"
#include "sim/granular_body.hpp"
#include "sim/surface_query.hpp"

namespace rscene::sim {

namespace particle_code = rscene::particle_code;  // RS7080-RS7089 (scene/granular.hpp)

// Why a system stopped the run (GranularFailure), at its record.
struct ParticleFailure {
  int recordIndex = -1;
  std::string path;
  GranularFailure failure;
};

// The particles of one record now, for the trajectory and the renderer.
using robot::ParticleState;

class ParticleSystems {
 public:
  // Builds a body per deformable and granular record (visible or not:
  // they are physics); a deformable's mesh is read through `assets`'s file
  // system.  False after adding an error at the record (and key) at fault.
  bool create(const Scene& scene, const Document* doc, asset::AssetCache& assets, Diagnostics& diagnostics);
  bool empty() const { return deformables_.empty() && granulars_.empty(); }
  std::size_t systems() const { return deformables_.size() + granulars_.size(); }
  std::size_t particles() const;  // of every system
  // Seconds spent in step() so far (steady clock), for rscene-sim --report:
  // where a run's time goes, particles or Bullet.
  double stepSeconds() const { return stepSeconds_; }
  // The granular solvers' counters and timings, summed (the largest
  // substepsPerStep and maxPenetration).
  GranularStats granularStats() const;

  // One world step of every system.
  void step(double dt, const Eigen::Vector3d& gravity, SurfaceQuery& surfaces);
  // Every particle slower than `speed` (m/s): the systems are at rest.
  bool atRest(double speed) const;
  std::vector<ParticleState> states() const;  // deformables in record order, then granulars
  // The first system whose particles are no longer finite: its record and path.
  std::optional<std::pair<int, std::string>> nonFinite() const;
  // Deformables (lib/sim/deformable_*): what each costs a world step
  // (DeformableBody::workPerStep), in record order, for the per-run cap.
  struct DeformableCost {
    int recordIndex = -1;
    std::string path;
    double workPerStep = 0;
  };
  std::vector<DeformableCost> deformableCosts() const;
  // Before the first step: false after an error (RS7077) at each deformable
  // whose free particle starts deeper than half its collisionRadius inside
  // a surface (pushing it out in one substep would throw it).  Shallower
  // overlaps are removed here (DeformableBody::pushOut), with a warning
  // (RS7016) at the record when one was deeper than a micrometre.
  bool checkDeformableStarts(SurfaceQuery& surfaces, const Document* doc, Diagnostics& diagnostics);
  // Granular records: grains, substeps a step and candidate pairs, in
  // record order, for the per-run cap (checkGranularWork, limits.hpp).
  struct GranularCost {
    int recordIndex = -1;
    std::string path;
    std::size_t grains = 0, pairs = 0;
    int substeps = 0;
    double workPerStep = 0;  // substeps x (grains + pairs)
  };
  std::vector<GranularCost> granularCosts() const;
  // Before the first step: false after an error (RS7091) at each granular
  // record whose grains start deeper inside a surface (the ground, a
  // static or dynamic body, a robot link) than granularStartDepthTolerance().
  bool checkGranularStarts(SurfaceQuery& surfaces, const Document* doc, Diagnostics& diagnostics) const;
  // The first deformable whose kinetic energy ran away (DeformableBody::
  // runaway): its record, path and the sentence with the figures.
  struct Runaway {
    int recordIndex = -1;
    std::string path, why;
  };
  std::optional<Runaway> deformableRunaway() const;
  // The first system that stopped itself (energy, bounds, pairs).
  std::optional<ParticleFailure> failure() const;
  // What sim writes, sim reads: the first granular record whose grains now
  // (as writeBack() would write them) the scene model would refuse
  // (granularSetup(): an overlap deeper than half the radii, a grain past
  // 1e9 m), as RS7084 naming the rule.  Run before writing.
  // With `surfaces`, grains settled deeper inside a surface than a run
  // would start them (RS7091) are one too.
  std::optional<ParticleFailure> unwritable(SurfaceQuery* surfaces = nullptr) const;
  // Granular records get `positions` and `radii` (in the record's frame):
  // RaiSim reads explicit positions in place of the box fill, so the
  // settled bed loads as it was left.  Deformables keep their record (the
  // format stores no deformed state).
  void writeBack(Document& doc) const;

 private:
  struct DeformableEntry {
    int recordIndex = -1;
    std::string path;
    std::unique_ptr<DeformableBody> body;
  };
  struct GranularEntry {
    int recordIndex = -1;
    std::string path;
    Pose frame;  // the record's world frame: written-back positions are in it
    std::unique_ptr<GranularBody> body;
    Granular record;  // without its grains: unwritable() judges the settled ones
  };
  // The grains of `g` in its record's frame, as writeBack() writes them.
  static std::vector<Eigen::Vector3d> local(const GranularEntry& g);
  // The grains of `g` deeper inside a surface than they may start.
  static GranularStartDepth startDepth(const GranularEntry& g, SurfaceQuery& surfaces);
  double timeStep_ = 0;
  std::vector<DeformableEntry> deformables_;
  std::vector<GranularEntry> granulars_;
  double stepSeconds_ = 0;
};

}  // namespace rscene::sim
