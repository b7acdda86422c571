#include "scene/scene.hpp"

#include <algorithm>
#include <limits>
#include <cmath>
#include <tuple>
#include <unordered_map>

#include "scene/limits.hpp"
#include "scene/reader.hpp"
#include "scene/visual_records_read.hpp"
#include "core/filesystem.hpp"
#include "core/text.hpp"

namespace rscene {
namespace {

// The last node of `nodes` whose id or path is `ref` (a child record
// belongs to the most recent parent of that name), or nullptr.
template <class Node>
Node* lastNamed(std::vector<Node>& nodes, const std::string& ref) {
  Node* found = nullptr;
  for (Node& n : nodes)
    if (n.id == ref || n.path == ref) found = &n;
  return found;
}

// Record kinds the view turns into structs; other node and child kinds are
// listed in Scene::skipped.
constexpr std::string_view kModelled[] = {"group",  "terrain_region", "terrain_splat_layer", "light",
                                          "camera", "object",         "compound",            "compound_child",
                                          "wire",   "instanced_visual", "point_cloud", "articulated",
                                          "articulated_ik", "sensor", "projected_decal", "local_fog",
                                          "irradiance_volume", "reflection_probe", "terrain_foliage_layer",
                                          "deformable", "granular"};

bool modelled(std::string_view tag) {
  return std::find(std::begin(kModelled), std::end(kModelled), tag) != std::end(kModelled);
}

// Record kinds SceneOptions::bodiesOnly builds.
bool forBodies(std::string_view tag) {
  return tag == "time_step" || tag == "group" || tag == "object" || tag == "compound" || tag == "compound_child" ||
         tag == "terrain_region" || tag == "wire" || tag == "point_cloud" || tag == "articulated_resource" ||
         tag == "articulated" || tag == "articulated_ik" || tag == "deformable" || tag == "granular" || tag == "terrain_foliage_layer";
}

Eigen::Quaterniond toQuat(const Eigen::Vector4d& wxyz) { return {wxyz[0], wxyz[1], wxyz[2], wxyz[3]}; }

class Builder {
 public:
  Builder(const Document& doc, const SceneOptions& opt, Scene& scene, Diagnostics& diags)
      : doc_(doc), opt_(opt), s_(scene), diags_(diags) {}

  void run() {
    s_.assetRoot = assetRootOf(doc_);
    absentSingletons();
    for (std::size_t i = 1; i < doc_.records.size(); ++i) {
      const Record& rec = doc_.records[i];
      if (!rec.kind) continue;
      const std::string& tag = rec.kind->tag;
      if (opt_.bodiesOnly && (rec.kind == objectKind_ ? plainBody(rec) : !forBodies(tag))) continue;
      RecordReader r(doc_, i, diags_);
      int idx = static_cast<int>(i);
      if (tag == "time_step") {
        s_.timeStepRecord = idx;
        s_.timeStep = r.number("dt");
      }
      else if (tag == "gravity") s_.gravity = r.vec3("gravity");
      else if (tag == "solver") readSolver(r, idx);
      else if (tag == "scene_graph") s_.inheritedTransforms = r.flag("inheritedTransforms");
      else if (tag == "environment") readEnvironment(r, idx);
      else if (tag == "weather") readWeather(r, idx);
      else if (tag == "rayrai_render") readRenderSettings(r, idx);
      else if (tag == "material") readMaterial(r, idx);
      else if (tag == "contact_material") readContact(r, idx);
      else if (tag == "terrain_texture") readTerrainTexture(r, idx);
      else if (tag == "group") readGroup(r, idx);
      else if (tag == "light") readLight(r, idx);
      else if (tag == "camera") readCamera(r, idx);
      else if (tag == "object") readObject(r, idx);
      else if (tag == "compound") readCompound(r, idx);
      else if (tag == "compound_child") readCompoundChild(r, idx);
      else if (tag == "terrain_region" && opt_.bodiesOnly) readTerrainNode(r, idx);
      else if (tag == "terrain_region") readTerrain(r, idx);
      else if (tag == "terrain_splat_layer") readSplat(r, idx);
      else if (tag == "wire") readWire(r, idx);
      else if (tag == "instanced_visual") readInstanced(r, idx);
      else if (tag == "point_cloud") readPointCloud(r, idx);
      else if (tag == "articulated_resource") readArticulatedResource(r, idx);
      else if (tag == "articulated") readArticulated(r, idx);
      else if (tag == "articulated_ik") readArticulatedIk(r, idx);
      else if (tag == "sensor") readSensor(r, idx);
      else if (tag == "projected_decal") node(s_.decals, readDecal(doc_, r, idx, assetFn()));
      else if (tag == "local_fog") node(s_.localFogs, readLocalFog(doc_, r, idx));
      else if (tag == "irradiance_volume") node(s_.irradianceVolumes, readIrradianceVolume(doc_, r, idx));
      else if (tag == "reflection_probe") node(s_.reflectionProbes, readReflectionProbe(doc_, r, idx));
      else if (tag == "terrain_foliage_layer") readFoliage(r, idx);
      else if (tag == "deformable") node(s_.deformables, readDeformable(doc_, r, idx, assetFn()));
      else if (tag == "granular") node(s_.granulars, readGranular(doc_, r, idx));
      else if ((rec.kind->role == Role::Node || rec.kind->role == Role::Child) && !modelled(tag))
        s_.skipped.push_back({idx, tag, nodePath(doc_, rec)});
    }
    defaults();
    resolveArticulated();
    if (!opt_.bodiesOnly) resolveWorld();  // checkScene() needs no world poses
    resolveWires();
  }

 private:
  std::string asset(const std::string& path) const {
    if (path.empty()) return path;
    std::string out = resolveAsset(opt_.baseDir.empty() ? opt_.sceneDir : opt_.baseDir, s_.assetRoot, path, opt_.exists);
    for (std::size_t at; (at = out.find("/./")) != std::string::npos;) out.erase(at, 2);  // "dir/./x" -> "dir/x"
    return out;
  }

