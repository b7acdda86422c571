#include "sim/prepare.hpp"

#include <cstdio>

#include "core/suggest.hpp"
#include "robot/check.hpp"
#include "robot/instance.hpp"
#include "robot/sensors.hpp"
#include "sim/limits.hpp"

namespace rscene::sim {
namespace {

bool noNewErrors(const Diagnostics& ds, std::size_t before) {
  for (std::size_t i = before; i < ds.size(); ++i)
    if (ds[i].severity == Severity::Error) return false;
  return true;
}

std::vector<std::shared_ptr<const robot::Model>> modelsOf(const std::vector<robot::RobotInstance>& robots) {
  std::vector<std::shared_ptr<const robot::Model>> models;  // indexed like Scene::articulated, as robots are
  for (const robot::RobotInstance& r : robots) models.push_back(r.model);
  return models;
}

// The step count, before anything is built: --max-steps bounds the run.
bool stepCount(const Document& doc, const PrepareOptions& o, double timeStep, std::uint64_t& total,
               Diagnostics& ds) {
  if (o.steps) {
    total = *o.steps;
    if (total <= o.maxSteps) return true;
    ds.push_back(tooManySteps(doc, "--steps " + std::to_string(total), o.maxSteps));
    return false;
  }
  if (std::optional<std::uint64_t> n = stepsFor(o.duration, timeStep, o.maxSteps)) {
    total = *n;
    return true;
  }
  char what[128];
  std::snprintf(what, sizeof what, "--duration %g at time_step %g is %.3g steps", o.duration, timeStep,
                o.duration / timeStep);
  ds.push_back(tooManySteps(doc, what, o.maxSteps));
  return false;
}

// --pd-gains naming a joint no articulated system has as a movable one.
std::string unknownJoint(const PdGains& pd, const std::vector<robot::RobotInstance>& robots) {
  for (const std::string& name : unknownPdJoints(pd, robots)) {
    std::vector<std::string_view> movable;  // every robot's movable joints, for the suggestion
    for (const robot::RobotInstance& r : robots)
      if (r.model)
        for (int j : r.coordinates.joints) movable.push_back(r.model->joints[static_cast<std::size_t>(j)].name);
    std::string close = closestName(name, movable);
    return "--pd-gains names joint '" + name + "', which no articulated system has as a movable joint" +
           (close.empty() ? std::string() : "; did you mean '" + close + "'?");
  }
  return {};
}

int leftOut(const Scene& scene) {
  int n = 0;
  for (const Articulated& a : scene.articulated) n += a.leftOut;
  return n;
}

}  // namespace

bool prepareSimulation(const Document& doc, const PrepareOptions& o, asset::AssetCache& assets, Prepared& out,
                       Diagnostics& ds, std::string& usageError) {
  const SceneOptions& so = o.scene;
  // lib/core's verdict first, as validate gives it; the model is built
  // only from a document that has none.
  bool ok = robot::checkDocument(doc, so.baseDir.empty() ? so.sceneDir : so.baseDir, ds) &&
            buildScene(doc, so, out.scene, ds);
  if (ok && o.allowMissingAssets) {
    skipBodiesWithMissingMeshes(doc, out.scene, assets, ds);
    robot::leaveOutMissingRobots(doc, out.scene, ds);
  }
  ok = ok && checkPhysics(doc, out.scene, ds, assets.fileSystem(), assets.meshReader(asset::MeshContent::Geometry));
  ok = ok && stepCount(doc, o, out.scene.timeStep, out.steps, ds);
  WorldOptions wo;
  wo.assets = &assets;
  wo.maxPairs = o.maxPairs;
  wo.document = &doc;
  wo.allowMissingAssets = o.allowMissingAssets;
  ok = ok && makeRobots(doc, out.scene, out.robots, ds, o.allowMissingAssets, o.models);
  wo.robots = &out.robots;
  if (!parsePdGains(o.pdGains, wo.pd, usageError)) return false;
  const int robotsLeftOut = ok ? leftOut(out.scene) : 0;
  if (robotsLeftOut > 0) {
    // The joint may be one of a robot left out, whose joints are not known:
    // a warning, not a usage error.
    for (const std::string& name : unknownPdJoints(wo.pd, out.robots)) {
      Diagnostic d;
      d.severity = Severity::Warning;
      d.code = scene_code::kMissingFile;
      d.message = "--pd-gains names joint '" + name +
                  "', which no articulated system loaded has as a movable joint; its gains are not used (" +
                  std::to_string(robotsLeftOut) + " left out by --allow-missing-assets)";
      ds.push_back(std::move(d));
    }
  } else if (ok) {
    usageError = unknownJoint(wo.pd, out.robots);
  }
  if (!usageError.empty()) return false;
  if (ok) {
    // --sensors: what will be recorded, checked before anything is built;
    // without it the sensors' mounts all the same (RS7045, as validate and
    // render say).
    std::size_t before = ds.size();
    std::vector<robot::SensorSpec> all = robot::collectSensors(doc, out.scene, modelsOf(out.robots), ds);
    if (o.recordSensors) {
      SensorPlanOptions po;
      po.imuFormat = o.imuFormat;
      out.sensors = planSensors(doc, all, po, ds);
    }
    ok = noNewErrors(ds, before);
  }
  if (ok) out.world = World::create(out.scene, ds, wo);
  // The deformables' work for the whole run, now that the step count and
  // their constraints are known: refused up front past the cap (RS7075).
  if (out.world && !checkDeformableWork(doc, *out.world, out.steps, ds)) out.world.reset();
  // The granular records' likewise (RS7093).
  if (out.world && !checkGranularWork(doc, *out.world, out.steps, ds)) out.world.reset();
  if (auto w = unsupportedWarning(out.scene)) ds.push_back(*w);
  return out.world != nullptr;
}

}  // namespace rscene::sim
