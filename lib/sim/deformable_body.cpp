// INTERIM (issue 14 foundation): the body holds its rest shape.  The XPBD
// solver replaces this file.
#include "sim/deformable_body.hpp"

namespace rscene::sim {
namespace {

class RestShape : public DeformableBody {
 public:
  explicit RestShape(std::vector<Eigen::Vector3d> p, double mass) : p_(std::move(p)), mass_(mass) {}
  void step(double, const Eigen::Vector3d&, SurfaceQuery&) override {}
  const std::vector<Eigen::Vector3d>& positions() const override { return p_; }
  std::size_t surfaceVertexCount() const override { return p_.size(); }
  double totalMass() const override { return mass_; }
  double maxSpeed() const override { return 0; }
  bool finite() const override { return true; }
  std::size_t distanceConstraintCount() const override { return 0; }
  std::size_t bendingConstraintCount() const override { return 0; }

 private:
  std::vector<Eigen::Vector3d> p_;
  double mass_;
};

}  // namespace

std::unique_ptr<DeformableBody> DeformableBody::create(const Deformable& record, const asset::ObjSurface& surface,
                                                       std::string&, std::string&) {
  std::vector<Eigen::Vector3d> p;
  for (const auto& v : surface.vertices)
    p.push_back((record.world * Pose{Eigen::Vector3d(v[0], v[1], v[2]).cwiseProduct(record.scale),
                                     Eigen::Quaterniond::Identity()})
                    .position);
  return std::make_unique<RestShape>(std::move(p), record.totalMass);
}

}  // namespace rscene::sim
