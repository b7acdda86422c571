// Single bodies (sphere, capsule, cylinder, box, mesh), ground and compound
// as object / compound / compound_child records (rscene-from-xml(1), the
// mapping table).
#include <filesystem>

#include "core/text.hpp"
#include "xml/from_xml_context.hpp"

namespace rscene::xml::detail {
namespace {

constexpr std::uint64_t kAllBits = ~std::uint64_t{0};

std::size_t errorCount(const Context& ctx) {
  std::size_t n = 0;
  for (const Diagnostic& d : ctx.result.diagnostics) n += d.severity == Severity::Error;
  return n;
}

// A size of <dim> (radius, height, a box side): the scene checks refuse a
// zero or negative one (RS7003), said here in the XML's words.
std::optional<double> length(Context& ctx, const Element& dim, const char* name) {
  const Attribute* a = ctx.require(dim, name);
  std::optional<double> v = ctx.number(dim, a);
  if (v && !(*v > 0)) {
    ctx.error(code::kBadValue, dim, *a, a->value + " is not a positive length");
    return std::nullopt;
  }
  return v;
}

// What every single body and the compound share.
struct Common {
  std::string path, label;
  std::string material = "default";
  std::string mode = "dynamic";
  std::optional<double> mass;
  std::uint64_t group = 1, mask = kAllBits;
  bool visible = true;  // appearance="hidden": false
  Vec3 pos{0, 0, 0};
  Quat quat{1, 0, 0, 0};
  std::optional<Vec3> inertia;  // diagonal
  std::optional<Vec3> com;
};

// <state pos quat lin_vel ang_vel>: the pose; a velocity has no field.
void readState(Context& ctx, const Element& owner, const std::string& label, Vec3& pos, Quat& quat) {
  const Element* state = owner.child("state");
  if (!state) return;
  ctx.checkAttributes(*state, label + " <state>", {"pos", "quat", "lin_vel", "linVel", "ang_vel", "angVel"});
  if (auto p = ctx.vec<3>(*state, state->attribute("pos"))) pos = *p;
  if (auto q = ctx.vec<4>(*state, state->attribute("quat"))) {
    if ((*q)[0] * (*q)[0] + (*q)[1] * (*q)[1] + (*q)[2] * (*q)[2] + (*q)[3] * (*q)[3] < 1e-24)
      ctx.error(code::kBadValue, *state, *state->attribute("quat"), "the zero quaternion is no orientation");
    else
      quat = *q;
  }
  for (auto [name, alias] : {std::pair{"lin_vel", "linVel"}, std::pair{"ang_vel", "angVel"}})
    if (const Attribute* a = state->attribute(name, alias))  // named as the file spells it
      if (auto v = ctx.vec<3>(*state, a); v && (*v != Vec3{0, 0, 0})) ctx.lost(label + ": " + a->name);
}

// <inertia xx xy xz yy yz zz>: the diagonal; off-diagonal terms have no field.
void readInertia(Context& ctx, const Element& owner, const std::string& label, std::optional<Vec3>& out) {
  const Element* in = owner.child("inertia");
  if (!in) return;
  ctx.checkAttributes(*in, label + " <inertia>", {"xx", "xy", "xz", "yy", "yz", "zz"});
  Vec3 d{};
  bool ok = true;
  const char* diagonal[] = {"xx", "yy", "zz"};
  for (int i = 0; i < 3; ++i) {
    const Attribute* a = ctx.require(*in, diagonal[i]);
    auto v = ctx.number(*in, a);
    if (!v) {
      ok = false;
      continue;
    }
    d[static_cast<std::size_t>(i)] = *v;
  }
  for (const char* off : {"xy", "xz", "yz"})
    if (auto v = ctx.number(*in, in->attribute(off)); v && *v != 0) ctx.lost(label + ": inertia " + off);
  if (ok) out = d;
}

bool readCommon(Context& ctx, const Element& e, Common& c) {
  std::size_t before = errorCount(ctx);
  c.path = ctx.takePath(e);
  c.label = labelOf(e);
  c.visible = ctx.visible(e, c.label);
  if (const Attribute* m = e.attribute("material"); m && !m->value.empty()) c.material = m->value;
  if (const Attribute* t = e.attribute("body_type", "bodyType")) {
    if (t->value == "dynamic" || t->value == "kinematic" || t->value == "static")
      c.mode = t->value;
    else
      ctx.error(code::kBadValue, e, *t, "'" + t->value + "' is not dynamic, kinematic or static");
  }
  c.mass = ctx.number(e, e.attribute("mass"));
  // RS4008 refuses a dynamic body without a positive mass; no body has a
  // negative one.
  if (c.mass && (*c.mass < 0 || (*c.mass == 0 && c.mode == "dynamic")))
    ctx.error(code::kBadValue, e, *e.attribute("mass"),
              e.attribute("mass")->value + " is not a positive mass" +
                  (*c.mass == 0 ? " (a dynamic body needs one)" : ""));
  if (auto g = ctx.group(e, e.attribute("collision_group", "collisionGroup"))) c.group = *g;
  if (auto m = ctx.group(e, e.attribute("collision_mask", "collisionMask"))) c.mask = *m;
  c.com = ctx.vec<3>(e, e.attribute("com"));
  readState(ctx, e, c.label, c.pos, c.quat);
  readInertia(ctx, e, c.label, c.inertia);
  // RaiSim needs a mass for a body that moves; validate refuses a dynamic
  // one without a positive mass.
  if (!c.mass && c.mode == "dynamic" && errorCount(ctx) == before)
    ctx.error(code::kMissing, e, "'mass' is required for a dynamic body");
  return errorCount(ctx) == before;
}

// object PATH PRIMITIVE pos quat scale radius height mass contactMaterial
// material visualOnly visible locked meshPath bodyMode collidable group mask
Line objectLine(const Common& c, std::string_view primitive, const Vec3& scale, double radius, double height,
                const std::string& meshPath) {
  Line l("object");
  l.text(c.path).raw(primitive).nums(c.pos).nums(c.quat).nums(scale).num(radius).num(height);
  l.num(c.mass.value_or(0)).text(c.material).text("").raw("false").raw(c.visible ? "true" : "false").raw("false");
  l.text(meshPath);
  l.raw(c.mode).raw("true").u64(c.group).u64(c.mask);
  return l;
}

}  // namespace

void convertSingleBody(Context& ctx, const Element& e) {
  const bool mesh = e.name == "mesh";
  ctx.checkAttributes(e, labelOf(e),
                      mesh ? std::initializer_list<std::string_view>{"name", "mass", "material", "body_type", "bodyType",
                                                                     "collision_group", "collisionGroup",
                                                                     "collision_mask", "collisionMask", "com",
                                                                     "file_name", "fileName", "scale", "appearance"}
                           : std::initializer_list<std::string_view>{"name", "mass", "material", "body_type", "bodyType",
                                                                     "collision_group", "collisionGroup",
                                                                     "collision_mask", "collisionMask", "com",
                                                                     "appearance"});
  ctx.checkChildren(e, labelOf(e), {"dim", "state", "inertia"});
  Common c;
  bool ok = readCommon(ctx, e, c);
  Vec3 scale{1, 1, 1};
  double radius = 0, height = 0;
  std::string meshPath;
  if (mesh) {
    const Attribute* file = ctx.requirePath(e, "file_name", "fileName");
    if (file) meshPath = ctx.assetPath(file->value);
    // As for a robot file that does not load, the scene is still written
    // (the mesh may be made later), but rscene-sim refuses a body whose
    // collision mesh is missing (RS5001): say so now, at the element.
    std::error_code ec;
    if (file && !file->value.empty() && !std::filesystem::is_regular_file(file->value, ec))
      ctx.result.diagnostics.push_back(attributeDiagnostic(
          Severity::Warning, code::kApproximate, e, *file,
          "mesh file '" + file->value + "' not found: rscene-sim will refuse the body until it exists"));
    if (auto s = ctx.vec<3>(e, e.attribute("scale"))) scale = *s;
    ok = ok && file;
  } else {
    const Element* dim = ctx.requireChild(e, "dim");
    if (!dim) return;
    std::size_t before = errorCount(ctx);
    if (e.name == "box") {
      ctx.checkAttributes(*dim, c.label + " <dim>", {"x", "y", "z"});
      for (int i = 0; i < 3; ++i) {
        const char* axis[] = {"x", "y", "z"};
        if (auto v = length(ctx, *dim, axis[i])) scale[static_cast<std::size_t>(i)] = *v;
      }
    } else {
      bool tall = e.name != "sphere";
      ctx.checkAttributes(*dim, c.label + " <dim>",
                          tall ? std::initializer_list<std::string_view>{"radius", "height"}
                               : std::initializer_list<std::string_view>{"radius"});
      if (auto r = length(ctx, *dim, "radius")) radius = *r;
      if (tall)
        if (auto h = length(ctx, *dim, "height")) height = *h;
    }
    ok = ok && errorCount(ctx) == before;
  }
  if (!ok) return;
  Line l = objectLine(c, e.name, scale, radius, height, meshPath);
  if (c.inertia) l.key("customInertia", "true").keyNums("inertiaDiagonal", *c.inertia);
  if (c.com) l.keyNums("centerOfMass", *c.com);
  ctx.add(l, e);
  ctx.bodies.emplace(xmlName(e), c.path);
}

// RaiSim's own exporter writes a ground as
//   <ground name body_type="static" collision_group collision_mask>
//     <dim height="0"/><state/></ground>
// so body_type static (the only kind a ground is), the height in <dim>
// and an empty <state> are read too.  RaiSim's ground reader does not
// read <state>: a pos or quat there is listed as not converted (the
// plane's height is `height`, never a pos z).
void convertGround(Context& ctx, const Element& e) {
  std::string label = labelOf(e);
  ctx.checkAttributes(e, label,
                      {"name", "height", "material", "collision_mask", "collisionMask", "collision_group",
                       "collisionGroup", "body_type", "bodyType", "appearance"});
  ctx.checkChildren(e, label, {"dim", "state"});
  std::size_t before = errorCount(ctx);
  Common c;
  c.path = ctx.takePath(e);
  c.visible = ctx.visible(e, label);
  c.mode = "static";
  c.mass = 0;
  if (const Attribute* t = e.attribute("body_type", "bodyType"); t && t->value != "static")
    ctx.error(code::kBadValue, e, *t, "'" + t->value + "': a ground is static");
  if (const Attribute* m = e.attribute("material"); m && !m->value.empty()) c.material = m->value;
  std::optional<double> height = ctx.number(e, e.attribute("height"));
  if (const Element* dim = e.child("dim")) {
    ctx.checkAttributes(*dim, label + " <dim>", {"height"});
    if (auto h = ctx.number(*dim, dim->attribute("height"))) {
      if (height && *height != *h)
        ctx.error(code::kBadValue, *dim, *dim->attribute("height"),
                  "differs from the ground's height attribute (" + numberText(*height) + ")");
      height = h;
    }
  }
  if (height) c.pos[2] = *height;
  if (const Element* state = e.child("state")) {
    ctx.checkAttributes(*state, label + " <state>", {"pos", "quat", "lin_vel", "linVel", "ang_vel", "angVel"});
    auto pos = ctx.vec<3>(*state, state->attribute("pos"));
    auto quat = ctx.vec<4>(*state, state->attribute("quat"));
    if (pos && *pos != Vec3{0, 0, 0}) ctx.lost(label + " <state>: pos (a ground's height is its height)");
    if (quat && *quat != Quat{1, 0, 0, 0}) ctx.lost(label + " <state>: quat (a ground is level)");
    for (auto [name, alias] : {std::pair{"lin_vel", "linVel"}, std::pair{"ang_vel", "angVel"}})
      if (const Attribute* a = state->attribute(name, alias))
        if (auto v = ctx.vec<3>(*state, a); v && (*v != Vec3{0, 0, 0})) ctx.lost(label + " <state>: " + a->name);
  }
  if (auto g = ctx.group(e, e.attribute("collision_group", "collisionGroup"))) c.group = *g;
  if (auto m = ctx.group(e, e.attribute("collision_mask", "collisionMask"))) c.mask = *m;
  if (errorCount(ctx) != before) return;
  // 10 x 10 is only the drawn plane's size: a ground is a half-space.
  ctx.add(objectLine(c, "ground", Vec3{10, 10, 1}, 0, 0, ""), e);
  ctx.bodies.emplace(xmlName(e), c.path);
}

namespace {

// One <children> entry: sphere, capsule, cylinder or box with dim, state
// pos quat and material.
bool compoundChild(Context& ctx, const std::string& compound, const std::string& label, const Element& e,
                   std::vector<std::pair<std::string, const Element*>>& out) {
  // One label for all children, so the not-converted line says "name" once.
  std::string childLabel = label + " <children>";
  ctx.checkAttributes(e, childLabel, {"material"}, {"name", "mass", "appearance", "body_type", "bodyType"});
  ctx.checkChildren(e, childLabel, {"dim", "state"}, {"inertia"});
  std::size_t before = errorCount(ctx);
  Vec3 pos{0, 0, 0};
  Quat quat{1, 0, 0, 0};
  readState(ctx, e, childLabel, pos, quat);
  const Element* dim = ctx.requireChild(e, "dim");
  if (!dim) return false;
  Line l("compound_child");
  l.text(compound).raw(e.name).nums(pos).nums(quat).nums(Vec3{1, 1, 1});
  if (e.name == "box") {
    ctx.checkAttributes(*dim, childLabel + " <dim>", {"x", "y", "z"});
    Vec3 size{};
    const char* axis[] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i)
      if (auto v = length(ctx, *dim, axis[i])) size[static_cast<std::size_t>(i)] = *v;
    l.keyNums("size", size);
  } else {
    bool tall = e.name != "sphere";
    ctx.checkAttributes(*dim, childLabel + " <dim>",
                        tall ? std::initializer_list<std::string_view>{"radius", "height"}
                             : std::initializer_list<std::string_view>{"radius"});
    if (auto r = length(ctx, *dim, "radius")) l.keyNum("radius", *r);
    if (tall)
      if (auto h = length(ctx, *dim, "height")) l.keyNum("height", *h);
  }
  const Attribute* m = e.attribute("material");
  l.keyText("contactMaterial", m && !m->value.empty() ? m->value : "default");
  if (errorCount(ctx) != before) return false;
  out.emplace_back(l.str(), &e);
  return true;
}

}  // namespace

