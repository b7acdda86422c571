// RowSpaceSolver (lib/sim/row_space_solver.hpp), Bullet's multibody
// iteration done on the rows' velocities, gives Bullet's solution: the same
// multibodies in two worlds, one solving in row space and one with Bullet's
// own iteration, stay together to rounding.  Contacts with the ground
// (sliding, so the friction cone clamps), joint motors and a joint at its
// limit (non-contact rows), a multibody landing on another (rows coupled
// across two multibodies), and a dynamic rigid body on a multibody (the
// path Bullet keeps).
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "sim/row_space_solver.hpp"

namespace {

constexpr double kDt = 0.0025;

struct Bodies {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  rscene::sim::RowSpaceSolver solver;
  btMultiBodyDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btCollisionObject>> objects;
  std::vector<std::unique_ptr<btMultiBody>> multiBodies;
  std::vector<std::unique_ptr<btMultiBodyConstraint>> constraints;
  std::vector<std::unique_ptr<btMotionState>> motions;

  explicit Bodies(bool rowSpace) {
    solver.setEnabled(rowSpace);
    world.setGravity(btVector3(0, 0, -9.81));
    // World's settings (lib/sim/world.cpp): Engine 2's 80 iterations at 1e-7.
    btContactSolverInfo& si = world.getSolverInfo();
    si.m_numIterations = 80;
    si.m_leastSquaresResidualThreshold = 1e-7;
    si.m_solverMode &= ~SOLVER_RANDMIZE_ORDER;
    si.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS | SOLVER_ENABLE_FRICTION_DIRECTION_CACHING;
    si.m_splitImpulse = true;
    shapes.emplace_back(new btStaticPlaneShape(btVector3(0, 0, 1), 0));
    auto* ground = new btRigidBody(0, nullptr, shapes.back().get());
    ground->setFriction(0.8);
    objects.emplace_back(ground);
    world.addRigidBody(ground);
  }
  ~Bodies() {
    for (auto& c : constraints) world.removeMultiBodyConstraint(c.get());
    for (auto& o : objects) {
      if (auto* rb = btRigidBody::upcast(o.get()))
        world.removeRigidBody(rb);
      else
        world.removeCollisionObject(o.get());
    }
    for (auto& m : multiBodies) world.removeMultiBody(m.get());
  }

  btCollisionShape* box(btVector3 half) {
    shapes.emplace_back(new btBoxShape(half));
    return shapes.back().get();
  }

  // A box on four legs, each a hinge about y held by a motor; the first leg
  // also has a joint limit it starts at.  Legs reach 5 cm below the feet's
  // start height `z - 0.25`.
  btMultiBody* quadruped(btVector3 at, btVector3 velocity) {
    btVector3 baseHalf(0.2, 0.1, 0.05), legHalf(0.02, 0.02, 0.1);
    btVector3 baseInertia, legInertia;
    box(baseHalf)->calculateLocalInertia(5, baseInertia);
    box(legHalf)->calculateLocalInertia(0.5, legInertia);
    auto* mb = new btMultiBody(4, 5, baseInertia, false, false);
    multiBodies.emplace_back(mb);
    mb->setBasePos(at);
    mb->setWorldToBaseRot(btQuaternion::getIdentity());
    const double xs[4] = {0.15, 0.15, -0.15, -0.15}, ys[4] = {0.08, -0.08, 0.08, -0.08};
    for (int i = 0; i < 4; ++i)
      mb->setupRevolute(i, 0.5, legInertia, -1, btQuaternion::getIdentity(), btVector3(0, 1, 0),
                        btVector3(xs[i], ys[i], -0.05), btVector3(0, 0, -0.1), true);
    mb->finalizeMultiDof();  // velocities and joint positions live in buffers it makes
    mb->setBaseVel(velocity);
    mb->setBaseOmega(btVector3(0, 0, 1.5));
    mb->setJointPos(0, 0.1);
    world.addMultiBody(mb);
    collider(mb, -1, box(baseHalf));
    for (int i = 0; i < 4; ++i) collider(mb, i, box(legHalf));
    btAlignedObjectArray<btQuaternion> q;
    btAlignedObjectArray<btVector3> m;
    mb->forwardKinematics(q, m);
    mb->updateCollisionObjectWorldTransforms(q, m);
    for (int i = 0; i < 4; ++i) {
      constraints.emplace_back(new btMultiBodyJointMotor(mb, i, 0, 2.0 * kDt * 20));
      world.addMultiBodyConstraint(constraints.back().get());
    }
    constraints.emplace_back(new btMultiBodyJointLimitConstraint(mb, 0, -0.1, 0.1));
    world.addMultiBodyConstraint(constraints.back().get());
    return mb;
  }

