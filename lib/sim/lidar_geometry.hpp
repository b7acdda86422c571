// The collision geometry of a simulated World as exact ray targets, for
// LiDAR scans (lidar.hpp).
//
// Why not btCollisionWorld::rayTest: one call per ray walks Bullet's
// broadphase tree and then runs a GJK-based convex cast per candidate; a
// 64 x 1024 scan of the warehouse's collision boxes costs well over the
// 20 ms a scan may take (bench/lidar).  Here every collision shape becomes
// exact ray-primitive tests (box, sphere, cylinder, capsule, convex hull as
// planes, triangles of meshes and height fields, half-space planes), kept
// in a flat bounding-volume hierarchy: one built once over the static
// bodies, one rebuilt per scan over the moving ones (dynamic, kinematic
// and robot bodies: few, so the rebuild is cheap).
//
// Conventions.  A solid (box, sphere, cylinder, capsule, convex hull, a
// ground's half-space) is hit where a ray enters it: a ray that starts
// inside one does not see it (as Bullet's own ray test).  Triangles (static
// meshes, height fields) are hit from either side.
#pragma once
#include <Eigen/Core>
#include <limits>
#include <memory>
#include <vector>

class btCollisionObject;

namespace rscene::sim {

class World;

class RayGeometry {
 public:
  // Reads every ray target of `world` (World::rayTargets) at its current
  // pose.
  explicit RayGeometry(const World& world);
  ~RayGeometry();
  RayGeometry(const RayGeometry&) = delete;
  RayGeometry& operator=(const RayGeometry&) = delete;

  // Re-reads the poses of the moving bodies (after the world stepped).
  void update(const World& world);

  // The distance along the unit direction `dir` from `origin` to the first
  // surface no farther than `maxRange`; infinity when there is none.
  // Surfaces of `exclude` (a body's collision object: the one a sensor
  // rides on; nullptr for none) are not seen.  Thread-safe between updates.
  double cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double maxRange,
              const btCollisionObject* exclude = nullptr) const;

  // What was read, for tests and benchmarks.
  std::size_t solidCount() const;
  std::size_t triangleCount() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

inline constexpr double kNoHit = std::numeric_limits<double>::infinity();

}  // namespace rscene::sim
