// The XPBD (or PBD) solver of a deformable body, RaiSim's DeformableObject
// step: per substep, gravity and a predicted position for every free
// particle; contacts gathered once against the rigid world; `iterations`
// Gauss-Seidel passes over the distance constraints, the bending
// constraints and the contacts, in a fixed order (runs are identical bit
// for bit); Coulomb friction against the surface's velocity; velocities
// from the positions' change, damped.  Contact reactions go back to
// dynamic bodies as forces averaged over the world step.
#pragma once
#include <vector>

#include "sim/deformable_body.hpp"
#include "sim/deformable_model.hpp"

namespace rscene::sim {

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
};

}  // namespace rscene::sim
