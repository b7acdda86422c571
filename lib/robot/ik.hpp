// Inverse kinematics of articulated_ik targets: joint positions that put
// named frames at target positions (and orientations), solved before a
// simulation steps (rscene-sim) and shared by nothing else.
//
// Choices (README, "Robots: inverse kinematics"):
// - The Jacobian is analytic (from the joint axes at the current pose), so
//   `finiteDifferenceStep` is read, range-checked and otherwise unused; a
//   unit test holds the analytic Jacobian to finite differences.
// - A floating base stays where the record puts it: only the joints move
//   (feet placed under a body that is where the scene says it is).
// - The targets of one robot are solved together, their rows stacked.  The
//   solver's knobs (method, iterations, damping, step size, maximum step,
//   SVD tolerance, transpose gain, limits, applyBestOnFailure) are the
//   first enabled target's; tolerances and orientationWeight are each
//   target's own.
// - Targets are in world coordinates, orientations w x y z in the world.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "core/codes.hpp"
#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "robot/instance.hpp"
#include "robot/kinematics.hpp"

namespace rscene::robot {

namespace code {
inline constexpr const char* kUnknownFrame = rs::RS7044;   // articulated_ik frame that is no joint or link of the model
inline constexpr const char* kIkNotReached = rs::RS7047;   // IK target not reached within its tolerances (warning)
inline constexpr const char* kIkSettings = rs::RS7048;     // articulated_ik knob that cannot be used
}  // namespace code

// Iterations are capped so a hostile maxIterations cannot hang a run, and
// the enabled targets of one robot so the stacked Jacobian (6 rows each)
// stays small whatever the scene holds (RS7048 past either).
inline constexpr int kMaxIkIterations = 10000;
inline constexpr std::size_t kMaxIkTargets = 1000;

enum class IkMethod { DampedLeastSquares, PseudoInverse, Transpose };

struct IkTarget {
  int link = -1;  // the frame's link (robot::frameLink)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  bool useOrientation = false;
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  double positionTolerance = 1e-3;     // m
  double orientationTolerance = 1e-2;  // rad
  double orientationWeight = 0.5;      // orientation rows (rad) against position rows (m)
};

struct IkSettings {
  IkMethod method = IkMethod::DampedLeastSquares;
  int maxIterations = 80;
  double damping = 0.05;       // lambda of (J J^T + lambda^2 I)
  double stepSize = 0.5;       // fraction of the solved step taken
  double maxStep = 0.1;        // largest change of one coordinate per iteration (rad or m); 0 = none
  double svdTolerance = 1e-6;  // pseudo-inverse: singular values below this times the largest are dropped
  double transposeGain = 0;    // transpose: the step's gain; 0 = the error-minimising gain of each step
  bool enforceJointLimits = true;
  bool applyBestOnFailure = true;
};

struct IkResidual {
  double position = 0;     // m
  double orientation = 0;  // rad (0 when the target has no orientation)
  bool reached = false;
};

struct IkResult {
  bool converged = false;
  int iterations = 0;
  bool applied = false;  // q was changed (converged, or the best pose on failure)
  std::vector<IkResidual> residuals;  // per target, at the q returned
};

// Jacobian of a point fixed to `link` (at world position `point`) and of
// the link's rotation, in the generalized velocity u: rows 0-2 linear
// velocity, 3-5 angular velocity, both in the world frame (RaiSim's
// convention, ArticulatedSystem.rst "Jacobians").  `poses` are linkPoses at q.
Eigen::MatrixXd frameJacobian(const Model& model, const Coordinates& c, const std::vector<Pose>& poses, int link,
                              const Eigen::Vector3d& point);

// Moves q by a generalized velocity step du (joints: q += du; spherical
// joints and the floating base: quaternion times exp(du)).
void integrate(const Model& model, const Coordinates& c, Eigen::VectorXd& q, const Eigen::VectorXd& du);

// Solves `targets` together for q (joints only).  q is replaced when the
// targets are reached, or by the best pose found when they are not and
// settings.applyBestOnFailure; otherwise it is left as it was.
IkResult solveTargets(const Model& model, const Coordinates& c, const Pose& base, const std::vector<IkTarget>& targets,
                      const IkSettings& settings, Eigen::VectorXd& q);

// What is wrong with one articulated_ik record's knobs: (field, message)
// pairs, none when every knob can be used.  Shared by rscene-validate and
// solveIk so both refuse the same records (RS7048).
std::vector<std::pair<std::string, std::string>> ikSettingsProblems(const ArticulatedIk& ik);

// The did-you-mean hint for a frame name the model lacks ("did you mean
// 'LF_FOOT'?"), or empty.
std::string frameHint(const Model& model, const std::string& frame);

// Solves the enabled articulated_ik targets of `robot`'s record for its q.
// Errors at the record's fields: an unknown frame (RS7044), a knob that
// cannot be used (RS7048); then nothing is solved and it returns false.  A
// target not reached is a warning naming its residual (RS7047), and true.
bool solveIk(const Document& doc, RobotInstance& robot, Diagnostics& diagnostics);

}  // namespace rscene::robot
