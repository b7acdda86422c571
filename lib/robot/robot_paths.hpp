// Where the files a robot description names are found: meshes and
// textures (package://, relative, absolute) and URDF modules, each in
// RaiSim's search order.  Existence is asked through a callback so tests
// can use an in-memory file set; nothing here reads a file.
#pragma once
#include <string>
#include <vector>

#include "core/assets.hpp"  // FileExists

namespace rscene::robot {

struct RobotPaths {
  std::string resourceDirectory;  // the record's resourceDirectory=, empty = none
  std::string robotDirectory;     // directory of the URDF being read
};

// The places where `uri` (a mesh or texture filename as written in an
// element of the file in `elementDirectory`) may be, in the order tried:
//   absolute (or file://ABS): as is;
//   package://NAME/REST (and Gazebo's model://NAME/REST): RaiSim resolves a
//     package against its resource directory, so first RES/REST and
//     RES/NAME/REST; then, walking up from the URDF's directory to the
//     file-system root, DIR/REST and DIR/NAME/REST, which finds the usual
//     ROS layout (a package folder holding urdf/ and meshes/) under any
//     folder name, as ANYmal C's `anymal_c_simple_description` does;
//   relative: elementDirectory/PATH, then RES/PATH.
std::vector<std::string> meshCandidates(const RobotPaths& paths, const std::string& elementDirectory,
                                        const std::string& uri);

// The first candidate that exists; empty when none does.
std::string resolveRobotFile(const RobotPaths& paths, const std::string& elementDirectory, const std::string& uri,
                             const FileExists& exists = fileExistsOnDisk);

// Module search order (ArticulatedSystem.rst, "URDF modules"), first match
// wins: absolute; BASE/M; BASE/modules/M; BASE/../modules/M; BASE/module/M;
// BASE/../module/M, where BASE is the resource directory when given, else
// the URDF's directory.
std::vector<std::string> moduleCandidates(const RobotPaths& paths, const std::string& module);

// Directory part of a file path ("" -> ".").
std::string parentDirectory(const std::string& path);

}  // namespace rscene::robot
