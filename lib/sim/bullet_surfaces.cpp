// INTERIM (issue 14 foundation): no surfaces yet.  The Bullet-backed
// queries replace this file.
#include "sim/bullet_surfaces.hpp"

#include <btBulletDynamicsCommon.h>

namespace rscene::sim {

struct BulletSurfaces::Impl {
  btCollisionWorld* world = nullptr;
  SurfaceFilter filter;
};

BulletSurfaces::BulletSurfaces(btCollisionWorld& world, SurfaceFilter filter) : impl_(std::make_unique<Impl>()) {
  impl_->world = &world;
  impl_->filter = std::move(filter);
}
BulletSurfaces::~BulletSurfaces() = default;
void BulletSurfaces::prepare(const Eigen::AlignedBox3d&, std::uint64_t, std::uint64_t, const std::string&) {}
void BulletSurfaces::contacts(const Eigen::Vector3d&, double, double, std::vector<SurfaceContact>&) const {}
Eigen::Vector3d BulletSurfaces::velocity(int, const Eigen::Vector3d&) const { return Eigen::Vector3d::Zero(); }
void BulletSurfaces::addForce(int, const Eigen::Vector3d&, const Eigen::Vector3d&) {}
void BulletSurfaces::applyForces() {}

}  // namespace rscene::sim
