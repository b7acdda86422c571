// What the simulator refuses before building a world (world.hpp).
#include <cmath>
#include <set>

#include "scene/reader.hpp"
#include "sim/world.hpp"

namespace rscene::sim {
namespace {

bool positive(double v) { return std::isfinite(v) && v > 0; }

// Size problem of a primitive, or empty.
std::string sizeProblem(const std::string& prim, const Eigen::Vector3d& box, double radius, double height) {
  if (prim == "box" && !(positive(box.x()) && positive(box.y()) && positive(box.z()))) return "box with a zero side";
  if ((prim == "sphere" || prim == "cylinder" || prim == "capsule") && !positive(radius))
    return prim + " with zero radius";
  if (prim == "cylinder" && !positive(height)) return "cylinder with zero height";
  if (prim == "capsule" && !(height >= 0)) return "capsule with negative height";
  return {};
}

}  // namespace

bool checkPhysics(const Document& doc, const Scene& scene, Diagnostics& diagnostics) {
  std::size_t before = diagnostics.size();
  std::set<std::string> names;
  for (const Object& o : scene.objects) {
    RecordReader r(doc, static_cast<std::size_t>(o.recordIndex), diagnostics);
    names.insert(o.id);
    names.insert(o.path);
    if (o.bodyMode == BodyMode::VisualOnly || o.primitive == "ground" || o.primitive == "half_space") continue;
    if (o.bodyMode == BodyMode::Dynamic && !(o.mass > 0))
      r.error("mass", scene_code::kBadMass, "dynamic body '" + o.path + "' needs a mass > 0",
              "give it a positive mass, or make it static");
    std::string problem = sizeProblem(o.primitive, o.scale, o.physicsRadius(), o.physicsHeight());
    if (o.primitive == "mesh" && !positive(o.meshScale())) problem = "mesh with zero scale";
    if (!problem.empty())
      r.error(o.primitive == "box" || o.primitive == "mesh" ? "scale" : "radius", scene_code::kZeroSize,
              problem + " ('" + o.path + "')");
    if (o.primitive == "mesh") {
      if (o.collisionMeshPath.empty())
        r.error("meshPath", scene_code::kMissingFile, "mesh object '" + o.path + "' has no mesh file");
      else if (!fileExistsOnDisk(o.collisionMeshPath))
        r.error(r.has("collisionMeshPath") ? "collisionMeshPath" : "meshPath", scene_code::kMissingFile,
                "mesh file '" + o.collisionMeshPath + "' does not exist");
    }
  }
  for (const Compound& c : scene.compounds) {
    RecordReader r(doc, static_cast<std::size_t>(c.recordIndex), diagnostics);
    names.insert(c.id);
    names.insert(c.path);
    if (c.bodyMode == BodyMode::VisualOnly) continue;
    if (c.bodyMode == BodyMode::Dynamic && !(c.mass > 0))
      r.error("mass", scene_code::kBadMass, "dynamic compound '" + c.path + "' needs a mass > 0");
    for (const CompoundChild& ch : c.children) {
      RecordReader cr(doc, static_cast<std::size_t>(ch.recordIndex), diagnostics);
      Eigen::Vector3d s = ch.scale.cwiseProduct(c.scale);
      Eigen::Vector3d box = ch.size.isZero() ? s : ch.size.cwiseProduct(s);
      std::string problem = sizeProblem(ch.primitive, box, ch.radius * s.x(), ch.height * s.z());
      if (!problem.empty()) cr.error("size", scene_code::kZeroSize, problem + " in compound '" + c.path + "'");
      if (ch.primitive == "mesh" && !fileExistsOnDisk(ch.meshPath))
        cr.error("meshPath", scene_code::kMissingFile, "mesh file '" + ch.meshPath + "' does not exist");
    }
  }
  for (const Terrain& t : scene.terrains) {
    names.insert(t.id);
    names.insert(t.path);
  }
  for (const Wire& w : scene.wires) {
    if (!w.enabled) continue;
    RecordReader r(doc, static_cast<std::size_t>(w.recordIndex), diagnostics);
    if (!(w.length >= 0)) r.error("length", scene_code::kBadValue, "wire '" + w.path + "' has a negative length");
    for (const std::string* ref : {&w.bodyA, &w.bodyB})
      if (!ref->empty() && !names.count(*ref))
        r.error(ref == &w.bodyA ? "bodyA" : "bodyB", scene_code::kUnknownRef,
                "wire '" + w.path + "' names unknown body '" + *ref + "'");
  }
  for (std::size_t i = before; i < diagnostics.size(); ++i)
    if (diagnostics[i].severity == Severity::Error) return false;
  return true;
}

std::optional<Diagnostic> unsupportedWarning(const Scene& scene) {
  std::string list;
  std::set<std::string> seen;
  // Scene records with physics this simulator does not model; purely
  // visual ones (decals, probes, fog volumes ...) are not worth a warning.
  auto physical = [](const std::string& tag) {
    return tag == "articulated" || tag == "articulated_ik" || tag == "deformable" || tag == "granular" ||
           tag == "sensor";
  };
  for (const SkippedRecord& s : scene.skipped) {
    if (!physical(s.tag) || !seen.insert(s.tag).second) continue;
    std::size_t n = 0;
    for (const SkippedRecord& t : scene.skipped) n += t.tag == s.tag;
    list += (list.empty() ? "" : ", ") + s.tag + " (" + std::to_string(n) + ")";
  }
  if (list.empty()) return std::nullopt;
  Diagnostic d;
  d.severity = Severity::Warning;
  d.code = scene_code::kUnsupported;
  d.message = "not simulated, kept unchanged: " + list;
  return d;
}

}  // namespace rscene::sim
