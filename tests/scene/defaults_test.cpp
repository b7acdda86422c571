// Defaults come from the schema table only (FieldDef::defaultValue): a
// scene that leaves every record out, and records that write no keys, give
// exactly the schema's defaults, and the model's structs hold no literal
// copy of them that could drift.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "core/loader.hpp"
#include "core/schema.hpp"
#include "core/text.hpp"
#include "scene/scene.hpp"

namespace rscene {
namespace {

// The schema default of tag.field, as text; fails the test when absent.
std::string def(const std::string& tag, const std::string& field) {
  const KindDef* kind = Schema::get().kind(tag);
  if (!kind) return ADD_FAILURE() << "no kind " << tag, "";
  const FieldDef* f = kind->key(field);
  for (const Layout& l : kind->layouts)
    for (const FieldDef& p : l.fields)
      if (!f && p.name == field) f = &p;
  if (!f || !f->defaultValue) return ADD_FAILURE() << tag << "." << field << " has no schema default", "";
  return *f->defaultValue;
}
double num(const std::string& tag, const std::string& field) { return parseNumber(def(tag, field)).value_or(-12345); }
bool flag(const std::string& tag, const std::string& field) { return parseFlag(def(tag, field)).value_or(false); }
std::uint64_t group(const std::string& tag, const std::string& field) {
  return parseGroup(def(tag, field)).value_or(12345);
}
std::string name(const std::string& tag, const std::string& field) {
  const KindDef* kind = Schema::get().kind(tag);
  std::string d = def(tag, field);
  const FieldDef* f = kind->key(field);
  for (const Layout& l : kind->layouts)
    for (const FieldDef& p : l.fields)
      if (!f && p.name == field) f = &p;
  if (f && f->enumDef)
    if (auto c = f->enumDef->canonical(d)) return std::string(*c);
  return d;
}
Eigen::VectorXd vec(const std::string& tag, const std::string& field) {
  std::vector<double> v;
  EXPECT_TRUE(parseNumberList(def(tag, field), v)) << tag << "." << field;
  Eigen::VectorXd out(static_cast<Eigen::Index>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) out[static_cast<Eigen::Index>(i)] = v[i];
  return out;
}
Eigen::Vector4d rgba(const std::string& tag, const std::string& field) {
  Eigen::VectorXd v = vec(tag, field);
  return {v[0], v[1], v[2], v.size() > 3 ? v[3] : 1.0};
}

Scene build(const std::string& text) {
  LoadResult r = parse(text);
  EXPECT_TRUE(r.ok()) << (r.diagnostics.empty() ? "" : r.diagnostics[0].message);
  Scene s;
  Diagnostics ds;
  EXPECT_TRUE(buildScene(r.document, {}, s, ds)) << (ds.empty() ? "" : ds[0].message);
  return s;
}

TEST(Defaults, AbsentSingletonsAreTheSchemas) {
  Scene s = build("raisim_engine_scene 2\n");
  EXPECT_EQ(s.timeStep, num("time_step", "dt"));
  EXPECT_EQ(s.gravity, Eigen::Vector3d(vec("gravity", "gravity")));
  EXPECT_EQ(s.inheritedTransforms, flag("scene_graph", "inheritedTransforms"));
  const Solver& v = s.solver;
  EXPECT_EQ(v.recordIndex, -1);
  EXPECT_EQ(v.iterations, num("solver", "iterations"));
  EXPECT_EQ(v.tolerance, num("solver", "tolerance"));
  EXPECT_EQ(v.erp, num("solver", "erp"));
  EXPECT_EQ(v.mode, name("solver", "mode"));
  EXPECT_EQ(v.erp2, num("solver", "erp2"));
  EXPECT_EQ(v.defaultFriction, num("solver", "defaultFriction"));
  EXPECT_EQ(v.defaultRestitution, num("solver", "defaultRestitution"));
  EXPECT_EQ(v.defaultRestitutionThreshold, num("solver", "defaultRestitutionThreshold"));
  EXPECT_EQ(v.defaultStaticFriction, num("solver", "defaultStaticFriction"));
  EXPECT_EQ(v.defaultStaticFrictionVelocityThreshold, num("solver", "defaultStaticFrictionVelocityThreshold"));
  EXPECT_EQ(v.defaultRollingFriction, num("solver", "defaultRollingFriction"));
  EXPECT_EQ(v.defaultSpinningFriction, num("solver", "defaultSpinningFriction"));
  EXPECT_EQ(v.contactMaxIterations, num("solver", "contactMaxIterations"));
  EXPECT_EQ(v.maxContactsPerPair, num("solver", "maxContactsPerPair"));
  EXPECT_EQ(v.sweptCcdEnabled, flag("solver", "sweptCcdEnabled"));
  EXPECT_EQ(v.sweptCcdMinSpeed, num("solver", "sweptCcdMinSpeed"));
  EXPECT_EQ(v.sweptCcdSpeculativeMargin, num("solver", "sweptCcdSpeculativeMargin"));
  EXPECT_EQ(v.sleepingEnabled, flag("solver", "sleepingEnabled"));
  EXPECT_EQ(v.sleepingLinearVelocityThreshold, num("solver", "sleepingLinearVelocityThreshold"));
  EXPECT_EQ(v.sleepingAngularVelocityThreshold, num("solver", "sleepingAngularVelocityThreshold"));
  EXPECT_EQ(v.sleepingQuietSteps, num("solver", "sleepingQuietSteps"));
  EXPECT_EQ(v.broadphaseType, name("solver", "broadphaseType"));
  EXPECT_EQ(v.broadphaseWorldMin, Eigen::Vector3d(vec("solver", "broadphaseWorldMin")));
  EXPECT_EQ(v.broadphaseWorldMax, Eigen::Vector3d(vec("solver", "broadphaseWorldMax")));
  EXPECT_EQ(v.broadphaseUseWorldBounds, flag("solver", "broadphaseUseWorldBounds"));
  EXPECT_EQ(v.fixedContactSolverIterationOrder, flag("solver", "fixedContactSolverIterationOrder"));
  EXPECT_EQ(v.worldTime, num("solver", "worldTime"));

  const Environment& e = s.environment;
  EXPECT_EQ(e.background, Eigen::Vector3d(vec("environment", "background")));
  EXPECT_EQ(e.ambient, Eigen::Vector3d(vec("environment", "ambient")));
  EXPECT_EQ(e.fogDensity, num("environment", "fogDensity"));
  EXPECT_EQ(e.shadows, flag("environment", "shadows"));
  EXPECT_EQ(e.fogColor.head<3>(), e.background);  // compat-notes.md: the background colour
  EXPECT_EQ(e.exposure, num("environment", "exposure"));
  EXPECT_EQ(e.gamma, num("environment", "gamma"));
  EXPECT_EQ(e.backgroundMode, name("environment", "backgroundMode"));
  EXPECT_EQ(e.pbrEnvironmentIntensity, num("environment", "pbrEnvironmentIntensity"));
  EXPECT_EQ(e.heightFogEnabled, flag("environment", "heightFogEnabled"));
  EXPECT_EQ(e.heightFogDensity, num("environment", "heightFogDensity"));
  EXPECT_EQ(e.heightFogBaseHeight, num("environment", "heightFogBaseHeight"));
  EXPECT_EQ(e.heightFogFalloff, num("environment", "heightFogFalloff"));

  const Weather& w = s.weather;
  EXPECT_EQ(w.enabled, flag("weather", "enabled"));
  EXPECT_EQ(w.preset, name("weather", "preset"));
  EXPECT_EQ(w.timeOfDay, num("weather", "timeOfDay"));
  EXPECT_EQ(w.useExplicitSunAngles, flag("weather", "useExplicitSunAngles"));
  EXPECT_EQ(w.sunAzimuthDegrees, num("weather", "sunAzimuthDegrees"));
  EXPECT_EQ(w.sunElevationDegrees, num("weather", "sunElevationDegrees"));
  EXPECT_EQ(w.fogDensity, num("weather", "fogDensity"));
  EXPECT_EQ(s.renderSettings.preset, name("rayrai_render", "preset"));

  // engine_default is the material schema's defaults (compat-notes.md).
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& m = s.materials[0];
  EXPECT_EQ(m.id, "engine_default");
  EXPECT_EQ(m.color, rgba("material", "color"));
  EXPECT_EQ(m.roughness, num("material", "roughness"));
  EXPECT_EQ(m.metallic, num("material", "metallic"));
  EXPECT_EQ(m.alphaMode, name("material", "alphaMode"));
  EXPECT_EQ(m.alphaCutoff, num("material", "alphaCutoff"));
  ASSERT_EQ(s.terrainTextures.size(), 2u);
  EXPECT_EQ(s.terrainTextures[1].uvScale, num("terrain_texture", "uvScale"));
  EXPECT_EQ(s.terrainTextures[1].roughness, num("terrain_texture", "roughness"));
}

TEST(Defaults, RecordsWithoutKeysAreTheSchemas) {
  Scene s = build(
      "raisim_engine_scene 2\n"
      "group /World/g\n"
      "light /World/l 0 0 -1 2\n"
      "camera /World/c 0 0 1 1 0 0 0 60 0.1 100 640 480 rgb true\n"
      "object /World/o box 0 0 1 1 0 0 0 1 1 1 0.5 1 1 default engine_default\n"
      "compound /World/k 0 0 1 1 0 0 0 1 1 1 2 dynamic true true\n"
      "compound_child /World/k box 0 0 0 1 0 0 0 1 1 1\n"
      "terrain_region /World/t 2 2 1 1 0 0 0\n"
      "terrain_splat_layer /World/t\n"
      "terrain_texture 3 rock3 rock3\n"
      "wire /World/w stiff /World/o /World/k 1\n"
      "instanced_visual /World/i box\n"
      "point_cloud /World/p\n");
  EXPECT_EQ(s.groups.at(0).visible, flag("group", "visible"));
  const Light& l = s.lights.at(0);
  EXPECT_EQ(l.type, name("light", "type"));
  EXPECT_EQ(l.position, Eigen::Vector3d(vec("light", "position")));
  EXPECT_EQ(l.color, rgba("light", "color"));
  EXPECT_EQ(l.attenuationConstant, num("light", "attenuationConstant"));
  EXPECT_EQ(l.attenuationLinear, num("light", "attenuationLinear"));
  EXPECT_EQ(l.attenuationQuadratic, num("light", "attenuationQuadratic"));
  EXPECT_EQ(l.range, num("light", "range"));
  EXPECT_EQ(l.coneAngle, num("light", "coneAngle"));
  EXPECT_EQ(l.innerConeAngle, num("light", "innerConeAngle"));
  EXPECT_EQ(l.radius, num("light", "radius"));
  EXPECT_EQ(l.areaSize, Eigen::Vector3d(vec("light", "areaSize")));
  EXPECT_EQ(l.shadows, flag("light", "shadows"));
  EXPECT_EQ(l.negative, flag("light", "negative"));
  const Camera& c = s.cameras.at(0);
  EXPECT_EQ(c.projection, name("camera", "projection"));
  EXPECT_EQ(c.horizontalFov, num("camera", "horizontalFov"));
  EXPECT_EQ(c.orthoScale, num("camera", "orthoScale"));
  // A 17-field object: the later fields of the 25-field layout are absent.
  const Object& o = s.objects.at(0);
  EXPECT_EQ(o.visible, flag("object", "visible"));
  EXPECT_EQ(o.collidable, flag("object", "collidable"));
  EXPECT_EQ(o.collisionGroup, group("object", "collisionGroup"));
  EXPECT_EQ(o.collisionMask, group("object", "collisionMask"));
  EXPECT_EQ(o.castShadow, flag("object", "castShadow"));
  EXPECT_EQ(o.collisionMode, name("object", "collisionMode"));
  EXPECT_EQ(o.bodyMode, BodyMode::Dynamic);  // compat-notes.md: a 17-field object is a dynamic body
  const Compound& k = s.compounds.at(0);
  EXPECT_EQ(k.collisionGroup, group("compound", "collisionGroup"));
  EXPECT_EQ(k.collisionMask, group("compound", "collisionMask"));
  const CompoundChild& ch = k.children.at(0);
  EXPECT_EQ(ch.size, Eigen::Vector3d(vec("compound_child", "size")));
  EXPECT_EQ(ch.radius, num("compound_child", "radius"));
  EXPECT_EQ(ch.height, num("compound_child", "height"));
  const Terrain& t = s.terrains.at(0);
  EXPECT_EQ(t.baseTexture, num("terrain_region", "baseTexture"));
  EXPECT_EQ(t.visible, flag("terrain_region", "visible"));
  EXPECT_EQ(t.collidable, flag("terrain_region", "collidable"));
  EXPECT_EQ(t.castShadow, flag("terrain_region", "castShadow"));
  EXPECT_EQ(t.receiveShadow, flag("terrain_region", "receiveShadow"));
  EXPECT_EQ(t.textureSplatting, flag("terrain_region", "textureSplattingEnabled"));
  EXPECT_EQ(t.sourceKind, name("terrain_region", "sourceKind"));
  const TerrainSplatLayer& sl = t.splatLayers.at(0);
  EXPECT_EQ(sl.slot, num("terrain_splat_layer", "slot"));
  EXPECT_EQ(sl.enabled, flag("terrain_splat_layer", "enabled"));
  EXPECT_EQ(sl.strength, num("terrain_splat_layer", "strength"));
  const TerrainTexture& tt = s.terrainTextures.at(0);
  EXPECT_EQ(tt.color, rgba("terrain_texture", "color"));
  EXPECT_EQ(tt.uvScale, num("terrain_texture", "uvScale"));
  EXPECT_EQ(tt.roughness, num("terrain_texture", "roughness"));
  const Wire& w = s.wires.at(0);
  EXPECT_EQ(w.localIndexA, num("wire", "localIndexA"));
  EXPECT_EQ(w.localIndexB, num("wire", "localIndexB"));
  EXPECT_EQ(w.localPositionA, Eigen::Vector3d(vec("wire", "localPositionA")));
  EXPECT_EQ(w.localPositionB, Eigen::Vector3d(vec("wire", "localPositionB")));
  EXPECT_EQ(w.stiffness, num("wire", "stiffness"));
  EXPECT_EQ(w.damping, num("wire", "damping"));
  EXPECT_EQ(w.compliance, num("wire", "compliance"));
  EXPECT_EQ(w.enabled, flag("wire", "enabled"));
  const InstancedVisual& iv = s.instancedVisuals.at(0);
  EXPECT_EQ(iv.size, Eigen::Vector3d(vec("instanced_visual", "size")));
  EXPECT_EQ(iv.colorA, rgba("instanced_visual", "colorA"));
  EXPECT_EQ(iv.colorB, rgba("instanced_visual", "colorB"));
  EXPECT_EQ(iv.castShadows, flag("instanced_visual", "castShadows"));
  EXPECT_EQ(iv.grassPatch, flag("instanced_visual", "grassPatch"));
  EXPECT_EQ(iv.enabled, flag("instanced_visual", "enabled"));
  EXPECT_EQ(s.pointClouds.at(0).pointSize, num("point_cloud", "pointSize"));
  EXPECT_EQ(s.pointClouds.at(0).enabled, flag("point_cloud", "enabled"));
}

// The structs of scene.hpp (after SceneOptions) initialise members to
// zero, false, empty, -1 or identity, never to a value: a literal there
// would be a second copy of a default, free to drift from the schema's.
TEST(Defaults, SceneStructsHoldNoLiteralDefaults) {
  std::ifstream in(std::filesystem::path(RSCENE_SOURCE_DIR) / "lib/scene/scene.hpp");
  std::stringstream text;
  text << in.rdbuf();
  static const std::regex literal(
      R"(^\s+[\w:<>]+\s+\w+\s*(=\s*(?!-1\s*[,;])(-?[0-9.]*[1-9][0-9.eE+-]*|true|"[^"]+")|\{[-0-9.eE, ]*[1-9][-0-9.eE, ]*\})\s*[,;])");
  // The pattern finds what it is for.
  for (const char* bad : {"  double erp = 0.2;", "  int iterations = 80;", "  bool shadows = true;",
                          "  std::string mode = \"accurate\";", "  Eigen::Vector3d gravity{0, 0, -9.81};"})
    EXPECT_TRUE(std::regex_search(std::string(bad), literal)) << bad;
  for (const char* fine : {"  int recordIndex = -1;", "  double erp{};", "  bool visible{};",
                           "  Eigen::Vector3d size = Eigen::Vector3d::Zero();"})
    EXPECT_FALSE(std::regex_search(std::string(fine), literal)) << fine;
  std::string line;
  int n = 0, checked = 0;
  bool structs = false;
  while (std::getline(text, line)) {
    ++n;
    if (line.find("const char* bodyModeName") != std::string::npos) structs = true;
    if (!structs) continue;
    ++checked;
    EXPECT_FALSE(std::regex_search(line, literal)) << "scene.hpp:" << n << ": " << line;
  }
  EXPECT_GT(checked, 200);
}

}  // namespace
}  // namespace rscene
