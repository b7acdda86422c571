// rscene-from-xml's mapping, top level: <raisim>'s physics settings and
// materials, then every <objects> child and <wire> by its handler
// (from_xml_bodies.cpp, from_xml_terrain.cpp, from_xml_robots.cpp).  The
// records are built as text, loaded by lib/core's loader and written in
// canonical form, so the output is exactly what rscene-fmt would write.
//
// No record gets an id, a parentGroupId or a group: every default is what
// validate expects (bodies sit in /World's frame, references are by path).
#include "core/loader.hpp"
#include "core/writer.hpp"
#include "xml/from_xml_context.hpp"

namespace rscene::xml {
namespace {

using detail::Context;
using detail::Line;
using detail::Vec3;
namespace code = detail::code;

// RaiSim's defaults where the XML leaves a setting out (they differ from
// the schema's, so they are written explicitly).
constexpr double kRaisimTimeStep = 0.005;
constexpr double kRaisimFriction = 0.8, kRaisimRestitution = 0, kRaisimRestitutionThreshold = 0;
constexpr double kSchemaStaticFrictionVelocityThreshold = 0.001;

struct Physics {
  double dt = kRaisimTimeStep;
  Vec3 gravity{0, 0, -9.81};
  double erp = 0.2, erp2 = 0;
  double friction = kRaisimFriction, restitution = kRaisimRestitution,
         restitutionThreshold = kRaisimRestitutionThreshold;
  // The elements the time_step, gravity and solver lines come from (the
  // <raisim> element where the XML leaves them out).
  std::vector<const Element*> origins;
};

void readValue(Context& ctx, const Element& e, double& out) {
  ctx.checkAttributes(e, e.name, {"value"});
  if (auto v = ctx.number(e, ctx.require(e, "value"))) out = *v;
}

void readPairProp(Context& ctx, const Element& e) {
  ctx.checkAttributes(e, "pair_prop",
                      {"name1", "name2", "friction", "restitution", "restitution_threshold", "static_friction",
                       "static_friction_velocity_threshold", "rolling_friction", "spinning_friction"});
  const Attribute* a = ctx.require(e, "name1");
  const Attribute* b = ctx.require(e, "name2");
  auto friction = ctx.number(e, ctx.require(e, "friction"));
  auto restitution = ctx.number(e, ctx.require(e, "restitution"));
  auto threshold = ctx.number(e, ctx.require(e, "restitution_threshold"));
  const Attribute* staticAttr = e.attribute("static_friction");
  auto staticFriction = ctx.number(e, staticAttr);
  auto staticThreshold = ctx.number(e, e.attribute("static_friction_velocity_threshold"));
  auto rolling = ctx.number(e, e.attribute("rolling_friction"));
  auto spinning = ctx.number(e, e.attribute("spinning_friction"));
  if (!a || !b || !friction || !restitution || !threshold) return;
  if (staticAttr && !staticFriction) return;
  Line l("contact_material");
  l.text(a->value).text(b->value).num(*friction).num(*restitution).num(*threshold);
  l.num(staticFriction.value_or(*friction)).num(staticThreshold.value_or(kSchemaStaticFrictionVelocityThreshold));
  l.num(rolling.value_or(0)).num(spinning.value_or(0));
  ctx.add(l, e);
}

void readMaterial(Context& ctx, const Element& e, Physics& p) {
  ctx.checkAttributes(e, "material", {});
  ctx.checkChildren(e, "material", {"default", "pair_prop"});
  for (const Element& c : e.children) {
    if (c.name == "default") {
      ctx.checkAttributes(c, "material <default>", {"friction", "restitution", "restitution_threshold"});
      if (auto v = ctx.number(c, c.attribute("friction"))) p.friction = *v;
      if (auto v = ctx.number(c, c.attribute("restitution"))) p.restitution = *v;
      if (auto v = ctx.number(c, c.attribute("restitution_threshold"))) p.restitutionThreshold = *v;
    } else if (c.name == "pair_prop") {
      readPairProp(ctx, c);
    }
  }
}

void readObjects(Context& ctx, const Element& objects) {
  for (const Element& e : objects.children) {
    const std::string& t = e.name;
    if (t == "sphere" || t == "capsule" || t == "cylinder" || t == "box" || t == "mesh")
      detail::convertSingleBody(ctx, e);
    else if (t == "ground")
      detail::convertGround(ctx, e);
    else if (t == "compound")
      detail::convertCompound(ctx, e);
    else if (t == "heightmap")
      detail::convertHeightmap(ctx, e);
    else if (t == "articulatedSystem" || t == "articulated_system")
      detail::convertArticulated(ctx, e);
    else {
      ctx.result.diagnostics.push_back(
          elementDiagnostic(Severity::Warning, code::kNotConverted, e, "unknown object, not converted"));
      ctx.lost("<" + t + ">");
    }
  }
}

std::string physicsRecords(const Physics& p) {
  Line dt("time_step");
  dt.num(p.dt);
  Line g("gravity");
  g.nums(p.gravity);
  // solver iterations tolerance erp mode: the schema's, but for erp.
  Line s("solver");
  s.raw("80").raw("1e-07").num(p.erp).raw("accurate").keyNum("erp2", p.erp2);
  s.keyNum("defaultFriction", p.friction).keyNum("defaultRestitution", p.restitution);
  s.keyNum("defaultRestitutionThreshold", p.restitutionThreshold);
  return dt.str() + '\n' + g.str() + '\n' + s.str() + '\n';
}

}  // namespace

FromXmlResult worldToScene(const Element& raisim, const FromXmlOptions& options) {
  FromXmlResult result;
  Context ctx{options, result};
  if (raisim.name != "raisim") {
    ctx.error(code::kBadValue, raisim, "the top element is not <raisim>");
    return result;
  }
  // RaiSim's own files write both spellings (<raisim Version="1.1.3">).
  ctx.checkAttributes(raisim, "raisim", {"version", "Version"});
  // params and object_class are the front end's (xml_tree.hpp): after
  // expansion they carry nothing left to convert.
  ctx.checkChildren(raisim, "raisim",
                    {"timeStep", "time_step", "gravity", "erp", "material", "objects", "wire", "params",
                     "object_class"},
                    {"camera"});
  Physics p;
  p.origins = {&raisim, &raisim, &raisim};
  for (const Element& e : raisim.children) {
    if (e.name == "timeStep" || e.name == "time_step") {
      p.origins[0] = &e;
      readValue(ctx, e, p.dt);
      if (const Attribute* a = e.attribute("value"); a && !(p.dt > 0))
        ctx.error(code::kBadValue, e, *a, a->value + " is not a positive time step");
    } else if (e.name == "gravity") {
      p.origins[1] = &e;
      ctx.checkAttributes(e, "gravity", {"value"});
      if (auto v = ctx.vec<3>(e, ctx.require(e, "value"))) p.gravity = *v;
    } else if (e.name == "erp") {
      p.origins[2] = &e;
      ctx.checkAttributes(e, "erp", {"erp", "erp2"});
      if (auto v = ctx.number(e, e.attribute("erp"))) p.erp = *v;
      if (auto v = ctx.number(e, e.attribute("erp2"))) p.erp2 = *v;
    } else if (e.name == "material") {
      if (p.origins[2] == &raisim) p.origins[2] = &e;
      readMaterial(ctx, e, p);
    }
  }
  // Bodies before wires, whatever the order in the file: a wire names them.
  for (const Element& e : raisim.children)
    if (e.name == "objects") readObjects(ctx, e);
  for (const Element& e : raisim.children)
    if (e.name == "wire") detail::convertWire(ctx, e);
  if (!ctx.renamed.empty()) {
    std::string list;
    // An array of 80 equally named bodies makes one entry, not 80.
    for (const auto& [want, paths] : ctx.renamed) {
      list += (list.empty() ? "" : "; ") + want + " -> " + paths.front();
      if (paths.size() > 3)
        list += " ... " + paths.back() + " (" + std::to_string(paths.size()) + " paths)";
      else
        for (std::size_t i = 1; i < paths.size(); ++i) list += ", " + paths[i];
    }
    result.diagnostics.push_back(elementDiagnostic(Severity::Warning, code::kApproximate, raisim,
                                                   "repeated names made unique: " + list));
  }
  if (!result.ok()) return result;

  std::string text = "raisim_engine_scene 1\n" + physicsRecords(p) + ctx.records;
  // Line L of `text` came from origins[L - 1]; the header from <raisim>.
  std::vector<const Element*> origins{&raisim};
  origins.insert(origins.end(), p.origins.begin(), p.origins.end());
  origins.insert(origins.end(), ctx.origins.begin(), ctx.origins.end());
  // What rscene-validate, rscene-sim or rscene-to-xml would refuse is
  // refused here, at the element that made it: the output always loads.
  // A text that does not load (only a bug of the mapping: every value was
  // checked above) is reported by the check like any other finding.
  Document doc;
  detail::checkConverted(ctx, std::move(text), raisim, origins, doc);
  if (!result.ok()) return result;
  result.text = canonicalText(doc);
  return result;
}

}  // namespace rscene::xml
