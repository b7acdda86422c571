// RS6xxx (--profile raisim): what RaiSim 2.7.1's reader refuses although
// Engine 2 loads it (compat-notes.md, "What RaiSim 2.7.1's reader
// refuses").  Repeated keys, unknown names and non-group parents are
// reported by the type and reference passes under their RS6xxx codes.
#include <algorithm>

#include "core/codes.hpp"
#include "core/check_context.hpp"
#include "core/text.hpp"

namespace rscene::checks {
namespace {

constexpr std::string_view kUnsupportedKinds[] = {
    "articulated_resource", "articulated", "articulated_ik", "compound",          "compound_child",
    "deformable",           "granular",    "projected_decal", "irradiance_volume", "point_cloud"};

bool isAbsolute(std::string_view p) { return !p.empty() && p[0] == '/'; }

bool enabled(Context& ctx, const Record& r) { return ctx.flag(r, "enabled").value_or(true); }

}  // namespace

void checkRaisim(Context& ctx, std::size_t i) {
  const Record& r = ctx.doc.records[i];
  const std::string& tag = r.kind->tag;
  if (std::find(std::begin(kUnsupportedKinds), std::end(kUnsupportedKinds), tag) != std::end(kUnsupportedKinds)) {
    ctx.report(rs::RS6001, r, r.tag, {}, "RaiSim does not load " + tag + " records");
    return;
  }
  if (tag == "asset_root" && ctx.doc.version == 1) {
    std::string root = ctx.text(r, "path");
    if (root != "." && !isAbsolute(root))
      ctx.report(rs::RS6003, r, ctx.spanOf(r, ctx.get(r, "path")), "path",
                 "version-1 asset_root '" + root + "' is neither . nor absolute",
                 "RaiSim cannot resolve a project-relative root; use version 2 or an absolute path");
  } else if (tag == "terrain_region") {
    FieldRef source = ctx.get(r, "sourceKind");
    if (source && source.def->enumDef) {
      auto kind = source.def->enumDef->canonical(percentDecode(ctx.doc.text(source.first->value)));
      if (kind && *kind != "samples")
        ctx.report(rs::RS6005, r, source.first->value, "sourceKind",
                   "terrain source " + std::string(*kind) + " is not samples; RaiSim reads only sampled heights");
    }
    for (const char* name : {"visible", "collidable"})
      if (ctx.flag(r, name) == std::optional<bool>(false))
        ctx.report(rs::RS6005, r, ctx.spanOf(r, ctx.get(r, name)), name,
                   std::string("terrain with ") + name + "=false; RaiSim refuses it");
  } else if (tag == "terrain_splat_layer" || tag == "terrain_foliage_layer") {
    const Record* t = ctx.terrain(ctx.text(r, "terrain"));
    if (t && t > &r)
      ctx.report(rs::RS6006, r, ctx.spanOf(r, ctx.get(r, "terrain")), "terrain",
                 tag + " comes before its terrain on line " + std::to_string(t->line),
                 "move the layer after its terrain_region");
  } else if (tag == "instanced_visual" && enabled(ctx, r)) {
    if (ctx.flag(r, "grassPatch") == std::optional<bool>(true))
      ctx.report(rs::RS6007, r, ctx.spanOf(r, ctx.get(r, "grassPatch")), "grassPatch",
                 "RaiSim refuses an enabled grass patch", "set enabled=false for RaiSim");
    FieldRef prim = ctx.get(r, "primitive");
    auto p = prim && prim.def->enumDef ? prim.def->enumDef->canonical(ctx.doc.text(prim.first->value)) : std::nullopt;
    if (p && *p == "ground")
      ctx.report(rs::RS6007, r, prim.first->value, "primitive", "RaiSim refuses an instanced ground");
  } else if (tag == "wire" && enabled(ctx, r)) {
    for (const char* name : {"length", "localIndexA", "localIndexB"})
      if (auto v = ctx.number(r, name); v && *v < 0)
        ctx.report(rs::RS6008, r, ctx.spanOf(r, ctx.get(r, name)), name,
                   std::string(name) + " is negative; RaiSim refuses the wire");
  }
}

}  // namespace rscene::checks
