// INTERIM (issue 14 foundation): the particles hold their places.  The DEM
// solver replaces this file.
#include "sim/granular_body.hpp"

namespace rscene::sim {
namespace {

class Still : public GranularBody {
 public:
  Still(std::vector<Eigen::Vector3d> p, std::vector<double> r) : p_(std::move(p)), r_(std::move(r)) {}
  void step(double, const Eigen::Vector3d&, SurfaceQuery&) override {}
  const std::vector<Eigen::Vector3d>& positions() const override { return p_; }
  const std::vector<double>& radii() const override { return r_; }
  double totalMass() const override { return 0; }
  double maxSpeed() const override { return 0; }
  bool finite() const override { return true; }

 private:
  std::vector<Eigen::Vector3d> p_;
  std::vector<double> r_;
};

}  // namespace

std::unique_ptr<GranularBody> GranularBody::create(const Granular& record, std::string& error, std::string& field) {
  std::vector<Eigen::Vector3d> p;
  std::vector<double> r;
  error = granularParticles(record, kMaxParticles, p, r);
  if (!error.empty()) {
    field = record.positions.empty() ? "maxParticles" : "positions";
    return nullptr;
  }
  for (Eigen::Vector3d& x : p) x = (record.world * Pose{x, Eigen::Quaterniond::Identity()}).position;
  return std::make_unique<Still>(std::move(p), std::move(r));
}

}  // namespace rscene::sim
