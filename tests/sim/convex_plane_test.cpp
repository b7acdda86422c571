// ConvexPlaneAlgorithm (lib/sim/convex_plane.hpp), Bullet's convex-plane
// algorithm left uncalled when it could add nothing, finds exactly Bullet's
// contacts: the same bodies in two worlds, one with Bullet's algorithm as
// registered by Bullet and one with the wrapper, stay bit for bit the same.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <memory>
#include <vector>

#include "bit_for_bit.hpp"
#include "sim/convex_plane.hpp"

namespace {

struct Bodies : rscene::sim::test::RigidWorld {
  rscene::sim::ConvexPlaneAlgorithm::CreateFunc convexPlane, planeConvex;

  explicit Bodies(bool ours) {
    config.setPlaneConvexMultipointIterations(3, 3);  // as World sets it
    if (ours) rscene::sim::useConvexPlaneAlgorithm(dispatcher, convexPlane, planeConvex, 3, 3);
    add(new btStaticPlaneShape(btVector3(0, 0, 1), 0), 0, btTransform::getIdentity());
    // A box that tips over and slides, a resting box (the turned queries at
    // work), a cylinder and a hull, falling from different heights.
    btTransform t;
    t.setIdentity();
    t.setRotation(btQuaternion(btVector3(1, 2, 0.5).normalized(), 0.7));
    t.setOrigin(btVector3(0, 0, 0.6));
    btRigidBody* sliding = add(new btBoxShape(btVector3(0.3, 0.2, 0.1)), 2, t);
    sliding->setLinearVelocity(btVector3(1.5, 0.3, 0));
    t.setIdentity();
    t.setOrigin(btVector3(2, 0, 0.1005));
    add(new btBoxShape(btVector3(0.2, 0.2, 0.1)), 1, t);
    t.setRotation(btQuaternion(btVector3(0, 1, 0), 0.4));
    t.setOrigin(btVector3(-2, 0, 1));
    add(new btCylinderShapeZ(btVector3(0.1, 0.1, 0.2)), 1, t);
    auto* hull = new btConvexHullShape();
    for (btVector3 p : {btVector3(0, 0, 0), btVector3(0.3, 0, 0), btVector3(0, 0.3, 0), btVector3(0, 0, 0.3),
                        btVector3(0.2, 0.2, 0.2)})
      hull->addPoint(p);
    t.setOrigin(btVector3(0, 2, 0.8));
    add(hull, 1, t);
    // A box resting on the plane and thrown up at 12 m/s (3 cm a step, in
    // the air to the end): it leaves with points in its manifold and is past
    // the threshold in one step; Bullet's algorithm refreshes them away.
    t.setIdentity();
    t.setOrigin(btVector3(-2, 2, 0.1));
    add(new btBoxShape(btVector3(0.15, 0.1, 0.1)), 1, t)->setLinearVelocity(btVector3(0, 0, 12));
  }
};

TEST(ConvexPlane, SameContactsAsBulletsAlgorithmBitForBit) {
  auto bullet = std::make_unique<Bodies>(false), ours = std::make_unique<Bodies>(true);
  int touching = rscene::sim::test::stepExpectingSameBits(*bullet, *ours, 600, 1);
  // The bodies did reach the plane (the comparison is not of free falls):
  // four resting shapes, several points each.
  EXPECT_GE(touching, 8);
  EXPECT_LT(ours->bodies[1]->getWorldTransform().getOrigin().z(), 0.35);
  EXPECT_GT(ours->bodies[1]->getWorldTransform().getOrigin().x(), 0.1);  // it slid
}

}  // namespace
