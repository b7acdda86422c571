#include "robot/kinematics.hpp"

#include <algorithm>
#include <unordered_map>

namespace rscene::robot {

int Joint::coordinateDim() const {
  switch (type) {
    case JointType::Fixed: return 0;
    case JointType::Spherical: return 4;
    default: return 1;
  }
}

int Joint::velocityDim() const {
  switch (type) {
    case JointType::Fixed: return 0;
    case JointType::Spherical: return 3;
    default: return 1;
  }
}

int Model::findLink(const std::string& name) const {
  for (std::size_t i = 0; i < links.size(); ++i)
    if (links[i].name == name) return static_cast<int>(i);
  return -1;
}

int Model::findJoint(const std::string& name) const {
  for (std::size_t i = 0; i < joints.size(); ++i)
    if (joints[i].name == name) return static_cast<int>(i);
  return -1;
}

double Model::totalMass() const {
  double m = 0;
  for (const Link& l : links) m += l.inertial.mass;
  return m;
}

std::vector<int> defaultJointOrder(const Model& model) {
  std::vector<int> order;
  if (model.links.empty()) return order;
  // Depth-first with an explicit stack (a long chain must not overflow the
  // call stack); children pushed in reverse so they pop in file order.
  std::vector<int> stack{model.root};
  std::vector<char> seen(model.links.size(), 0);
  while (!stack.empty()) {
    int link = stack.back();
    stack.pop_back();
    if (seen[static_cast<std::size_t>(link)]) continue;  // a malformed tree never loops here
    seen[static_cast<std::size_t>(link)] = 1;
    const std::vector<int>& kids = model.links[static_cast<std::size_t>(link)].childJoints;
    for (auto it = kids.rbegin(); it != kids.rend(); ++it) {
      int child = model.joints[static_cast<std::size_t>(*it)].childLink;
      if (child >= 0) stack.push_back(child);
    }
    int pj = model.links[static_cast<std::size_t>(link)].parentJoint;
    if (pj >= 0 && model.joints[static_cast<std::size_t>(pj)].type != JointType::Fixed) order.push_back(pj);
  }
  return order;
}

namespace {

void layout(const Model& model, const std::vector<int>& joints, Coordinates& out) {
  out = Coordinates{};
  out.joints = joints;
  out.coordinateIndex.assign(model.joints.size(), -1);
  out.velocityIndex.assign(model.joints.size(), -1);
  out.baseCoordinates = model.floatingBase ? 7 : 0;
  out.baseVelocities = model.floatingBase ? 6 : 0;
  int q = out.baseCoordinates, u = out.baseVelocities;
  for (int j : joints) {
    const Joint& joint = model.joints[static_cast<std::size_t>(j)];
    out.coordinateIndex[static_cast<std::size_t>(j)] = q;
    out.velocityIndex[static_cast<std::size_t>(j)] = u;
    q += joint.coordinateDim();
    u += joint.velocityDim();
  }
  out.coordinateDim = q;
  out.velocityDim = u;
}

}  // namespace

std::vector<JointOrderProblem> makeCoordinates(const Model& model, const std::vector<std::string>& order,
                                               Coordinates& out) {
  std::vector<int> fallback = defaultJointOrder(model);
  std::vector<JointOrderProblem> problems;
  if (order.empty()) {
    layout(model, fallback, out);
    return problems;
  }
  std::vector<int> joints;
  std::vector<char> used(model.joints.size(), 0);
  for (const std::string& name : order) {
    int j = model.findJoint(name);
    if (j < 0) {
      problems.push_back({JointOrderProblem::Unknown, name});
    } else if (model.joints[static_cast<std::size_t>(j)].type == JointType::Fixed) {
      problems.push_back({JointOrderProblem::Fixed, name});
    } else if (used[static_cast<std::size_t>(j)]) {
      problems.push_back({JointOrderProblem::Repeated, name});
    } else {
      used[static_cast<std::size_t>(j)] = 1;
      joints.push_back(j);
    }
  }
  for (int j : fallback)
    if (!used[static_cast<std::size_t>(j)])
      problems.push_back({JointOrderProblem::Missing, model.joints[static_cast<std::size_t>(j)].name});
  layout(model, problems.empty() ? joints : fallback, out);
  return problems;
}

std::vector<std::string> coordinateNames(const Model& model, const Coordinates& c, bool velocity) {
  std::vector<std::string> names;
  if (model.floatingBase) {
    if (velocity)
      names = {"base_vx", "base_vy", "base_vz", "base_wx", "base_wy", "base_wz"};
    else
      names = {"base_x", "base_y", "base_z", "base_qw", "base_qx", "base_qy", "base_qz"};
  }
  for (int j : c.joints) {
    const Joint& joint = model.joints[static_cast<std::size_t>(j)];
    if (joint.type != JointType::Spherical) {
      names.push_back(joint.name);
    } else if (velocity) {
      for (const char* s : {"_wx", "_wy", "_wz"}) names.push_back(joint.name + s);
    } else {
      for (const char* s : {"_qw", "_qx", "_qy", "_qz"}) names.push_back(joint.name + s);
    }
  }
  return names;
}

Eigen::VectorXd neutralCoordinate(const Model& model, const Coordinates& c, const Pose& base) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(c.coordinateDim);
  if (model.floatingBase) {
    const Pose start = base * model.baseStart;
    q.head<3>() = start.position;
    q[3] = start.orientation.w();
    q[4] = start.orientation.x();
    q[5] = start.orientation.y();
    q[6] = start.orientation.z();
  }
  for (int j : c.joints) {
    const Joint& joint = model.joints[static_cast<std::size_t>(j)];
    const int at = c.coordinateIndex[static_cast<std::size_t>(j)];
    if (joint.type == JointType::Spherical)
      q[at] = 1;
    else if (joint.coordinateDim() == 1)
      q[at] = joint.initial;
  }
  return q;
}

