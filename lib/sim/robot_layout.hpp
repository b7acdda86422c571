// How a robot model (lib/robot) becomes Featherstone bodies, before any
// Bullet type is involved (so it is testable with Eigen alone).
//
// Fixed joints are merged away: a link joined to its parent by a fixed
// joint belongs to the parent's body.  What is left is RaiSim's "movable
// bodies": body 0 is the root (the floating base, or the link fixed to the
// world), then one body per movable joint in RaiSim's joint order
// (depth-first, children in file order: parents before children, as
// Featherstone needs; RaiSim's body index = joint index, ArticulatedSystem.rst
// "Types of Indices").  A jointOrder= list reorders the coordinates only.  A body's frame is its root link's frame (the child link of
// its joint); its mass properties are the sum of its links' inertials,
// combined about the common centre of mass by the parallel-axis theorem.
//
// Rotor inertia (RaiSim's <dynamics rotor_inertia>, MJCF armature) is added
// to the body below the joint as a massless inertia I_r about the joint
// axis (I_r a a^T): the mass-matrix entry of that joint grows by exactly
// I_r, as in RaiSim; unlike RaiSim (which adds it to that diagonal entry
// only) the rotor also couples to ancestor joints whose axes are not
// perpendicular (by I_r (a . a_k)), which is what a real rotor fixed in the
// child body does, less its gyroscopic effect.  A spherical joint's rotor
// inertia is I_r on all three axes; a prismatic joint's is not modelled.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "robot/kinematics.hpp"
#include "robot/model.hpp"

namespace rscene::sim {

struct RobotBody {
  int joint = -1;       // the movable joint above it (Model::joints index); -1 for the root body
  int parentBody = -1;  // index into RobotLayout::bodies; -1 for the root body
  std::vector<int> links;            // model links merged into it (its own link first)
  std::vector<Pose> linkInBody;      // each link's frame in the body frame, same order
  Pose jointInParent;                // the joint frame (body frame at q = 0) in the parent body frame
  double mass = 0;
  // Principal frame at the centre of mass, in the body frame: Bullet's
  // link frame.  `inertia` is the diagonal there.
  Pose com;
  Eigen::Vector3d inertia = Eigen::Vector3d::Zero();
};

struct RobotLayout {
  std::vector<RobotBody> bodies;  // 0: root, then in RaiSim's joint order
  std::vector<int> bodyOfLink;    // per Model::links entry
};

// Masses below this are raised to it (Bullet divides by them); a link of
// zero mass (a frame) adds nothing.
inline constexpr double kMinBodyMass = 1e-6;
inline constexpr double kMinBodyInertia = 1e-9;

RobotLayout makeLayout(const robot::Model& model);

}  // namespace rscene::sim
