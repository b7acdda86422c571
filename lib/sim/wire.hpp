// Wires (compat-notes.md, "Wire kinds").
//  - RopeConstraint: a one-sided length limit, |pB - pA| <= length, slack
//    when shorter; used for `stiff` and `custom` wires.  One solver row
//    whose impulse may only pull.
//  - Spring: `compliant` wires, a spring-damper that pulls with
//    stiffness * (d - length) + damping * d' when stretched beyond length.
// Bullet-facing: included only by lib/sim sources.
#pragma once
#include <btBulletDynamicsCommon.h>

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

struct Spring {
  btRigidBody* a = nullptr;
  btRigidBody* b = nullptr;  // nullptr: pivotB is fixed in the world
  btVector3 pivotA, pivotB;  // in the bodies' frames
  double length = 1, stiffness = 1000, damping = 0;
  void apply() const;  // adds this step's forces
};

}  // namespace rscene::sim