  // The id and path index of every node, built on the first lookup: a
  // bodiesOnly build of a scene without wires never needs it.
  void indexNodes() const {
    indexed_ = true;
    for (std::size_t i = 1; i < doc_.records.size(); ++i) {
      const Record& rec = doc_.records[i];
      if (!rec.kind || rec.kind->role != Role::Node) continue;
      std::string id = nodeId(doc_, rec), path = nodePath(doc_, rec);
      if (!id.empty()) byId_.emplace(id, i);
      if (!path.empty()) byPath_.emplace(path, i);
    }
  }

  // Record index of a node named by id or by path, or -1.
  int lookup(const std::string& ref) const {
    if (ref.empty()) return -1;
    if (!indexed_) indexNodes();
    if (auto it = byId_.find(ref); it != byId_.end()) return static_cast<int>(it->second);
    if (auto it = byPath_.find(ref); it != byPath_.end()) return static_cast<int>(it->second);
    return -1;
  }

  void readSolver(const RecordReader& r, int idx) {
    Solver& v = s_.solver;
    v.recordIndex = idx;
    v.iterations = static_cast<int>(r.integer("iterations"));
    v.tolerance = r.number("tolerance");
    v.erp = r.number("erp");
    v.mode = r.name("mode");
    v.erp2 = r.number("erp2");
    v.defaultFriction = r.number("defaultFriction");
    v.defaultRestitution = r.number("defaultRestitution");
    v.defaultRestitutionThreshold = r.number("defaultRestitutionThreshold");
    v.defaultStaticFriction = r.number("defaultStaticFriction");
    v.defaultStaticFrictionVelocityThreshold = r.number("defaultStaticFrictionVelocityThreshold");
    v.defaultRollingFriction = r.number("defaultRollingFriction");
    v.defaultSpinningFriction = r.number("defaultSpinningFriction");
    v.contactMaxIterations = static_cast<int>(r.integer("contactMaxIterations"));
    v.maxContactsPerPair = static_cast<int>(r.integer("maxContactsPerPair"));
    v.sweptCcdEnabled = r.flag("sweptCcdEnabled");
    v.sweptCcdMinSpeed = r.number("sweptCcdMinSpeed");
    v.sweptCcdSpeculativeMargin = r.number("sweptCcdSpeculativeMargin");
    v.sleepingEnabled = r.flag("sleepingEnabled");
    v.sleepingLinearVelocityThreshold = r.number("sleepingLinearVelocityThreshold");
    v.sleepingAngularVelocityThreshold = r.number("sleepingAngularVelocityThreshold");
    v.sleepingQuietSteps = static_cast<int>(r.integer("sleepingQuietSteps"));
    v.broadphaseType = r.name("broadphaseType");
    v.broadphaseWorldMin = r.vec3("broadphaseWorldMin");
    v.broadphaseWorldMax = r.vec3("broadphaseWorldMax");
    v.broadphaseUseWorldBounds = r.flag("broadphaseUseWorldBounds");
    v.fixedContactSolverIterationOrder = r.flag("fixedContactSolverIterationOrder");
    v.worldTime = r.number("worldTime");
  }

  void readEnvironment(const RecordReader& r, int idx) {
    Environment& e = s_.environment;
    e = Environment{};
    e.recordIndex = idx;
    e.background = r.color("background").head<3>();
    e.ambient = r.color("ambient").head<3>();
    e.fogDensity = r.number("fogDensity");
    e.shadows = r.flag("shadows");
    e.envMapPath = asset(r.str("envMapPath"));
    Eigen::Vector4d bg(e.background.x(), e.background.y(), e.background.z(), 1);
    e.fogColor = r.color("fogColor", bg);  // the background colour when absent (compat-notes.md)
    e.exposure = r.number("exposure");
    e.gamma = r.number("gamma");
    e.backgroundMode = r.name("backgroundMode");
    e.colorMode = r.name("colorMode", "");  // empty: not written
    e.pbrEnvironmentIntensity = r.number("pbrEnvironmentIntensity");
    e.heightFogEnabled = r.flag("heightFogEnabled");
    e.heightFogDensity = r.number("heightFogDensity");
    e.heightFogBaseHeight = r.number("heightFogBaseHeight");
    e.heightFogFalloff = r.number("heightFogFalloff");
    e.bloomIntensity = r.number("bloomIntensity");
    e.bloomThreshold = r.number("bloomThreshold");
    e.bloomRadius = r.number("bloomRadius");
    e.fxaa = r.flag("fxaa");
    e.ssao = r.flag("ssao");
    e.shadowMapSize = r.integer("shadowMapSize");
    e.shadowedLightBudget = r.integer("shadowedLightBudget");
  }

  void readWeather(const RecordReader& r, int idx) {
    Weather& w = s_.weather;
    w.recordIndex = idx;
    w.enabled = r.flag("enabled");
    w.preset = r.name("preset");
    w.timeOfDay = r.number("timeOfDay");
    w.useExplicitSunAngles = r.flag("useExplicitSunAngles");
    w.sunAzimuthDegrees = r.number("sunAzimuthDegrees");
    w.sunElevationDegrees = r.number("sunElevationDegrees");
    w.fogDensity = r.number("fogDensity");
    if (r.has("cloudCoverage")) w.cloudCoverage = r.number("cloudCoverage");
  }

  void readRenderSettings(const RecordReader& r, int idx) {
    RenderSettings& v = s_.renderSettings;
    v.recordIndex = idx;
    v.preset = r.name("preset");
    v.colorMode = r.name("colorMode", "");  // empty: not written
    v.custom = r.flag("custom");
    v.msaaSamples = r.integer("viewerMsaaSamples");
    v.shadowResolution = r.integer("shadowResolution");
    v.shadowBias = r.number("shadowBias");
    v.shadowStrength = r.number("shadowStrength");
    v.shadowPcfRadius = r.number("shadowPcfRadius");
    v.autoExposure = r.flag("autoExposure");
    v.autoExposureKey = r.number("autoExposureKey");
    v.autoExposureSpeed = r.number("autoExposureSpeed");
    v.pbrExposure = r.number("pbrExposure");
    v.pbrEnvironmentIntensity = r.number("pbrEnvironmentIntensity");
    v.reflectiveGround = r.flag("reflectiveGround");
    v.screenSpaceReflections = r.flag("screenSpaceReflections");
    v.screenSpaceReflectionStrength = r.number("screenSpaceReflectionStrength");
    v.volumetricFog = r.flag("volumetricFog");
    v.volumetricFogDensity = r.number("volumetricFogDensity");
    v.volumetricLightStrength = r.number("volumetricLightStrength");
    v.contactShadows = r.flag("contactShadows");
    v.contactShadowsLength = r.number("contactShadowsLength");
    v.contactShadowsStrength = r.number("contactShadowsStrength");
    v.depthOfField = r.flag("depthOfField");
    v.depthOfFieldFocusDistance = r.number("depthOfFieldFocusDistance");
    v.depthOfFieldAperture = r.number("depthOfFieldAperture");
    v.motionBlur = r.flag("motionBlur");
  }

