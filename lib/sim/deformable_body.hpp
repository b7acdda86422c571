// One deformable record simulated as RaiSim's DeformableObject does
// (../shared/spec/raisim/DeformableObject.rst): particles at the OBJ's
// vertices, XPBD (or PBD) distance constraints along the mesh's edges and
// isometric bending constraints across adjacent triangles, a spherical
// proxy of collisionRadius per particle for contacts, pinned particles held
// in place.  The man page rscene-sim(1) has the key-by-key mapping.
#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "asset/obj_surface.hpp"
#include "scene/deformable_model.hpp"
#include "scene/visual_records.hpp"
#include "sim/surface_query.hpp"

namespace rscene::sim {

class DeformableBody {
 public:
  // Most particles one deformable may have (surface vertices plus a fem
  // fill), so a fine spacing is refused before it is allocated.
  static constexpr std::uint64_t kMaxParticles = kMaxDeformableParticles;

  // Builds the body from its record and its OBJ surface (the file's frame:
  // placed by the record's world pose and scale).  nullptr with `error`
  // (a sentence naming the key at fault, e.g. "pinnedVertices 40 is not a
  // vertex of meshes/flag.obj (it has 36)") when the record cannot be
  // simulated; `errorField` then names that key ("" for the record).
  static std::unique_ptr<DeformableBody> create(const Deformable& record, const asset::ObjSurface& surface,
                                                std::string& error, std::string& errorField);
  virtual ~DeformableBody() = default;

  // One world step of dt seconds (the record's substeps inside it), under
  // gravity, against `surfaces` (prepared by the body itself).
  virtual void step(double dt, const Eigen::Vector3d& gravity, SurfaceQuery& surfaces) = 0;

  // Particle positions, world: the OBJ's vertices first, in file order
  // (what the trajectory carries and the renderer draws with the OBJ's
  // triangles), then fill particles (fem) if any.
  virtual const std::vector<Eigen::Vector3d>& positions() const = 0;
  virtual std::size_t surfaceVertexCount() const = 0;
  virtual double totalMass() const = 0;     // of the free particles plus the pinned ones' share
  virtual double maxSpeed() const = 0;      // largest particle speed after the last step
  virtual bool finite() const = 0;          // every position and velocity finite
  virtual std::size_t distanceConstraintCount() const = 0;
  virtual std::size_t bendingConstraintCount() const = 0;
  // Solver updates one world step costs: iterations x substeps x
  // (constraints + particles), the unit of rscene-sim's per-run cap (RS7075).
  virtual double workPerStep() const = 0;
  // The deepest a free particle's sphere starts inside a surface of
  // `surfaces` (m, its radius minus the centre's distance; 0 when none
  // overlaps), with that particle's index.  Before the first step.
  virtual double startOverlap(SurfaceQuery& surfaces, std::size_t& particle) const = 0;
  // Before the first step: moves each free particle whose sphere starts
  // inside a surface out along that surface's normal until it touches it
  // (a micrometre clear), so that the first substep does not push it out
  // with speed.  Returns the deepest start overlap it removed (m; 0 when
  // none), `moved` the particles that were in it.  Meant for centres up to
  // half the radius inside (deeper ones are refused first, RS7077).
  virtual double pushOut(SurfaceQuery& surfaces, std::size_t& moved) = 0;
  // Collision radius of the particles' proxy spheres (m).
  virtual double collisionRadius() const = 0;
  // Empty while the body's kinetic energy stays within what gravity and
  // the surfaces it touched have given it (with a margin); else a sentence
  // with the figures, for the divergence error (RS7024).
  virtual std::string runaway() const = 0;
};

}  // namespace rscene::sim
