#include "sim/sensor_paths.hpp"

#include <cstdio>

namespace rscene::sim {

std::string sensorFileName(const std::string& path) {
  std::string out;
  bool componentStart = true;
  for (std::size_t i = !path.empty() && path[0] == '/' ? 1 : 0; i < path.size(); ++i) {
    unsigned char c = static_cast<unsigned char>(path[i]);
    bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
                 (c == '.' && !componentStart);
    componentStart = c == '/';
    if (c == '/') {
      out += '+';
    } else if (plain) {
      out += static_cast<char>(c);
    } else {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", c);
      out += hex;
    }
  }
  return out.empty() ? "%2F" : out;  // the path "/" alone (never a sensor's, but total)
}

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