  // Singleton records a scene may leave out hold every field's schema
  // default: read through a reader of an absent record, so that no struct
  // keeps a second copy of them.
  void absentSingletons() {
    auto absent = [&](const char* tag) { return RecordReader(doc_, *Schema::get().kind(tag), diags_); };
    s_.timeStep = absent("time_step").number("dt");
    s_.gravity = absent("gravity").vec3("gravity");
    s_.inheritedTransforms = absent("scene_graph").flag("inheritedTransforms");
    readSolver(absent("solver"), -1);
    readEnvironment(absent("environment"), -1);
    readWeather(absent("weather"), -1);
    readRenderSettings(absent("rayrai_render"), -1);
    s_.defaultMaterial = material(absent("material"), -1);
    s_.defaultMaterial.id = s_.defaultMaterial.name = "engine_default";
  }

  void readMaterial(const RecordReader& r, int idx) { s_.materials.push_back(material(r, idx)); }

  Material material(const RecordReader& r, int idx) {
    Material m;
    m.recordIndex = idx;
    m.name = r.str("name");
    m.id = r.present() ? nodeId(doc_, r.record()) : std::string();
    m.color = r.color("color");
    m.metallic = r.number("metallic");
    m.roughness = r.number("roughness");
    m.emissive = r.color("emissive").head<3>();
    m.emissiveStrength = r.number("emissiveStrength");
    m.doubleSided = r.flag("doubleSided");
    m.alphaMode = r.name("alphaMode");
    m.alphaCutoff = r.number("alphaCutoff");
    m.albedoTexture = asset(r.str("albedoTexture"));
    m.normalTexture = asset(r.str("normalTexture"));
    m.metallicTexture = asset(r.str("metallicTexture"));
    m.roughnessTexture = asset(r.str("roughnessTexture"));
    m.aoTexture = asset(r.str("aoTexture"));
    m.emissiveTexture = asset(r.str("emissiveTexture"));
    return m;
  }

  void readContact(const RecordReader& r, int idx) {
    ContactMaterial c;
    const Solver& sv = s_.solver;
    c.recordIndex = idx;
    c.materialA = r.str("materialA");
    c.materialB = r.str("materialB");
    c.friction = r.number("friction", sv.defaultFriction);
    c.restitution = r.number("restitution", sv.defaultRestitution);
    c.restitutionThreshold = r.number("restitutionThreshold", sv.defaultRestitutionThreshold);
    c.staticFriction = r.number("staticFriction", sv.defaultStaticFriction);
    c.staticFrictionVelocityThreshold =
        r.number("staticFrictionVelocityThreshold", sv.defaultStaticFrictionVelocityThreshold);
    c.rollingFriction = r.number("rollingFriction", sv.defaultRollingFriction);
    c.spinningFriction = r.number("spinningFriction", sv.defaultSpinningFriction);
    s_.contactMaterials.push_back(std::move(c));
  }

  void readTerrainTexture(const RecordReader& r, int idx) {
    TerrainTexture t = terrainTexture(r);
    t.recordIndex = idx;
    t.slot = static_cast<int>(r.integer("slot"));
    t.id = r.str("id");
    t.name = r.str("name");
    s_.terrainTextures.push_back(std::move(t));
  }

  // What a terrain_texture record holds beside its slot and names.
  TerrainTexture terrainTexture(const RecordReader& r) {
    TerrainTexture t;
    t.color = r.color("color");
    t.albedo = asset(r.str("albedo"));
    t.normal = asset(r.str("normal"));
    t.uvScale = r.number("uvScale");
    t.roughness = r.number("roughness");
    return t;
  }

  void readGroup(const RecordReader& r, int idx) {
    Group g;
    g.recordIndex = idx;
    g.path = nodePath(doc_, r.record());
    g.id = nodeId(doc_, r.record());
    g.parentId = r.str("parentId");
    g.visible = r.flag("visible");
    parentOf_[idx] = g.parentId;
    if (!g.visible) hiddenGroups_.push_back(idx);
    s_.groups.push_back(std::move(g));
  }

  void readLight(const RecordReader& r, int idx) {
    Light l;
    l.recordIndex = idx;
    l.path = nodePath(doc_, r.record());
    l.id = nodeId(doc_, r.record());
    l.type = r.name("type");
    Eigen::Vector3d d = r.vec3("direction");
    l.direction = d.norm() > 1e-12 ? d.normalized() : Eigen::Vector3d(0, 0, -1);
    l.intensity = r.number("intensity");
    l.position = r.vec3("position");
    l.color = r.color("color");
    l.attenuationConstant = r.number("attenuationConstant");
    l.attenuationLinear = r.number("attenuationLinear");
    l.attenuationQuadratic = r.number("attenuationQuadratic");
    l.range = r.number("range");
    l.coneAngle = r.number("coneAngle");
    l.innerConeAngle = r.number("innerConeAngle");
    l.radius = r.number("radius");
    l.areaSize = r.vec3("areaSize");
    l.shadows = r.flag("shadows");
    l.negative = r.flag("negative");
    l.shadowResolution = r.integer("shadowResolution");
    l.shadowBias = r.number("shadowBias");
    l.shadowStrength = r.number("shadowStrength");
    l.shadowPcfRadius = r.number("shadowPcfRadius");
    l.shadowOrthoHalfSize = r.number("shadowOrthoHalfSize");
    l.shadowNear = r.number("shadowNear");
    l.shadowFar = r.number("shadowFar");
    l.shadowCenter = r.vec3("shadowCenter");
    l.shadowPosition = r.vec3("shadowPosition");
    l.shadowUseCustomPosition = r.flag("shadowUseCustomPosition");
    l.distanceFadeEnabled = r.flag("distanceFadeEnabled");
    l.distanceFadeBegin = r.number("distanceFadeBegin");
    l.distanceFadeShadow = r.number("distanceFadeShadow");
    l.distanceFadeLength = r.number("distanceFadeLength");
    l.parentId = r.str("parentGroupId");
    parentOf_[idx] = l.parentId;
    s_.lights.push_back(std::move(l));
  }