Pose jointMotion(const Joint& joint, const double* q) {
  Pose m;
  switch (joint.type) {
    case JointType::Revolute:
    case JointType::Continuous: m.orientation = Eigen::AngleAxisd(q[0], joint.axis); break;
    case JointType::Prismatic: m.position = joint.axis * q[0]; break;
    case JointType::Spherical: {
      Eigen::Quaterniond r(q[0], q[1], q[2], q[3]);
      m.orientation = r.norm() > 1e-12 ? r.normalized() : Eigen::Quaterniond::Identity();
      break;
    }
    case JointType::Fixed: break;
  }
  return m;
}

std::vector<Pose> linkPoses(const Model& model, const Coordinates& c, const Pose& base, const Eigen::VectorXd& q) {
  std::vector<Pose> poses(model.links.size());
  if (model.links.empty()) return poses;
  Pose root = base;
  if (model.floatingBase && q.size() >= 7) {
    root.position = q.head<3>();
    Eigen::Quaterniond r(q[3], q[4], q[5], q[6]);
    root.orientation = r.norm() > 1e-12 ? r.normalized() : Eigen::Quaterniond::Identity();
  }
  poses[static_cast<std::size_t>(model.root)] = root;
  // Parents before children: the depth-first order from the root.
  std::vector<int> stack{model.root};
  std::vector<char> seen(model.links.size(), 0);
  while (!stack.empty()) {
    int link = stack.back();
    stack.pop_back();
    if (seen[static_cast<std::size_t>(link)]) continue;
    seen[static_cast<std::size_t>(link)] = 1;
    for (int j : model.links[static_cast<std::size_t>(link)].childJoints) {
      const Joint& joint = model.joints[static_cast<std::size_t>(j)];
      if (joint.childLink < 0) continue;
      int at = c.coordinateIndex.empty() ? -1 : c.coordinateIndex[static_cast<std::size_t>(j)];
      Pose motion = at >= 0 && at + joint.coordinateDim() <= q.size() ? jointMotion(joint, q.data() + at) : Pose{};
      poses[static_cast<std::size_t>(joint.childLink)] = poses[static_cast<std::size_t>(link)] * joint.origin * motion;
      stack.push_back(joint.childLink);
    }
  }
  return poses;
}

int frameLink(const Model& model, const std::string& name) {
  int j = model.findJoint(name);
  if (j >= 0) return model.joints[static_cast<std::size_t>(j)].childLink;
  return model.findLink(name);
}

}  // namespace rscene::robot
