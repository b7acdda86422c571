#include "sim/robot_layout.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>

namespace rscene::sim {
namespace {

using robot::JointType;

// Mass, centre of mass and inertia (about that centre, body axes) of a body.
void massProperties(const robot::Model& model, RobotBody& body) {
  double mass = 0;
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < body.links.size(); ++k) {
    const robot::Inertial& in = model.links[static_cast<std::size_t>(body.links[k])].inertial;
    if (!(in.mass > 0)) continue;
    mass += in.mass;
    weighted += in.mass * (body.linkInBody[k] * in.origin).position;
  }
  Eigen::Vector3d com = mass > 0 ? Eigen::Vector3d(weighted / mass) : Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < body.links.size(); ++k) {
    const robot::Inertial& in = model.links[static_cast<std::size_t>(body.links[k])].inertial;
    Pose at = body.linkInBody[k] * in.origin;
    Eigen::Matrix3d r = at.orientation.toRotationMatrix();
    inertia += r * in.inertia * r.transpose();
    if (in.mass > 0) {
      Eigen::Vector3d d = at.position - com;  // parallel axes
      inertia += in.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
    }
  }
  if (body.joint >= 0) {  // the rotor: massless, so its axis may pass anywhere
    const robot::Joint& j = model.joints[static_cast<std::size_t>(body.joint)];
    if (j.rotorInertia > 0) {
      if (j.type == JointType::Spherical) inertia += j.rotorInertia * Eigen::Matrix3d::Identity();
      // A prismatic joint's reflected inertia would be a mass that gravity
      // does not pull: Featherstone bodies cannot have one (not modelled).
      else if (j.type != JointType::Prismatic) inertia += j.rotorInertia * j.axis * j.axis.transpose();
    }
  }
  body.mass = std::max(mass, kMinBodyMass);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (inertia + inertia.transpose()));
  Eigen::Matrix3d axes = eig.eigenvectors();
  if (axes.determinant() < 0) axes.col(2) *= -1;  // a rotation, not a reflection
  body.com.position = com;
  body.com.orientation = Eigen::Quaterniond(axes).normalized();
  body.inertia = eig.eigenvalues().cwiseMax(kMinBodyInertia);
}

}  // namespace

RobotLayout makeLayout(const robot::Model& model) {
  RobotLayout out;
  out.bodyOfLink.assign(model.links.size(), -1);
  if (model.links.empty()) return out;
  std::vector<int> order = robot::defaultJointOrder(model);
  std::vector<int> bodyOfJoint(model.joints.size(), -1);
  out.bodies.resize(order.size() + 1);
  for (std::size_t i = 0; i < order.size(); ++i) {
    bodyOfJoint[static_cast<std::size_t>(order[i])] = static_cast<int>(i + 1);
    out.bodies[i + 1].joint = order[i];
  }
  // Walk the tree from the root: a fixed child joins its parent's body at
  // the pose the fixed joints put it; a movable child starts its own body.
  struct Item {
    int link, body;
    Pose inBody;
  };
  std::vector<Item> stack{{model.root, 0, Pose{}}};
  while (!stack.empty()) {
    Item it = stack.back();
    stack.pop_back();
    if (out.bodyOfLink[static_cast<std::size_t>(it.link)] >= 0) continue;  // never in a tree; guards a bad one
    out.bodyOfLink[static_cast<std::size_t>(it.link)] = it.body;
    RobotBody& body = out.bodies[static_cast<std::size_t>(it.body)];
    body.links.push_back(it.link);
    body.linkInBody.push_back(it.inBody);
    const std::vector<int>& kids = model.links[static_cast<std::size_t>(it.link)].childJoints;
    for (auto k = kids.rbegin(); k != kids.rend(); ++k) {
      const robot::Joint& j = model.joints[static_cast<std::size_t>(*k)];
      if (j.childLink < 0) continue;
      Pose at = it.inBody * j.origin;
      int b = bodyOfJoint[static_cast<std::size_t>(*k)];
      if (b < 0) {
        stack.push_back({j.childLink, it.body, at});
      } else {
        out.bodies[static_cast<std::size_t>(b)].parentBody = it.body;
        out.bodies[static_cast<std::size_t>(b)].jointInParent = at;
        stack.push_back({j.childLink, b, Pose{}});
      }
    }
  }
  for (RobotBody& b : out.bodies) massProperties(model, b);
  return out;
}

}  // namespace rscene::sim
