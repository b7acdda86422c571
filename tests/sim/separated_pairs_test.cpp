// skipSeparatedPairs (lib/sim/separated_pairs.hpp), the near callback that
// leaves a pair's narrowphase uncalled when its shapes are too far apart
// for a point, finds exactly Bullet's contacts: the same bodies in two
// worlds, one with Bullet's own near callback, stay bit for bit the same.
// Compound bodies (a robot link's shape) over a plane and a height field,
// pairs of compounds near each other, and bodies that leave a contact
// (points in the manifold: Bullet must remove them) and come back.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "bit_for_bit.hpp"
#include "sim/convex_plane.hpp"
#include "sim/separated_pairs.hpp"

namespace {

struct Bodies : rscene::sim::test::RigidWorld {
  rscene::sim::ConvexPlaneAlgorithm::CreateFunc convexPlane, planeConvex;
  std::vector<btScalar> heights;

  explicit Bodies(bool ours) {
    config.setPlaneConvexMultipointIterations(3, 3);  // as World sets both
    rscene::sim::useConvexPlaneAlgorithm(dispatcher, convexPlane, planeConvex, 3, 3);
    if (ours) rscene::sim::skipSeparatedPairs(dispatcher);
    btTransform t = btTransform::getIdentity();
    add(new btStaticPlaneShape(btVector3(0, 0, 1), 0), 0, t);
    // A 2 x 2 m height field (bumps up to 0.2 m) at x = 6.
    for (int j = 0; j < 21; ++j)
      for (int i = 0; i < 21; ++i) heights.push_back(0.1 + 0.1 * std::sin(i * 0.7) * std::cos(j * 0.5));
    auto* field = new btHeightfieldTerrainShape(21, 21, heights.data(), 1, 0, 0.2, 2, PHY_DOUBLE, false);
    field->setLocalScaling(btVector3(0.1, 0.1, 1));
    t.setOrigin(btVector3(6, 0, 0.1));
    add(field, 0, t);
    // Compounds: one sliding and tumbling onto the plane, one dropped on the
    // field, one dropped onto the first (compound against compound).
    t.setIdentity();
    t.setRotation(btQuaternion(btVector3(1, 1, 0).normalized(), 0.6));
    t.setOrigin(btVector3(0, 0, 0.8));
    add(link(), 2, t)->setLinearVelocity(btVector3(1, 0.2, 0));
    t.setOrigin(btVector3(6, 0, 0.9));
    add(link(), 2, t);
    t.setOrigin(btVector3(0.3, 0.05, 2.0));
    add(link(), 1, t);
    // A sphere thrown up from the plane (points in its manifold as it
    // leaves; it lands again) and one that lands on the field.
    t.setIdentity();
    t.setOrigin(btVector3(-2, 0, 0.1));
    add(new btSphereShape(0.1), 1, t)->setLinearVelocity(btVector3(0, 0, 3));
    t.setOrigin(btVector3(6.4, 0.3, 1.2));
    add(new btSphereShape(0.05), 1, t);
    // A compound resting on the plane thrown up at 30 m/s: 7.5 cm a step,
    // past the reach in one step with points in its manifold (the
    // broadphase box Bullet gives it spans both poses of the step, so the
    // pair is still refreshed as it leaves).
    t.setOrigin(btVector3(-2, 2, 0.1));
    add(link(), 1, t)->setLinearVelocity(btVector3(0, 0, 30));
  }
  // A robot link's shape: a box and a cylinder, both off its origin.
  btCollisionShape* link() {
    auto* compound = new btCompoundShape();
    btTransform c = btTransform::getIdentity();
    c.setOrigin(btVector3(0.1, 0, 0));
    shapes.emplace_back(new btBoxShape(btVector3(0.1, 0.05, 0.05)));
    compound->addChildShape(c, shapes.back().get());
    c.setOrigin(btVector3(-0.1, 0, -0.05));
    shapes.emplace_back(new btCylinderShapeZ(btVector3(0.04, 0.04, 0.1)));
    compound->addChildShape(c, shapes.back().get());
    return compound;
  }
};


TEST(SeparatedPairs, SameContactsAsBulletsNearCallbackBitForBit) {
  auto bullet = std::make_unique<Bodies>(false), ours = std::make_unique<Bodies>(true);
  int touching = rscene::sim::test::stepExpectingSameBits(*bullet, *ours, 800, 2);
  // Not free falls: the bodies reached the plane, the field and each other.
  EXPECT_GE(touching, 8);
  EXPECT_GE(ours->contacts(ours->bodies[1].get()), 2);  // the compound and the sphere rest on the field
  EXPECT_LT(ours->bodies[3]->getWorldTransform().getOrigin().z(), 0.5);
  EXPECT_LT(ours->bodies[4]->getWorldTransform().getOrigin().z(), 0.6);  // came down onto the first compound or the plane
  EXPECT_LT(ours->bodies[5]->getWorldTransform().getOrigin().z(), 0.2);  // the thrown sphere landed again
}

// Compounds bouncing on a height field and leaving its box: Bullet's
// compound algorithm drops a child's algorithm (and its manifold) when
// the child leaves the other shape's box, which reorders the solver's
// rows; a skipped pair must not keep what Bullet would drop.
TEST(SeparatedPairs, CompoundsBouncingOnAHeightFieldBitForBit) {
  struct Field : rscene::sim::test::RigidWorld {
    rscene::sim::ConvexPlaneAlgorithm::CreateFunc convexPlane, planeConvex;
    std::vector<btScalar> heights;
    explicit Field(bool ours) {
      config.setPlaneConvexMultipointIterations(3, 3);
      rscene::sim::useConvexPlaneAlgorithm(dispatcher, convexPlane, planeConvex, 3, 3);
      if (ours) rscene::sim::skipSeparatedPairs(dispatcher);
      std::mt19937 random(11);
      std::uniform_real_distribution<double> unit(0, 1);
      for (int i = 0; i < 81; ++i) heights.push_back(0.3 * unit(random));
      auto* field = new btHeightfieldTerrainShape(9, 9, heights.data(), 1, 0, 0.3, 2, PHY_DOUBLE, false);
      field->setLocalScaling(btVector3(1, 1, 1));
      add(field, 0, btTransform(btQuaternion::getIdentity(), btVector3(0, 0, 0.15)))->setRestitution(0.6);
      for (int c = 0; c < 12; ++c) {
        auto* compound = new btCompoundShape();
        for (int k = 0; k < 3; ++k) {
          shapes.emplace_back(new btBoxShape(btVector3(0.1, 0.1, 0.1)));
          btVector3 at(0.6 * unit(random) - 0.3, 0.6 * unit(random) - 0.3, 0.3 * unit(random) - 0.15);
          compound->addChildShape(btTransform(btQuaternion::getIdentity(), at), shapes.back().get());
        }
        btTransform t(btQuaternion(btVector3(1, 0, 0), 0.785),
                      btVector3(2 * unit(random) - 1, 2 * unit(random) - 1, 0.8 + 1.5 * unit(random)));
        btRigidBody* body = add(compound, 3, t);
        body->setRestitution(0.6);
        body->setFriction(0.6);
      }
    }
  };
  auto bullet = std::make_unique<Field>(false), ours = std::make_unique<Field>(true);
  int touching = rscene::sim::test::stepExpectingSameBits(*bullet, *ours, 1600, 1);
  EXPECT_GE(touching, 12);  // they landed
}

// The geometric test itself, against Bullet's closest points: wherever it
// says a link's shape is farther from the plane or the height field than
// the pair's threshold plus the turned queries' reach, Bullet finds no
// point within the threshold.  Random poses from high above to deep in.
TEST(SeparatedPairs, FartherApartOnlyWhereBulletFindsNoPoint) {
  Bodies w(true);
  btRigidBody* link = w.add(w.link(), 1, btTransform::getIdentity());
  btRigidBody* ball = w.add(new btSphereShape(0.06), 1, btTransform::getIdentity());  // a box that fits
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0, 1);
  int skipped = 0, nearKept = 0;
  for (int i = 0; i < 4000; ++i) {
    bool overField = i % 2 == 0;
    btRigidBody* probe = i % 4 < 2 ? link : ball;
    btTransform at;
    at.setRotation(btQuaternion(btVector3(unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5).normalized(),
                                unit(random) * 6.28));
    at.setOrigin(btVector3(overField ? 5.1 + 1.8 * unit(random) : -1 + 2 * unit(random), -0.9 + 1.8 * unit(random),
                           -0.05 + 0.85 * unit(random)));
    probe->setWorldTransform(at);
    probe->setInterpolationWorldTransform(at);  // else its box spans the previous pose too
    w.world.updateSingleAabb(probe);
    btCollisionObject* ground = w.bodies[overField ? 1 : 0].get();
    btScalar threshold = std::min(probe->getCollisionShape()->getContactBreakingThreshold(gContactBreakingThreshold),
                                  ground->getCollisionShape()->getContactBreakingThreshold(gContactBreakingThreshold));
    struct Nearest : btCollisionWorld::ContactResultCallback {
      btScalar distance = BT_LARGE_FLOAT;
      btScalar addSingleResult(btManifoldPoint& cp, const btCollisionObjectWrapper*, int, int,
                               const btCollisionObjectWrapper*, int, int) override {
        distance = std::min(distance, cp.getDistance());
        return 0;
      }
    } nearest;
    nearest.m_closestDistanceThreshold = threshold + gContactBreakingThreshold;
    w.world.contactPairTest(probe, ground, nearest);
    bool far = rscene::sim::fartherApartThan(*probe, *ground, threshold + gContactBreakingThreshold);
    if (far) {
      ++skipped;
      ASSERT_GT(nearest.distance, threshold) << "pose " << i << (overField ? " over the field" : " over the plane");
    } else if (nearest.distance > threshold + gContactBreakingThreshold) {
      ++nearKept;  // far enough, but the boxes could not tell
    }
  }
  EXPECT_GT(skipped, 1000);
  EXPECT_GT(nearKept, 0);
}

}  // namespace
