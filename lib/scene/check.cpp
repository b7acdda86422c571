#include "scene/check.hpp"

#include "core/check.hpp"

#include <cmath>
#include <set>
#include <tuple>

#include "scene/deformable_check.hpp"
#include "scene/deformable_model.hpp"
#include "scene/granular.hpp"
#include "scene/limits.hpp"
#include "scene/reader.hpp"
#include "scene/sensor_check.hpp"
#include "scene/start_pose.hpp"

namespace rscene {
namespace {

bool positive(double v) { return std::isfinite(v) && v > 0; }

// Size problem of a primitive at physical size, or empty.
std::string sizeProblem(const std::string& prim, const Eigen::Vector3d& box, double radius, double height) {
  if (prim == "box" && !(positive(box.x()) && positive(box.y()) && positive(box.z())))
    return "box with a zero or negative side";
  if ((prim == "sphere" || prim == "cylinder" || prim == "capsule") && !positive(radius))
    return prim + " with a zero or negative radius";
  if (prim == "cylinder" && !positive(height)) return "cylinder with a zero or negative height";
  if (prim == "capsule" && !(height >= 0)) return "capsule with a negative height";
  return {};
}

// The field a size problem is reported at: what the user would change.
const char* sizeField(const std::string& prim, const std::string& problem, bool child, const RecordReader& r) {
  if (prim == "box") return child && r.has("size") ? "size" : "scale";
  if (prim == "mesh") return "scale";
  if (problem.find("height") != std::string::npos) return "height";
  return child && !r.has("radius") ? "primitive" : "radius";
}

class Checker {
 public:
  Checker(const Document& doc, const Scene& scene, const SceneCheckOptions& opt, Diagnostics& out)
      : doc_(doc), s_(scene), opt_(opt), out_(out) {}

  void run() {
    // A body record with a value its reader could not parse (RS2xxx,
    // already in `out_`) is not judged by the rules below: they read the
    // fallback, and one typo would be two errors (`0.8x` as a side is
    // RS2001, not also a zero-size box; `spacing=0.043m` not also a fill
    // past maxParticles).  The typo's error stands; fix it and the rules run.
    for (const Diagnostic& d : out_) {
      const CheckInfo* info = checkInfo(d.code);
      if (d.severity == Severity::Error && d.file.empty() && info && info->layer == CheckLayer::Core)
        unparsed_.insert(d.line);
    }
    const bool stepUnparsed = s_.timeStepRecord >= 0 && !judged(s_.timeStepRecord);
    if (!stepUnparsed) timeStep();
    for (const Object& o : s_.objects)
      if (judged(o.recordIndex)) object(o);
    for (const Compound& c : s_.compounds)
      if (judged(c.recordIndex)) compound(c);
    for (const Wire& w : s_.wires) wire(w);
    for (const Deformable& d : s_.deformables)
      if (judged(d.recordIndex)) deformable(d);
    for (const Granular& g : s_.granulars)  // their substeps depend on the time step too
      if (judged(g.recordIndex) && !stepUnparsed) granular(g);
    if (opt_.visualAssets) {
      for (const Terrain& t : s_.terrains)
        for (const FoliageLayer& l : t.foliageLayers)
          if (judged(l.recordIndex)) foliage(l);
      for (const InstancedVisual& v : s_.instancedVisuals)
        if (judged(v.recordIndex)) instanced(v);
    }
  }

  bool judged(int recordIndex) const {
    return recordIndex < 0 || !unparsed_.count(doc_.records[static_cast<std::size_t>(recordIndex)].line);
  }

 private:
  RecordReader reader(int recordIndex) const { return {doc_, static_cast<std::size_t>(recordIndex), out_}; }

  void timeStep() {
    if (s_.timeStepRecord < 0 || positive(s_.timeStep)) return;
    reader(s_.timeStepRecord)
        .error("dt", scene_code::kBadTimeStep, "time step must be positive", "Engine 2 writes 0.0025 (400 Hz)");
  }

  void mass(const RecordReader& r, BodyMode mode, double mass, const std::string& path) {
    if (mode == BodyMode::Dynamic && !(mass > 0))
      r.error("mass", scene_code::kBadMass, "dynamic body '" + path + "' needs a mass > 0",
              "give it a positive mass, or make it static or kinematic");
  }

  void meshFile(const RecordReader& r, const std::string& resolved, const char* field, const std::string& path) {
    if (resolved.empty()) {
      r.error(field, scene_code::kNoMesh, "mesh body '" + path + "' has no mesh file");
      return;
    }
    if (opt_.checkFiles && !opt_.exists(resolved))
      r.error(field, scene_code::kMissingFile, "mesh file '" + resolved + "' " + whyNotAFile(resolved),
              "paths resolve against the scene's directory, then against asset_root");
    else
      readable(r, resolved, field, "body '" + path + "': ");
  }

