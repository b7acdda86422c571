// What rscene-validate says about robots: each articulated record read
// against its model (robot::makeInstance: RS7040-RS7043), its IK targets
// (frames RS7044, knobs RS7048), sensors on its links (RS7045) and wires
// to its bodies (RS7046).  With checkFiles, also whether the robot file
// loads (RS7030-RS7034, RS5001 for its meshes), findings that name the
// robot file and the line in it (Diagnostic::file).
//
// Without checkFiles, a model that cannot be read is not mentioned (that is
// --check-files' job) and the checks that need it are skipped; what is
// wrong inside a sensor-set file that was found (RS7061, RS7062,
// RS7064-RS7067: sim and render refuse those) is said all the same.  A
// sensor record named as a robot's sensor-set sensor is RS7070.  A robot
// file that does not exist is lib/core's RS5001 at the scene's path field.
#pragma once
#include <vector>

#include "core/codes.hpp"
#include "core/assets.hpp"
#include "core/document.hpp"
#include "robot/kinematics.hpp"
#include "robot/load.hpp"
#include "scene/scene.hpp"
#include "scene/triangle_surface.hpp"
#include "scene/validate.hpp"

namespace rscene::robot {

namespace code {
inline constexpr const char* kSensorLink = rs::RS7045;  // sensor parentLink that is no link of its robot
inline constexpr const char* kWireBody = rs::RS7046;    // wire localIndexA/B past the robot's body count
}  // namespace code

struct RobotCheckOptions {
  bool checkFiles = false;
  FileExists exists = fileExistsOnDisk;
  // With checkFiles: reads a collision mesh as rscene-sim builds it (a
  // mesh that does not read is RS7007 at the articulated record's resource
  // field, where sim says it); empty: not read.
  MeshReader readMesh;
};

// RaiSim's body count of a robot: every movable body, the base included
// (fixed bodies merge into the movable body they hang from), so a wire's
// localIndex runs from 0 to movable joints.
int bodyCount(const Coordinates& c);

// Appends the findings about every articulated record of `scene` to `out`,
// a finding inside a robot file listed at the line of the record that
// names the file.  `cache` should live for one scene: a model's load
// findings are reported by its first request only.
void checkRobots(const Document& doc, const Scene& scene, const RobotCheckOptions& options, ModelCache& cache,
                 std::vector<SceneFinding>& out);

// rscene::checkDocument (scene/validate.hpp) with these robot checks: the
// verdict rscene-validate gives a scene (no files), which rscene-sim,
// rscene-render and rscene-to-xml take before they build their model.
bool checkDocument(const Document& doc, const std::string& sceneDir, Diagnostics& out);

}  // namespace rscene::robot
