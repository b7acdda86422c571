// One articulated system as a Bullet Featherstone btMultiBody (double
// precision).  Bullet-facing: included only by lib/sim sources.
//
// Frames.  Bullet puts each link's frame at its centre of mass on the
// principal axes (RobotBody::com); the model's joint frames differ from it
// by that constant pose, so:
//  - a revolute/prismatic axis a (joint frame) is R_c^-1 a in Bullet;
//  - a spherical joint's quaternion r (child in the joint frame, RaiSim's
//    convention) is R_c^-1 r R_c in Bullet (which applies it in the link's
//    centre-of-mass frame), stored x y z w; its angular velocity (joint
//    frame in RaiSim) is R_c^-1 w;
//  - the floating base: RaiSim's base position is the root link's frame
//    origin and its linear velocity that origin's, in the world frame;
//    Bullet's base is the root body's centre of mass, so
//    v_origin = v_com + w x (p_origin - p_com).  Both keep the base's
//    angular velocity in the world frame (btMultiBody::getBaseOmega is in
//    the world frame, as RaiSim's u[3..5] is): no conversion there.
//
// Joint forces, applied every step before Bullet's step (springs toward
// spring_mount, viscous damping, and the PD of --pd-gains) are implicit in
// the joint alone: for stiffness k, damping c and the joint's inertia m
// (the mass-matrix diagonal entry of the subtree below it, computed at the
// initial pose), the torque is what one backward-Euler step of
// m v' = m v - dt (k (q + dt v' - q0) + c v') gives,
//   tau = s (-k (q - q0) - (c + dt k) v),  s = m / (m + dt c + dt^2 k),
// stable for any gains (RaiSim's stable PD is implicit in the whole mass
// matrix; this is its diagonal).  The price: at rest against a load the
// joint is as stiff as s k, not k.  Coulomb friction is a velocity motor
// whose impulse is capped at friction * dt (it holds a joint until the
// load passes the friction, then resists with exactly the friction); joint
// limits are Bullet's unilateral limit constraints (a hard stop, as
// RaiSim's), in the world only while the joint is at or past a limit:
// Bullet 3.24 makes their rows only then, and a limit constraint in the
// world costs every step even when it makes none (sorting, islands).
// updateLimits() before each step puts in the world exactly those that
// will make rows in it.  Friction and limits are for 1-dof joints; a spherical
// joint's are not modelled.
#pragma once
#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "robot/instance.hpp"
#include "sim/robot_layout.hpp"
#include "sim/world.hpp"

namespace rscene::sim {

class SimRobot {
 public:
  // A collision shape for a model geometry (the world's: shared meshes),
  // nullptr with `error` set when it cannot be made; nullptr with no
  // error leaves that collision out (--allow-missing-assets).
  using ShapeMaker = std::function<btCollisionShape*(const robot::Geometry&, std::string& error)>;

  // Builds the multibody at the instance's state.  `pd` drives every
  // movable joint toward its initial position.  Returns nullptr with
  // `error` (naming the link) when a shape fails.
  static std::unique_ptr<SimRobot> create(const robot::RobotInstance& instance, const ShapeMaker& shapes,
                                          const PdGains& pd, bool canSleep, std::string& error);
  ~SimRobot();

  btMultiBody* multiBody() { return body_.get(); }
  const robot::RobotInstance& instance() const { return instance_; }
  const RobotLayout& layout() const { return layout_; }
  // Colliders by body; a body without collision shapes has one of an
  // empty shape (hasShapes() false), which must collide with nothing.
  const std::vector<btMultiBodyLinkCollider*>& colliders() const { return colliders_; }
  bool hasShapes(int body) const { return colliders_[static_cast<std::size_t>(body)]->getCollisionShape()->getShapeType() != EMPTY_SHAPE_PROXYTYPE; }
  // Multibody constraints it owns that act every step (friction motors):
  // added to the world by the caller.  Its joint limits are added and
  // removed by updateLimits().
  const std::vector<std::unique_ptr<btMultiBodyConstraint>>& constraints() const { return constraints_; }
  // Puts in `world` the limit constraints of the joints now at or past a
  // limit and takes out the others; call before each step.
  void updateLimits(btMultiBodyDynamicsWorld& world);
  // Takes all its limit constraints out of `world`.
  void removeLimits(btMultiBodyDynamicsWorld& world);