  // RS7007 when an existing mesh file does not read as a mesh (readMesh).
  // `who` starts the message, as rscene-sim's World said it ("body 'P': ").
  void readable(const RecordReader& r, const std::string& resolved, const char* field, const std::string& who) {
    std::string why;
    if (opt_.readMesh && !resolved.empty() && opt_.exists(resolved) && !opt_.readMesh(resolved, why))
      r.error(field, scene_code::kBadMesh, who + "cannot read mesh '" + resolved + "': " + why);
  }

  void foliage(const FoliageLayer& l) {
    if (l.enabled && l.primitive == "mesh") readable(reader(l.recordIndex), l.meshPath, "meshPath", "foliage layer '" + l.name + "': ");
  }

  // An enabled mesh with instances (shown or hidden by its group: the
  // file is judged the same in validate's build, which resolves no groups).
  void instanced(const InstancedVisual& v) {
    if (v.enabled && !v.instances.empty() && v.primitive == "mesh")
      readable(reader(v.recordIndex), v.meshPath, "meshPath", "instanced visual '" + v.path + "': ");
  }

  void object(const Object& o) {
    if (o.bodyMode == BodyMode::VisualOnly || o.primitive == "ground" || o.primitive == "half_space") return;
    RecordReader r = reader(o.recordIndex);
    mass(r, o.bodyMode, o.mass, o.path);
    std::string problem = sizeProblem(o.primitive, o.scale, o.physicsRadius(), o.physicsHeight());
    if (o.primitive == "mesh" && !positive(o.meshScale())) problem = "mesh with a zero or negative scale";
    if (!problem.empty())
      r.error(sizeField(o.primitive, problem, false, r), scene_code::kZeroSize, problem + " ('" + o.path + "')",
              "sizes are box sides, radius x scale.x and height x scale.z (compat-notes.md)");
    if (o.primitive == "mesh") {
      const char* field = r.has("collisionMeshPath") ? "collisionMeshPath"
                          : r.has("renderMeshPath")  ? "renderMeshPath"
                                                     : "meshPath";
      meshFile(r, o.collisionMeshPath, field, o.path);
    }
  }

  void compound(const Compound& c) {
    if (c.bodyMode == BodyMode::VisualOnly) return;
    mass(reader(c.recordIndex), c.bodyMode, c.mass, c.path);
    for (const CompoundChild& ch : c.children) {
      if (!judged(ch.recordIndex)) continue;
      RecordReader r = reader(ch.recordIndex);
      // A plane has no place inside a body (Bullet has no compound of one).
      if (ch.primitive == "ground" || ch.primitive == "half_space") {
        r.error("primitive", scene_code::kBadChildShape,
                "a " + ch.primitive + " cannot be a child of compound '" + c.path + "'",
                "make it an object of its own (a static ground or half_space)");
        continue;
      }
      std::string problem = sizeProblem(ch.primitive, childBox(c, ch), childRadius(c, ch), childHeight(c, ch));
      if (ch.primitive == "mesh" && !positive(childScale(c, ch).mean())) problem = "mesh with a zero or negative scale";
      if (!problem.empty())
        r.error(sizeField(ch.primitive, problem, true, r), scene_code::kZeroSize,
                problem + " in compound '" + c.path + "'",
                r.has("radius") || ch.primitive == "box" ? "" : "a child's radius and height default to 0");
      if (ch.primitive == "mesh") meshFile(r, ch.meshPath, "meshPath", c.path);
    }
  }

  void wire(const Wire& w) {
    if (!w.enabled) return;
    for (auto [end, field, ref] : {std::tuple{w.endA, "bodyA", &w.bodyA}, std::tuple{w.endB, "bodyB", &w.bodyB}})
      if (end == WireEnd::Unknown)
        reader(w.recordIndex)
            .error(field, scene_code::kUnknownBody, "body '" + *ref + "' does not exist", "name a node by its id or path");
    auto skipped = [](WireEnd e) { return e == WireEnd::NotSimulated; };
    bool a = skipped(w.endA);
    if (!a && !skipped(w.endB)) return;
    const char* field = a ? "bodyA" : "bodyB";
    const std::string& ref = a ? w.bodyA : w.bodyB;
    const std::string& tag = a ? w.tagA : w.tagB;
    std::string what = tag == "object" || tag == "compound" ? "a visual-only " + tag
                       : tag.find_first_of("aeiou") == 0          ? "an " + tag
                                                                  : "a " + tag;
    reader(w.recordIndex)
        .error(field, scene_code::kWireSkipped,
               "wire '" + w.path + "' is not simulated: " + field + " '" + ref + "' is " + what +
                   ", which rscene-sim does not model",
               "", Severity::Warning);
  }

