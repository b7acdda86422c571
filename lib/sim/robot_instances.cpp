// The articulated records of a scene read against their models, once per
// run (robot::makeInstance through one robot::ModelCache).
#include "sim/world.hpp"

namespace rscene::sim {

bool makeRobots(const Document& doc, const Scene& scene, std::vector<robot::RobotInstance>& robots,
                Diagnostics& diagnostics) {
  robot::ModelCache cache;
  robots.clear();
  robots.resize(scene.articulated.size());
  bool ok = true;
  for (std::size_t i = 0; i < scene.articulated.size(); ++i)
    ok = robot::makeInstance(doc, scene.articulated[i], cache, robots[i], diagnostics) && ok;
  return ok;
}

}  // namespace rscene::sim
