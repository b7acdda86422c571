#include "sim/sensor_paths.hpp"

#include <cstdio>

#include "scene/sensor_check.hpp"

namespace rscene::sim {

std::string sensorFileName(const std::string& path) { return rscene::sensorFileName(path); }

bool safeRelativePath(const std::string& p, std::string& why) {
  if (p.find('\0') != std::string::npos) return why = "it contains a NUL byte", false;
  if (!p.empty() && p.front() == '/') return why = "it is absolute; name a place under the --sensors folder", false;
  std::size_t start = 0;
  while (start <= p.size()) {
    std::size_t end = p.find('/', start);
    if (end == std::string::npos) end = p.size();
    if (p.compare(start, end - start, "..") == 0 && end - start == 2)
      return why = "it has a '..' component; name a place under the --sensors folder", false;
    start = end + 1;
  }
  return true;
}

}  // namespace rscene::sim
