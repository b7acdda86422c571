#include "scene/scene_builder.hpp"

namespace rscene::scene_build {

void Builder::readSolver(const RecordReader& r, int idx) {
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

void Builder::readEnvironment(const RecordReader& r, int idx) {
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

void Builder::readWeather(const RecordReader& r, int idx) {
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

void Builder::readRenderSettings(const RecordReader& r, int idx) {
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

void Builder::absentSingletons() {
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

Material Builder::material(const RecordReader& r, int idx) {
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

void Builder::readContact(const RecordReader& r, int idx) {
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

void Builder::readTerrainTexture(const RecordReader& r, int idx) {
  TerrainTexture t = terrainTexture(r);
  t.recordIndex = idx;
  t.slot = static_cast<int>(r.integer("slot"));
  t.id = r.str("id");
  t.name = r.str("name");
  s_.terrainTextures.push_back(std::move(t));
}

TerrainTexture Builder::terrainTexture(const RecordReader& r) {
  TerrainTexture t;
  t.color = r.color("color");
  t.albedo = asset(r.str("albedo"));
  t.normal = asset(r.str("normal"));
  t.uvScale = r.number("uvScale");
  t.roughness = r.number("roughness");
  return t;
}

void Builder::readGroup(const RecordReader& r, int idx) {
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

void Builder::readLight(const RecordReader& r, int idx) {
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

int Builder::pixelCount(const RecordReader& r, const char* name) {
  std::int64_t v = r.integer(name);
  return v >= 0 && v <= kMaxCameraSide ? static_cast<int>(v) : 0;
}

void Builder::readCamera(const RecordReader& r, int idx) {
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

}  // namespace rscene::scene_build
