// What a deformable record becomes before it is simulated: particles,
// their masses, the constraints between them and the solver's settings,
// all in world coordinates.  buildDeformableModel() reads the record and
// its OBJ surface (every check of a hostile value is here, before anything
// is allocated); DeformableSolver (deformable_solver.hpp) steps the model.
// Tests build models by hand to compare the solver with closed forms.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/triangle_surface.hpp"
#include "scene/visual_records.hpp"

namespace rscene {

struct DistanceConstraint {
  std::uint32_t a = 0, b = 0;
  double rest = 0;        // m
  double compliance = 0;  // m/N; 0 rigid
};

// Bending across the edge (c, d) shared by the triangles (a, c, d) and
// (b, d, c): the signed dihedral angle held at its rest value.
struct BendConstraint {
  std::uint32_t a = 0, b = 0, c = 0, d = 0;
  double restAngle = 0;   // rad
  double compliance = 0;  // rad/(N m); 0 rigid
};

struct DeformableModel {
  std::vector<Eigen::Vector3d> positions;  // world; the OBJ's vertices first, then fill particles
  std::vector<double> inverseMass;         // 0 for pinned particles
  std::size_t surfaceCount = 0;
  double particleMass = 0;                 // every particle's share of totalMass
  std::vector<DistanceConstraint> distances;  // solved in this order
  std::vector<BendConstraint> bends;          // then these
  int iterations = 20;
  int substeps = 1;
  bool xpbd = true;        // else PBD: no accumulated multiplier (stiffness grows with iterations)
  double damping = 0;      // fraction of velocity removed per world step, [0, 1]
  double collisionRadius = 0;
  bool collidable = true;
  std::uint64_t collisionGroup = 1, collisionMask = ~std::uint64_t{0};
  std::string contactMaterial;
};

// Bounds that keep one body's memory and one world step's work finite.
inline constexpr std::uint64_t kMaxDeformableParticles = 1'000'000;
inline constexpr std::uint64_t kMaxDeformableConstraints = 16'000'000;
// (constraints + particles) x iterations x substeps per world step: about
// 20 s of one core (a 64 x 64 cloth at 20 iterations takes 5e5).
inline constexpr double kMaxDeformableWorkPerStep = 1e9;

// False with `error` (a sentence) and `field` (the record's key at fault,
// "" for the record) when the record cannot be simulated.
bool buildDeformableModel(const Deformable& record, const TriangleSurface& surface, DeformableModel& model,
                          std::string& error, std::string& field);

// Signed dihedral angle across the edge (c, d) of the triangles (a, c, d)
// and (b, d, c), in [-pi, pi]; 0 when flat.
inline double dihedralAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                            const Eigen::Vector3d& d) {
  Eigen::Vector3d e = d - c;
  Eigen::Vector3d n1 = (c - a).cross(d - a), n2 = (d - b).cross(c - b);
  double len = e.norm();
  if (!(len > 0)) return 0;
  return std::atan2(n1.cross(n2).dot(e) / len, n1.dot(n2));
}

}  // namespace rscene