  // A camera's image size.  A value past 32 bits is RS2003 (the reader's,
  // never a wrap: 4294967297 would be 1); one outside 0..16384 is
  // checkNumericLimits()'s RS7028; either way the size is left to the tool.
  static int pixelCount(const RecordReader& r, const char* name) {
    std::int64_t v = r.integer(name);
    return v >= 0 && v <= kMaxCameraSide ? static_cast<int>(v) : 0;
  }

  void readCamera(const RecordReader& r, int idx) {
    Camera c;
    c.recordIndex = idx;
    c.path = nodePath(doc_, r.record());
    c.id = nodeId(doc_, r.record());
    c.local = readPose(r, "position", "orientation");
    c.verticalFov = std::clamp(r.number("verticalFov"), 1.0, 175.0);
    c.horizontalFov = r.number("horizontalFov");
    c.nearPlane = r.number("nearPlane");
    c.farPlane = r.number("farPlane");
    c.width = pixelCount(r, "width");
    c.height = pixelCount(r, "height");
    c.renderMode = r.name("renderMode");
    c.projection = r.name("projection");
    c.orthoScale = r.number("orthoScale");
    c.enabled = r.flag("enabled");
    c.outputPath = r.str("outputPath");
    parentOf_[idx] = r.str("parentGroupId");
    s_.cameras.push_back(std::move(c));
  }

