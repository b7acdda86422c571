// Readers of the records of visual_records.hpp (called by scene.cpp's
// Builder, which resolves their parents and world poses) and the granular
// box fill.
#include "scene/visual_records_read.hpp"

#include <cmath>
#include <limits>
#include "core/codes.hpp"
#include "core/text.hpp"

namespace rscene {
namespace {

Eigen::Vector2d vec2(const RecordReader& r, std::string_view name, const Eigen::Vector2d& fallback) {
  std::vector<double> xs;
  if (!r.numbers(name, xs) || xs.size() < 2) return fallback;
  return {xs[0], xs[1]};
}

template <typename T>
void identity(const Document& doc, const RecordReader& r, int idx, T& out) {
  out.recordIndex = idx;
  out.path = nodePath(doc, r.record());
  out.id = nodeId(doc, r.record());
  out.parentId = r.str("parentGroupId");
}

}  // namespace

Pose readPose(const RecordReader& r, std::string_view pos, std::string_view rot) {
  Pose p;
  p.position = r.vec3(pos);
  Eigen::Vector4d q = r.quat(rot);  // w, x, y, z
  p.orientation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
  return p;
}

Decal readDecal(const Document& doc, const RecordReader& r, int idx, const AssetPath& asset) {
  Decal d;
  identity(doc, r, idx, d);
  d.local = readPose(r, "position", "orientation");
  d.scale = r.vec3("scale", Eigen::Vector3d::Ones());
  d.halfExtents = r.vec3("halfExtents");
  d.color = r.color("color");
  d.edgeFade = r.number("edgeFade");
  d.normalFade = r.number("normalFade");
  d.upperFade = r.number("upperFade");
  d.lowerFade = r.number("lowerFade");
  d.albedoTexture = asset(r.str("albedoTexture"));
  d.emissionTexture = asset(r.str("emissionTexture"));
  d.normalTexture = asset(r.str("normalTexture"));
  d.ormTexture = asset(r.str("ormTexture"));
  d.uvScale = vec2(r, "uvScale", Eigen::Vector2d::Ones());
  d.uvOffset = vec2(r, "uvOffset", Eigen::Vector2d::Zero());
  d.albedoMix = r.number("albedoMix");
  d.emissionEnergy = r.number("emissionEnergy");
  d.normalStrength = r.number("normalStrength");
  d.ormStrength = r.number("ormStrength");
  d.distanceFadeEnabled = r.flag("distanceFadeEnabled");
  d.distanceFadeBegin = r.number("distanceFadeBegin");
  d.distanceFadeLength = r.number("distanceFadeLength");
  d.enabled = r.flag("enabled");
  return d;
}

LocalFog readLocalFog(const Document& doc, const RecordReader& r, int idx) {
  LocalFog f;
  identity(doc, r, idx, f);
  f.localCenter = f.center = r.vec3("center");
  f.radius = r.number("radius");
  f.color = r.color("color").head<3>();
  f.density = r.number("density");
  f.edgeFade = r.number("edgeFade");
  f.noiseScale = r.number("noiseScale");
  f.noiseStrength = r.number("noiseStrength");
  f.enabled = r.flag("enabled");
  return f;
}

IrradianceVolume readIrradianceVolume(const Document& doc, const RecordReader& r, int idx) {
  IrradianceVolume v;
  identity(doc, r, idx, v);
  v.local = readPose(r, "position", "orientation");
  v.scale = r.vec3("scale", Eigen::Vector3d::Ones());
  v.halfExtents = r.vec3("halfExtents");
  v.color = r.color("color");
  v.strength = r.number("strength");
  v.edgeFade = r.number("edgeFade");
  v.normalBias = r.number("normalBias");
  v.enabled = r.flag("enabled");
  return v;
}

ReflectionProbe readReflectionProbe(const Document& doc, const RecordReader& r, int idx) {
  ReflectionProbe p;
  identity(doc, r, idx, p);
  p.localPosition = p.position = r.vec3("position");
  p.radius = r.number("radius");
  p.strength = r.number("strength");
  p.boxProjection = r.flag("boxProjection");
  p.boxMin = r.vec3("boxMin");
  p.boxMax = r.vec3("boxMax");
  p.cubemapSize = r.integer("cubemapSize");
  p.captureDrawVisualizationObjects = r.flag("captureDrawVisualizationObjects");
  p.captureDrawPointClouds = r.flag("captureDrawPointClouds");
  p.captureShadows = r.flag("captureShadows");
  p.captureEnvironmentBackground = r.flag("captureEnvironmentBackground");
  p.captureEnvironmentExposure = r.number("captureEnvironmentExposure");
  p.irradianceResolution = r.integer("irradianceResolution");
  p.irradianceSamples = r.integer("irradianceSamples");
  p.prefilteredResolution = r.integer("prefilteredResolution");
  p.prefilteredMipLevels = r.integer("prefilteredMipLevels");
  p.prefilteredSamples = r.integer("prefilteredSamples");
  p.brdfLutSize = r.integer("brdfLutSize");
  p.brdfLutSamples = r.integer("brdfLutSamples");
  p.enabled = r.flag("enabled");
  return p;
}

FoliageLayer readFoliageLayer(const RecordReader& r, int idx, const AssetPath& asset) {
  FoliageLayer l;
  l.recordIndex = idx;
  l.id = r.str("id");
  l.name = r.str("name");
  l.enabled = r.flag("enabled");
  l.primitive = r.name("primitive");
  l.meshPath = asset(r.str("meshPath"));
  l.size = r.vec3("size");
  l.colorA = r.color("colorA");
  l.colorB = r.color("colorB");
  l.densityPerSquareMeter = r.number("densityPerSquareMeter");
  l.maxInstances = r.integer("maxInstances");
  l.minScale = r.number("minScale");
  l.maxScale = r.number("maxScale");
  l.randomYawDegrees = r.number("randomYawDegrees");
  l.randomPitchDegrees = r.number("randomPitchDegrees");
  l.randomRollDegrees = r.number("randomRollDegrees");
  l.alignToNormal = r.flag("alignToNormal");
  l.minHeight = r.number("minHeight");
  l.maxHeight = r.number("maxHeight");
  l.minSlopeDegrees = r.number("minSlopeDegrees");
  l.maxSlopeDegrees = r.number("maxSlopeDegrees");
  l.castShadows = r.flag("castShadows");
  l.maxRenderedInstances = r.integer("maxRenderedInstances");
  l.renderedInstanceStride = r.integer("renderedInstanceStride");
  l.seed = r.integer("seed");
  return l;
}

Deformable readDeformable(const Document& doc, const RecordReader& r, int idx, const AssetPath& asset) {
  Deformable d;
  identity(doc, r, idx, d);
  d.kind = r.name("kind");
  d.meshPath = asset(r.str("meshPath"));
  d.meshToken = r.positionalToken("meshPath");
  d.local = readPose(r, "position", "orientation");
  d.scale = r.vec3("scale", Eigen::Vector3d::Ones());
  // The named uniform `scale=` (the positional scale shares its name, so
  // the reader finds that one first): multiplies it.
  std::string_view named = doc.value(r.record(), "scale");
  if (!named.empty()) {
    char* end = nullptr;
    std::string text(named);
    double s = std::strtod(text.c_str(), &end);
    if (end && *end == '\0' && std::isfinite(s)) d.scale *= s;
  }
  std::vector<double> pins;
  bool reported = false;
  if (r.numbers("pinnedVertices", pins))
    for (double p : pins) {
      // Only whole numbers a vertex index can be; anything else (2.7, 1e30,
      // NaN) becomes -1, which no mesh has, so the simulator refuses it at
      // this key instead of reading it as another vertex (or, for 1e30,
      // converting out of range).
      bool whole = p == std::floor(p) && std::abs(p) < 9007199254740992.0;
      if (!whole && !reported)  // lib/core's RS2003, so the model does not judge this record again
        r.error("pinnedVertices", rs::RS2003, "pinnedVertices holds a value that is not a whole number"), reported = true;
      bool index = whole && p >= 0;
      d.pinnedVertices.push_back(index ? static_cast<std::int64_t>(p) : -1);
    }
  d.totalMass = r.number("totalMass");
  d.distanceCompliance = r.number("distanceCompliance");
  d.distanceStiffness = r.number("distanceStiffness");
  d.bendCompliance = r.number("bendCompliance");
  d.bendStiffness = r.number("bendStiffness");
  d.youngsModulus = r.number("youngsModulus");
  d.poissonRatio = r.number("poissonRatio");
  d.thickness = r.number("thickness");
  d.damping = r.number("damping");
  d.collisionRadius = r.number("collisionRadius");
  d.iterations = r.integer("iterations");
  d.substeps = r.integer("substeps");
  d.solverMode = r.name("solverMode");
  d.particleMode = r.name("particleMode");
  d.particleSpacing = r.number("particleSpacing");
  d.contactMaterial = r.str("contactMaterial");
  d.material = r.str("material");
  d.visible = r.flag("visible");
  d.collidable = r.flag("collidable");
  d.collisionGroup = r.group("collisionGroup");
  d.collisionMask = r.group("collisionMask");
  return d;
}

Granular readGranular(const Document& doc, const RecordReader& r, int idx) {
  Granular g;
  identity(doc, r, idx, g);
  g.kind = r.name("kind", std::string());  // free text RaiSim does not read; `-` (empty) is allowed, as validate says
  g.local = readPose(r, "position", "orientation");
  g.scale = r.vec3("scale", Eigen::Vector3d::Ones());
  std::vector<double> xs;
  if (r.numbers("positions", xs)) {
    if (xs.size() % 3)
      r.error("positions", rs::RS2008, "positions holds " + std::to_string(xs.size()) + " numbers, not a multiple of 3");
    else
      for (std::size_t i = 0; i + 2 < xs.size(); i += 3) g.positions.emplace_back(xs[i], xs[i + 1], xs[i + 2]);
  }
  r.numbers("radii", g.radii);
  g.boxMin = r.vec3("boxMin");
  g.boxMax = r.vec3("boxMax");
  g.radius = r.number("radius");
  g.spacing = r.number("spacing");
  g.maxParticles = r.integer("maxParticles");
  g.velocity = r.vec3("velocity");
  g.angularVelocity = r.vec3("angularVelocity");
  g.materialId = r.integer("materialId");
  g.fixed = r.flag("fixed");
  g.density = r.number("density");
  g.normalStiffness = r.number("normalStiffness");
  g.normalDamping = r.number("normalDamping");
  g.tangentialStiffness = r.number("tangentialStiffness");
  g.tangentialDamping = r.number("tangentialDamping");
  g.friction = r.number("friction");
  g.rollingFriction = r.number("rollingFriction");
  g.cohesionStiffness = r.number("cohesionStiffness");
  g.cohesionMaxDistance = r.number("cohesionMaxDistance");
  g.normalContactModel = r.name("normalContactModel");
  g.substeps = r.integer("substeps");
  g.visible = r.flag("visible");
  return g;
}

std::string granularParticles(const Granular& g, std::uint64_t hardLimit, std::vector<Eigen::Vector3d>& positions,
                              std::vector<double>& radii) {
  positions.clear();
  radii.clear();
  std::uint64_t limit = hardLimit;
  if (g.maxParticles > 0) limit = std::min<std::uint64_t>(limit, static_cast<std::uint64_t>(g.maxParticles));
  // A count past 1e18 (or one that would wrap) is said as such, never as
  // the 2^64 - 1 it was clamped to.
  auto tooMany = [&](std::uint64_t n) {
    return "granular " + g.path + " has " +
           (n >= std::uint64_t{1'000'000'000'000'000'000} ? std::string("more than 1e18") : std::to_string(n)) +
           " particles, more than " +
           (g.maxParticles > 0 && static_cast<std::uint64_t>(g.maxParticles) <= hardLimit
                ? "its maxParticles " + std::to_string(g.maxParticles)
                : "the limit of " + std::to_string(hardLimit));
  };
  if (!g.positions.empty()) {
    if (g.positions.size() > limit) return tooMany(g.positions.size());
    if (!g.radii.empty() && g.radii.size() != 1 && g.radii.size() != g.positions.size())
      return "granular " + g.path + " has " + std::to_string(g.radii.size()) + " radii for " +
             std::to_string(g.positions.size()) + " positions";
    positions = g.positions;
    radii.resize(positions.size());
    for (std::size_t i = 0; i < positions.size(); ++i)
      radii[i] = g.radii.empty() ? g.radius : g.radii.size() == 1 ? g.radii[0] : g.radii[i];
    return {};
  }
  if (!(g.radius > 0) || !(g.spacing > 0) || !std::isfinite(g.radius) || !std::isfinite(g.spacing))
    return "granular " + g.path + " fills its box with radius " + numberText(g.radius) + " and spacing " +
           numberText(g.spacing) + ": both must be positive";
  // Counts per axis, computed before anything is allocated.
  std::uint64_t count[3];
  std::uint64_t total = 1;
  for (int a = 0; a < 3; ++a) {
    double span = (g.boxMax[a] - g.radius) - (g.boxMin[a] + g.radius);
    if (!std::isfinite(span)) return "granular " + g.path + " has a box that is not finite";
    double n = span < 0 ? 0 : std::floor(span / g.spacing + 1e-9) + 1;
    if (n > 1e18) return tooMany(std::numeric_limits<std::uint64_t>::max());
    count[a] = static_cast<std::uint64_t>(n);
    total = count[a] == 0 ? 0 : total > std::numeric_limits<std::uint64_t>::max() / count[a] ? std::numeric_limits<std::uint64_t>::max() : total * count[a];
  }
  if (total > limit) return tooMany(total);
  positions.reserve(total);
  for (std::uint64_t z = 0; z < count[2]; ++z)
    for (std::uint64_t y = 0; y < count[1]; ++y)
      for (std::uint64_t x = 0; x < count[0]; ++x)
        positions.emplace_back(g.boxMin.x() + g.radius + double(x) * g.spacing,
                               g.boxMin.y() + g.radius + double(y) * g.spacing,
                               g.boxMin.z() + g.radius + double(z) * g.spacing);
  radii.assign(positions.size(), g.radius);
  return {};
}

}  // namespace rscene
