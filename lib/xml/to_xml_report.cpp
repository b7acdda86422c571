#include "xml/to_xml_report.hpp"

#include <map>
#include <string_view>

#include "core/schema.hpp"
#include "core/text.hpp"
#include "scene/reader.hpp"

namespace rscene::xml {

namespace {

// One entry of the line per kind, in this order.  `counted`: "3 lights";
// otherwise the name alone ("environment").  Tags not listed here are
// exported, or carry nothing a world XML could hold (header, asset_root,
// scene_graph: their effect is in the world poses and paths written).
struct Kind {
  const char* singular;
  const char* plural;
  bool counted;
  std::vector<std::string_view> tags;
};

const std::vector<Kind>& kinds() {
  static const std::vector<Kind> k = {
      {"light", "lights", true, {"light"}},
      {"camera", "cameras", true, {"camera"}},
      {"materials' looks", "materials' looks", false, {"material", "terrain_texture"}},
      {"environment", "environment", false, {"environment"}},
      {"weather", "weather", false, {"weather"}},
      {"render settings", "render settings", false, {"rayrai_render", "render_bake"}},
      {"group", "groups", true, {"group"}},
      {"editor state", "editor state", false, {"snapping", "editor_ux", "prefab_override", "asset"}},
      {"sensor", "sensors", true, {"sensor"}},
      {"visual-only body", "visual-only bodies", true, {}},  // counted from the scene model
      {"deformable", "deformables", true, {"deformable"}},
      {"granular", "granular", true, {"granular"}},
      {"instanced visual", "instanced visuals", true, {"instanced_visual"}},
      {"point cloud", "point clouds", true, {"point_cloud"}},
      {"probe", "probes", true, {"reflection_probe", "irradiance_volume"}},
      {"decal", "decals", true, {"projected_decal"}},
      {"fog volume", "fog volumes", true, {"local_fog"}},
      {"IK target", "IK targets", true, {"articulated_ik"}},
      {"terrain layer", "terrain layers", true, {"terrain_splat_layer", "terrain_foliage_layer"}},
      {"wire not simulated", "wires not simulated", true, {}},  // counted from the scene model
      {"unknown record", "unknown records", true, {}},          // tags the schema does not know
  };
  return k;
}

std::string entry(const Kind& k, std::size_t n) {
  if (!k.counted) return k.plural;
  return std::to_string(n) + " " + (n == 1 ? k.singular : k.plural);
}

}  // namespace

void listRecordsNotExported(const Document& doc, const Scene& scene, std::vector<std::string>& out) {
  std::map<std::string_view, std::size_t> byTag;
  std::size_t unknown = 0;
  for (std::size_t i = 1; i < doc.records.size(); ++i) {
    const Record& r = doc.records[i];
    if (!r.kind) ++unknown;
    else ++byTag[doc.tag(r)];
  }
  std::size_t visualOnly = 0, idleWires = 0;
  for (const Object& o : scene.objects) visualOnly += !simulated(o);
  for (const Compound& c : scene.compounds) visualOnly += !simulated(c);
  for (const Terrain& t : scene.terrains) visualOnly += !simulated(t);
  for (const Wire& w : scene.wires) idleWires += !w.simulated();
  for (const Kind& k : kinds()) {
    std::size_t n = 0;
    for (std::string_view tag : k.tags)
      if (auto it = byTag.find(tag); it != byTag.end()) n += it->second;
    if (std::string_view(k.singular) == "visual-only body") n = visualOnly;
    if (std::string_view(k.singular) == "wire not simulated") n = idleWires;
    if (std::string_view(k.singular) == "unknown record") n = unknown;
    if (n) out.push_back(entry(k, n));
  }
}

void listSolverNotExported(const Document& doc, const Scene& scene, std::vector<std::string>& out) {
  if (scene.solver.recordIndex < 0) return;  // absent: every key at its default
  const KindDef* kind = Schema::get().kind("solver");
  if (!kind) return;
  // The solver keys a world XML holds (erp, erp2, material/default).
  static const std::vector<std::string_view> exported = {"erp", "erp2", "defaultFriction", "defaultRestitution",
                                                         "defaultRestitutionThreshold"};
  Diagnostics ignored;  // buildScene already reported every value problem
  RecordReader written(doc, static_cast<std::size_t>(scene.solver.recordIndex), ignored);
  RecordReader defaults(doc, *kind, ignored);
  auto check = [&](const FieldDef& f) {
    for (std::string_view e : exported)
      if (f.name == e) return;
    if (!written.has(f.name)) return;
    std::optional<std::string> now = written.text(f.name), was = defaults.text(f.name);
    if (now && was && sameValue(*now, *was, f.type)) return;
    out.push_back("solver " + f.name);
  };
  for (const FieldDef& f : kind->layouts.front().fields) check(f);
  for (const FieldDef& f : kind->keys) check(f);
}

}  // namespace rscene::xml
