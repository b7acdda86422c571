#include "robot/ik.hpp"

#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/suggest.hpp"
#include "core/text.hpp"
#include "scene/reader.hpp"

namespace rscene::robot {
namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// Rotation vector of a unit quaternion (angle times axis), angle in [0, pi].
Eigen::Vector3d rotationVector(Eigen::Quaterniond q) {
  if (q.w() < 0) q.coeffs() = -q.coeffs();  // the shorter way round
  double s = q.vec().norm();
  if (s < 1e-12) return 2 * q.vec();
  return 2 * std::atan2(s, q.w()) / s * q.vec();
}

Eigen::Quaterniond expRotation(const Eigen::Vector3d& v) {
  double angle = v.norm();
  if (angle < 1e-12) return Eigen::Quaterniond(1, v.x() / 2, v.y() / 2, v.z() / 2).normalized();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, v / angle));
}

std::string number(double v) { return roundedNumber(v, 3); }

// The stacked error of every target at one q, with what it costs.
struct Evaluation {
  Eigen::VectorXd error;  // rows per target: position (3), then weighted orientation (3) when used
  std::vector<IkResidual> residuals;
  double cost = 0;  // squared norm of `error`
  bool reached = true;
};

class Solver {
 public:
  Solver(const Model& m, const Coordinates& c, const Pose& base, const std::vector<IkTarget>& t, const IkSettings& s)
      : model_(m), c_(c), base_(base), targets_(t), settings_(s) {
    for (const IkTarget& target : targets_) rows_ += target.useOrientation ? 6 : 3;
  }

  Evaluation evaluate(const Eigen::VectorXd& q, std::vector<Pose>& poses) const {
    poses = linkPoses(model_, c_, base_, q);
    Evaluation e;
    e.error.resize(rows_);
    int row = 0;
    for (const IkTarget& t : targets_) {
      const Pose& frame = poses[static_cast<std::size_t>(t.link)];
      IkResidual r;
      Eigen::Vector3d dp = t.position - frame.position;
      e.error.segment<3>(row) = dp;
      row += 3;
      r.position = dp.norm();
      bool reached = r.position <= t.positionTolerance;
      if (t.useOrientation) {
        Eigen::Vector3d dr = rotationVector(t.orientation * frame.orientation.conjugate());
        e.error.segment<3>(row) = t.orientationWeight * dr;
        row += 3;
        r.orientation = dr.norm();
        reached = reached && r.orientation <= t.orientationTolerance;
      }
      r.reached = reached;
      e.reached = e.reached && reached;
      e.residuals.push_back(r);
    }
    e.cost = e.error.squaredNorm();
    if (!std::isfinite(e.cost)) e.cost = std::numeric_limits<double>::infinity();
    return e;
  }

  // Rows like Evaluation::error; the base's columns are zero (joints only).
  Eigen::MatrixXd jacobian(const std::vector<Pose>& poses) const {
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(rows_, c_.velocityDim);
    int row = 0;
    for (const IkTarget& t : targets_) {
      Eigen::MatrixXd f =
          frameJacobian(model_, c_, poses, t.link, poses[static_cast<std::size_t>(t.link)].position);
      J.middleRows(row, 3) = f.topRows(3);
      row += 3;
      if (t.useOrientation) {
        J.middleRows(row, 3) = t.orientationWeight * f.bottomRows(3);
        row += 3;
      }
    }
    J.leftCols(c_.baseVelocities).setZero();
    return J;
  }