  void collider(btMultiBody* mb, int link, btCollisionShape* shape) {
    auto* c = new btMultiBodyLinkCollider(mb, link);
    c->setCollisionShape(shape);
    c->setFriction(0.8);
    objects.emplace_back(c);
    world.addCollisionObject(c, btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter);
    if (link < 0)
      mb->setBaseCollider(c);
    else
      mb->getLink(link).m_collider = c;
  }

  btRigidBody* rigidBox(btVector3 half, double mass, btVector3 at) {
    btCollisionShape* shape = box(half);
    btVector3 inertia;
    shape->calculateLocalInertia(mass, inertia);
    btTransform t;
    t.setIdentity();
    t.setOrigin(at);
    motions.emplace_back(new btDefaultMotionState(t));
    auto* body = new btRigidBody(mass, motions.back().get(), shape, inertia);
    body->setFriction(0.8);
    body->setActivationState(DISABLE_DEACTIVATION);
    objects.emplace_back(body);
    world.addRigidBody(body);
    return body;
  }

  void run(int steps) {
    for (int i = 0; i < steps; ++i) world.stepSimulation(kDt, 0, kDt);
  }
};

// Largest difference between the two worlds' multibody states.
double gap(const Bodies& a, const Bodies& b) {
  double worst = 0;
  for (std::size_t k = 0; k < a.multiBodies.size(); ++k) {
    const btMultiBody& x = *a.multiBodies[k];
    const btMultiBody& y = *b.multiBodies[k];
    worst = std::max(worst, (x.getBasePos() - y.getBasePos()).length());
    worst = std::max(worst, (x.getBaseVel() - y.getBaseVel()).length());
    worst = std::max(worst, (x.getBaseOmega() - y.getBaseOmega()).length());
    for (int j = 0; j < x.getNumLinks(); ++j) {
      worst = std::max(worst, std::fabs(x.getJointPos(j) - y.getJointPos(j)));
      worst = std::max(worst, std::fabs(x.getJointVel(j) - y.getJointVel(j)));
    }
  }
  return worst;
}

TEST(RowSpaceSolver, SlidingQuadrupedWithMotorsAndALimitFollowsBullet) {
  Bodies ours(true), bullet(false);
  for (Bodies* w : {&ours, &bullet}) w->quadruped(btVector3(0, 0, 0.32), btVector3(1.2, 0.4, 0));
  ours.run(400);
  bullet.run(400);
  EXPECT_LT(gap(ours, bullet), 1e-9);
  EXPECT_GT(ours.solver.solves(), 0);
  EXPECT_EQ(ours.solver.rowSpaceSolves(), ours.solver.solves());
  EXPECT_EQ(bullet.solver.rowSpaceSolves(), 0);
  // It landed, slid and stopped on its feet: contacts and friction were at work.
  const btMultiBody& mb = *ours.multiBodies[0];
  EXPECT_GT(mb.getBasePos().x(), 0.05);
  EXPECT_LT(mb.getBaseVel().length(), 0.05);
  EXPECT_NEAR(mb.getBasePos().z(), 0.27, 0.02);
}

TEST(RowSpaceSolver, AMultibodyLandingOnAnotherFollowsBullet) {
  Bodies ours(true), bullet(false);
  for (Bodies* w : {&ours, &bullet}) {
    w->quadruped(btVector3(0, 0, 0.27), btVector3(0, 0, 0));
    w->quadruped(btVector3(0.05, 0, 0.62), btVector3(0, 0, -0.5));
  }
  ours.run(300);
  bullet.run(300);
  EXPECT_LT(gap(ours, bullet), 1e-8);  // ~3e-10 here: the impact amplifies rounding
  EXPECT_EQ(ours.solver.rowSpaceSolves(), ours.solver.solves());
  // The upper one rests on the lower one, not on the ground.
  EXPECT_GT(ours.multiBodies[1]->getBasePos().z(), 0.4);
}

TEST(RowSpaceSolver, ADynamicRigidBodyOnAMultibodyIsLeftToBullet) {
  Bodies ours(true), bullet(false);
  for (Bodies* w : {&ours, &bullet}) {
    w->quadruped(btVector3(0, 0, 0.27), btVector3(0, 0, 0));
    w->rigidBox(btVector3(0.05, 0.05, 0.05), 1, btVector3(0, 0, 0.4));
  }
  ours.run(300);
  bullet.run(300);
  EXPECT_LT(gap(ours, bullet), 1e-7);
  EXPECT_GT(ours.solver.rowSpaceSolves(), 0);  // before the box lands
  EXPECT_LT(ours.solver.rowSpaceSolves(), ours.solver.solves());
}

}  // namespace
