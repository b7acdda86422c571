// SurfaceQuery over a Bullet world: the particles of deformables and
// granular media meet every collision object the world holds (the ground
// plane, terrain heightfields, boxes, spheres, cylinders, capsules, convex
// hulls, static triangle meshes, compounds and robot link colliders).
// Contacts with a dynamic rigid body or a robot link carry a body handle;
// their reaction forces are summed and applied to Bullet before its step
// (btRigidBody::applyCentralForce/applyTorque, btMultiBody::addLinkForce/
// addLinkTorque), and the body is woken.  A kinematic body has a handle
// too, so that velocity() gives its motion, but takes no force; static
// bodies (and a fixed robot base) are -1.  Handles are made in the world's
// object order when this is built and stay valid for the world's life; a
// body that left the world is no candidate and takes no more force.
// Bullet's types appear only here, in surface_shapes.* and in world.cpp.
//
// Cost: prepare() gathers the static and sleeping bodies in the region
// from Bullet's broadphase and tests every awake moving body's box; contacts() then walks the
// prepared primitives (compounds opened), a box test each, closed-form
// geometry for primitives.  A grain on the ground plane costs about 10 ns
// a query, on a box 30 ns, on a convex hull's face 40 ns (near its edges,
// GJK/EPA: 1 us), on an 8,192-triangle mesh 0.4 us (bench/soft/surfaces.sh).  The walk is linear in the primitives that
// reach into the region: a system spread over thousands of bodies pays
// for each of them per query.
#pragma once
#include <functional>
#include <memory>
#include <string>

#include "sim/surface_query.hpp"

class btCollisionObject;
class btCollisionWorld;

namespace rscene::sim {

struct SurfaceFilter {
  // Whether a particle system of (group, mask) collides with `object`
  // (the world's 64-bit group/mask test, and not a body that left the world).
  std::function<bool(const btCollisionObject& object, std::uint64_t group, std::uint64_t mask)> collides;
  // The friction between `object` and a particle system of `contactMaterial`
  // (the scene's contact_material pair, else the solver's default friction).
  std::function<double(const btCollisionObject& object, const std::string& contactMaterial)> friction;
};

class BulletSurfaces : public SurfaceQuery {
 public:
  BulletSurfaces(btCollisionWorld& world, SurfaceFilter filter);
  ~BulletSurfaces() override;
  BulletSurfaces(const BulletSurfaces&) = delete;
  BulletSurfaces& operator=(const BulletSurfaces&) = delete;

  void prepare(const Eigen::AlignedBox3d& region, std::uint64_t group, std::uint64_t mask,
               const std::string& contactMaterial) override;
  void contacts(const Eigen::Vector3d& centre, double radius, double margin,
                std::vector<SurfaceContact>& out) const override;
  Eigen::Vector3d velocity(int body, const Eigen::Vector3d& point) const override;
  // `force` is the force's average over the coming world step (a solver
  // that substeps adds each substep's force times its share of the step).
  void addForce(int body, const Eigen::Vector3d& point, const Eigen::Vector3d& force) override;

  // Applies the summed forces to Bullet's bodies and clears them: once per
  // world step of `dt` seconds, after the particle systems stepped and
  // before Bullet does.  A sleeping rigid body wakes only when its force
  // or torque would change its velocity within the step by more than its
  // sleeping thresholds (below them the push is dropped, as Bullet would
  // let the body sleep through it).
  void applyForces(double dt);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rscene::sim
