// rscene-to-xml's mapping, records -> elements (to_xml.hpp; the mapping
// table is man/rscene-to-xml.1's, and rscene-from-xml reads it back).
#include "xml/to_xml.hpp"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>

#include "core/codes.hpp"
#include "scene/mass_properties.hpp"
#include "scene/reader.hpp"
#include "xml/to_xml_report.hpp"
#include "xml/to_xml_robot.hpp"
#include "xml/to_xml_writer.hpp"

namespace rscene::xml {

namespace {

constexpr const char* kCannotWrite = rs::RS8130;
constexpr std::uint64_t kAllBits = ~std::uint64_t{0};
// rscene wires resist stretch only, spelt as RaiSim's own exporter writes
// it (rscene-from-xml also reads the enum's name STRETCH_RESISTANT_ONLY).
constexpr const char* kStretchOnly = "stretch_only";

class Exporter {
 public:
  Exporter(const Document& doc, const Scene& scene, const ToXmlOptions& options, ToXmlResult& result)
      : doc_(doc), scene_(scene), options_(options), r_(result) {
    for (const Object& o : scene.objects) name(o.id, o.path);
    for (const Compound& c : scene.compounds) name(c.id, c.path);
    for (const Terrain& t : scene.terrains) name(t.id, t.path);
    for (const Articulated& a : scene.articulated) name(a.id, a.path);
  }

  OutElement run() {
    OutElement root("raisim");
    root.text("version", "1.0");
    root.add(OutElement("timeStep").number("value", scene_.timeStep));
    root.add(OutElement("gravity").vec3("value", scene_.gravity));
    root.add(OutElement("erp").number("erp", scene_.solver.erp).number("erp2", scene_.solver.erp2));
    root.add(materials());
    root.add(objects());
    for (const Wire& w : scene_.wires)
      if (w.simulated())
        if (std::optional<OutElement> e = wire(w)) root.add(std::move(*e));
    return root;
  }

  std::vector<std::string> losses;  // per record and field, in record order

 private:
  void name(const std::string& id, const std::string& path) {
    if (!id.empty()) paths_.emplace(id, path);
    paths_[path] = path;
  }

  // An exported asset path: "[THIS_DIR]/" + the path relative to the
  // XML's directory, or absolute.
  std::string assetPath(const std::string& resolved) const {
    namespace fs = std::filesystem;
    if (resolved.empty()) return resolved;
    std::error_code ec;
    fs::path p = fs::absolute(resolved, ec).lexically_normal();
    if (ec) return resolved;
    if (options_.absolutePaths) return p.generic_string();
    fs::path base = fs::absolute(options_.outputDir.empty() ? "." : options_.outputDir, ec).lexically_normal();
    if (ec) return p.generic_string();
    if (!base.has_filename()) base = base.parent_path();  // "/a/b/" -> "/a/b"
    fs::path rel = p.lexically_relative(base);
    if (rel.empty()) return p.generic_string();  // no relative form (another root)
    return "[THIS_DIR]/" + rel.generic_string();
  }

  static std::string materialName(const std::string& contactMaterial) {
    return contactMaterial.empty() ? "default" : contactMaterial;
  }

  OutElement materials() const {
    OutElement m("material");
    const Solver& s = scene_.solver;
    m.add(OutElement("default")
              .number("friction", s.defaultFriction)
              .number("restitution", s.defaultRestitution)
              .number("restitution_threshold", s.defaultRestitutionThreshold));
    for (const ContactMaterial& c : scene_.contactMaterials)
      m.add(OutElement("pair_prop")
                .text("name1", c.materialA)
                .text("name2", c.materialB)
                .number("friction", c.friction)
                .number("restitution", c.restitution)
                .number("restitution_threshold", c.restitutionThreshold)
                .number("static_friction", c.staticFriction)
                .number("static_friction_velocity_threshold", c.staticFrictionVelocityThreshold)
                .number("rolling_friction", c.rollingFriction)
                .number("spinning_friction", c.spinningFriction));
    return m;
  }

