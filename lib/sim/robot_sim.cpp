#include "sim/robot_sim.hpp"

#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>

#include <algorithm>
#include <cmath>

#include "sim/bt_eigen.hpp"

namespace rscene::sim {
namespace {

using robot::JointType;

bool oneDof(JointType t) { return t == JointType::Revolute || t == JointType::Continuous || t == JointType::Prismatic; }

Eigen::Quaterniond quat(const Eigen::Vector4d& wxyz) {
  Eigen::Quaterniond q(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
  return q.norm() > 1e-12 ? q.normalized() : Eigen::Quaterniond::Identity();
}

// Rotation vector of q (angle in [-pi, pi]).
Eigen::Vector3d rotationVector(Eigen::Quaterniond q) {
  if (q.w() < 0) q.coeffs() *= -1;
  Eigen::AngleAxisd aa(q);
  return aa.angle() * aa.axis();
}

}  // namespace

SimRobot::~SimRobot() = default;

std::unique_ptr<SimRobot> SimRobot::create(const robot::RobotInstance& instance, const ShapeMaker& shapes,
                                           const PdGains& pd, bool canSleep, std::string& error) {
  std::unique_ptr<SimRobot> r(new SimRobot());
  r->instance_ = instance;
  const robot::Model& model = *instance.model;
  r->layout_ = makeLayout(model);
  const std::vector<RobotBody>& bodies = r->layout_.bodies;
  const int links = static_cast<int>(bodies.size()) - 1;
  const RobotBody& root = bodies[0];
  r->body_ = std::make_unique<btMultiBody>(links, root.mass, bt(root.inertia), !model.floatingBase, canSleep);
  btMultiBody* mb = r->body_.get();
  bool noParent = instance.record ? instance.record->doNotCollideWithParent : true;
  for (int i = 1; i <= links; ++i) {
    const RobotBody& b = bodies[static_cast<std::size_t>(i)];
    const robot::Joint& j = model.joints[static_cast<std::size_t>(b.joint)];
    const RobotBody& parent = bodies[static_cast<std::size_t>(b.parentBody)];
    Pose inA = parent.com.inverse() * b.jointInParent;  // joint frame in the parent's centre-of-mass frame
    Pose inB = b.com.inverse();                         // body frame in its own centre-of-mass frame
    btQuaternion parentToThis = bt(inB.orientation * inA.orientation.inverse());
    btVector3 axis = bt(inB.orientation * j.axis), pivot = bt(inA.position), toCom = bt(-inB.position);
    switch (j.type) {
      case JointType::Prismatic:
        mb->setupPrismatic(i - 1, b.mass, bt(b.inertia), b.parentBody - 1, parentToThis, axis, pivot, toCom, noParent);
        break;
      case JointType::Spherical:
        mb->setupSpherical(i - 1, b.mass, bt(b.inertia), b.parentBody - 1, parentToThis, pivot, toCom, noParent);
        break;
      default:
        mb->setupRevolute(i - 1, b.mass, bt(b.inertia), b.parentBody - 1, parentToThis, axis, pivot, toCom, noParent);
        break;
    }
  }
  mb->finalizeMultiDof();
  // Bullet's defaults damp every link (0.04) and cap joint speeds at 100 and
  // impulses at 1000: none of that is in RaiSim's model.
  mb->setLinearDamping(0);
  mb->setAngularDamping(0);
  mb->setUseGyroTerm(true);
  mb->setMaxCoordinateVelocity(kMaxJointSpeed);
  mb->setMaxAppliedImpulse(1e12);
  mb->setHasSelfCollision(true);  // which pairs meet is the world's filter's business
  mb->setBaseWorldTransform(bt(instance.base * root.com));
  r->setState(instance.q, instance.u);

  // One compound per body, its children about the body's centre of mass.
  r->colliders_.assign(bodies.size(), nullptr);
  for (int i = 0; i <= links; ++i) {
    const RobotBody& b = bodies[static_cast<std::size_t>(i)];
    btCompoundShape* compound = nullptr;
    for (std::size_t k = 0; k < b.links.size(); ++k) {
      const robot::Link& link = model.links[static_cast<std::size_t>(b.links[k])];
      for (const robot::Collision& c : link.collisions) {
        std::string why;
        btCollisionShape* shape = shapes(c.geometry, why);
        if (!shape && why.empty()) continue;  // left out by the maker (--allow-missing-assets)
        if (!shape) {
          error = "link '" + link.name + "': " + why;
          return nullptr;
        }
        if (!compound) {
          compound = new btCompoundShape();
          r->compounds_.emplace_back(compound);
        }
        compound->addChildShape(bt(b.com.inverse() * b.linkInBody[k] * c.origin), shape);
      }
    }
    // A body without shapes still gets a collider (an empty shape the
    // world's filter pairs with nothing): Bullet's island manager assigns
    // a multibody's limit and motor constraints to the islands of their
    // links' colliders, and drops the constraints of a link without one.
    btCollisionShape* shape = compound;
    if (!shape) {
      shape = new btEmptyShape();
      r->compounds_.emplace_back(shape);
    }
    auto* col = new btMultiBodyLinkCollider(mb, i - 1);
    r->ownedColliders_.emplace_back(col);
    col->setCollisionShape(shape);
    col->setWorldTransform(bt(r->bodyPose(i) * b.com));
    if (i == 0) {
      mb->setBaseCollider(col);
      if (!model.floatingBase) col->setCollisionFlags(col->getCollisionFlags() | btCollisionObject::CF_STATIC_OBJECT);
    } else {
      mb->getLink(i - 1).m_collider = col;
    }
    r->colliders_[static_cast<std::size_t>(i)] = col;
  }

  // Limits, friction and the joint drives.
  const robot::Coordinates& coords = instance.coordinates;
  for (int i = 1; i <= links; ++i) {
    const robot::Joint& j = model.joints[static_cast<std::size_t>(bodies[static_cast<std::size_t>(i)].joint)];
    if (oneDof(j.type) && j.type != JointType::Continuous && j.hasLimits && j.lower <= j.upper) {
      auto* limit = new btMultiBodyJointLimitConstraint(mb, i - 1, j.lower, j.upper);
      limit->setMaxAppliedImpulse(1e12);
      r->limits_.push_back({std::unique_ptr<btMultiBodyConstraint>(limit), i - 1, j.lower, j.upper, false});
    }
    Drive d;
    d.link = i - 1;
    d.joint = bodies[static_cast<std::size_t>(i)].joint;
    d.q = coords.coordinateIndex[static_cast<std::size_t>(d.joint)];
    d.u = coords.velocityIndex[static_cast<std::size_t>(d.joint)];
    if (pd.enabled) {
      auto it = pd.joints.find(j.name);
      d.kp.setConstant(it != pd.joints.end() ? it->second.first : pd.kp);
      d.kd.setConstant(it != pd.joints.end() ? it->second.second : pd.kd);
    }
    d.stiffness = j.stiffness;
    d.damping = j.damping;
    int n = j.coordinateDim();
    if (d.q >= 0 && d.q + n <= instance.q.size()) d.pdTarget.head(n) = instance.q.segment(d.q, n);
    if (n == 4) d.springTarget << 1, 0, 0, 0;
    if (static_cast<int>(j.springMount.size()) == n) d.springTarget.head(n) = Eigen::Map<const Eigen::VectorXd>(j.springMount.data(), n);
    r->drives_.push_back(d);
    // Coulomb friction: a motor toward zero speed whose impulse is capped
    // per step; the world sets the cap once it knows the time step.
    if (oneDof(j.type) && j.friction > 0) r->friction_.push_back({i - 1, j.friction});
  }
  r->computeJointInertia();
  return r;
}

void SimRobot::updateLimits(btMultiBodyDynamicsWorld& world) {
  for (Limit& l : limits_) {
    // Bullet's test (btMultiBodyJointLimitConstraint::createConstraintRows):
    // a row for a bound whose distance q - lower or upper - q is not > 0.
    double q = body_->getJointPos(l.link);
    bool rows = !(q - l.lower > 0) || !(l.upper - q > 0);
    if (rows && !l.inWorld) world.addMultiBodyConstraint(l.constraint.get());
    if (!rows && l.inWorld) world.removeMultiBodyConstraint(l.constraint.get());
    l.inWorld = rows;
  }
}

void SimRobot::removeLimits(btMultiBodyDynamicsWorld& world) {
  for (Limit& l : limits_)
    if (l.inWorld) world.removeMultiBodyConstraint(l.constraint.get());
  for (Limit& l : limits_) l.inWorld = false;
}

void SimRobot::addFriction(double dt) {
  for (const auto& [link, friction] : friction_) {
    auto* motor = new btMultiBodyJointMotor(body_.get(), link, 0, friction * dt);
    constraints_.emplace_back(motor);
  }
  friction_.clear();
}

// The mass-matrix diagonal entry of each driven dof at the initial pose:
// the subtree below the joint as one rigid body, about the joint axis
// (revolute, each axis of the joint frame for a spherical joint) or along
// it (prismatic).
void SimRobot::computeJointInertia() {
  const std::vector<RobotBody>& bodies = layout_.bodies;
  std::vector<Pose> at(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) at[i] = bodyPose(static_cast<int>(i));
  const robot::Model& model = *instance_.model;
  for (Drive& d : drives_) {
    if (d.inertiaKnown || !d.active()) continue;
    d.inertiaKnown = true;
    int top = d.link + 1;
    const robot::Joint& j = model.joints[static_cast<std::size_t>(d.joint)];
    std::vector<Eigen::Vector3d> axes;
    if (j.type == JointType::Spherical) axes = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
    else axes = {j.axis};
    for (std::size_t k = 0; k < axes.size(); ++k) {
      Eigen::Vector3d a = at[static_cast<std::size_t>(top)].orientation * axes[k];
      Eigen::Vector3d p = at[static_cast<std::size_t>(top)].position;
      double m = 0;
      for (std::size_t s = static_cast<std::size_t>(top); s < bodies.size(); ++s) {
        int up = static_cast<int>(s);  // is `top` an ancestor of s (or s itself)?
        while (up > top) up = bodies[static_cast<std::size_t>(up)].parentBody;
        if (up != top) continue;
        const RobotBody& b = bodies[s];
        if (j.type == JointType::Prismatic) {
          m += b.mass;
          continue;
        }
        Pose com = at[s] * b.com;
        Eigen::Matrix3d r = com.orientation.toRotationMatrix();
        Eigen::Matrix3d inertia = r * b.inertia.asDiagonal() * r.transpose();
        m += b.mass * a.cross(com.position - p).squaredNorm() + a.dot(inertia * a);
      }
      d.inertia[static_cast<Eigen::Index>(k)] = std::max(m, kMinBodyInertia);
    }
  }
}

void SimRobot::applyJointForces(double dt) {
  btMultiBody* mb = body_.get();
  const std::vector<RobotBody>& bodies = layout_.bodies;
  for (const Drive& d : drives_) {
    if (!d.active()) continue;
    const robot::Joint& j = instance_.model->joints[static_cast<std::size_t>(d.joint)];
    if (j.type != JointType::Spherical) {
      double k = d.kp[0] + d.stiffness, c = d.kd[0] + d.damping;
      double q = mb->getJointPos(d.link), v = mb->getJointVel(d.link);
      double q0 = k > 0 ? (d.kp[0] * d.pdTarget[0] + d.stiffness * d.springTarget[0]) / k : q;
      double m = d.inertia[0], s = m / (m + dt * c + dt * dt * k);
      mb->addJointTorque(d.link, s * (-k * (q - q0) + d.kd[0] * d.velocityTarget[0] - (c + dt * k) * v));
      continue;
    }
    const Eigen::Quaterniond rc = bodies[static_cast<std::size_t>(d.link + 1)].com.orientation;
    const btScalar* x = mb->getJointPosMultiDof(d.link);
    const btScalar* w = mb->getJointVelMultiDof(d.link);
    Eigen::Quaterniond r = rc * Eigen::Quaterniond(x[3], x[0], x[1], x[2]).normalized() * rc.conjugate();
    Eigen::Vector3d omega = rc * Eigen::Vector3d(w[0], w[1], w[2]);
    Eigen::Vector3d spring = d.kp.cwiseProduct(rotationVector(quat(d.pdTarget).conjugate() * r)) +
                             d.stiffness * rotationVector(quat(d.springTarget).conjugate() * r);
    Eigen::Vector3d tau;
    for (int a = 0; a < 3; ++a) {
      double k = d.kp[a] + d.stiffness, c = d.kd[a] + d.damping;
      double m = d.inertia[a], s = m / (m + dt * c + dt * dt * k);
      tau[a] = s * (-spring[a] + d.kd[a] * d.velocityTarget[a] - (c + dt * k) * omega[a]);
    }
    btVector3 tb = bt(rc.conjugate() * tau);
    btScalar t[3] = {tb.x(), tb.y(), tb.z()};
    mb->addJointTorqueMultiDof(d.link, t);
  }
  if (force_.size() == 0) return;
  if (instance_.model->floatingBase) {
    // A force at the base frame's origin is that force and a torque about
    // the centre of mass, where Bullet applies the base's.
    Pose base = bodyPose(0), com = base * bodies[0].com;
    Eigen::Vector3d f = force_.head<3>(), t = force_.segment<3>(3);
    mb->addBaseForce(bt(f));
    mb->addBaseTorque(bt(Eigen::Vector3d(t + (base.position - com.position).cross(f))));
  }
  for (const Drive& d : drives_) {
    const robot::Joint& j = instance_.model->joints[static_cast<std::size_t>(d.joint)];
    if (j.type != JointType::Spherical) {
      mb->addJointTorque(d.link, force_[d.u]);
      continue;
    }
    const Eigen::Quaterniond rc = bodies[static_cast<std::size_t>(d.link + 1)].com.orientation;
    btVector3 tb = bt(rc.conjugate() * Eigen::Vector3d(force_.segment<3>(d.u)));
    btScalar t[3] = {tb.x(), tb.y(), tb.z()};
    mb->addJointTorqueMultiDof(d.link, t);
  }
}

void SimRobot::setPdGains(const Eigen::VectorXd& kp, const Eigen::VectorXd& kd) {
  for (Drive& d : drives_) {
    int n = instance_.model->joints[static_cast<std::size_t>(d.joint)].velocityDim();  // 1, or 3 for a spherical joint
    d.kp.setZero();
    d.kd.setZero();
    d.kp.head(n) = kp.segment(d.u, n);
    d.kd.head(n) = kd.segment(d.u, n);
  }
  computeJointInertia();
}

void SimRobot::setPdTarget(const Eigen::VectorXd& q, const Eigen::VectorXd& u) {
  for (Drive& d : drives_) {
    int n = instance_.model->joints[static_cast<std::size_t>(d.joint)].velocityDim();  // 1, or 3 for a spherical joint
    d.pdTarget.setZero();
    d.velocityTarget.setZero();
    if (n == 3) {
      Eigen::Quaterniond t = quat(q.segment<4>(d.q));
      d.pdTarget << t.w(), t.x(), t.y(), t.z();
    } else {
      d.pdTarget[0] = q[d.q];
    }
    d.velocityTarget.head(n) = u.segment(d.u, n);
  }
}

void SimRobot::setGeneralizedForce(const Eigen::VectorXd& tau) {
  if (tau.size() == 0 || (tau.array() == 0).all()) force_.resize(0);
  else force_ = tau;
  body_->wakeUp();
}

void SimRobot::setState(const Eigen::VectorXd& q, const Eigen::VectorXd& u) {
  btMultiBody* mb = body_.get();
  const robot::Model& model = *instance_.model;
  const robot::Coordinates& c = instance_.coordinates;
  const std::vector<RobotBody>& bodies = layout_.bodies;
  if (model.floatingBase) {
    Pose base{q.head<3>(), quat(q.segment<4>(3))};
    Pose com = base * bodies[0].com;
    mb->setBaseWorldTransform(bt(com));
    Eigen::Vector3d omega = u.segment<3>(3);
    mb->setBaseOmega(bt(omega));
    mb->setBaseVel(bt(Eigen::Vector3d(u.head<3>() + omega.cross(com.position - base.position))));
  }
  for (std::size_t i = 1; i < bodies.size(); ++i) {
    int link = static_cast<int>(i) - 1;
    std::size_t j = static_cast<std::size_t>(bodies[i].joint);
    int qi = c.coordinateIndex[j], ui = c.velocityIndex[j];
    if (model.joints[j].type == JointType::Spherical) {
      const Eigen::Quaterniond& rc = bodies[i].com.orientation;
      Eigen::Quaterniond b = rc.conjugate() * quat(q.segment<4>(qi)) * rc;
      double x[4] = {b.x(), b.y(), b.z(), b.w()};
      mb->setJointPosMultiDof(link, x);
      Eigen::Vector3d w = rc.conjugate() * Eigen::Vector3d(u.segment<3>(ui));
      double v[3] = {w.x(), w.y(), w.z()};
      mb->setJointVelMultiDof(link, v);
    } else {
      mb->setJointPos(link, q[qi]);
      mb->setJointVel(link, u[ui]);
    }
  }
  btAlignedObjectArray<btQuaternion> rot;
  btAlignedObjectArray<btVector3> origin;
  mb->forwardKinematics(rot, origin);
  mb->updateCollisionObjectWorldTransforms(rot, origin);
}

void SimRobot::state(Eigen::VectorXd& q, Eigen::VectorXd& u) const {
  const btMultiBody* mb = body_.get();
  const robot::Model& model = *instance_.model;
  const robot::Coordinates& c = instance_.coordinates;
  const std::vector<RobotBody>& bodies = layout_.bodies;
  q.setZero(c.coordinateDim);
  u.setZero(c.velocityDim);
  if (model.floatingBase) {
    Pose com = pose(mb->getBaseWorldTransform());
    Pose base = com * bodies[0].com.inverse();
    Eigen::Quaterniond o = base.orientation;
    q.head<3>() = base.position;
    q.segment<4>(3) << o.w(), o.x(), o.y(), o.z();
    Eigen::Vector3d omega = eig(mb->getBaseOmega());
    u.head<3>() = eig(mb->getBaseVel()) + omega.cross(base.position - com.position);
    u.segment<3>(3) = omega;
  }
  for (std::size_t i = 1; i < bodies.size(); ++i) {
    int link = static_cast<int>(i) - 1;
    std::size_t j = static_cast<std::size_t>(bodies[i].joint);
    int qi = c.coordinateIndex[j], ui = c.velocityIndex[j];
    if (model.joints[j].type == JointType::Spherical) {
      const Eigen::Quaterniond& rc = bodies[i].com.orientation;
      const btScalar* x = mb->getJointPosMultiDof(link);
      const btScalar* w = mb->getJointVelMultiDof(link);
      Eigen::Quaterniond r = rc * Eigen::Quaterniond(x[3], x[0], x[1], x[2]) * rc.conjugate();
      q.segment<4>(qi) << r.w(), r.x(), r.y(), r.z();
      u.segment<3>(ui) = rc * Eigen::Vector3d(w[0], w[1], w[2]);
    } else {
      q[qi] = mb->getJointPos(link);
      u[ui] = mb->getJointVel(link);
    }
  }
}

Pose SimRobot::bodyPose(int body) const {
  const btMultiBody* mb = body_.get();
  const RobotBody& b = layout_.bodies[static_cast<std::size_t>(body)];
  Pose com;
  if (body == 0) {
    com = pose(mb->getBaseWorldTransform());
  } else {
    btMatrix3x3 r = mb->localFrameToWorld(body - 1, btMatrix3x3::getIdentity());
    btQuaternion o;
    r.getRotation(o);
    com = {eig(mb->localPosToWorld(body - 1, btVector3(0, 0, 0))), eig(o).normalized()};
  }
  return com * b.com.inverse();
}

Eigen::Vector3d SimRobot::pointVelocity(int body, const Eigen::Vector3d& p, Eigen::Vector3d* omegaOut) const {
  const btMultiBody* mb = body_.get();
  btAlignedObjectArray<btVector3> omega, vel;
  omega.resize(mb->getNumLinks() + 1);
  vel.resize(mb->getNumLinks() + 1);
  mb->compTreeLinkVelocities(&omega[0], &vel[0]);  // in each body's own (centre-of-mass) frame
  Pose com = bodyPose(body) * layout_.bodies[static_cast<std::size_t>(body)].com;
  Eigen::Vector3d w = com.orientation * eig(omega[body]), v = com.orientation * eig(vel[body]);
  if (omegaOut) *omegaOut = w;
  return v + w.cross(p - com.position);
}

void SimRobot::applyForce(int body, const Eigen::Vector3d& force, const Eigen::Vector3d& p) {
  btMultiBody* mb = body_.get();
  Pose com = bodyPose(body) * layout_.bodies[static_cast<std::size_t>(body)].com;
  btVector3 f = bt(force), t = bt(Eigen::Vector3d((p - com.position).cross(force)));
  if (body == 0) {
    mb->addBaseForce(f);
    mb->addBaseTorque(t);
  } else {
    mb->addLinkForce(body - 1, f);
    mb->addLinkTorque(body - 1, t);
  }
  mb->wakeUp();
}

}  // namespace rscene::sim
