// <articulatedSystem> as articulated_resource + articulated records, and
// <wire> as a wire record.  lib/robot says whether a robot's base floats
// (its qpos then starts with the base pose) and which body a wire's
// `frame` is on; a robot file that does not load is still converted.
#include <algorithm>
#include <filesystem>

#include "robot/kinematics.hpp"
#include "xml/from_xml_context.hpp"

namespace rscene::xml::detail {
namespace {

std::vector<std::string> words(std::string_view s) {
  std::vector<std::string> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r')) ++i;
    std::size_t j = i;
    while (j < s.size() && !(s[j] == ' ' || s[j] == '\t' || s[j] == '\n' || s[j] == '\r')) ++j;
    if (j > i) out.emplace_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

// The articulated_resource of a robot file: one per distinct file.
std::string resourceFor(Context& ctx, const std::string& file, const Element& from) {
  if (auto it = ctx.resourceOf.find(file); it != ctx.resourceOf.end()) return it->second;
  std::string stem = std::filesystem::path(file).stem().string();
  if (stem.empty()) stem = "robot";
  std::string id = "res_" + stem;
  for (int n = 2; ctx.resourceIds.count(id); ++n) id = "res_" + stem + "_" + std::to_string(n);
  ctx.resourceIds.insert(id);
  ctx.resourceOf.emplace(file, id);
  Line l("articulated_resource");
  l.text(id).text(stem).text(ctx.assetPath(file));
  ctx.add(l, from);
  return id;
}

}  // namespace

void convertArticulated(Context& ctx, const Element& e) {
  std::string label = labelOf(e);
  ctx.checkAttributes(e, label,
                      {"name", "urdf_path", "urdfPath", "res_dir", "resDir", "modules", "collision_group",
                       "collisionGroup", "collision_mask", "collisionMask", "appearance"});
  const bool visible = ctx.visible(e, label);
  // RaiSim's exporter writes an empty <dim/> in every articulatedSystem.
  ctx.checkChildren(e, label, {"state", "dim"});
  if (const Element* dim = e.child("dim")) ctx.checkAttributes(*dim, label + " <dim>", {});
  std::string path = ctx.takePath(e);
  const Attribute* urdf = ctx.requirePath(e, "urdf_path", "urdfPath");
  const Attribute* resDir = e.attribute("res_dir", "resDir");
  const Attribute* modules = e.attribute("modules");
  auto group = ctx.group(e, e.attribute("collision_group", "collisionGroup"));
  auto mask = ctx.group(e, e.attribute("collision_mask", "collisionMask"));
  std::vector<double> qpos, qvel;
  bool ok = urdf != nullptr;
  if (const Element* state = e.child("state")) {
    ctx.checkAttributes(*state, label + " <state>", {"qpos", "qvel"});
    if (const Attribute* q = state->attribute("qpos")) ok = ctx.numbers(*state, *q, qpos) && ok;
    if (const Attribute* u = state->attribute("qvel")) ok = ctx.numbers(*state, *u, qvel) && ok;
  }
  if (!ok) return;

  robot::LoadOptions lo;
  if (resDir) lo.resourceDirectory = resDir->value;
  if (modules) lo.modules = words(modules->value);
  Diagnostics loadDiags;
  std::shared_ptr<const robot::Model> model = ctx.models.get(urdf->value, lo, loadDiags);
  Vec3 pos{0, 0, 0};
  Quat quat{1, 0, 0, 0};
  if (model) {
    robot::Coordinates c;
    robot::makeCoordinates(*model, {}, c);
    const Element* state = e.child("state");
    auto size = [&](const char* name, const std::vector<double>& v, int want) {
      if (v.empty() || static_cast<int>(v.size()) == want) return true;
      ctx.error(code::kBadValue, *state, *state->attribute(name),
                "has " + std::to_string(v.size()) + " numbers, the robot has " + std::to_string(want));
      return false;
    };
    if (!size("qpos", qpos, c.coordinateDim) || !size("qvel", qvel, c.velocityDim)) return;
    if (model->floatingBase && qpos.size() >= 7) {
      pos = {qpos[0], qpos[1], qpos[2]};
      quat = {qpos[3], qpos[4], qpos[5], qpos[6]};
    }
  } else {
    std::string why = "it did not load";
    for (const Diagnostic& d : loadDiags)
      if (d.severity == Severity::Error) {
        why = d.message;
        break;
      }
    ctx.warning(code::kApproximate, e,
                "robot file not read (" + why + "): placed at the origin, qpos kept as written");
  }
  std::string resource = resourceFor(ctx, urdf->value, e);
  // articulated PATH resource pos quat visible collidable
  Line l("articulated");
  l.text(path).text(resource).nums(pos).nums(quat).raw(visible ? "true" : "false").raw("true");
  if (resDir) l.keyText("resourceDirectory", ctx.assetPath(resDir->value));
  if (modules && !words(modules->value).empty()) l.keyList("modules", words(modules->value));
  // The schema's defaults (1, all bits) are left out, as rscene-to-xml
  // leaves them out of the XML, so a round trip gives the same record.
  if (group && *group != 1) l.key("collisionGroup", std::to_string(*group));
  if (mask && *mask != ~std::uint64_t{0}) l.key("collisionMask", std::to_string(*mask));
  if (!qpos.empty()) l.keyNums("generalizedCoordinate", qpos.data(), qpos.size());
  if (!qvel.empty()) l.keyNums("generalizedVelocity", qvel.data(), qvel.size());
  ctx.add(l, e);
  ctx.robots.emplace(xmlName(e), Context::Robot{path, model});
}

namespace {

// RaiSim's body index of a link: 0 for the root body, else 1 + the index
// of the movable joint above it in RaiSim's joint order (fixed joints merge
// a link into its parent's body).  `inBody` is the link's frame in that
// body's frame.
int bodyIndexOf(const robot::Model& model, int link, Pose& inBody) {
  robot::Coordinates c;
  robot::makeCoordinates(model, {}, c);
  std::vector<Pose> poses = robot::linkPoses(model, c, Pose{}, robot::neutralCoordinate(model, c, Pose{}));
  int bodyLink = link;
  while (true) {
    int j = model.links[static_cast<std::size_t>(bodyLink)].parentJoint;
    if (j < 0 || model.joints[static_cast<std::size_t>(j)].type != robot::JointType::Fixed) break;
    bodyLink = model.joints[static_cast<std::size_t>(j)].parentLink;
  }
  inBody = poses[static_cast<std::size_t>(bodyLink)].inverse() * poses[static_cast<std::size_t>(link)];
  int j = model.links[static_cast<std::size_t>(bodyLink)].parentJoint;
  if (j < 0) return 0;
  auto it = std::find(c.joints.begin(), c.joints.end(), j);
  return it == c.joints.end() ? 0 : static_cast<int>(it - c.joints.begin()) + 1;
}

bool stretchOnly(std::string_view v) {
  std::string lower;
  for (char c : v) lower += static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return lower == "stretch_only" || lower == "stretch_resistant_only";
}

struct End {
  std::string body;
  int index = 0;
  Vec3 pos{0, 0, 0};
};

bool wireEnd(Context& ctx, const Element& wire, const std::string& label, const char* tag, End& out) {
  const Element* e = ctx.requireChild(wire, tag);
  if (!e) return false;
  std::string endLabel = label + " <" + tag + ">";
  ctx.checkAttributes(*e, endLabel, {"name", "local_index", "localIndex", "pos", "frame"});
  const Attribute* name = ctx.require(*e, "name");
  if (!name) return false;
  bool ok = true;
  if (auto p = ctx.vec<3>(*e, e->attribute("pos"))) out.pos = *p;
  else ok = !e->attribute("pos");
  if (const Attribute* li = e->attribute("local_index", "localIndex")) {
    auto v = ctx.integer(*e, li, 0, 1000000);
    if (!v) return false;
    out.index = static_cast<int>(*v);
  }
  if (auto body = ctx.bodies.find(name->value); body != ctx.bodies.end()) {
    out.body = body->second;
    if (const Attribute* frame = e->attribute("frame"))
      ctx.error(code::kBadValue, *e, *frame, "a frame names a link of an articulated system, '" + name->value +
                                                 "' is a single body");
    return ok && !e->attribute("frame");
  }
  auto robot = ctx.robots.find(name->value);
  if (robot == ctx.robots.end()) {
    ctx.error(code::kBadValue, *e, *name, "no object named '" + name->value + "' before this wire");
    return false;
  }
  out.body = robot->second.path;
  const Attribute* frame = e->attribute("frame");
  if (!frame) return ok;
  if (!robot->second.model) {
    ctx.lost(endLabel + ": frame '" + frame->value + "' (robot file not read)");
    return ok;
  }
  const robot::Model& model = *robot->second.model;
  int link = robot::frameLink(model, frame->value);
  if (link < 0) {
    ctx.error(code::kBadValue, *e, *frame, "'" + name->value + "' has no frame named '" + frame->value + "'");
    return false;
  }
  Pose inBody;
  out.index = bodyIndexOf(model, link, inBody);
  Eigen::Vector3d p = inBody.position + inBody.orientation * Eigen::Vector3d(out.pos[0], out.pos[1], out.pos[2]);
  out.pos = {p.x(), p.y(), p.z()};
  return ok;
}

}  // namespace

void convertWire(Context& ctx, const Element& e) {
  std::string label = labelOf(e);
  ctx.checkAttributes(e, label,
                      {"name", "type", "length", "stiffness", "stretch_type", "stretchType"},
                      {"appearance", "damping"});
  ctx.checkChildren(e, label, {"object1", "object2"});
  std::string path = ctx.takePath(e);
  const Attribute* type = ctx.require(e, "type");
  auto length = ctx.number(e, ctx.require(e, "length"));
  auto stiffness = ctx.number(e, e.attribute("stiffness"));
  bool ok = type && length;
  if (type && type->value != "stiff" && type->value != "compliant" && type->value != "custom") {
    ctx.error(code::kBadValue, e, *type, "'" + type->value + "' is not stiff, compliant or custom");
    ok = false;
  }
  if (type && type->value == "compliant" && !stiffness) {
    ctx.error(code::kMissing, e, "'stiffness' is required for a compliant wire");
    ok = false;
  }
  // rscene wires resist stretch only: RaiSim's exporter spells that
  // "stretch_only" (the enum STRETCH_RESISTANT_ONLY); "both" and
  // "compression_only" (BOTH, COMPRESSION_RESISTANT_ONLY) are lost.
  if (const Attribute* st = e.attribute("stretch_type", "stretchType"); st && !stretchOnly(st->value))
    ctx.lost(label + ": stretch_type " + st->value + " (rscene wires resist stretch only)");
  End a, b;
  ok = wireEnd(ctx, e, label, "object1", a) && ok;
  ok = wireEnd(ctx, e, label, "object2", b) && ok;
  if (!ok) return;
  // wire PATH kind bodyA bodyB length
  Line l("wire");
  l.text(path).raw(type->value).text(a.body).text(b.body).num(*length);
  l.key("localIndexA", std::to_string(a.index)).key("localIndexB", std::to_string(b.index));
  l.keyNums("localPositionA", a.pos).keyNums("localPositionB", b.pos);
  if (stiffness) l.keyNum("stiffness", *stiffness);
  ctx.add(l, e);
}

}  // namespace rscene::xml::detail
