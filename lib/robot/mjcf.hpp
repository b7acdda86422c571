// MJCF specifics of robot loading (loadMjcf itself is declared in
// load.hpp): the diagnostic codes only the MJCF reader raises, and the
// conversion of a compiled MuJoCo model into the robot model, apart from
// the loading so that tests can convert a model they compiled themselves.
#pragma once
#include <string>

#include "core/diagnostic.hpp"
#include "robot/model.hpp"

struct mjModel_;

namespace rscene::robot {

namespace code {
// MJCF the robot model cannot hold: a free joint below the top level or
// beside other joints, a second top-level body beside a floating base.
inline constexpr const char* kMjcfUnsupported = "RS7036";
// MJCF element converted approximately (an ellipsoid geom as a sphere), or
// a warning of MuJoCo's compiler.
inline constexpr const char* kMjcfApproximated = "RS7037";
}  // namespace code

// Reads the compiled model `m` (compiled from `path`, named in
// diagnostics) into `out`.  Returns false after an error diagnostic.
//
// The coordinates are MuJoCo's qpos: a joint's value in the robot model is
// its qpos entry, including a joint's `ref` offset (the joint origin holds
// the offset), so a qpos logged in MuJoCo is a generalizedCoordinate here.
bool convertMjcf(const mjModel_& m, const std::string& path, Model& out, Diagnostics& diagnostics);

}  // namespace rscene::robot
