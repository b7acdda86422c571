// TEMPORARY: replaced by the mjcf branch
// Lets the urdf branch link (loadModel dispatches <mujoco> files here)
// before MuJoCo support lands; the lead takes the mjcf branch's file.
#include "robot/load.hpp"

namespace rscene::robot {

bool loadMjcf(const std::string& path, const LoadOptions&, Model&, Diagnostics& diagnostics) {
  Diagnostic d;
  d.code = code::kBadFile;
  d.file = path;
  d.message = "MJCF support is not in this build";
  diagnostics.push_back(d);
  return false;
}

}  // namespace rscene::robot