  // A deformable's own values (scene/deformable_check.hpp), then its mesh
  // file when files are checked.
  void deformable(const Deformable& d) {
    RecordReader r = reader(d.recordIndex);
    std::string error, field;
    const bool ownValues = checkDeformableRecord(d, error, field);
    if (!ownValues) r.error(field, particle_code::kDeformable, "deformable '" + d.path + "': " + error);
    if (d.meshPath.empty()) {  // `-`: rscene-sim has no particles to make, rscene-render nothing to draw
      r.error("meshPath", scene_code::kNoMesh, "deformable '" + d.path + "' has no mesh file");
      return;
    }
    if (!opt_.exists(d.meshPath)) {
      // Unless files are checked, a missing file is the caller's to report
      // (rscene-render draws a placeholder where missing assets are allowed).
      if (opt_.checkFiles)
        r.error("meshPath", scene_code::kMissingFile, "mesh file '" + d.meshPath + "' " + whyNotAFile(d.meshPath),
                "paths resolve against the scene's directory, then against asset_root");
      return;
    }
    if (!opt_.readSurface || !ownValues) return;
    TriangleSurface surface;
    if (!opt_.readSurface(d.meshPath, surface, error)) {
      r.error("meshPath", particle_code::kDeformableMesh,
              "deformable '" + d.path + "': mesh " + d.meshPath + ": " + error);
      return;
    }
    DeformableModel model;
    if (!buildDeformableModel(d, surface, model, error, field))
      r.error(field, particle_code::kDeformable, "deformable '" + d.path + "': " + error);
  }

  // A granular record's material, grains and substeps
  // (scene/granular.hpp): the findings rscene-sim builds its solver after.
  void granular(const Granular& g) {
    std::vector<ParticleFinding> found;
    std::optional<GranularSetup> setup = granularSetup(g, s_.timeStep, found, /*world=*/false);
    // Grains starting inside the ground (RS7091): the planes the simulator
    // builds, those whose collision filter meets the grains' (group 1,
    // every mask bit).  Poses as written: rscene-validate's model resolves
    // no world poses, so records under a parent, and other bodies, are
    // rscene-sim's to measure (the same rule, the same code).
    // A group is a folder in the world frame: under one, local is world.
    auto inWorldFrame = [&](const std::string& parent) {
      if (parent.empty()) return true;
      for (const Group& grp : s_.groups)
        if (grp.id == parent || grp.path == parent) return true;
      return false;
    };
    if (setup && !g.fixed && inWorldFrame(g.parentId)) {
      std::vector<double> heights;
      for (const Object& o : s_.objects)
        if ((o.primitive == "ground" || o.primitive == "half_space") && o.bodyMode != BodyMode::VisualOnly &&
            inWorldFrame(o.parentId) && o.collisionGroup != 0 && (o.collisionMask & 1) != 0)
          heights.push_back(o.local.position.z());
      for (Eigen::Vector3d& x : setup->positions) x = g.local.position + g.local.orientation * x;
      GranularStartDepth deep = granularGroundDepth(*setup, heights);
      if (deep.count) found.push_back(granularStartDepthFinding(g, deep, "the ground"));
    }
    RecordReader r = reader(g.recordIndex);
    for (const ParticleFinding& f : found)
      if (f.error || opt_.stepWarnings) r.error(f.field, f.code, f.message, {}, f.error ? Severity::Error : Severity::Warning);
  }

  const Document& doc_;
  const Scene& s_;
  const SceneCheckOptions& opt_;
  Diagnostics& out_;
  std::set<std::uint32_t> unparsed_;  // lines of records with a value that does not parse
};

}  // namespace

bool checkScene(const Document& doc, const Scene& scene, const SceneCheckOptions& options, Diagnostics& diagnostics) {
  std::size_t before = diagnostics.size();
  Checker(doc, scene, options, diagnostics).run();
  checkNumericLimits(doc, scene, diagnostics);
  checkSensors(doc, scene, diagnostics);
  // RS7013 for a primitive starting in the ground or in another: a warning about stepping.
  if (options.stepWarnings) checkGroundStarts(doc, scene, diagnostics);
  for (std::size_t i = before; i < diagnostics.size(); ++i)
    if (diagnostics[i].severity == Severity::Error) return false;
  return true;
}

}  // namespace rscene
