#include "sim/sensor_paths.hpp"

#include <cstdio>

#include "scene/sensor_check.hpp"

namespace rscene::sim {

std::string sensorFileName(const std::string& path) { return rscene::sensorFileName(path); }

bool safeRelativePath(const std::string& p, std::string& why) {
  // The scene model's one rule for an outputPath (NUL, absolute, a drive,
  // '..' in '/' or '\\' parts): validate says the same of the record.
  why = rscene::outputPathProblem(p);
  if (why.empty()) return true;
  why = "it " + why + "; name a place under the --sensors folder";
  return false;
}

}  // namespace rscene::sim