  Eigen::VectorXd step(const Eigen::MatrixXd& J, const Eigen::VectorXd& e) const {
    Eigen::VectorXd du = Eigen::VectorXd::Zero(J.cols());
    if (J.size() == 0) return du;  // nothing moves (Eigen's SVD asserts on an empty matrix)
    switch (settings_.method) {
      case IkMethod::DampedLeastSquares: {
        // J^T (J J^T + l^2 I)^-1 e, or the same (J^T J + l^2 I)^-1 J^T e
        // when there are fewer coordinates than rows: the smaller system.
        double l2 = settings_.damping * settings_.damping;
        if (J.rows() <= J.cols()) {
          Eigen::MatrixXd A = J * J.transpose();
          A.diagonal().array() += l2;
          du = J.transpose() * A.ldlt().solve(e);
        } else {
          Eigen::MatrixXd A = J.transpose() * J;
          A.diagonal().array() += l2;
          du = A.ldlt().solve(J.transpose() * e);
        }
        break;
      }
      case IkMethod::PseudoInverse: {
        Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeThinU | Eigen::ComputeThinV);
        const Eigen::VectorXd& s = svd.singularValues();
        double cut = s.size() ? settings_.svdTolerance * s[0] : 0;
        Eigen::VectorXd inv = Eigen::VectorXd::Zero(s.size());
        for (Eigen::Index i = 0; i < s.size(); ++i)
          if (s[i] > cut && s[i] > 0) inv[i] = 1 / s[i];
        du = svd.matrixV() * inv.asDiagonal() * (svd.matrixU().transpose() * e);
        break;
      }
      case IkMethod::Transpose: {
        du = J.transpose() * e;
        double gain = settings_.transposeGain;
        if (!(gain > 0)) {  // the gain that minimises |e - J du| along J^T e
          Eigen::VectorXd Jg = J * du;
          double d = Jg.squaredNorm();
          gain = d > 0 ? e.dot(Jg) / d : 0;
        }
        du *= gain;
        break;
      }
    }
    du *= settings_.stepSize;
    double largest = du.size() ? du.cwiseAbs().maxCoeff() : 0;
    if (settings_.maxStep > 0 && largest > settings_.maxStep) du *= settings_.maxStep / largest;
    return du;
  }

  void clampToLimits(Eigen::VectorXd& q) const {
    if (!settings_.enforceJointLimits) return;
    for (int j : c_.joints) {
      const Joint& joint = model_.joints[static_cast<std::size_t>(j)];
      bool limited = joint.type == JointType::Revolute || joint.type == JointType::Prismatic;
      if (!limited || !joint.hasLimits || !(joint.lower <= joint.upper)) continue;
      double& v = q[c_.coordinateIndex[static_cast<std::size_t>(j)]];
      v = std::clamp(v, joint.lower, joint.upper);
    }
  }

 private:
  const Model& model_;
  const Coordinates& c_;
  const Pose& base_;
  const std::vector<IkTarget>& targets_;
  const IkSettings& settings_;
  int rows_ = 0;
};

IkMethod methodOf(const std::string& name) {
  if (name == "pseudo_inverse") return IkMethod::PseudoInverse;
  if (name == "transpose") return IkMethod::Transpose;
  return IkMethod::DampedLeastSquares;
}

}  // namespace

Eigen::MatrixXd frameJacobian(const Model& model, const Coordinates& c, const std::vector<Pose>& poses, int link,
                              const Eigen::Vector3d& point) {
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(6, c.velocityDim);
  if (model.floatingBase && c.baseVelocities == 6) {
    const Eigen::Vector3d r = point - poses[static_cast<std::size_t>(model.root)].position;
    J.block<3, 3>(0, 0).setIdentity();
    J.block<3, 3>(0, 3) = -skew(r);  // w x r
    J.block<3, 3>(3, 3).setIdentity();
  }
  // Up the tree from the link: each movable joint on the way moves the point.
  std::size_t guard = model.joints.size() + 1;
  for (int j = link >= 0 ? model.links[static_cast<std::size_t>(link)].parentJoint : -1; j >= 0 && guard--;) {
    const Joint& joint = model.joints[static_cast<std::size_t>(j)];
    int col = c.velocityIndex.empty() ? -1 : c.velocityIndex[static_cast<std::size_t>(j)];
    if (col >= 0 && joint.childLink >= 0) {
      // The joint frame is its child link's frame (linkPoses: parent * origin * motion).
      const Pose& frame = poses[static_cast<std::size_t>(joint.childLink)];
      const Eigen::Vector3d r = point - frame.position;
      const Eigen::Matrix3d R = frame.orientation.toRotationMatrix();
      switch (joint.type) {
        case JointType::Revolute:
        case JointType::Continuous: {
          Eigen::Vector3d a = R * joint.axis;
          J.block<3, 1>(0, col) = a.cross(r);
          J.block<3, 1>(3, col) = a;
          break;
        }
        case JointType::Prismatic: J.block<3, 1>(0, col) = R * joint.axis; break;
        case JointType::Spherical:  // angular velocity in the joint (child) frame
          for (int k = 0; k < 3; ++k) {
            J.block<3, 1>(0, col + k) = R.col(k).cross(r);
            J.block<3, 1>(3, col + k) = R.col(k);
          }
          break;
        case JointType::Fixed: break;
      }
    }
    if (joint.parentLink < 0) break;
    j = model.links[static_cast<std::size_t>(joint.parentLink)].parentJoint;
  }
  return J;
}