  void readObject(const RecordReader& r, int idx) {
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

  // Body mode of an object (compat-notes.md, "object record"): #21 when it
  // names a known mode, else #17 visualOnly / #19 locked (the 19-field
  // layout: #18 fixed), else dynamic; ground and half_space are static,
  // collidable=false is visual-only.
  static BodyMode objectMode(const RecordReader& r, const std::string& primitive, bool collidable) {
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

  // bodiesOnly: whether an object certainly passes checkScene(), so that
  // building it can be skipped: visual-only by its written #21 or #22, or
  // a primitive other than a mesh whose mass, scale, radius and height are
  // all positive numbers, whatever its mode, and no inertiaDiagonal.
  // Anything less plain is built and checked in full.
  bool plainBody(const Record& rec) {
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

  // Whether `s` is a short plain decimal ("0.5", "12") below 10^12 (so
  // within scene/limits.hpp's kMaxLength): finite, and its square neither
  // overflows nor underflows to zero unless it is zero.
  static bool plainDecimal(std::string_view s) {
    if (s.empty() || s.size() >= 32 || s.front() == '.') return false;
    int dots = 0, whole = 0;
    for (char c : s) {
      if (c == '.') ++dots;
      else if (c < '0' || c > '9') return false;
      else if (!dots) ++whole;
    }
    return dots <= 1 && whole <= 12;
  }

  // Whether `s` is a finite number in (0, max] (a normal double: 4.9e-324
  // is RS7020's).  Plain decimals below 10^12 ("0.5", "12") are read from
  // their digits, which keeps a bodiesOnly build cheap on scenes with
  // hundreds of thousands of objects; anything else is parsed.
  static bool positiveNumber(std::string_view s, double max) {
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

  void readCompound(const RecordReader& r, int idx) {
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

  void readCompoundChild(const RecordReader& r, int idx) {
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

  // Parses a per-sample list: empty, or exactly `per * samples` numbers.
  bool sampleList(const RecordReader& r, std::string_view name, std::size_t samples, int per,
                  std::vector<double>& out) {
    if (!r.numbers(name, out)) return false;
    if (out.empty() || out.size() == samples * per) return true;
    r.error(name, "RS4003",
            std::string(name) + " has " + std::to_string(out.size() / per) + " entries, expected " +
                std::to_string(samples) + " (one per sample) or none");
    out.clear();
    return false;
  }

  void readTerrain(const RecordReader& r, int idx) {
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
        if (read) r.error(name, "RS4001", std::string(name) + " is " + std::to_string(v) + ", outside 2..16384");
        countsOk = false;
      }
    if (countsOk && static_cast<std::uint64_t>(xs) * static_cast<std::uint64_t>(ys) > kMaxTerrainSamples) {
      r.error("xSamples", "RS4002", "terrain has " + std::to_string(xs * ys) + " samples, more than 64 Mi");
      countsOk = false;
    }
    bool sizeOk = true;
    for (auto [name, v] : {std::pair{"xSize", t.xSize}, std::pair{"ySize", t.ySize}})
      if (!(v > 0)) {
        r.error(name, "RS4014", std::string(name) + " is not positive");
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
        r.error("vertexColors", "RS4006", "vertexColors needs one color per sample or none");
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

  // A terrain as a body wires can name, without its samples (bodiesOnly).
  void readTerrainNode(const RecordReader& r, int idx) {
    Terrain t;
    t.recordIndex = idx;
    t.path = nodePath(doc_, r.record());
    t.id = nodeId(doc_, r.record());
    t.parentId = r.str("parentGroupId");
    parentOf_[idx] = t.parentId;
    s_.terrains.push_back(std::move(t));
  }

  AssetPath assetFn() const {
    return [this](const std::string& p) { return asset(p); };
  }

  // A node of visual_records.hpp: its parent noted for resolveWorld().
  template <typename T>
  void node(std::vector<T>& into, T value) {
    parentOf_[value.recordIndex] = value.parentId;
    into.push_back(std::move(value));
  }

  void readFoliage(const RecordReader& r, int idx) {
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

  void readSplat(const RecordReader& r, int idx) {
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

  void readWire(const RecordReader& r, int idx) {
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

  // A resource directory: like an asset path, but the candidate must be a
  // directory.
  std::string assetDirectory(const std::string& path) const {
    if (path.empty()) return path;
    auto isDir = [](const std::string& p) { return DiskFileSystem().stat(p).kind == FileKind::Directory; };
    std::string out = resolveAsset(opt_.baseDir.empty() ? opt_.sceneDir : opt_.baseDir, s_.assetRoot, path, isDir);
    for (std::size_t at; (at = out.find("/./")) != std::string::npos;) out.erase(at, 2);
    return out;
  }

  static std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> out;
    std::size_t start = 0;
    while (start <= text.size()) {
      std::size_t end = text.find_first_of(";,", start);
      if (end == std::string::npos) end = text.size();
      if (end > start) out.push_back(text.substr(start, end - start));
      start = end + 1;
    }
    return out;
  }

  // A child record (compound_child, terrain layer, articulated_ik) belongs
  // to the most recent parent of its name before it; with none, lib/core's
  // finding, in its words and at its place.
  static void orphan(const RecordReader& r, const std::string& parentTag) {
    r.error("", "RS3015", r.record().kind->tag + " has no " + parentTag + " record before it");
  }

  void readArticulatedResource(const RecordReader& r, int idx) {
    ArticulatedResource a;
    a.recordIndex = idx;
    a.id = r.str("id");
    a.name = r.str("name");
    a.path = asset(r.str("path"));
    a.resourceDirectory = assetDirectory(r.str("resourceDirectory"));
    a.modules = splitList(r.str("modules"));
    a.jointOrder = splitList(r.str("jointOrder"));
    a.doNotCollideWithParent = r.flag("doNotCollideWithParent");
    a.convexifyCollisionMeshes = r.flag("convexifyCollisionMeshes");
    s_.articulatedResources.push_back(std::move(a));
  }

  void readSensor(const RecordReader& r, int idx) {
    Sensor v;
    v.recordIndex = idx;
    v.path = nodePath(doc_, r.record());
    v.id = nodeId(doc_, r.record());
    v.kind = r.name("kind");
    v.parentObject = r.str("parentObject");
    if (v.parentObject == "-") v.parentObject.clear();
    v.parentLink = r.str("parentLink");
    if (v.parentLink == "-") v.parentLink.clear();
    v.local = readPose(r, "position", "orientation");
    SensorParams& p = v.params;
    p.width = pixelCount(r, "width");
    p.height = pixelCount(r, "height");
    p.updateRate = r.number("updateRate");
    p.verticalFov = r.number("verticalFov");
    p.horizontalFov = r.number("horizontalFov");
    p.nearPlane = r.number("nearPlane");
    p.farPlane = r.number("farPlane");
    p.lidarChannels = static_cast<int>(std::clamp<std::int64_t>(r.integer("lidarChannels"), 0, INT32_MAX));
    p.lidarSamples = static_cast<int>(std::clamp<std::int64_t>(r.integer("lidarSamples"), 0, INT32_MAX));
    p.lidarMinRange = r.number("lidarMinRange");
    p.lidarMaxRange = r.number("lidarMaxRange");
    // lidarVerticalFov: a span centred on the horizon.
    p.lidarMaxPitch = r.number("lidarVerticalFov") / 2;
    p.lidarMinPitch = -p.lidarMaxPitch;
    p.segmentation = r.flag("segmentation");
    p.fx = r.number("calibrationFx");
    p.fy = r.number("calibrationFy");
    p.cx = r.number("calibrationCx");
    p.cy = r.number("calibrationCy");
    p.noiseMean = r.number("noiseMean");
    p.noiseStddev = r.number("noiseStddev");
    p.noiseSeed = static_cast<std::uint64_t>(r.integer("noiseSeed"));
    v.enabled = r.flag("enabled");
    v.outputPath = r.str("outputPath");
    parentOf_[idx] = r.str("parentGroupId");
    s_.sensors.push_back(std::move(v));
  }

  void readArticulated(const RecordReader& r, int idx) {
    Articulated a;
    a.recordIndex = idx;
    a.path = nodePath(doc_, r.record());
    a.id = nodeId(doc_, r.record());
    a.parentId = r.str("parentGroupId");
    a.resourceRef = r.str("resource");
    // Fields the record writes; the rest come from its resource once every
    // resource is read (resolveArticulated: a resource is scene-global).
    Written w;
    w.source = r.has("sourcePath");
    w.directory = r.has("resourceDirectory");
    w.modules = r.has("modules");
    w.order = r.has("jointOrder");
    w.noParent = r.has("doNotCollideWithParent");
    w.convexify = r.has("convexifyCollisionMeshes");
    a.sourcePath = asset(r.str("sourcePath"));
    a.resourceDirectory = assetDirectory(r.str("resourceDirectory"));
    a.modules = splitList(r.str("modules"));
    a.jointOrder = splitList(r.str("jointOrder"));
    a.doNotCollideWithParent = r.flag("doNotCollideWithParent");
    a.convexifyCollisionMeshes = r.flag("convexifyCollisionMeshes");
    written_.push_back(w);
    a.local = readPose(r, "position", "orientation");
    a.positionToken = r.positionalToken("position");
    a.scale = r.vec3("scale");
    a.visible = r.flag("visible");
    a.collidable = r.flag("collidable");
    a.collisionGroup = r.group("collisionGroup");
    a.collisionMask = r.group("collisionMask");
    // An empty list (`-` or nothing after `=`) gives no state, like no key.
    a.hasCoordinate = r.has("generalizedCoordinate") && r.numbers("generalizedCoordinate", a.generalizedCoordinate) &&
                      !a.generalizedCoordinate.empty();
    a.hasVelocity = r.has("generalizedVelocity") && r.numbers("generalizedVelocity", a.generalizedVelocity) &&
                    !a.generalizedVelocity.empty();
    a.semanticClass = r.str("semanticClass");
    parentOf_[idx] = a.parentId;
    s_.articulated.push_back(std::move(a));
  }

  // Which of the fields a resource provides an articulated record wrote.
  struct Written {
    bool source = false, directory = false, modules = false, order = false, noParent = false, convexify = false;
  };

  void resolveArticulated() {
    for (std::size_t n = 0; n < s_.articulated.size(); ++n) {
      Articulated& a = s_.articulated[n];
      const Written& w = written_[n];
      for (std::size_t i = 0; i < s_.articulatedResources.size(); ++i)  // the last of that id or name
        if (s_.articulatedResources[i].id == a.resourceRef || s_.articulatedResources[i].name == a.resourceRef)
          a.resource = static_cast<int>(i);
      if (a.resource < 0) continue;
      const ArticulatedResource& res = s_.articulatedResources[static_cast<std::size_t>(a.resource)];
      a.resourceRecord = res.recordIndex;
      if (!w.source) a.sourcePath = res.path;
      if (!w.directory) a.resourceDirectory = res.resourceDirectory;
      if (!w.modules) a.modules = res.modules;
      if (!w.order) a.jointOrder = res.jointOrder;
      if (!w.noParent) a.doNotCollideWithParent = res.doNotCollideWithParent;
      if (!w.convexify) a.convexifyCollisionMeshes = res.convexifyCollisionMeshes;
    }
  }

  void readArticulatedIk(const RecordReader& r, int idx) {
    std::string ref = r.str("articulated");
    Articulated* owner = lastNamed(s_.articulated, ref);
    if (!owner) {
      orphan(r, "articulated");
      return;
    }
    ArticulatedIk k;
    k.recordIndex = idx;
    k.frame = r.str("frame");
    k.target = r.vec3("target", Eigen::Vector3d::Zero());
    k.enabled = r.flag("enabled");
    k.useOrientation = r.flag("useOrientation");
    Eigen::Quaterniond q = toQuat(r.quat("orientation"));
    k.orientation = q.norm() > 1e-12 ? q.normalized() : Eigen::Quaterniond::Identity();
    k.maxIterations = static_cast<int>(r.integer("maxIterations"));
    k.positionTolerance = r.number("positionTolerance");
    k.orientationTolerance = r.number("orientationTolerance");
    k.orientationWeight = r.number("orientationWeight");
    k.damping = r.number("damping");
    k.stepSize = r.number("stepSize");
    k.maxStep = r.number("maxStep");
    k.svdTolerance = r.number("svdTolerance");
    k.finiteDifferenceStep = r.number("finiteDifferenceStep");
    k.transposeGain = r.number("transposeGain");
    k.applyBestOnFailure = r.flag("applyBestOnFailure");
    k.enforceJointLimits = r.flag("enforceJointLimits");
    k.inverseMethod = r.name("inverseMethod");
    owner->ik.push_back(std::move(k));
  }

  void readInstanced(const RecordReader& r, int idx) {
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
        r.error("instances", "RS4004", "instances holds " + std::to_string(xs.size()) +
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

  void readPointCloud(const RecordReader& r, int idx) {
    PointCloud p;
    p.recordIndex = idx;
    p.path = nodePath(doc_, r.record());
    p.id = nodeId(doc_, r.record());
    std::vector<double> xs;
    if (r.numbers("points", xs)) {
      if (xs.size() % 3) {
        r.error("points", "RS2008", "points holds " + std::to_string(xs.size()) +
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

  void defaults() {
    if (s_.materials.empty()) s_.materials.push_back(s_.defaultMaterial);
    if (s_.terrainTextures.empty()) {
      // compat-notes.md, "Identity and defaults": two slots of their own
      // colors; their other fields are the schema's.
      struct Slot {
        int slot;
        const char* name;
        double r, g, b;
      };
      constexpr Slot kSlots[] = {{0, "terrain_grass", 0.28, 0.43, 0.20}, {1, "terrain_rock", 0.42, 0.40, 0.36}};
      for (const Slot& k : kSlots) {
        TerrainTexture t = terrainTexture(RecordReader(doc_, *Schema::get().kind("terrain_texture"), diags_));
        t.slot = k.slot;
        t.id = t.name = k.name;
        t.color = {k.r, k.g, k.b, 1};
        s_.terrainTextures.push_back(std::move(t));
      }
    }
  }

  // Local pose of a node that has one (object, compound, camera), or nullptr.
  const Pose* localPose(int idx) const {
    auto it = poses_.find(idx);
    return it == poses_.end() ? nullptr : it->second;
  }

  // Parent record of each node, or -1 (none, unresolved, or itself).
  // Resolved once so that the walks below cost one array read per step.
  void resolveParents() {
    parentIdx_.assign(doc_.records.size(), -1);
    for (const auto& [idx, ref] : parentOf_) {
      int parent = lookup(ref);
      if (parent != idx) parentIdx_[static_cast<std::size_t>(idx)] = parent;
      else reportCycle(idx);  // its own parent: the shortest cycle
    }
  }

  // Memoised resolution over the parent links, for any depth: each node's
  // value is computed once, by an explicit stack instead of recursion (a
  // million-deep chain must not overflow the call stack), so that resolving
  // every node costs time linear in the number of nodes.  `stops(n)` says
  // that node n's value does not depend on its parent's (its value is then
  // `root(n)`); otherwise it is `step(n, value of parent)`.  The nodes of a
  // parent cycle (lib/core reports it, RS3xxx) all get `cycle(members)`.
  template <typename T, typename Stops, typename Root, typename Step, typename Cycle>
  void resolveChains(std::vector<T>& value, Stops stops, Root root, Step step, Cycle cycle) {
    enum : unsigned char { kTodo, kOnStack, kDone };
    std::vector<unsigned char> state(doc_.records.size(), kTodo);
    value.assign(doc_.records.size(), T{});
    std::vector<int> stack;
    for (std::size_t start = 0; start < state.size(); ++start) {
      if (state[start] == kDone) continue;
      // Climb until a node whose value is known or needs no parent.
      int n = static_cast<int>(start);
      while (true) {
        state[static_cast<std::size_t>(n)] = kOnStack;
        stack.push_back(n);
        int parent = parentIdx_[static_cast<std::size_t>(n)];
        if (parent < 0 || stops(n)) {
          value[static_cast<std::size_t>(n)] = root(n);
          state[static_cast<std::size_t>(n)] = kDone;
          stack.pop_back();
          break;
        }
        if (state[static_cast<std::size_t>(parent)] == kDone) break;
        if (state[static_cast<std::size_t>(parent)] == kOnStack) {
          auto first = std::find(stack.begin(), stack.end(), parent);
          std::vector<int> members(first, stack.end());
          T v = cycle(members);
          for (int m : members) {
            value[static_cast<std::size_t>(m)] = v;
            state[static_cast<std::size_t>(m)] = kDone;
          }
          stack.erase(first, stack.end());
          break;
        }
        n = parent;
      }
      // Come back down: each node's parent is now done.
      for (auto it = stack.rbegin(); it != stack.rend(); ++it) {
        auto i = static_cast<std::size_t>(*it);
        value[i] = step(*it, value[static_cast<std::size_t>(parentIdx_[i])]);
        state[i] = kDone;
      }
      stack.clear();
    }
  }

  // The world pose of the frame each node's pose is written in: its
  // parent's world pose when the parent has a pose of its own; groups and
  // pose-less nodes are folders in the world frame.  In a cycle there is
  // no parent frame to inherit, so its members keep the world frame.
  void resolveFrames() {
    std::vector<Pose> frames;
    if (s_.inheritedTransforms) {
      auto stops = [&](int n) { return localPose(parentIdx_[static_cast<std::size_t>(n)]) == nullptr; };
      auto root = [](int) { return Pose{}; };
      auto step = [&](int n, const Pose& parentFrame) {
        return parentFrame * *localPose(parentIdx_[static_cast<std::size_t>(n)]);
      };
      auto cycle = [](const std::vector<int>&) { return Pose{}; };
      resolveChains(frames, stops, root, step, cycle);
    } else {
      frames.assign(doc_.records.size(), Pose{});
    }
    frames_ = std::move(frames);
  }

  // Whether a group with visible=false is among each node's ancestors (in
  // a cycle, every member is an ancestor of every other).
  void resolveHidden() {
    std::vector<char> hiddenGroup(doc_.records.size(), 0);
    for (int g : hiddenGroups_) hiddenGroup[static_cast<std::size_t>(g)] = 1;
    auto stops = [](int) { return false; };
    auto root = [](int) { return char{0}; };
    auto step = [&](int n, char parentHidden) {
      return static_cast<char>(parentHidden || hiddenGroup[static_cast<std::size_t>(parentIdx_[static_cast<std::size_t>(n)])]);
    };
    auto cycle = [&](const std::vector<int>& members) {
      reportCycle(members.front());
      return static_cast<char>(std::any_of(members.begin(), members.end(),
                                           [&](int m) { return hiddenGroup[static_cast<std::size_t>(m)] != 0; }));
    };
    resolveChains(hidden_, stops, root, step, cycle);
  }

  // A parent cycle has no world pose to give its members: sim and render
  // refuse it with lib/core's code, at the record and field lib/core's
  // check names (both walk the records in order and report the node where
  // the walk comes back to itself).  validate's bodiesOnly build resolves
  // no world, so the finding is not doubled there.
  void reportCycle(int idx) {
    RecordReader r(doc_, static_cast<std::size_t>(idx), diags_);
    const std::string& tag = doc_.records[static_cast<std::size_t>(idx)].kind->tag;
    const char* field = tag == "group" ? "parentId" : "parentGroupId";
    if (!r.has(field)) field = "parentGroupId";
    r.error(field, "RS3017", "node '" + nodePath(doc_, r.record()) + "' is its own ancestor",
            "break the cycle of parents");
  }

  Pose parentFrame(int idx) const { return frames_[static_cast<std::size_t>(idx)]; }

  // The body a record index is, as a Mount (World when it is none).
  Mount mountOf(int record) const {
    Mount m;
    auto find = [&](const auto& list, Mount::Kind kind) {
      for (std::size_t i = 0; i < list.size(); ++i)
        if (list[i].recordIndex == record) {
          m.kind = kind;
          m.index = static_cast<int>(i);
          return true;
        }
      return false;
    };
    if (record >= 0) find(s_.objects, Mount::Kind::Object) || find(s_.compounds, Mount::Kind::Compound) ||
                         find(s_.articulated, Mount::Kind::Articulated);
    return m;
  }

  // A camera rides on the body its parentGroupId names; a sensor on its
  // parentObject (at parentLink on a robot).  An unknown name is lib/core's
  // RS3012 (validate) and leaves the sensor in the world.
  void resolveMounts() {
    for (Camera& c : s_.cameras) c.mount = mountOf(parentIdx_[static_cast<std::size_t>(c.recordIndex)]);
    for (Sensor& v : s_.sensors) {
      v.mount = mountOf(lookup(v.parentObject));
      if (v.mount.kind == Mount::Kind::Articulated) v.mount.link = v.parentLink;
    }
  }

  // The world pose of the frame a sensor's local pose is written in: its
  // mount body's (a robot's base: lib/robot's sensor rig places it on the
  // link), else its parent folder's.
  Pose mountFrame(const Mount& m, int record) const {
    switch (m.kind) {
      case Mount::Kind::Object: return s_.objects[static_cast<std::size_t>(m.index)].world;
      case Mount::Kind::Compound: return s_.compounds[static_cast<std::size_t>(m.index)].world;
      case Mount::Kind::Articulated: return s_.articulated[static_cast<std::size_t>(m.index)].world;
      case Mount::Kind::World: break;
    }
    return parentFrame(record);
  }
  bool hiddenByGroup(int idx) const { return hidden_[static_cast<std::size_t>(idx)] != 0; }

  void resolveWorld() {
    for (const Object& o : s_.objects) poses_[o.recordIndex] = &o.local;
    for (const Compound& c : s_.compounds) poses_[c.recordIndex] = &c.local;
    for (const Camera& c : s_.cameras) poses_[c.recordIndex] = &c.local;
    for (const Articulated& a : s_.articulated) poses_[a.recordIndex] = &a.local;
    resolveParents();
    resolveFrames();
    resolveHidden();
    for (Object& o : s_.objects) o.world = parentFrame(o.recordIndex) * o.local;
    for (Compound& c : s_.compounds) c.world = parentFrame(c.recordIndex) * c.local;
    resolveMounts();
    for (Camera& c : s_.cameras) c.world = parentFrame(c.recordIndex) * c.local;
    for (Articulated& a : s_.articulated) {
      a.world = parentFrame(a.recordIndex) * a.local;
      a.hiddenByGroup = hiddenByGroup(a.recordIndex);
    }
    for (Sensor& v : s_.sensors) v.world = mountFrame(v.mount, v.recordIndex) * v.local;
    for (Object& o : s_.objects) o.hiddenByGroup = hiddenByGroup(o.recordIndex);
    for (Compound& c : s_.compounds) c.hiddenByGroup = hiddenByGroup(c.recordIndex);
    for (Terrain& t : s_.terrains) t.hiddenByGroup = hiddenByGroup(t.recordIndex);
    for (InstancedVisual& v : s_.instancedVisuals) v.hiddenByGroup = hiddenByGroup(v.recordIndex);
    for (PointCloud& p : s_.pointClouds) p.hiddenByGroup = hiddenByGroup(p.recordIndex);
    resolveVisualRecords();
    for (Light& l : s_.lights) {
      l.hiddenByGroup = hiddenByGroup(l.recordIndex);
      Pose f = parentFrame(l.recordIndex);
      l.position = f.position + f.orientation * l.position;
      l.direction = f.orientation * l.direction;
    }
  }

  // visual_records.hpp nodes: carried by their parent's frame like a light.
  void resolveVisualRecords() {
    auto placed = [&](auto& v) {
      v.world = parentFrame(v.recordIndex) * v.local;
      v.hiddenByGroup = hiddenByGroup(v.recordIndex);
    };
    for (Decal& d : s_.decals) placed(d);
    for (IrradianceVolume& v : s_.irradianceVolumes) placed(v);
    for (Deformable& d : s_.deformables) placed(d);
    for (Granular& g : s_.granulars) placed(g);
    for (LocalFog& f : s_.localFogs) {
      Pose p = parentFrame(f.recordIndex);
      f.center = p.position + p.orientation * f.localCenter;
      f.hiddenByGroup = hiddenByGroup(f.recordIndex);
    }
    for (ReflectionProbe& pr : s_.reflectionProbes) {
      Pose p = parentFrame(pr.recordIndex);
      pr.position = p.position + p.orientation * pr.localPosition;
      pr.hiddenByGroup = hiddenByGroup(pr.recordIndex);
    }
  }

  // What each wire end names: the world, a body the simulator models, a
  // node it does not (an articulated system, a visual-only object ...), or
  // nothing (lib/core's validator reports that as RS3012).
  void resolveWires() {
    std::unordered_map<int, bool> simulatedBody;
    for (const Object& o : s_.objects) simulatedBody[o.recordIndex] = o.bodyMode != BodyMode::VisualOnly;
    for (const Compound& c : s_.compounds) simulatedBody[c.recordIndex] = c.bodyMode != BodyMode::VisualOnly;
    for (const Terrain& t : s_.terrains) simulatedBody[t.recordIndex] = true;
    std::unordered_map<int, bool> robot;
    for (const Articulated& a : s_.articulated) robot[a.recordIndex] = true;
    auto classify = [&](const std::string& ref, WireEnd& end, std::string& tag, int& record) {
      if (ref.empty()) return;
      int target = lookup(ref);
      record = target;
      if (target < 0) {
        end = WireEnd::Unknown;
        return;
      }
      tag = doc_.records[static_cast<std::size_t>(target)].kind->tag;
      if (robot.count(target)) {
        end = WireEnd::Articulated;
        return;
      }
      auto it = simulatedBody.find(target);
      if (it == simulatedBody.end() && tag == "object") {  // skipped by a bodiesOnly build
        RecordReader r(doc_, static_cast<std::size_t>(target), diags_);
        bool simulated = objectMode(r, r.name("primitive"), r.flag("collidable")) != BodyMode::VisualOnly;
        it = simulatedBody.emplace(target, simulated).first;
      }
      end = it != simulatedBody.end() && it->second ? WireEnd::Body : WireEnd::NotSimulated;
    };
    for (Wire& w : s_.wires) {
      classify(w.bodyA, w.endA, w.tagA, w.recordA);
      classify(w.bodyB, w.endB, w.tagB, w.recordB);
    }
  }

  const Document& doc_;
  const SceneOptions& opt_;
  Scene& s_;
  Diagnostics& diags_;
  mutable std::unordered_map<std::string, std::size_t> byId_, byPath_;
  mutable bool indexed_ = false;
  const KindDef* objectKind_ = Schema::get().kind("object");
  // Per object layout, the tokens of primitive, scale x3, radius, height,
  // mass, then bodyMode and collidable (-1 when the layout has none).
  std::unordered_map<const Layout*, std::vector<int>> plainSlots_;
  std::unordered_map<int, std::string> parentOf_;
  std::vector<Written> written_;  // per Scene::articulated entry
  std::unordered_map<int, const Pose*> poses_;
  std::vector<int> hiddenGroups_;  // record indices of groups with visible=false
  std::vector<int> parentIdx_;     // per record: its parent's record index, or -1
  std::vector<Pose> frames_;       // per record: the world pose of its parent frame
  std::vector<char> hidden_;       // per record: a hidden group is among its ancestors
};

}  // namespace

const char* bodyModeName(BodyMode m) {
  switch (m) {
    case BodyMode::Static: return "static";
    case BodyMode::Kinematic: return "kinematic";
    case BodyMode::Dynamic: return "dynamic";
    case BodyMode::VisualOnly: return "visual_only";
  }
  return "dynamic";
}

const Material* Scene::findMaterial(const std::string& id) const {
  for (const Material& m : materials)
    if (m.id == id || m.name == id) return &m;
  return nullptr;
}

const ContactMaterial* Scene::findContact(const std::string& a, const std::string& b) const {
  const ContactMaterial* found = nullptr;
  for (const ContactMaterial& c : contactMaterials)
    if ((c.materialA == a && c.materialB == b) || (c.materialA == b && c.materialB == a)) found = &c;
  return found;  // the last record of a pair wins
}

bool buildScene(const Document& doc, const SceneOptions& options, Scene& scene, Diagnostics& diagnostics) {
  std::size_t before = diagnostics.size();
  Scene built;
  Builder(doc, options, built, diagnostics).run();
  scene = std::move(built);
  for (std::size_t i = before; i < diagnostics.size(); ++i)
    if (diagnostics[i].severity == Severity::Error) return false;
  return true;
}

}  // namespace rscene
