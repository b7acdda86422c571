// Where rscene-sim --sensors DIR writes a sensor's stream, relative to DIR
// (the rule itself is scene/sensor_check.hpp's, which validate uses too).
//
// A sensor's default name is its path made one safe file name: the leading
// '/' dropped, every other '/' written '+', bytes other than ASCII letters,
// digits, '.', '_' and '-' (so '+' and '%' themselves too) written %XX
// (upper-case hex), and a '.' that starts a component written %2E (no
// hidden file, never "." or "..").  Every output byte sequence decodes back
// to one path, so two sensors (whose paths all start with '/') never share
// a name:  /World/Robot/Imu -> World+Robot+Imu,
//   /World/anymal/os1_64/lidar (a URDF sensor set) -> World+anymal+os1_64+lidar.
// A record's outputPath, where set, is used instead, as written, relative
// to DIR: an absolute path or one with a '..' component is refused (RS7069,
// scene/sensor_check.hpp).
#pragma once
#include <string>

namespace rscene::sim {

std::string sensorFileName(const std::string& sensorPath);

// Whether `outputPath` may name a place under the sensors directory; why
// not in `why` (lower-case).  Empty and "-" mean "not set" and are not
// asked about.
bool safeRelativePath(const std::string& outputPath, std::string& why);

}  // namespace rscene::sim