void integrate(const Model& model, const Coordinates& c, Eigen::VectorXd& q, const Eigen::VectorXd& du) {
  if (model.floatingBase && c.baseCoordinates == 7) {
    q.head<3>() += du.head<3>();
    Eigen::Quaterniond b(q[3], q[4], q[5], q[6]);
    b = (expRotation(du.segment<3>(3)) * b).normalized();  // world-frame angular velocity
    q.segment<4>(3) << b.w(), b.x(), b.y(), b.z();
  }
  for (int j : c.joints) {
    const Joint& joint = model.joints[static_cast<std::size_t>(j)];
    int qi = c.coordinateIndex[static_cast<std::size_t>(j)], ui = c.velocityIndex[static_cast<std::size_t>(j)];
    if (joint.type == JointType::Spherical) {
      Eigen::Quaterniond s(q[qi], q[qi + 1], q[qi + 2], q[qi + 3]);
      s = (s * expRotation(du.segment<3>(ui))).normalized();  // joint-frame angular velocity
      q.segment<4>(qi) << s.w(), s.x(), s.y(), s.z();
    } else if (joint.type != JointType::Fixed) {
      q[qi] += du[ui];
    }
  }
}

IkResult solveTargets(const Model& model, const Coordinates& c, const Pose& base, const std::vector<IkTarget>& targets,
                      const IkSettings& settings, Eigen::VectorXd& q) {
  IkResult result;
  if (targets.empty() || targets.size() > kMaxIkTargets || q.size() != c.coordinateDim) return result;
  for (const IkTarget& t : targets)
    if (t.link < 0 || static_cast<std::size_t>(t.link) >= model.links.size()) return result;
  Solver solver(model, c, base, targets, settings);
  const int maxIterations = std::clamp(settings.maxIterations, 0, kMaxIkIterations);
  std::vector<Pose> poses;
  Eigen::VectorXd current = q, best = q;
  Evaluation first, bestEval;
  bestEval.cost = std::numeric_limits<double>::infinity();
  for (int it = 0;; ++it) {
    Evaluation e = solver.evaluate(current, poses);
    if (it == 0) first = e;
    if (e.cost < bestEval.cost) {
      best = current;
      bestEval = e;
    }
    result.iterations = it;
    if (e.reached) {
      result.converged = true;
      bestEval = e;
      best = current;
      break;
    }
    if (it >= maxIterations) break;
    Eigen::VectorXd du = solver.step(solver.jacobian(poses), e.error);
    if (!du.allFinite() || du.isZero(0)) break;  // nothing left to move (or a singular step)
    integrate(model, c, current, du);
    solver.clampToLimits(current);
    if (!current.allFinite()) break;
  }
  if (result.converged || settings.applyBestOnFailure) {
    result.applied = best != q;
    q = best;
    result.residuals = bestEval.residuals;
  } else {
    result.residuals = first.residuals;
  }
  return result;
}

std::vector<std::pair<std::string, std::string>> ikSettingsProblems(const ArticulatedIk& ik) {
  std::vector<std::pair<std::string, std::string>> out;
  auto need = [&](const char* field, double v, bool ok, const char* what) {
    if (!std::isfinite(v) || !ok) out.emplace_back(field, std::string(field) + " is " + number(v) + "; it must be " + what);
  };
  if (ik.maxIterations < 1 || ik.maxIterations > kMaxIkIterations)
    out.emplace_back("maxIterations", "maxIterations is " + std::to_string(ik.maxIterations) + "; it must be 1 to " +
                                          std::to_string(kMaxIkIterations));
  need("positionTolerance", ik.positionTolerance, ik.positionTolerance >= 0, "0 or more");
  need("orientationTolerance", ik.orientationTolerance, ik.orientationTolerance >= 0, "0 or more");
  need("orientationWeight", ik.orientationWeight, ik.orientationWeight >= 0, "0 or more");
  need("damping", ik.damping, ik.damping >= 0, "0 or more");
  need("stepSize", ik.stepSize, ik.stepSize > 0, "more than 0");
  need("maxStep", ik.maxStep, ik.maxStep >= 0, "0 (no limit) or more");
  need("svdTolerance", ik.svdTolerance, ik.svdTolerance >= 0, "0 or more");
  need("finiteDifferenceStep", ik.finiteDifferenceStep, ik.finiteDifferenceStep > 0, "more than 0");
  need("transposeGain", ik.transposeGain, ik.transposeGain >= 0, "0 (automatic) or more");
  if (!ik.target.allFinite()) out.emplace_back("target", "target is not finite");
  const std::string& m = ik.inverseMethod;
  if (m != "damped_least_squares" && m != "pseudo_inverse" && m != "transpose")
    out.emplace_back("inverseMethod",
                     "inverseMethod '" + m + "' is not damped_least_squares, pseudo_inverse or transpose");
  return out;
}

