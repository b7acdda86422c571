// The rigid world as the particle systems (deformable_body.hpp,
// granular_body.hpp) see it: every particle is a sphere, and a query gives
// its contacts with the surfaces near it (the ground, terrain, objects,
// compounds, robot links), the velocity of the surface at the contact, and
// takes the reaction force back to the body it came from.
//
// Two implementations: BulletSurfaces (bullet_surfaces.hpp) over the
// World's Bullet bodies, and AnalyticSurfaces below (planes and spheres),
// which the solvers' tests use to compare with closed-form answers.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace rscene::sim {

struct SurfaceContact {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   // the surface point closest to the centre, world
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ(); // unit, from the surface toward the centre
  double depth = 0;      // radius minus the centre's distance to the surface: > 0 overlaps
  int body = -1;         // for velocity() and addForce(); -1: static (never moves, takes no force)
  double friction = 0.8; // of the surface for this system (its contact material, or the solver's default)
};

class SurfaceQuery {
 public:
  virtual ~SurfaceQuery() = default;
  // Before a (sub)step of one particle system: the region its particles can
  // reach in it (their bounds grown by the largest radius and the distance
  // they can travel), its collision filter (a pair collides when
  // (group & bodyMask) and (bodyGroup & mask) are both non-zero) and its
  // contact material name ("" for the default).  Queries then consider only
  // the surfaces that reach into `region`.
  virtual void prepare(const Eigen::AlignedBox3d& region, std::uint64_t group, std::uint64_t mask,
                       const std::string& contactMaterial) = 0;
  // Appends the contacts of the sphere (centre, radius) with every prepared
  // surface within radius + margin of the centre (depth >= -margin).
  virtual void contacts(const Eigen::Vector3d& centre, double radius, double margin,
                        std::vector<SurfaceContact>& out) const = 0;
  // World velocity of the body's material point `point` (zero for static).
  virtual Eigen::Vector3d velocity(int body, const Eigen::Vector3d& point) const = 0;
  // Adds a force on `body` at `point` (world) for the rigid world's next
  // step: the reaction of the particles' contacts.  Ignored for static.
  virtual void addForce(int body, const Eigen::Vector3d& point, const Eigen::Vector3d& force) = 0;
};

// Horizontal planes and spheres, static or moving at a constant velocity:
// enough for closed-form tests of the solvers.  Forces are summed per body
// so a test can check what the particles pushed back with.
class AnalyticSurfaces : public SurfaceQuery {
 public:
  struct Sphere {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double radius = 0;
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
    bool dynamic = false;  // takes forces (summed in force)
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
  };
  std::vector<double> groundHeights;  // planes z = h, normal +z, static
  std::vector<Sphere> spheres;        // body index = index here
  double friction = 0.8;

  void prepare(const Eigen::AlignedBox3d&, std::uint64_t, std::uint64_t, const std::string&) override {}
  void contacts(const Eigen::Vector3d& c, double r, double margin, std::vector<SurfaceContact>& out) const override {
    for (double h : groundHeights) {
      double depth = r - (c.z() - h);
      if (depth >= -margin) out.push_back({Eigen::Vector3d(c.x(), c.y(), h), Eigen::Vector3d::UnitZ(), depth, -1, friction});
    }
    for (std::size_t i = 0; i < spheres.size(); ++i) {
      const Sphere& s = spheres[i];
      Eigen::Vector3d d = c - s.centre;
      double dist = d.norm();
      double depth = r + s.radius - dist;
      if (depth < -margin) continue;
      Eigen::Vector3d n = dist > 1e-12 ? Eigen::Vector3d(d / dist) : Eigen::Vector3d::UnitZ();
      out.push_back({s.centre + n * s.radius, n, depth, s.dynamic ? static_cast<int>(i) : -1, friction});
    }
  }
  Eigen::Vector3d velocity(int body, const Eigen::Vector3d&) const override {
    return body < 0 ? Eigen::Vector3d::Zero() : spheres[static_cast<std::size_t>(body)].velocity;
  }
  void addForce(int body, const Eigen::Vector3d&, const Eigen::Vector3d& f) override {
    if (body >= 0) spheres[static_cast<std::size_t>(body)].force += f;
  }
};

}  // namespace rscene::sim
