#include "scene/scene_builder.hpp"

namespace rscene::scene_build {

void Builder::readObject(const RecordReader& r, int idx) {
  Object o;
  o.recordIndex = idx;
  o.path = nodePath(doc_, r.record());
  o.id = nodeId(doc_, r.record());
  o.parentId = r.str("parentGroupId");
  o.primitive = r.name("primitive");
  o.local = readPose(r, "position", "orientation");
  o.positionToken = r.positionalToken("position");
  o.scale = r.vec3("scale");
  o.radius = r.number("radius");
  o.height = r.number("height");
  o.mass = r.number("mass");
  o.contactMaterial = r.str("contactMaterial");
  o.material = r.str("material");
  o.collidable = r.flag("collidable");
  o.collisionGroup = r.group("collisionGroup");
  o.collisionMask = r.group("collisionMask");
  o.bodyMode = objectMode(r, o.primitive, o.collidable);
  o.visible = r.flag("visible");
  o.castShadow = r.flag("castShadow");
  o.semanticClass = r.str("semanticClass");
  if (o.semanticClass == "-") o.semanticClass.clear();
  o.instanceId = r.has("instanceId") ? r.integer("instanceId") : -1;
  if (r.has("segmentationColor")) o.segmentationColor = r.color("segmentationColor");
  std::string mesh = r.str("meshPath");
  if (std::string render = r.str("renderMeshPath"); !render.empty()) mesh = render;
  std::string collision = r.str("collisionMeshPath");
  o.meshPath = asset(mesh);
  o.collisionMeshPath = collision.empty() ? o.meshPath : asset(collision);
  o.collisionMode = r.has("collisionMode") ? r.name("collisionMode")
                                           : r.name("meshCollision");
  o.hasInertia = r.flag("customInertia", false) && r.has("inertiaDiagonal");
  o.inertiaDiagonal = r.vec3("inertiaDiagonal", Eigen::Vector3d::Zero());  // unused unless hasInertia
  parentOf_[idx] = o.parentId;
  s_.objects.push_back(std::move(o));
}

BodyMode Builder::objectMode(const RecordReader& r, const std::string& primitive, bool collidable) {
  BodyMode m = BodyMode::Dynamic;
  std::optional<std::string_view> mode;
  if (std::optional<std::string> t = r.text("bodyMode"))
    if (const EnumDef* e = Schema::get().enumDef("body_mode")) mode = e->canonical(*t);
  if (mode) {
    m = *mode == "static"      ? BodyMode::Static
        : *mode == "kinematic" ? BodyMode::Kinematic
        : *mode == "dynamic"   ? BodyMode::Dynamic
                               : BodyMode::VisualOnly;
  } else if (r.flag("visualOnly")) {
    m = BodyMode::VisualOnly;
  } else if (r.flag("locked") || r.flag("fixed")) {
    m = BodyMode::Static;
  }
  if ((primitive == "ground" || primitive == "half_space") && m != BodyMode::VisualOnly) m = BodyMode::Static;
  return collidable ? m : BodyMode::VisualOnly;
}

bool Builder::plainBody(const Record& rec) {
  const Layout* layout = rec.kind->layoutFor(rec.positionalCount);
  if (!layout) return false;
  auto [it, added] = plainSlots_.try_emplace(layout);
  std::vector<int>& slots = it->second;
  if (added) {
    for (const char* name : {"primitive", "scale", "radius", "height", "mass"})
      for (std::size_t t = 0; t < layout->tokens.size(); ++t) {
        const FieldDef& f = layout->fields[static_cast<std::size_t>(layout->tokens[t].first)];
        if (f.name != name || layout->tokens[t].second != 0) continue;
        for (int c = 0; c < f.width; ++c) slots.push_back(static_cast<int>(t) + c);
      }
    if (slots.size() != 7) slots.clear();  // not the layout this test knows: build in full
    for (const char* name : {"bodyMode", "collidable"}) {
      int t = -1;
      for (std::size_t k = 0; k < layout->tokens.size() && !slots.empty(); ++k)
        if (layout->fields[static_cast<std::size_t>(layout->tokens[k].first)].name == name) t = static_cast<int>(k);
      if (!slots.empty()) slots.push_back(t);
    }
    // slots[9..15]: position and orientation, for checkNumericLimits().
    std::size_t poseStart = slots.size();
    for (const char* name : {"position", "orientation"})
      for (std::size_t t = 0; t < layout->tokens.size() && !slots.empty(); ++t) {
        const FieldDef& f = layout->fields[static_cast<std::size_t>(layout->tokens[t].first)];
        if (f.name != name || layout->tokens[t].second != 0) continue;
        for (int c = 0; c < f.width; ++c) slots.push_back(static_cast<int>(t) + c);
      }
    if (!slots.empty() && slots.size() - poseStart != 7) slots.clear();
  }
  if (slots.empty()) return false;
  if (doc_.find(rec, "inertiaDiagonal")) return false;  // a custom inertia is checked (RS7090)
  if (slots[7] >= 0) {
    std::string_view mode = doc_.positionalText(rec, static_cast<std::uint32_t>(slots[7]));
    if (mode == "visual_only" || mode == "visualonly" || mode == "visual") return true;
  }
  if (slots[8] >= 0 && parseFlag(doc_.positionalText(rec, static_cast<std::uint32_t>(slots[8]))) == false) return true;
  static constexpr std::string_view kPlain[] = {"box",    "cube",   "sphere",    "cylinder",
                                                "capsule", "ground", "plane",     "half_space"};
  std::string_view prim = doc_.positionalText(rec, static_cast<std::uint32_t>(slots[0]));
  if (std::find(std::begin(kPlain), std::end(kPlain), prim) == std::end(kPlain)) return false;
  // The ground rule (scene/start_pose.hpp) reads the planes and the bodies
  // that may move; only static and kinematic boxes and spheres are left out.
  if (prim == "ground" || prim == "plane" || prim == "half_space" || slots[7] < 0) return false;
  if (std::string_view mode = doc_.positionalText(rec, static_cast<std::uint32_t>(slots[7]));
      mode != "static" && mode != "fixed" && mode != "kinematic")
    return false;
  for (std::size_t k = 1; k < 7; ++k)  // scale x3, radius, height, mass
    if (!positiveNumber(doc_.positionalText(rec, static_cast<std::uint32_t>(slots[k])), k == 6 ? kMaxMass : kMaxLength))
      return false;
  bool rotates = false;  // an orientation of four zeros does not normalise
  for (std::size_t k = 9; k < 16; ++k) {
    std::string_view v = doc_.positionalText(rec, static_cast<std::uint32_t>(slots[k]));
    if (!v.empty() && v.front() == '-') v.remove_prefix(1);
    if (!plainDecimal(v)) return false;
    rotates = rotates || (k >= 12 && positiveNumber(v, kMaxLength));
  }
  return rotates;
}

bool Builder::plainDecimal(std::string_view s) {
  if (s.empty() || s.size() >= 32 || s.front() == '.') return false;
  int dots = 0, whole = 0;
  for (char c : s) {
    if (c == '.') ++dots;
    else if (c < '0' || c > '9') return false;
    else if (!dots) ++whole;
  }
  return dots <= 1 && whole <= 12;
}

bool Builder::positiveNumber(std::string_view s, double max) {
  bool digits = !s.empty() && s.size() < 32, nonZero = false;
  int dots = 0, whole = 0;
  for (char c : s) {
    if (c == '.') ++dots;
    else if (c < '0' || c > '9') digits = false;
    else {
      nonZero = nonZero || c != '0';
      if (!dots) ++whole;
    }
  }
  if (digits && dots <= 1 && s.front() != '.' && whole <= 12) return nonZero;
  std::optional<double> v = parseNumber(s);
  return v && std::isnormal(*v) && *v > 0 && *v <= max;
}

void Builder::readCompound(const RecordReader& r, int idx) {
  Compound c;
  c.recordIndex = idx;
  c.path = nodePath(doc_, r.record());
  c.id = nodeId(doc_, r.record());
  c.parentId = r.str("parentGroupId");
  c.local = readPose(r, "position", "orientation");
  c.positionToken = r.positionalToken("position");
  c.scale = r.vec3("scale");
  c.mass = r.number("mass");
  std::string mode = r.name("bodyMode");
  c.bodyMode = mode == "static"      ? BodyMode::Static
               : mode == "kinematic" ? BodyMode::Kinematic
               : mode == "dynamic"   ? BodyMode::Dynamic
                                     : BodyMode::VisualOnly;
  c.visible = r.flag("visible");
  c.collidable = r.flag("collidable");
  if (!c.collidable) c.bodyMode = BodyMode::VisualOnly;
  c.hasCenterOfMass = r.has("centerOfMass");
  c.centerOfMass = r.vec3("centerOfMass", Eigen::Vector3d::Zero());  // unused when absent
  c.hasInertia = r.has("inertiaDiagonal");
  c.inertiaDiagonal = r.vec3("inertiaDiagonal", Eigen::Vector3d::Zero());  // unused when absent
  c.collisionGroup = r.group("collisionGroup");
  c.collisionMask = r.group("collisionMask");
  c.contactMaterial = r.str("contactMaterial");
  c.material = r.str("material");
  c.semanticClass = r.str("semanticClass");
  if (c.semanticClass == "-") c.semanticClass.clear();
  parentOf_[idx] = c.parentId;
  s_.compounds.push_back(std::move(c));
}

void Builder::readCompoundChild(const RecordReader& r, int idx) {
  std::string ref = r.str("compound");
  Compound* owner = lastNamed(s_.compounds, ref);
  if (!owner) {
    orphan(r, "compound");
    return;
  }
  CompoundChild ch;
  ch.recordIndex = idx;
  ch.primitive = r.name("primitive");
  ch.local = readPose(r, "position", "orientation");
  ch.scale = r.vec3("scale");
  ch.size = r.vec3("size");
  ch.radius = r.number("radius");
  ch.height = r.number("height");
  ch.contactMaterial = r.str("contactMaterial", owner->contactMaterial);
  ch.material = r.str("material", owner->material);
  ch.meshPath = asset(r.str("meshPath"));
  owner->children.push_back(std::move(ch));
}

bool Builder::sampleList(const RecordReader& r, std::string_view name, std::size_t samples, int per,
                         std::vector<double>& out) {
  if (!r.numbers(name, out)) return false;
  if (out.empty() || out.size() == samples * per) return true;
  r.error(name, rs::RS4003,
          std::string(name) + " has " + std::to_string(out.size() / per) + " entries, expected " +
              std::to_string(samples) + " (one per sample) or none");
  out.clear();
  return false;
}

void Builder::readTerrain(const RecordReader& r, int idx) {
  Terrain t;
  t.recordIndex = idx;
  t.path = nodePath(doc_, r.record());
  t.id = nodeId(doc_, r.record());
  t.parentId = r.str("parentGroupId");
  // A count that is not a 32-bit integer is the reader's RS2003 already
  // (as in validate); it is not then also "0, outside 2..16384".
  std::size_t before = diags_.size();
  std::int64_t xs = r.integer("xSamples");
  bool xRead = diags_.size() == before;
  before = diags_.size();
  std::int64_t ys = r.integer("ySamples");
  bool yRead = diags_.size() == before;
  t.xSize = r.number("xSize");
  t.ySize = r.number("ySize");
  t.center = r.vec3("center");
  // Counts are checked before any list is parsed, so a hostile header
  // cannot ask for an unbounded allocation.
  // The validator's codes: RS4001 per axis, RS4002 in total, RS4014 sizes.
  bool countsOk = true;
  for (auto [name, v, read] : {std::tuple{"xSamples", xs, xRead}, std::tuple{"ySamples", ys, yRead}})
    if (v < 2 || v > 16384) {
      if (read) r.error(name, rs::RS4001, std::string(name) + " is " + std::to_string(v) + ", outside 2..16384");
      countsOk = false;
    }
  if (countsOk && static_cast<std::uint64_t>(xs) * static_cast<std::uint64_t>(ys) > kMaxTerrainSamples) {
    r.error("xSamples", rs::RS4002, "terrain has " + std::to_string(xs * ys) + " samples, more than 64 Mi");
    countsOk = false;
  }
  bool sizeOk = true;
  for (auto [name, v] : {std::pair{"xSize", t.xSize}, std::pair{"ySize", t.ySize}})
    if (!(v > 0)) {
      r.error(name, rs::RS4014, std::string(name) + " is not positive");
      sizeOk = false;
    }
  if (!countsOk || !sizeOk) return;
  t.xSamples = static_cast<int>(xs);
  t.ySamples = static_cast<int>(ys);
  std::size_t n = static_cast<std::size_t>(xs * ys);
  if (!sampleList(r, "heights", n, 1, t.heights)) return;
  if (t.heights.empty()) t.heights.assign(n, 0.0);
  t.material = r.str("material");
  t.contactMaterial = r.str("contactMaterial");
  t.baseTexture = static_cast<int>(r.integer("baseTexture"));
  t.visible = r.flag("visible");
  t.collidable = r.flag("collidable");
  t.castShadow = r.flag("castShadow");
  t.receiveShadow = r.flag("receiveShadow");
  t.textureSplatting = r.flag("textureSplattingEnabled");
  t.sourceKind = r.name("sourceKind");
  sampleList(r, "texturePrimary", n, 1, t.texturePrimary);
  sampleList(r, "textureSecondary", n, 1, t.textureSecondary);
  sampleList(r, "textureBlend", n, 1, t.textureBlend);
  sampleList(r, "wetness", n, 1, t.wetness);
  sampleList(r, "holes", n, 1, t.holes);
  std::vector<double> colors;
  if (r.numbers("vertexColors", colors) && !colors.empty()) {
    int per = colors.size() == n * 4 ? 4 : colors.size() == n * 3 ? 3 : 0;
    if (!per) {
      r.error("vertexColors", rs::RS4006, "vertexColors needs one color per sample or none");
    } else {
      t.vertexColors.reserve(n);
      for (std::size_t i = 0; i < n; ++i)
        t.vertexColors.emplace_back(colors[i * per], colors[i * per + 1], colors[i * per + 2],
                                    per == 4 ? colors[i * per + 3] : 1.0);
    }
  }
  parentOf_[idx] = t.parentId;
  s_.terrains.push_back(std::move(t));
}

void Builder::readTerrainNode(const RecordReader& r, int idx) {
  Terrain t;
  t.recordIndex = idx;
  t.path = nodePath(doc_, r.record());
  t.id = nodeId(doc_, r.record());
  t.parentId = r.str("parentGroupId");
  parentOf_[idx] = t.parentId;
  s_.terrains.push_back(std::move(t));
}

void Builder::readFoliage(const RecordReader& r, int idx) {
  Terrain* owner = lastNamed(s_.terrains, r.str("terrain"));
  if (!owner) {
    orphan(r, "terrain_region");
    return;
  }
  FoliageLayer l = readFoliageLayer(r, idx, assetFn());
  if (!opt_.bodiesOnly) {  // a terrain node of a bodiesOnly build has no samples (validate checks the list)
    std::size_t samples = static_cast<std::size_t>(owner->xSamples) * owner->ySamples;
    sampleList(r, "density", samples, 1, l.density);
  }
  owner->foliageLayers.push_back(std::move(l));
}

void Builder::readSplat(const RecordReader& r, int idx) {
  std::string ref = r.str("terrain");
  Terrain* owner = lastNamed(s_.terrains, ref);
  if (!owner) {
    orphan(r, "terrain_region");
    return;
  }
  TerrainSplatLayer l;
  l.recordIndex = idx;
  l.slot = static_cast<int>(r.integer("slot"));
  l.enabled = r.flag("enabled");
  l.strength = r.number("strength");
  sampleList(r, "weights", static_cast<std::size_t>(owner->xSamples) * owner->ySamples, 1, l.weights);
  owner->splatLayers.push_back(std::move(l));
}

void Builder::readWire(const RecordReader& r, int idx) {
  Wire w;
  w.recordIndex = idx;
  w.path = nodePath(doc_, r.record());
  w.id = nodeId(doc_, r.record());
  w.kind = r.name("kind");
  w.bodyA = r.str("bodyA");
  w.bodyB = r.str("bodyB");
  w.length = r.number("length");
  w.localIndexA = static_cast<int>(r.integer("localIndexA"));
  w.localIndexB = static_cast<int>(r.integer("localIndexB"));
  w.localPositionA = r.vec3("localPositionA");
  w.localPositionB = r.vec3("localPositionB");
  w.stiffness = r.number("stiffness");
  w.damping = r.number("damping");
  w.compliance = r.number("compliance");
  w.visualizationWidth = r.number("visualizationWidth");
  w.enabled = r.flag("enabled");
  s_.wires.push_back(std::move(w));
}

void Builder::readInstanced(const RecordReader& r, int idx) {
  InstancedVisual v;
  v.recordIndex = idx;
  v.path = nodePath(doc_, r.record());
  v.id = nodeId(doc_, r.record());
  v.primitive = r.name("primitive");
  v.meshPath = asset(r.str("meshPath"));
  v.size = r.vec3("size");
  v.colorA = r.color("colorA");
  v.colorB = r.color("colorB");
  std::vector<double> xs;
  if (r.numbers("instances", xs)) {
    if (xs.size() % 10) {
      r.error("instances", rs::RS4004, "instances holds " + std::to_string(xs.size()) +
                                                      " numbers, not a multiple of 10");
    } else {
      v.instances.reserve(xs.size() / 10);
      for (std::size_t i = 0; i < xs.size(); i += 10) {
        Instance in;
        in.position = {xs[i], xs[i + 1], xs[i + 2]};
        Eigen::Quaterniond q(xs[i + 3], xs[i + 4], xs[i + 5], xs[i + 6]);
        in.orientation = q.norm() > 1e-12 ? q.normalized() : Eigen::Quaterniond::Identity();
        in.scale = {xs[i + 7], xs[i + 8], xs[i + 9]};
        v.instances.push_back(in);
      }
    }
  }
  r.numbers("colorWeights", v.colorWeights);
  v.maxRendered = r.integer("maxRenderedInstances", 0);
  v.renderedStride = r.integer("renderedInstanceStride", 1);
  v.castShadows = r.flag("castShadows");
  v.grassPatch = r.flag("grassPatch");
  v.terrainBinding = r.str("terrainBinding");
  v.terrainFoliageLayer = r.integer("terrainFoliageLayer", -1);
  v.enabled = r.flag("enabled");
  v.parentId = r.str("parentGroupId");
  parentOf_[idx] = v.parentId;
  s_.instancedVisuals.push_back(std::move(v));
}

void Builder::readPointCloud(const RecordReader& r, int idx) {
  PointCloud p;
  p.recordIndex = idx;
  p.path = nodePath(doc_, r.record());
  p.id = nodeId(doc_, r.record());
  std::vector<double> xs;
  if (r.numbers("points", xs)) {
    if (xs.size() % 3) {
      r.error("points", rs::RS2008, "points holds " + std::to_string(xs.size()) +
                                                   " numbers, not a multiple of 3");
    } else {
      for (std::size_t i = 0; i < xs.size(); i += 3) p.points.emplace_back(xs[i], xs[i + 1], xs[i + 2]);
    }
  }
  if (r.numbers("colors", xs) && !xs.empty() && !p.points.empty()) {
    std::size_t per = xs.size() == p.points.size() * 4 ? 4 : xs.size() == p.points.size() * 3 ? 3 : 0;
    if (per)
      for (std::size_t i = 0; i < p.points.size(); ++i)
        p.colors.emplace_back(xs[i * per], xs[i * per + 1], xs[i * per + 2], per == 4 ? xs[i * per + 3] : 1.0);
    else
      r.error("colors", scene_code::kBadValue, "colors needs one color per point or none");
  }
  p.pointSize = r.number("pointSize");
  p.maxRendered = r.integer("maxRenderedPoints", 0);
  p.renderedStride = r.integer("renderedPointStride", 1);
  p.enabled = r.flag("enabled");
  p.parentId = r.str("parentGroupId");
  parentOf_[idx] = p.parentId;
  s_.pointClouds.push_back(std::move(p));
}

}  // namespace rscene::scene_build
