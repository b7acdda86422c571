// MultiBodyWorld (lib/sim/multibody_world.hpp) leaves out the robots'
// predicted transforms and nothing else: the same robots, a fast box under
// continuous collision detection, and a robot that falls asleep step bit
// for bit as in Bullet's own world.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <cstring>
#include <memory>
#include <vector>

#include "sim/multibody_world.hpp"

namespace {

struct Worlds {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btMultiBodyConstraintSolver solver;
  rscene::sim::MultiBodyWorld world{&dispatcher, &broadphase, &solver, &config};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btCollisionObject>> objects;
  std::vector<std::unique_ptr<btMultiBody>> robots;
  btRigidBody* box = nullptr;

  explicit Worlds(bool skip) {
    world.setSkipPrediction(skip);
    world.setGravity(btVector3(0, 0, -9.81));
    shapes.emplace_back(new btStaticPlaneShape(btVector3(0, 0, 1), 0));
    auto* ground = new btRigidBody(0, nullptr, shapes.back().get());
    objects.emplace_back(ground);
    world.addRigidBody(ground);
    chain(btVector3(0, 0, 1.0), btVector3(0.5, 0, 0), 0.4);
    chain(btVector3(2, 0, 0.1), btVector3(0, 0, 0), 0);  // lies on the ground and falls asleep
    // A small box thrown fast at the first chain, with continuous collision.
    shapes.emplace_back(new btBoxShape(btVector3(0.02, 0.02, 0.02)));
    btVector3 inertia;
    shapes.back()->calculateLocalInertia(0.1, inertia);
    btTransform at(btQuaternion::getIdentity(), btVector3(-3, 0, 0.6));
    box = new btRigidBody(0.1, nullptr, shapes.back().get(), inertia);
    box->setWorldTransform(at);
    box->setLinearVelocity(btVector3(60, 0, 0));
    box->setCcdMotionThreshold(0.01);
    box->setCcdSweptSphereRadius(0.015);
    objects.emplace_back(box);
    world.addRigidBody(box);
  }
  ~Worlds() {
    for (auto& o : objects) {
      if (auto* rb = btRigidBody::upcast(o.get()))
        world.removeRigidBody(rb);
      else
        world.removeCollisionObject(o.get());
    }
    for (auto& r : robots) world.removeMultiBody(r.get());
  }

  // A floating sphere with three hinged spheres hanging from it.
  void chain(btVector3 at, btVector3 velocity, double bend) {
    shapes.emplace_back(new btSphereShape(0.1));
    btCollisionShape* sphere = shapes.back().get();
    btVector3 inertia;
    sphere->calculateLocalInertia(1, inertia);
    auto robot = std::make_unique<btMultiBody>(3, 1, inertia, false, true);
    for (int i = 0; i < 3; ++i)
      robot->setupRevolute(i, 1, inertia, i - 1, btQuaternion::getIdentity(), btVector3(0, 1, 0),
                           btVector3(0.1, 0, 0), btVector3(0.1, 0, 0));
    robot->finalizeMultiDof();
    robot->setBasePos(at);
    robot->setBaseVel(velocity);
    robot->setJointPos(0, bend);
    world.addMultiBody(robot.get());
    for (int link = -1; link < 3; ++link) {
      auto* collider = new btMultiBodyLinkCollider(robot.get(), link);
      collider->setCollisionShape(sphere);
      objects.emplace_back(collider);
      world.addCollisionObject(collider, btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter);
      if (link < 0)
        robot->setBaseCollider(collider);
      else
        robot->getLink(link).m_collider = collider;
    }
    robots.push_back(std::move(robot));
  }

  // Every number the state is made of, as bits.
  std::vector<btScalar> state() {
    std::vector<btScalar> s;
    for (auto& r : robots) {
      for (int k = 0; k < 3; ++k) s.push_back(r->getBasePos()[k]);
      for (int k = 0; k < 4; ++k) s.push_back(r->getWorldToBaseRot()[k]);
      for (int k = 0; k < r->getNumDofs() + 6; ++k) s.push_back(r->getVelocityVector()[k]);
      for (int i = 0; i < r->getNumLinks(); ++i) s.push_back(r->getJointPos(i));
    }
    for (int k = 0; k < 3; ++k) s.push_back(box->getWorldTransform().getOrigin()[k]);
    for (int k = 0; k < 3; ++k) s.push_back(box->getLinearVelocity()[k]);
    return s;
  }
};

TEST(MultiBodyWorld, StepsBitForBitAsBulletsOwnWorld) {
  Worlds ours(true), bullets(false);
  bool slept = false;
  for (int step = 0; step < 2400; ++step) {
    ours.world.stepSimulation(0.0025, 0);
    bullets.world.stepSimulation(0.0025, 0);
    std::vector<btScalar> a = ours.state(), b = bullets.state();
    ASSERT_EQ(a.size(), b.size());
    ASSERT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(btScalar))) << "step " << step;
    slept = slept || ours.robots[1]->getBaseCollider()->getActivationState() == ISLAND_SLEEPING;
  }
  EXPECT_TRUE(slept) << "the resting chain never slept: the sleeping path went untested";
  EXPECT_GT(ours.box->getWorldTransform().getOrigin().x(), -3.0) << "the box never moved";
}

}  // namespace