  // Makes the Coulomb friction motors, whose impulse cap depends on the
  // time step; call once before constraints() is read.
  void addFriction(double dt);
  // Adds this step's joint torques (springs, damping, PD).
  void applyJointForces(double dt);

  void setState(const Eigen::VectorXd& q, const Eigen::VectorXd& u);
  // The generalized coordinate and velocity now (RaiSim's layout).
  void state(Eigen::VectorXd& q, Eigen::VectorXd& u) const;
  // World pose of a body's frame (RobotLayout::bodies index).
  Pose bodyPose(int body) const;
  // World-frame velocity of a point fixed in a body (p in world
  // coordinates); the body's angular velocity into `omega` when given.
  Eigen::Vector3d pointVelocity(int body, const Eigen::Vector3d& p, Eigen::Vector3d* omega = nullptr) const;
  // Applies a world-frame force at world point p of a body, for one step.
  void applyForce(int body, const Eigen::Vector3d& force, const Eigen::Vector3d& p);

  // Control by a program that embeds lib/sim (World::setRobotPd...), in
  // RaiSim's ArticulatedSystem conventions; sizes and values are the
  // caller's to check.  Gains per entry of u (a floating base's six are
  // ignored: the base has no actuator), targets in q's layout (position)
  // and u's (velocity), acting through the implicit drive of the header
  // from the next step on and kept until changed; they replace --pd-gains.
  void setPdGains(const Eigen::VectorXd& kp, const Eigen::VectorXd& kd);
  void setPdTarget(const Eigen::VectorXd& q, const Eigen::VectorXd& u);
  // A feedforward generalized force in u's layout (a floating base's: a
  // world-frame force at the base frame's origin, then a world-frame
  // torque), added every step until changed (RaiSim's setGeneralizedForce).
  void setGeneralizedForce(const Eigen::VectorXd& tau);

 private:
  struct Drive {  // one movable joint's spring, damper and PD
    int link = -1;  // Bullet link index
    int joint = -1;
    int q = 0, u = 0;  // first entries in RaiSim's q and u
    Eigen::Vector3d kp = Eigen::Vector3d::Zero(), kd = Eigen::Vector3d::Zero();  // per dof (1 or 3)
    double stiffness = 0, damping = 0;
    Eigen::Vector4d pdTarget = Eigen::Vector4d::Zero();     // 1 number, or quaternion w x y z
    Eigen::Vector3d velocityTarget = Eigen::Vector3d::Zero();  // per dof
    Eigen::Vector4d springTarget = Eigen::Vector4d::Zero();
    Eigen::Vector3d inertia = Eigen::Vector3d::Zero();  // per dof (1 or 3), m of the header's formula
    bool inertiaKnown = false;
    bool active() const { return (kp.array() != 0).any() || (kd.array() != 0).any() || stiffness > 0 || damping > 0; }
  };
  SimRobot() = default;
  // The inertia of every active drive that has none yet, at the pose now.
  void computeJointInertia();

  robot::RobotInstance instance_;
  RobotLayout layout_;
  std::unique_ptr<btMultiBody> body_;
  std::vector<btMultiBodyLinkCollider*> colliders_;
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> ownedColliders_;
  std::vector<std::unique_ptr<btCollisionShape>> compounds_;
  std::vector<std::unique_ptr<btMultiBodyConstraint>> constraints_;
  struct Limit {
    std::unique_ptr<btMultiBodyConstraint> constraint;
    int link = -1;
    double lower = 0, upper = 0;
    bool inWorld = false;
  };
  std::vector<Limit> limits_;
  std::vector<Drive> drives_;  // every movable joint, in body order
  Eigen::VectorXd force_;      // setGeneralizedForce; empty: none
  std::vector<std::pair<int, double>> friction_;  // Bullet link, Coulomb friction (until addFriction)
};

}  // namespace rscene::sim
