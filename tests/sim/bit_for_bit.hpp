// Bit-for-bit comparison of two rigid bodies' states, for tests that step
// the same world two ways (Bullet's own algorithm against ours) and expect
// the very same numbers.
#pragma once
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <vector>

namespace rscene::sim::test {

inline bool sameBits(const btVector3& a, const btVector3& b) {
  return std::memcmp(a.m_floats, b.m_floats, 3 * sizeof(btScalar)) == 0;
}

// Position, orientation and both velocities; says which part differs.
inline ::testing::AssertionResult sameState(const btRigidBody& a, const btRigidBody& b) {
  if (!sameBits(a.getWorldTransform().getOrigin(), b.getWorldTransform().getOrigin()))
    return ::testing::AssertionFailure() << "positions differ";
  for (int r = 0; r < 3; ++r)
    if (!sameBits(a.getWorldTransform().getBasis()[r], b.getWorldTransform().getBasis()[r]))
      return ::testing::AssertionFailure() << "orientations differ";
  if (!sameBits(a.getLinearVelocity(), b.getLinearVelocity())) return ::testing::AssertionFailure() << "velocities differ";
  if (!sameBits(a.getAngularVelocity(), b.getAngularVelocity()))
    return ::testing::AssertionFailure() << "angular velocities differ";
  return ::testing::AssertionSuccess();
}

// A rigid-body world for those tests: Bullet's parts, the bodies it owns,
// and its contact points (all, or those of one body).
struct RigidWorld {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btRigidBody>> bodies;

  RigidWorld() { world.setGravity(btVector3(0, 0, -9.81)); }
  RigidWorld(const RigidWorld&) = delete;
  RigidWorld& operator=(const RigidWorld&) = delete;
  ~RigidWorld() {
    for (auto& b : bodies) world.removeRigidBody(b.get());
  }
  btRigidBody* add(btCollisionShape* shape, double mass, const btTransform& at) {
    shapes.emplace_back(shape);
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
    info.m_startWorldTransform = at;
    bodies.emplace_back(new btRigidBody(info));
    bodies.back()->setActivationState(DISABLE_DEACTIVATION);
    world.addRigidBody(bodies.back().get());
    return bodies.back().get();
  }
  int contacts(const btCollisionObject* with = nullptr) {
    int n = 0;
    for (int i = 0; i < dispatcher.getNumManifolds(); ++i) {
      const btPersistentManifold* m = dispatcher.getManifoldByIndexInternal(i);
      if (!with || m->getBody0() == with || m->getBody1() == with) n += m->getNumContacts();
    }
    return n;
  }
};

// Steps both worlds `steps` times at 400 Hz, asserting after each step the
// same number of contact points and the same bits in every body from
// `firstMoving` on; returns the most points seen at once (0 after a failure).
inline int stepExpectingSameBits(RigidWorld& bullet, RigidWorld& ours, int steps, std::size_t firstMoving) {
  int touching = 0;
  for (int step = 0; step < steps; ++step) {
    bullet.world.stepSimulation(1.0 / 400, 0, 1.0 / 400);
    ours.world.stepSimulation(1.0 / 400, 0, 1.0 / 400);
    EXPECT_EQ(bullet.contacts(), ours.contacts()) << "step " << step;
    for (std::size_t i = firstMoving; i < ours.bodies.size(); ++i) {
      ::testing::AssertionResult same = sameState(*bullet.bodies[i], *ours.bodies[i]);
      EXPECT_TRUE(same) << "body " << i << " step " << step;
      if (!same) return 0;
    }
    if (bullet.contacts() != ours.contacts()) return 0;
    touching = std::max(touching, ours.contacts());
  }
  return touching;
}

}  // namespace rscene::sim::test
