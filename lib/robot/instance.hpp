// One articulated record read against its model: the one reading of a
// robot's state that sim, render and validate share (so they cannot
// disagree about where a robot stands).
#pragma once
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "core/codes.hpp"
#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "robot/kinematics.hpp"
#include "robot/load.hpp"
#include "scene/scene.hpp"

namespace rscene::robot {

// Diagnostic codes of an articulated record read against its model.
namespace code {
inline constexpr const char* kCoordinateLength = rs::RS7040;  // generalizedCoordinate length differs from the model's
inline constexpr const char* kVelocityLength = rs::RS7041;    // generalizedVelocity length differs from the model's
inline constexpr const char* kJointOrder = rs::RS7042;        // jointOrder names an unknown, fixed or repeated joint, or omits one
inline constexpr const char* kQuaternion = rs::RS7043;        // quaternion in generalizedCoordinate not of unit length (warning) or zero
inline constexpr const char* kStateRange = rs::RS7049;        // coordinate or velocity entry beyond 1e12 (or not finite)
inline constexpr const char* kStartLimits = rs::RS7056;      // warning: a start pose with a joint outside its limits
inline constexpr const char* kTooLarge = rs::RS7052;          // more than kMaxRobotBodies bodies
}  // namespace code

// Most bodies (movable joints + 1) of one robot: Bullet's cost grows with
// the square of a robot's bodies (its self-collision pairs), and 20,000
// links took 8 GB and then crashed.  A rule of the instance, so validate,
// sim and render refuse such a robot alike.
inline constexpr std::size_t kMaxRobotBodies = 1000;

struct RobotInstance {
  const Articulated* record = nullptr;
  std::shared_ptr<const Model> model;
  Coordinates coordinates;
  Pose base;          // the record's world pose (fixed base: where it is fixed)
  Eigen::VectorXd q;  // generalized coordinate, quaternions normalised
  Eigen::VectorXd u;  // generalized velocity
};

struct InstanceOptions {
  bool reportModel = true;  // false: a missing or broken model is left to --check-files (validate)
  bool allowMissingMeshes = false;  // --allow-missing-assets (LoadOptions)
};

// Loads the record's model through `cache` and reads its state: q from
// generalizedCoordinate (base pose from the record when it has none), u
// from generalizedVelocity (zeros when absent).  A length that does not
// match the model is an error at the field (RS7040, RS7041); a non-unit
// quaternion is normalised with a warning (RS7043).  Returns false after an
// error; `out.model` is null when the model did not load.
bool makeInstance(const Document& doc, const Articulated& record, ModelCache& cache, RobotInstance& out,
                  Diagnostics& diagnostics, const InstanceOptions& options = {});

// Where a field an articulated record shares with its resource was
// written: the articulated record when it writes it (or names no
// resource), else its resource record.  Findings about the field point
// there.  The record's `sourcePath` is the resource's `path`.
struct FieldSource {
  int record = -1;            // record index
  const char* field = nullptr;  // the field's name in that record
};
FieldSource writtenBy(const Document& doc, const Articulated& record, const char* field);

// RS5001 at the field that names the robot file when that file is not a
// regular file (render, sim and validate --check-files say it there, not
// in a file that does not exist).  False after the error.
bool checkRobotFile(const Document& doc, const Articulated& record, Diagnostics& diagnostics);

// rscene-sim and rscene-render --allow-missing-assets: every articulated
// record whose robot file is not a regular file is marked leftOut, with
// one warning (RS5001) per file at the field that names it, naming the
// first robot and how many more; wires and sensors attached to one are
// disabled with a warning (scene/left_out.hpp).  Returns how many robots
// were left out.
int leaveOutMissingRobots(const Document& doc, Scene& scene, Diagnostics& diagnostics);

// LoadOptions of a record (its resource directory, modules and scale);
// `allowMissingMeshes` as LoadOptions says.
LoadOptions loadOptionsOf(const Articulated& record, bool allowMissingMeshes = false);

// World poses of the instance's links at its current q.
inline std::vector<Pose> linkPoses(const RobotInstance& r) {
  return linkPoses(*r.model, r.coordinates, r.base, r.q);
}

}  // namespace rscene::robot