  // Bodies in record order (the order of the scene file).
  OutElement objects() {
    std::vector<std::pair<int, std::function<OutElement()>>> bodies;
    for (const Object& o : scene_.objects)
      if (simulated(o)) bodies.emplace_back(o.recordIndex, [this, &o] { return object(o); });
    for (const Compound& c : scene_.compounds)
      if (simulated(c)) bodies.emplace_back(c.recordIndex, [this, &c] { return compound(c); });
    for (const Terrain& t : scene_.terrains)
      if (simulated(t)) bodies.emplace_back(t.recordIndex, [this, &t] { return heightmap(t); });
    for (const Articulated& a : scene_.articulated)
      bodies.emplace_back(a.recordIndex, [this, &a] { return articulated(a); });
    std::stable_sort(bodies.begin(), bodies.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    OutElement list("objects");
    for (auto& [index, make] : bodies) list.add(make());
    return list;
  }

  static void groups(OutElement& e, std::uint64_t group, std::uint64_t mask) {
    if (group != 1) e.text("collision_group", collisionBits(group));
    if (mask != kAllBits) e.text("collision_mask", collisionBits(mask));
  }

  // A body that is not drawn: RaiSim's appearance="hidden" (from-xml reads
  // it back as visible=false).
  static void hidden(OutElement& e, bool visible) {
    if (!visible) e.text("appearance", "hidden");
  }

  static OutElement state(const Pose& p) {
    const Eigen::Quaterniond& q = p.orientation;
    double wxyz[4] = {q.w(), q.x(), q.y(), q.z()};
    OutElement s("state");
    s.vec3("pos", p.position);
    s.numbers("quat", wxyz, 4);
    return s;
  }

  static OutElement dim(const std::string& primitive, const Eigen::Vector3d& box, double radius, double height) {
    OutElement d("dim");
    if (primitive == "box") d.number("x", box.x()).number("y", box.y()).number("z", box.z());
    else d.number("radius", radius);
    if (primitive == "capsule" || primitive == "cylinder") d.number("height", height);
    return d;
  }

  OutElement object(const Object& o) {
    Diagnostics ignored;  // buildScene read these records already
    RecordReader r(doc_, static_cast<std::size_t>(o.recordIndex), ignored);
    if (o.primitive == "ground" || o.primitive == "half_space") {
      OutElement g("ground");
      g.text("name", o.path).number("height", o.world.position.z()).text("material", materialName(o.contactMaterial));
      if (o.collisionGroup != 1) g.text("collision_group", collisionBits(o.collisionGroup));
      if (o.collisionMask != kAllBits) g.text("collision_mask", collisionBits(o.collisionMask));
      hidden(g, o.visible);
      return g;
    }
    const std::string& tag = o.primitive;  // sphere, box, capsule, cylinder, mesh: RaiSim's element names
    OutElement e(tag);
    e.text("name", o.path).number("mass", o.mass).text("material", materialName(o.contactMaterial));
    e.text("body_type", bodyModeName(o.bodyMode));
    groups(e, o.collisionGroup, o.collisionMask);
    hidden(e, o.visible);
    if (tag == "mesh") {
      e.text("file_name", assetPath(o.collisionMeshPath));
      e.vec3("scale", o.scale);
    }
    if (r.has("centerOfMass")) e.vec3("com", r.vec3("centerOfMass", Eigen::Vector3d::Zero()));
    if (tag != "mesh") e.add(dim(tag, o.scale, o.physicsRadius(), o.physicsHeight()));
    if (r.flag("customInertia", false)) {
      Eigen::Vector3d d = r.vec3("inertiaDiagonal", Eigen::Vector3d::Zero());
      e.add(OutElement("inertia").number("xx", d.x()).number("xy", 0).number("xz", 0).number("yy", d.y())
                .number("yz", 0).number("zz", d.z()));
    }
    e.add(state(o.world));
    return e;
  }

  OutElement compound(const Compound& c) {
    OutElement e("compound");
    e.text("name", c.path).number("mass", c.mass).text("material", materialName(c.contactMaterial));
    e.text("body_type", bodyModeName(c.bodyMode));
    groups(e, c.collisionGroup, c.collisionMask);
    hidden(e, c.visible);
    // RaiSim's compound requires `com`: where rscene-sim puts it
    // (scene/mass_properties.hpp), so both engines turn the compound about
    // the same point.  Only the children the XML holds count: a mesh child
    // is not exported (listed), and RaiSim's compound will not have it.
    // from-xml reads it back as centerOfMass=: the same physics, spelt out.
    std::vector<double> volumes;
    for (const CompoundChild& ch : c.children) volumes.push_back(primitiveVolume(c, ch));
    e.vec3("com", compoundCenterOfMass(c, volumes));
    if (c.hasInertia) {
      const Eigen::Vector3d& d = c.inertiaDiagonal;
      e.add(OutElement("inertia").number("xx", d.x()).number("xy", 0).number("xz", 0).number("yy", d.y())
                .number("yz", 0).number("zz", d.z()));
    }
    OutElement children("children");
    for (const CompoundChild& ch : c.children) {
      if (ch.primitive != "box" && ch.primitive != "sphere" && ch.primitive != "capsule" && ch.primitive != "cylinder") {
        losses.push_back("compound " + c.path + ": " + ch.primitive + " child");
        continue;
      }
      OutElement child(ch.primitive);
      child.text("material", materialName(ch.contactMaterial));
      child.add(dim(ch.primitive, childBox(c, ch), childRadius(c, ch), childHeight(c, ch)));
      child.add(state(childPose(c, ch)));
      children.add(std::move(child));
    }
    e.add(std::move(children));
    e.add(state(c.world));
    return e;
  }

  OutElement heightmap(const Terrain& t) {
    Diagnostics ignored;
    RecordReader r(doc_, static_cast<std::size_t>(t.recordIndex), ignored);
    OutElement e("heightmap");
    e.text("name", t.path)
        .integer("x_sample", t.xSamples)
        .integer("y_sample", t.ySamples)
        .number("x_size", t.xSize)
        .number("y_size", t.ySize)
        .number("center_x", t.center.x())
        .number("center_y", t.center.y())
        .text("material", materialName(t.contactMaterial));
    // The XML has no centre height: it is added to every sample (the
    // same surface), and to a generator's height_offset.
    double z = t.center.z();
    if (t.sourceKind == "procedural" && !r.has("heights")) {
      OutElement p("terrain_properties");
      static const std::pair<const char*, const char*> keys[] = {
          {"proceduralZScale", "z_scale"},         {"proceduralOctaves", "fractal_octaves"},
          {"proceduralLacunarity", "fractal_lacunarity"}, {"proceduralGain", "fractal_gain"},
          {"proceduralStepSize", "step_size"},     {"proceduralHeightOffset", "height_offset"},
          {"proceduralFrequency", "frequency"},    {"proceduralSeed", "seed"}};
      for (auto [key, attribute] : keys) {
        bool offset = std::string_view(attribute) == "height_offset";
        if (!r.has(key) && !(offset && z != 0)) continue;
        if (std::string_view(attribute) == "fractal_octaves" || std::string_view(attribute) == "seed")
          p.integer(attribute, r.integer(key, 0));
        else
          p.number(attribute, r.number(key, 0.0) + (offset ? z : 0.0));
      }
      e.add(std::move(p));
      return e;
    }
    std::vector<double> heights = t.heights;
    if (z != 0)
      for (double& h : heights) h += z;
    e.numbers("height", heights);
    return e;
  }

  OutElement articulated(const Articulated& a) {
    OutElement e("articulatedSystem");
    e.text("name", a.path).text("urdf_path", assetPath(a.sourcePath));
    hidden(e, a.visible);
    if (!a.resourceDirectory.empty()) e.text("res_dir", assetPath(a.resourceDirectory));
    if (!a.modules.empty()) {
      std::string list;
      for (const std::string& m : a.modules) list += (list.empty() ? "" : " ") + m;
      e.text("modules", list);
    }
    // rscene-sim gives a non-collidable robot's bodies group and mask 0.
    groups(e, a.collidable ? a.collisionGroup : 0, a.collidable ? a.collisionMask : 0);
    RobotExport state = exportRobotState(doc_, a, robots_);
    r_.diagnostics.insert(r_.diagnostics.end(), state.diagnostics.begin(), state.diagnostics.end());
    losses.insert(losses.end(), state.losses.begin(), state.losses.end());
    if (!a.scale.isOnes()) losses.push_back("articulated " + a.path + ": scale");
    if (state.qpos) {
      OutElement s("state");
      s.numbers("qpos", *state.qpos);
      if (state.qvel) s.numbers("qvel", *state.qvel);
      e.add(std::move(s));
    }
    return e;
  }

  std::optional<OutElement> wire(const Wire& w) {
    auto body = [&](const std::string& ref) -> std::string {
      auto it = paths_.find(ref);
      return it == paths_.end() ? ref : it->second;
    };
    if (w.endA == WireEnd::World || w.endB == WireEnd::World) {
      losses.push_back("wire " + w.path + ": end in the world");
      return std::nullopt;
    }
    OutElement e("wire");
    e.text("name", w.path).text("type", w.kind).number("length", w.length);
    // rscene-sim gives a compliant wire a spring (stiffness, damping); a
    // stiff or custom one is a rope and uses neither, nor does any use
    // `compliance`.  Only a spring's damping is lost.
    if (w.kind == "compliant") e.number("stiffness", w.stiffness);
    e.text("stretch_type", kStretchOnly);
    if (w.kind == "compliant" && w.damping != 0) losses.push_back("wire " + w.path + ": damping");
    e.add(OutElement("object1").text("name", body(w.bodyA)).integer("local_index", w.localIndexA).vec3("pos", w.localPositionA));
    e.add(OutElement("object2").text("name", body(w.bodyB)).integer("local_index", w.localIndexB).vec3("pos", w.localPositionB));
    return e;
  }

  const Document& doc_;
  const Scene& scene_;
  const ToXmlOptions& options_;
  ToXmlResult& r_;
  std::map<std::string, std::string> paths_;  // body id or path -> path
  robot::ModelCache robots_;
};

// Why `text` cannot be written as an XML value that rscene-from-xml reads
// back unchanged, or "" when it can: from-xml substitutes @@NAME and
// [THIS_DIR] and evaluates {...} in every attribute (a lone '}' is an
// error there), and XML holds no C0 control other than tab and newline,
// and only UTF-8.  Refused rather than escaped: RaiSim's template language
// has no escape for them, so no spelling would load in RaiSim as written.
std::string unwritable(std::string_view text) {
  if (text.find("@@") != std::string_view::npos) return "'@@', which rscene-from-xml reads as a parameter";
  if (text.find("[THIS_DIR]") != std::string_view::npos)
    return "'[THIS_DIR]', which rscene-from-xml replaces with the XML's directory";
  if (text.find_first_of("{}") != std::string_view::npos)
    return "'{' or '}', which rscene-from-xml evaluates as an expression";
  std::string escaped;
  if (!escapeAttribute(text, escaped)) return "a control character or a byte that is not UTF-8, which XML cannot hold";
  return {};
}

// Every name the XML writes (bodies, wires, contact materials), checked
// where the scene writes it, before anything is exported (RS8132).
void checkNames(const Document& doc, const Scene& scene, Diagnostics& diagnostics) {
  auto check = [&](int recordIndex, const char* field, const std::string& value, const char* what) {
    if (std::string why = unwritable(value); !why.empty())
      reportAt(&doc, recordIndex, field, rs::RS8132,
               std::string(what) + " cannot be written to a world XML: it holds " + why, diagnostics,
               Severity::Error, "rename it");
  };
  auto body = [&](int recordIndex, const std::string& path, const std::string& material) {
    check(recordIndex, "path", path, "the name");
    check(recordIndex, "contactMaterial", material, "the contact material");
  };
  for (const Object& o : scene.objects)
    if (simulated(o)) body(o.recordIndex, o.path, o.contactMaterial);
  for (const Compound& c : scene.compounds)
    if (simulated(c)) body(c.recordIndex, c.path, c.contactMaterial);
  for (const Terrain& t : scene.terrains)
    if (simulated(t)) body(t.recordIndex, t.path, t.contactMaterial);
  for (const Articulated& a : scene.articulated) check(a.recordIndex, "path", a.path, "the name");
  for (const Wire& w : scene.wires)
    if (w.simulated()) check(w.recordIndex, "path", w.path, "the name");
  for (const ContactMaterial& m : scene.contactMaterials) {
    check(m.recordIndex, "materialA", m.materialA, "the material name");
    check(m.recordIndex, "materialB", m.materialB, "the material name");
  }
}

}  // namespace

ToXmlResult sceneToXml(const Document& doc, const Scene& scene, const ToXmlOptions& options) {
  ToXmlResult result;
  checkNames(doc, scene, result.diagnostics);
  if (!result.ok()) return result;
  Exporter exporter(doc, scene, options, result);
  OutElement root = exporter.run();
  if (std::string problem = root.firstProblem(); !problem.empty()) {
    Diagnostic d;
    d.code = kCannotWrite;
    d.message = problem + ": a value XML cannot hold (not finite, a control character, or not UTF-8)";
    result.diagnostics.push_back(std::move(d));
  }
  listRecordsNotExported(doc, scene, result.notExported);
  listSolverNotExported(doc, scene, result.notExported);
  result.notExported.insert(result.notExported.end(), exporter.losses.begin(), exporter.losses.end());
  if (result.ok()) result.xml = printDocument(root);
  return result;
}

}  // namespace rscene::xml
