// Generalized coordinates and forward kinematics of a robot model, shared
// by sim, render and validate (ArticulatedSystem.rst, "State
// Representation", "Joints").
//
// Layout of the generalized coordinate q and velocity u:
//   floating base: q = [position (3), quaternion w x y z (4), joints...],
//                  u = [linear velocity (3), angular velocity (3), joints...],
//                  both base velocities in the world frame;
//   fixed base:    joints only.
//   revolute, continuous, prismatic: 1 entry in q and 1 in u;
//   spherical: a quaternion w x y z (4) in q, an angular velocity (3) in u,
//              expressed in the joint (child) frame.
// Joints come in RaiSim's order (depth-first from the root, children in
// file order), or in the order a `jointOrder=` list names them.
#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

#include "robot/model.hpp"

namespace rscene::robot {

struct Coordinates {
  std::vector<int> joints;           // movable joints, in coordinate order
  std::vector<int> coordinateIndex;  // per Model::joints entry: first index in q, -1 when fixed
  std::vector<int> velocityIndex;    // per Model::joints entry: first index in u, -1 when fixed
  int baseCoordinates = 0;           // 7 with a floating base, else 0
  int baseVelocities = 0;            // 6 with a floating base, else 0
  int coordinateDim = 0, velocityDim = 0;
};

// Movable joints in RaiSim's order: depth-first from the root, children in
// file order.
std::vector<int> defaultJointOrder(const Model& model);

// What is wrong with a jointOrder= list, one entry per problem.
struct JointOrderProblem {
  enum Kind { Unknown, Fixed, Repeated, Missing } kind;
  std::string name;  // the name written (Unknown, Fixed, Repeated) or the joint left out (Missing)
};

// The layout for `order` (joint names; empty = RaiSim's order).  Returns the
// problems of a non-empty `order`; with any, `out` has the default order.
std::vector<JointOrderProblem> makeCoordinates(const Model& model, const std::vector<std::string>& order,
                                               Coordinates& out);

// Name of each entry of q (or u when `velocity`): "base_x", "base_qw", ...,
// a 1-dof joint's name, "NAME_qw".."NAME_qz" (q) or "NAME_wx".."NAME_wz" (u)
// for a spherical joint.  Used in CSV headers and diffs.
std::vector<std::string> coordinateNames(const Model& model, const Coordinates& c, bool velocity);

// q at rest, where a record without coordinates starts: a floating base at
// `base` * Model::baseStart, 1-dof joints at Joint::initial (MJCF's qpos0,
// else 0), quaternions identity.
Eigen::VectorXd neutralCoordinate(const Model& model, const Coordinates& c, const Pose& base);

// The motion of one joint for its entries of q (a 1-dof value, or a
// quaternion w x y z for a spherical joint), as a pose in the joint frame.
Pose jointMotion(const Joint& joint, const double* q);

// World pose of every link (indexed like Model::links) for coordinate q.
// A fixed base sits at `base`; a floating base at q's first 7 entries.
std::vector<Pose> linkPoses(const Model& model, const Coordinates& c, const Pose& base, const Eigen::VectorXd& q);

// RaiSim frames: every joint has a frame of its name (at its child link's
// frame) and so does every link.  Returns the link whose frame it is, or -1.
int frameLink(const Model& model, const std::string& name);

}  // namespace rscene::robot
