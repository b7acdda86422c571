// The XPBD (or PBD) solver of a deformable body, RaiSim's DeformableObject
// step: per substep, gravity and a predicted position for every free
// particle; contacts gathered once against the rigid world; `iterations`
// Gauss-Seidel passes over the distance constraints, the bending
// constraints and the contacts, in a fixed order (runs are identical bit
// for bit); Coulomb friction against the surface's velocity; velocities
// from the positions' change, damped.  Contact reactions go back to
// dynamic bodies as forces averaged over the world step.
#pragma once
#include <string>
#include <vector>

#include "sim/deformable_body.hpp"
#include "scene/deformable_model.hpp"

namespace rscene::sim {

// The angle's gradient per particle; false when a triangle is degenerate
// (no gradient).  The angle too when `angle` is given (one computation of
// the normals for both).  Inline: the solver's innermost loop.
inline bool dihedralGradient(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                             const Eigen::Vector3d& d, Eigen::Vector3d g[4], double* angle = nullptr) {
  // Bridson, Marino and Fedkiw (2003), "Simulation of clothing with folds
  // and wrinkles": the angle's gradient from the area-weighted normals.
  Eigen::Vector3d e = d - c;
  Eigen::Vector3d n1 = (c - a).cross(d - a), n2 = (d - b).cross(c - b);
  double len = e.norm(), s1 = n1.squaredNorm(), s2 = n2.squaredNorm();
  if (!(len > 1e-12) || !(s1 > 1e-24) || !(s2 > 1e-24)) return false;
  const double invLen = 1 / len;
  if (angle) *angle = std::atan2(n1.cross(n2).dot(e) * invLen, n1.dot(n2));
  n1 *= 1 / s1;  // one division, not three
  n2 *= 1 / s2;
  g[0] = -len * n1;
  g[1] = -len * n2;
  g[2] = -(((a - d).dot(e) * invLen) * n1 + ((b - d).dot(e) * invLen) * n2);
  g[3] = -g[0] - g[1] - g[2];  // the angle does not change when all four move together
  return true;
}



class XpbdDeformable final : public DeformableBody {
 public:
  explicit XpbdDeformable(DeformableModel model);

  void step(double dt, const Eigen::Vector3d& gravity, SurfaceQuery& surfaces) override;
  const std::vector<Eigen::Vector3d>& positions() const override { return m_.positions; }
  std::size_t surfaceVertexCount() const override { return m_.surfaceCount; }
  double totalMass() const override { return m_.particleMass * static_cast<double>(m_.positions.size()); }
  double maxSpeed() const override { return maxSpeed_; }
  bool finite() const override { return finite_; }
  std::size_t distanceConstraintCount() const override { return m_.distances.size(); }
  std::size_t bendingConstraintCount() const override { return m_.bends.size(); }
  double workPerStep() const override {
    return static_cast<double>(m_.distances.size() + m_.bends.size() + m_.positions.size()) *
           static_cast<double>(m_.iterations) * static_cast<double>(m_.substeps);
  }
  double startOverlap(SurfaceQuery& surfaces, std::size_t& particle) const override;
  double pushOut(SurfaceQuery& surfaces, std::size_t& moved) override;
  double collisionRadius() const override { return m_.collisionRadius; }
  std::string runaway() const override;
  // The energy balance after the last step (J): kinetic energy of the free
  // particles, the work gravity did on them since the start, and the work
  // moving surfaces did through contacts.
  double kineticEnergy() const { return kinetic_; }
  double gravityWork() const { return gravityWork_; }
  double surfaceWork() const { return surfaceWork_; }

  const std::vector<Eigen::Vector3d>& velocities() const { return v_; }
  const DeformableModel& model() const { return m_; }

 private:
  struct Contact {
    std::uint32_t particle;
    SurfaceContact surface;
    double pushed = 0;  // m along the normal, summed over the iterations
  };
  void gatherContacts(SurfaceQuery& surfaces);
  void solveDistances(double h);
  void solveBends(double h);
  void solveContacts();
  void applyFriction(SurfaceQuery& surfaces, double h, double dt);

  DeformableModel m_;
  std::vector<Eigen::Vector3d> v_, previous_;
  std::vector<double> lambda_;  // per constraint: distances, then bends
  std::vector<Contact> contacts_;
  std::vector<SurfaceContact> found_;
  double maxSpeed_ = 0;
  bool finite_ = true;
  Eigen::Vector3d startSum_ = Eigen::Vector3d::Zero();  // sum of the free particles' start positions
  double freeMass_ = 0;                                 // kg, free particles
  double kinetic_ = 0, gravityWork_ = 0, surfaceWork_ = 0;
};

}  // namespace rscene::sim
