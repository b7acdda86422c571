// Bullet's multibody world without the robots' predicted transforms
// (issue 26).
//
// Each step btMultiBodyDynamicsWorld::predictUnconstraintMotion integrates
// every robot's positions a step ahead (predictPositionsMultiDof) and sets
// its links' "interpolation" transforms from them, about 3% of a standing
// ANYmal's step.  Only continuous collision reads those transforms:
// Bullet's swept AABBs and time-of-impact queries, which it takes for rigid
// bodies only, and the deformable multibody world, which lib/sim does not
// use (its soft bodies are its own).  The integration at the end of the
// step computes the positions anew.  So the prediction is left out; what
// else the step does there is kept: the rigid bodies' prediction, and the
// clearing of a sleeping robot's velocities.  Tests step the same robots
// with Bullet's own world and compare bit for bit.
// Bullet-facing: included only by lib/sim sources.
#pragma once
#include <btBulletDynamicsCommon.h>

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

namespace rscene::sim {

class MultiBodyWorld : public btMultiBodyDynamicsWorld {
 public:
  using btMultiBodyDynamicsWorld::btMultiBodyDynamicsWorld;

  // Off: Bullet's own prediction (tests compare the two).
  void setSkipPrediction(bool on) { skipPrediction_ = on; }

 protected:
  void predictUnconstraintMotion(btScalar timeStep) override {
    if (!skipPrediction_) {
      btMultiBodyDynamicsWorld::predictUnconstraintMotion(timeStep);
      return;
    }
    btDiscreteDynamicsWorld::predictUnconstraintMotion(timeStep);
    for (int i = 0; i < getNumMultibodies(); ++i) {
      btMultiBody* robot = getMultiBody(i);
      if (sleeping(*robot)) robot->clearVelocities();
    }
  }

 private:
  // Bullet's test in predictMultiBodyTransforms: any collider asleep.
  static bool sleeping(const btMultiBody& robot) {
    if (robot.getBaseCollider() && robot.getBaseCollider()->getActivationState() == ISLAND_SLEEPING) return true;
    for (int l = 0; l < robot.getNumLinks(); ++l) {
      const btMultiBodyLinkCollider* c = robot.getLink(l).m_collider;
      if (c && c->getActivationState() == ISLAND_SLEEPING) return true;
    }
    return false;
  }

  bool skipPrediction_ = true;
};

}  // namespace rscene::sim
