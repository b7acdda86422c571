// The `state qpos qvel` of an exported articulated system: the record's
// generalized coordinate as written, else one made from its world pose
// (a floating base) and zero joints with the model's sizes (lib/robot),
// in RaiSim's joint order (a jointOrder= list is undone, as the XML has
// none).  The same reading of the record as rscene-sim's (makeInstance),
// so a length the model refuses is the same error here.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "robot/load.hpp"
#include "scene/scene.hpp"

namespace rscene::xml {

struct RobotExport {
  bool modelLoaded = false;
  std::optional<std::vector<double>> qpos, qvel;  // absent: not written
  Diagnostics diagnostics;         // errors refuse the export; RS8131 when the model does not load
  std::vector<std::string> losses;  // what the XML cannot say ("fixed base away from the origin")
};

RobotExport exportRobotState(const Document& doc, const Articulated& record, robot::ModelCache& cache);

}  // namespace rscene::xml