void convertCompound(Context& ctx, const Element& e) {
  ctx.checkAttributes(e, labelOf(e),
                      {"name", "mass", "material", "body_type", "bodyType", "collision_group", "collisionGroup",
                       "collision_mask", "collisionMask", "com", "appearance"});
  ctx.checkChildren(e, labelOf(e), {"children", "state", "inertia"});
  Common c;
  bool ok = readCommon(ctx, e, c);
  const Element* children = ctx.requireChild(e, "children");
  if (!children) return;
  std::vector<std::pair<std::string, const Element*>> childLines;
  for (const Element& child : children->children) {
    if (child.name == "sphere" || child.name == "capsule" || child.name == "cylinder" || child.name == "box") {
      ok = compoundChild(ctx, c.path, c.label, child, childLines) && ok;
    } else {
      ctx.result.diagnostics.push_back(elementDiagnostic(Severity::Warning, code::kNotConverted, child,
                                                         "not a compound child (sphere, capsule, cylinder, box)"));
      ctx.lost(c.label + ": <" + child.name + ">");
    }
  }
  if (!ok) return;
  // compound PATH pos quat scale mass bodyMode visible collidable
  Line l("compound");
  l.text(c.path).nums(c.pos).nums(c.quat).nums(Vec3{1, 1, 1}).num(c.mass.value_or(0)).raw(c.mode);
  l.raw(c.visible ? "true" : "false").raw("true");
  // Without `com` the record has no centerOfMass either: rscene-sim then
  // puts it at the children's volume-weighted centroid, and rscene-to-xml
  // writes no `com` for such a record, so the two stay inverse.
  if (c.com) l.keyNums("centerOfMass", *c.com);
  if (c.inertia) l.keyNums("inertiaDiagonal", *c.inertia);
  l.key("collisionGroup", std::to_string(c.group)).key("collisionMask", std::to_string(c.mask));
  l.keyText("contactMaterial", c.material);
  ctx.add(l, e);
  for (const auto& [line, child] : childLines) ctx.add(line, *child);
  ctx.bodies.emplace(xmlName(e), c.path);
}

}  // namespace rscene::xml::detail
