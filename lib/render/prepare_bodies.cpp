#include "render/preparer.hpp"

namespace rscene::render::preparer_detail {

void Preparer::object(const Object& o, int index) {
  if (!o.visible || o.hiddenByGroup) return;
  Drawable d;
  d.segment = segment("object", o.recordIndex, o.path, o.id, o.semanticClass, o.instanceId, o.segmentationColor);
  d.worldObject = o.bodyMode != BodyMode::VisualOnly;
  d.line = lineOf(o.recordIndex);
  d.shape = shapeOf(o.primitive);
  d.material = materialIndex(o.material);
  d.castShadow = o.castShadow;
  Affine3d pose = affine(o.world);
  if (d.shape == Shape::Ground) {
    d.world = Eigen::Translation3d(o.world.position) *
              Eigen::Scaling(std::max(o.scale.x(), kMinGroundSize), std::max(o.scale.y(), kMinGroundSize), 1.0);
    d.castShadow = false;
  } else if (d.shape == Shape::Capsule) {
    d.capsuleRadius = o.physicsRadius();
    d.capsuleHeight = o.physicsHeight();
    d.world = pose;
  } else {
    if (d.shape == Shape::Mesh) {
      d.meshPath = o.meshPath;
      d.meshColumn = columnOf(o.recordIndex, hasField(o.recordIndex, "renderMeshPath") ? "renderMeshPath" : "meshPath");
    }
    d.world = pose * Eigen::Scaling(shapeScale(d.shape, o.scale, o.radius, o.height, o.scale));
  }
  // A static body never moves; the ground is drawn about its position only.
  if (o.bodyMode != BodyMode::Static && d.shape != Shape::Ground) attach(d, Mount::Kind::Object, index, o.world);
  addDrawable(std::move(d));
}

void Preparer::compound(const Compound& c, int index) {
  if (!c.visible || c.hiddenByGroup) return;
  Affine3d pose = affine(c.world);
  int fallbackMaterial = materialIndex(c.material);
  int seg = segment("compound", c.recordIndex, c.path, c.id, c.semanticClass, -1);
  for (const CompoundChild& ch : c.children) {
    Drawable d;
    d.segment = seg;
    d.worldObject = c.bodyMode != BodyMode::VisualOnly;
    d.line = lineOf(ch.recordIndex);
    d.shape = shapeOf(ch.primitive);
    if (d.shape == Shape::Ground) d.shape = Shape::Box;
    d.material = ch.material.empty() ? fallbackMaterial : materialIndex(ch.material);
    // The physical sizes of the scene model (scene.hpp, childBox ...),
    // as the simulator collides with them.
    Affine3d local = affine(childPose(c, ch));
    double radius = childRadius(c, ch), height = childHeight(c, ch);
    if (d.shape == Shape::Capsule) {
      d.capsuleRadius = radius;
      d.capsuleHeight = height;
      d.world = pose * local;
    } else {
      if (d.shape == Shape::Mesh) {
        d.meshPath = ch.meshPath;
        d.meshColumn = columnOf(ch.recordIndex, "meshPath");
      }
      Vector3d unit = d.shape == Shape::Box    ? childBox(c, ch)
                      : d.shape == Shape::Mesh ? childScale(c, ch)
                                               : Vector3d(radius, radius, height);
      if (d.shape == Shape::Sphere) unit = Vector3d::Constant(radius);
      d.world = pose * local * Eigen::Scaling(unit);
    }
    if (c.bodyMode != BodyMode::Static) attach(d, Mount::Kind::Compound, index, c.world);
    addDrawable(std::move(d));
  }
}

int Preparer::robotBodyLink(std::size_t robot, int body) const {
  if (robot >= out_.robotModels.size() || !out_.robotModels[robot] || robot >= robotLinks_.size() || body < 0)
    return -1;
  const robot::Model& model = *out_.robotModels[robot];
  int link = model.root;
  if (body > 0) {
    std::vector<int> order = robot::defaultJointOrder(model);
    if (std::size_t(body) > order.size()) return -1;
    link = model.joints[std::size_t(order[std::size_t(body) - 1])].childLink;
  }
  return link >= 0 && std::size_t(link) < robotLinks_[robot].size() ? link : -1;
}

bool Preparer::wireEnd(const std::string& ref, int record, int localIndex, const Vector3d& point, Attachment& at,
                       Vector3d& world) const {
  at = Attachment{};
  at.local = Affine3d(Eigen::Translation3d(point));
  world = point;
  if (ref.empty()) return true;
  // The record the scene model resolved the name to (Wire::recordA/B).
  auto named = [&](const auto& node) { return record >= 0 && node.recordIndex == record; };
  for (std::size_t i = 0; i < s_.objects.size(); ++i)
    if (named(s_.objects[i])) {
      at.kind = Mount::Kind::Object;
      at.index = int(i);
      world = affine(s_.objects[i].world) * point;
      return true;
    }
  for (std::size_t i = 0; i < s_.compounds.size(); ++i)
    if (named(s_.compounds[i])) {
      at.kind = Mount::Kind::Compound;
      at.index = int(i);
      world = affine(s_.compounds[i].world) * point;
      return true;
    }
  for (const Terrain& t : s_.terrains)  // a terrain does not move: its centre is its frame
    if (named(t)) {
      world = t.center + point;
      at.local = Affine3d(Eigen::Translation3d(world));
      return true;
    }
  for (std::size_t i = 0; i < s_.articulated.size(); ++i)
    if (named(s_.articulated[i])) {
      int link = robotBodyLink(i, localIndex);
      if (link < 0) return false;
      at.kind = Mount::Kind::Articulated;
      at.index = int(i);
      at.link = link;
      world = affine(robotLinks_[i][std::size_t(link)]) * point;
      return true;
    }
  return false;
}

void Preparer::wire(const Wire& w) {
  if (!w.enabled) return;
  // A localIndex past its robot's bodies is the error validate and sim
  // give (RS7046 at the key), not a wire left undrawn.
  auto robotEnd = [&](int record, int localIndex, const char* key) {
    for (std::size_t i = 0; i < s_.articulated.size() && i < out_.robotModels.size(); ++i) {
      if (s_.articulated[i].recordIndex != record || !out_.robotModels[i]) continue;
      if (robotBodyLink(i, localIndex) >= 0) return true;
      int bodies = static_cast<int>(robot::defaultJointOrder(*out_.robotModels[i]).size()) + 1;
      RecordReader(doc_, static_cast<std::size_t>(w.recordIndex), diags_)
          .error(key, robot::code::kWireBody,
                 std::string(key) + " is " + std::to_string(localIndex) + "; '" + s_.articulated[i].path +
                     "' has bodies 0 to " + std::to_string(bodies - 1),
                 "RaiSim's body index: the base is 0, then one body per movable joint in joint order");
      ok_ = false;
      return false;
    }
    return true;
  };
  if ((w.endA == WireEnd::Articulated && !robotEnd(w.recordA, w.localIndexA, "localIndexA")) ||
      (w.endB == WireEnd::Articulated && !robotEnd(w.recordB, w.localIndexB, "localIndexB")))
    return;
  WireSpan span;
  if (!wireEnd(w.bodyA, w.recordA, w.localIndexA, w.localPositionA, span.endA, span.a) ||
      !wireEnd(w.bodyB, w.recordB, w.localIndexB, w.localPositionB, span.endB, span.b)) {
    ++out_.skipped["wire"];
    return;
  }
  span.width = std::isfinite(w.visualizationWidth) ? std::max(w.visualizationWidth, 0.0) : 0.0;
  if (wireMaterial_ < 0) {
    RenderMaterial m;
    m.id = "(wire)";
    m.color = Vector4f(0.06f, 0.06f, 0.065f, 1.0f);  // neutral dark: a steel cable in shade
    m.roughness = 0.45f;
    m.isDefault = false;
    wireMaterial_ = static_cast<int>(out_.materials.size());
    out_.materials.push_back(m);
  }
  Drawable d;
  d.shape = Shape::Cylinder;
  d.material = wireMaterial_;
  d.line = lineOf(w.recordIndex);
  d.segment = segment("wire", w.recordIndex, w.path, w.id, "", -1);
  d.world = wireTransform(span.a, span.b, span.width);
  // The renderer moves drawables that are attached; poseScene() sets the
  // transform from both ends.
  d.attachment = span.endA.kind != Mount::Kind::World ? span.endA : span.endB;
  d.wire = static_cast<int>(out_.wires.size());
  span.drawable = out_.drawables.size();
  out_.wires.push_back(span);
  addDrawable(std::move(d));
}

void Preparer::robots() {
  if (s_.articulated.empty()) return;
  RobotDrawer drawer(out_, assets());
  robot::ModelCache models;
  out_.robotModels.assign(s_.articulated.size(), nullptr);
  robotLinks_.assign(s_.articulated.size(), {});
  robot::InstanceOptions io;
  io.allowMissingMeshes = limits_.allowMissingAssets;
  for (std::size_t i = 0; i < s_.articulated.size(); ++i) {
    const Articulated& a = s_.articulated[i];
    if (a.leftOut) continue;  // --allow-missing-assets: robot::leaveOutMissingRobots warned
    if (!robot::checkRobotFile(doc_, a, diags_)) {
      ok_ = false;
      continue;
    }
    robot::RobotInstance r;
    // An error (a model that does not load, a coordinate of the wrong
    // length) fails the render; what could be read is still drawn.
    if (!robot::makeInstance(doc_, a, models, r, diags_, io)) ok_ = false;
    if (!r.model) continue;
    out_.robotModels[i] = r.model;
    robotLinks_[i] = robot::linkPoses(r);
    if (!a.visible || a.hiddenByGroup) continue;
    int seg = segment("articulated", a.recordIndex, a.path, a.id, a.semanticClass, -1);
    if (drawer.add(*r.model, robotLinks_[i], static_cast<int>(i), seg) == 0) {
      // Not an error (a collision-only model simulates), but an empty
      // picture needs a reason.
      Diagnostic d;
      d.severity = Severity::Warning;
      d.code = rs::RS9030;
      d.line = lineOf(a.recordIndex);
      d.column = d.line ? 1 : 0;
      d.message = "articulated system '" + a.path + "' draws nothing: its model '" + r.model->name +
                  "' has no visual elements";
      diags_.push_back(std::move(d));
    }
    ++out_.robots;
  }
}

}  // namespace rscene::render::preparer_detail
