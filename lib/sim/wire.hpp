// Wires (compat-notes.md, "Wire kinds").
//  - RopeConstraint: a one-sided length limit, |pB - pA| <= length, slack
//    when shorter; used for `stiff` and `custom` wires.  One solver row
//    whose impulse may only pull.
//  - Spring: `compliant` wires, a spring-damper that pulls with
//    stiffness * (d - length) + damping * d' when stretched beyond length.
//  - MultiBodyRope: the rope when an end is a body of an articulated
//    system (a Featherstone link), as a btMultiBodyConstraint row.
// Bullet-facing: included only by lib/sim sources.
#pragma once
#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraint.h>

#include "sim/robot_sim.hpp"

namespace rscene::sim {

class RopeConstraint : public btTypedConstraint {
 public:
  // `b` may be nullptr: then `pivotB` is a point fixed in the world.
  RopeConstraint(btRigidBody& a, btRigidBody* b, const btVector3& pivotA, const btVector3& pivotB, double length);
  void getInfo1(btConstraintInfo1* info) override;
  void getInfo2(btConstraintInfo2* info) override;
  void setParam(int, btScalar, int) override {}
  btScalar getParam(int, int) const override { return 0; }

 private:
  btVector3 worldA() const;
  btVector3 worldB() const;
  btVector3 pivotA_, pivotB_;
  bool hasB_;
  double length_;
};

// One end of a wire: a rigid body, a body of a robot, or (neither) a
// point fixed in the world.
struct WireAnchor {
  btRigidBody* rigid = nullptr;
  SimRobot* robot = nullptr;
  int body = 0;      // the robot's body (RaiSim's body index)
  btVector3 local;   // rigid: centre-of-mass frame; robot: body frame; world: world point
  btVector3 world() const;
  btVector3 velocity(const btVector3& at) const;
  void apply(const btVector3& force, const btVector3& at) const;
};

struct Spring {
  WireAnchor a, b;
  double length = 1, stiffness = 1000, damping = 0;
  void apply() const;  // adds this step's forces
};

// A rope (|pB - pA| <= length) with at least one end on a robot: end A is
// a robot's body; end B a robot's body, a rigid body or the world.
class MultiBodyRope : public btMultiBodyConstraint {
 public:
  MultiBodyRope(const WireAnchor& a, const WireAnchor& b, double length);
  void finalizeMultiDof() override;
  int getIslandIdA() const override;
  int getIslandIdB() const override;
  void createConstraintRows(btMultiBodyConstraintArray& rows, btMultiBodyJacobianData& data,
                            const btContactSolverInfo& info) override;
  void debugDraw(btIDebugDraw*) override {}
  const btRigidBody* rigid() const { return b_.rigid; }

 private:
  WireAnchor a_, b_;
  btVector3 comA_, comB_;  // the pivots in the links' centre-of-mass frames
  double length_;
};

}  // namespace rscene::sim
