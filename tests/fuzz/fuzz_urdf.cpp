// libFuzzer target (tests/fuzz/run.sh): the URDF reader on arbitrary bytes, then coordinates,
// forward kinematics and scaling of whatever model it accepts.
#include <tinyxml2.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "robot/kinematics.hpp"
#include "robot/load.hpp"
#include "robot/urdf_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(reinterpret_cast<const char*>(data), size) != tinyxml2::XML_SUCCESS) return 0;
  rscene::robot::Model m;
  rscene::Diagnostics d;
  rscene::robot::LoadOptions o;
  if (!rscene::robot::urdf::loadDocument("/nonexistent/fuzz/robot.urdf", doc, o, m, d)) return 0;
  rscene::robot::Coordinates c;
  rscene::robot::makeCoordinates(m, {}, c);
  Eigen::VectorXd q = rscene::robot::neutralCoordinate(m, c, {});
  rscene::robot::linkPoses(m, c, {}, q);
  rscene::robot::scaleModel(m, {2, 0.5, 3});
  return 0;
}
