// The articulated records of a scene read against their models, once per
// run (robot::makeInstance through one robot::ModelCache), with their
// enabled articulated_ik targets solved before the first step.
#include "robot/ik.hpp"
#include "scene/reader.hpp"
#include "sim/world.hpp"

namespace rscene::sim {

bool makeRobots(const Document& doc, const Scene& scene, std::vector<robot::RobotInstance>& robots,
                Diagnostics& diagnostics, bool allowMissingMeshes, robot::ModelCache* models) {
  robot::ModelCache own;
  robot::ModelCache& cache = models ? *models : own;
  cache.nextScene();  // a shared cache reports each file's load findings to this scene too
  robots.clear();
  robots.resize(scene.articulated.size());
  bool ok = true;
  robot::InstanceOptions io;
  io.allowMissingMeshes = allowMissingMeshes;
  for (std::size_t i = 0; i < scene.articulated.size(); ++i) {
    if (scene.articulated[i].leftOut) continue;  // --allow-missing-assets: no model, not simulated
    if (!robot::checkRobotFile(doc, scene.articulated[i], diagnostics)) {
      ok = false;
      continue;
    }
    if (!robot::makeInstance(doc, scene.articulated[i], cache, robots[i], diagnostics, io)) {
      ok = false;
      continue;
    }
    // (A robot past robot::kMaxRobotBodies is makeInstance's RS7052.)
    // The joints start where the targets put them (a target not reached is
    // a warning, RS7047); --steps 0 writes that pose back.
    ok = robot::solveIk(doc, robots[i], diagnostics) && ok;
  }
  return ok;
}

}  // namespace rscene::sim