std::string frameHint(const Model& model, const std::string& frame) {
  std::vector<std::string_view> names;
  for (const Joint& j : model.joints) names.push_back(j.name);
  for (const Link& l : model.links) names.push_back(l.name);
  std::string best = closestName(frame, names);
  return best.empty() ? "frames are the model's joint and link names" : "did you mean '" + best + "'?";
}

bool solveIk(const Document& doc, RobotInstance& robot, Diagnostics& diags) {
  if (!robot.model || !robot.record) return false;
  const Model& model = *robot.model;
  std::vector<IkTarget> targets;
  std::vector<const ArticulatedIk*> records;
  IkSettings settings;
  bool ok = true;
  for (const ArticulatedIk& ik : robot.record->ik) {
    if (!ik.enabled) continue;
    RecordReader r(doc, static_cast<std::size_t>(ik.recordIndex), diags);
    for (const auto& [field, message] : ikSettingsProblems(ik)) {
      r.error(field, code::kIkSettings, message);
      ok = false;
    }
    if (targets.size() == kMaxIkTargets) {
      r.error("frame", code::kIkSettings,
              "more than " + std::to_string(kMaxIkTargets) + " enabled IK targets on one articulated system");
      return false;
    }
    IkTarget t;
    t.link = frameLink(model, ik.frame);
    if (t.link < 0) {
      r.error("frame", code::kUnknownFrame, "frame '" + ik.frame + "' is no joint or link of the model '" + model.name + "'",
              frameHint(model, ik.frame));
      ok = false;
      continue;
    }
    if (targets.empty()) {
      settings.method = methodOf(ik.inverseMethod);
      settings.maxIterations = ik.maxIterations;
      settings.damping = ik.damping;
      settings.stepSize = ik.stepSize;
      settings.maxStep = ik.maxStep;
      settings.svdTolerance = ik.svdTolerance;
      settings.transposeGain = ik.transposeGain;
      settings.enforceJointLimits = ik.enforceJointLimits;
      settings.applyBestOnFailure = ik.applyBestOnFailure;
    }
    t.position = ik.target;
    t.useOrientation = ik.useOrientation;
    t.orientation = ik.orientation;
    t.positionTolerance = ik.positionTolerance;
    t.orientationTolerance = ik.orientationTolerance;
    t.orientationWeight = ik.orientationWeight;
    targets.push_back(t);
    records.push_back(&ik);
  }
  if (!ok || targets.empty()) return ok;
  IkResult result = solveTargets(model, robot.coordinates, robot.base, targets, settings, robot.q);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const IkResidual& res = result.residuals[i];
    if (res.reached) continue;
    std::string message = "IK target of frame '" + records[i]->frame + "' not reached after " +
                          std::to_string(result.iterations) + " iterations: position residual " +
                          number(res.position) + " m (tolerance " + number(targets[i].positionTolerance) + ")";
    if (targets[i].useOrientation)
      message += ", orientation residual " + number(res.orientation) + " rad (tolerance " +
                 number(targets[i].orientationTolerance) + ")";
    message += settings.applyBestOnFailure ? "; the best pose found is used" : "; the record's pose is kept";
    RecordReader(doc, static_cast<std::size_t>(records[i]->recordIndex), diags)
        .error("target", code::kIkNotReached, message, {}, Severity::Warning);
  }
  return true;
}

}  // namespace rscene::robot
