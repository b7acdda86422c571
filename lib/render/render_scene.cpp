#include "render/render_scene.hpp"
#include "core/codes.hpp"
#include "render/render_effects.hpp"

#include "scene/reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <unordered_map>

#include "asset/obj_surface.hpp"
#include "render/deformed_surface.hpp"
#include "render/render_bodies.hpp"
#include "render/render_foliage.hpp"
#include "render/robot_drawables.hpp"
#include "robot/check.hpp"
#include "robot/instance.hpp"
#include "robot/kinematics.hpp"
#include "core/assets.hpp"
#include "scene/check.hpp"
#include "scene/validate.hpp"
#include "scene/granular.hpp"
#include "scene/reader.hpp"

namespace rscene::render {
namespace {

using Eigen::Affine3d;
using Eigen::Vector3d;
using Eigen::Vector3f;
using Eigen::Vector4d;
using Eigen::Vector4f;

constexpr double kPi = 3.14159265358979323846;
constexpr double kMinGroundSize = 200;  // metres: the ground reads as "large" from any camera

// Colours, intensities and other shading inputs as floats the shaders can
// multiply without overflowing: beyond +-1e6 (which tone mapping saturates
// long before) they are drawn as +-1e6, and NaN as 0.  A light of 1e39 was
// infinite in float and turned the lit surfaces black (NaN).
constexpr double kMaxShade = 1e6;
float shade(double v) { return std::isnan(v) ? 0.f : float(std::clamp(v, -kMaxShade, kMaxShade)); }
Vector4f toF(const Vector4d& v) { return {shade(v[0]), shade(v[1]), shade(v[2]), shade(v[3])}; }
Vector3f toF(const Vector3d& v) { return {shade(v[0]), shade(v[1]), shade(v[2])}; }
Vector3f rgb(const Vector4d& v) { return toF(Vector3d(v.head<3>())); }

Shape shapeOf(const std::string& primitive) {
  if (primitive == "sphere") return Shape::Sphere;
  if (primitive == "cylinder") return Shape::Cylinder;
  if (primitive == "capsule") return Shape::Capsule;
  if (primitive == "mesh") return Shape::Mesh;
  if (primitive == "ground" || primitive == "half_space") return Shape::Ground;
  return Shape::Box;
}

// Unit shape -> local frame at physical size (compat-notes.md "Sizes").
Vector3d shapeScale(Shape s, const Vector3d& scale, double radius, double height, const Vector3d& boxSize) {
  switch (s) {
    case Shape::Box: return boxSize;
    case Shape::Sphere: return Vector3d::Constant(radius * scale.x());
    case Shape::Cylinder: return {radius * scale.x(), radius * scale.x(), height * scale.z()};
    case Shape::Mesh: return scale;
    default: return Vector3d::Ones();
  }
}

Affine3d affine(const Pose& p) {
  Affine3d m = Affine3d::Identity();
  m.translate(p.position);
  m.rotate(p.orientation);
  return m;
}

class Preparer {
 public:
  Preparer(const Document& doc, const Scene& scene, RenderScene& out, Diagnostics& diags, const DrawLimits& limits,
           asset::AssetCache* assets)
      : doc_(doc), s_(scene), out_(out), diags_(diags), limits_(limits), assets_(assets) {}

  bool ok() const { return ok_; }

  void run() {
    out_ = RenderScene{};
    materials();
    look();
    for (std::size_t i = 0; i < s_.objects.size(); ++i) object(s_.objects[i], static_cast<int>(i));
    for (std::size_t i = 0; i < s_.compounds.size(); ++i) compound(s_.compounds[i], static_cast<int>(i));
    for (const Light& l : s_.lights) light(l);
    for (const Camera& c : s_.cameras) camera(c);
    terrainColors();
    for (const Terrain& t : s_.terrains) terrain(t);
    for (const Terrain& t : s_.terrains) foliage(t);
    for (const InstancedVisual& v : s_.instancedVisuals) instanced(v);
    for (const PointCloud& p : s_.pointClouds) points(p);
    robots();
    out_.deformableSurfaces.assign(s_.deformables.size(), -1);
    out_.granularBatches.assign(s_.granulars.size(), -1);
    for (std::size_t i = 0; i < s_.deformables.size(); ++i) deformable(s_.deformables[i], i);
    for (std::size_t i = 0; i < s_.granulars.size(); ++i) granular(s_.granulars[i], i);
    for (const Wire& w : s_.wires) wire(w);  // after robots(): an end may be a robot's link
    for (const SkippedRecord& r : s_.skipped) ++out_.skipped[r.tag];
  }

 private:
  std::uint32_t lineOf(int recordIndex) const {
    return recordIndex >= 0 && std::size_t(recordIndex) < doc_.records.size() ? doc_.records[std::size_t(recordIndex)].line
                                                                              : 0;
  }

  // Column of a field of a record, for messages about the file it names.
  std::uint32_t columnOf(int recordIndex, std::string_view field) const {
    if (recordIndex < 0 || std::size_t(recordIndex) >= doc_.records.size()) return 0;
    Diagnostics unused;
    return RecordReader(doc_, std::size_t(recordIndex), unused).columnOf(field);
  }
  bool hasField(int recordIndex, std::string_view field) const {
    Diagnostics unused;
    return recordIndex >= 0 && RecordReader(doc_, std::size_t(recordIndex), unused).has(field);
  }

  int materialIndex(const std::string& ref) const {
    if (ref.empty()) return 0;
    auto it = materialByRef_.find(ref);
    return it == materialByRef_.end() ? 0 : it->second;
  }

  // A scene material as the shaders take it.
  RenderMaterial renderMaterial(const Material& src) const {
    RenderMaterial m;
    m.id = src.id;
    m.color = toF(src.color);
    m.metallic = float(src.metallic);
    m.roughness = float(std::clamp(src.roughness, 0.03, 1.0));
    m.emissive = toF(Vector3d(src.emissive * std::clamp(src.emissiveStrength, -kMaxShade, kMaxShade)));
    m.doubleSided = src.doubleSided;
    m.blend = src.alphaMode == "blend" || m.color.w() < 0.999f;
    m.albedoTexture = src.albedoTexture;
    m.line = lineOf(src.recordIndex);
    m.textureColumn = columnOf(src.recordIndex, "albedoTexture");
    m.isDefault = src.name == "engine_default";
    return m;
  }

  void materials() {
    out_.materials.push_back(renderMaterial(s_.defaultMaterial));
    for (const Material& src : s_.materials) {
      RenderMaterial m = renderMaterial(src);
      int index = static_cast<int>(out_.materials.size());
      if (m.isDefault) {  // redefines the default in place
        index = 0;
        out_.materials[0] = m;
      } else {
        out_.materials.push_back(m);
      }
      materialByRef_[src.name] = index;
      if (!m.id.empty()) materialByRef_[m.id] = index;
    }
  }

  void look() {
    const Environment& env = s_.environment;
    Look& e = out_.environment;
    e.background = toF(env.background);
    e.ambient = toF(env.ambient);
    // The weather's fog (when it is enabled) adds to the environment's.
    const Weather& wx = s_.weather;
    e.fogDensity = float(std::max(0.0, env.fogDensity) + (wx.recordIndex >= 0 && wx.enabled ? std::max(0.0, wx.fogDensity) : 0.0));
    e.fogColor = rgb(env.fogColor);
    e.shadows = env.shadows;
    e.exposure = shade(env.exposure);
    e.gamma = float(env.gamma);
    if (!(e.gamma > 0.1f)) e.gamma = 2.2f;
    e.mode = env.backgroundMode == "plain_color" ? Background::PlainColor
             : env.backgroundMode == "hdr"       ? Background::Hdr
                                                 : Background::Sky;
    e.hdrPath = env.envMapPath;
    e.hdrLine = lineOf(env.recordIndex);
    // The environment's colorMode when written, else the view settings'.
    const std::string& c = !env.colorMode.empty() ? env.colorMode : s_.renderSettings.colorMode;
    e.toneMap = c == "fast_linear"             ? ToneMap::Linear
                : c == "filmic_approx"         ? ToneMap::Filmic
                : c == "agx_approx"            ? ToneMap::AgX
                : c == "unreal_preview_approx" ? ToneMap::Unreal
                                               : ToneMap::Aces;
    const Weather& w = s_.weather;
    double azimuth = 180, elevation = 42;
    if (w.recordIndex >= 0) {
      const std::string& p = w.preset;
      e.overcast = p == "overcast" || p == "rain" || p == "heavy_rain" || p == "storm" || p == "snow" || p == "fog" ||
                   p == "night_rain";
      e.night = p == "night_clear" || p == "night_rain";
      e.cloudCoverage = float(std::clamp(w.cloudCoverage.value_or(e.overcast ? 0.9 : 0.05), 0.0, 1.0));
      if (w.useExplicitSunAngles) {
        azimuth = w.sunAzimuthDegrees;
        elevation = w.sunElevationDegrees;
      } else {
        // Time of day without the astronomical solver: sunrise 6h in the
        // east, noon at 70 degrees in the south, sunset 18h in the west.
        double t = w.timeOfDay;
        elevation = 70 * std::sin(kPi * (t - 6) / 12);
        azimuth = 90 + (t - 6) * 15;
      }
      if (e.night) elevation = -20;
    }
    // Azimuth clockwise from north (+y) towards east (+x).
    double az = azimuth * kPi / 180, el = elevation * kPi / 180;
    e.sunDirection = Vector3d(std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)).normalized();
  }

  // The legend entry of a record, added once per record.
  int segment(const char* kind, int recordIndex, const std::string& path, const std::string& id,
              const std::string& semanticClass, std::int64_t instanceId,
              const std::optional<Eigen::Vector4d>& color = std::nullopt) {
    auto [it, added] = segmentOf_.try_emplace(recordIndex, static_cast<int>(out_.segments.size()));
    if (!added) return it->second;
    Segment g;
    segmentColor(color, instanceId, semanticClass, path, g.rgb);
    g.kind = kind;
    g.path = path;
    g.id = id;
    g.semanticClass = semanticClass;
    g.instanceId = instanceId;
    g.line = lineOf(recordIndex);
    out_.segments.push_back(std::move(g));
    return it->second;
  }

  // `body` moves it (rscene-render --trajectory): the drawable keeps its
  // transform relative to the body's pose.
  static void attach(Drawable& d, Mount::Kind kind, int index, const Pose& body, int link = -1) {
    d.attachment.kind = kind;
    d.attachment.index = index;
    d.attachment.link = link;
    d.attachment.local = affine(body).inverse() * d.world;
  }

  // `local`: the bounds `world` maps from, when not the unit shape's (a
  // mesh read for its size).
  void addDrawable(Drawable d, const std::optional<Eigen::AlignedBox3d>& local = std::nullopt) {
    d.localBounds = local && !local->isEmpty() ? *local : unitShapeBounds(d.shape, d.capsuleRadius, d.capsuleHeight);
    d.bounds = transformBox(d.world, d.localBounds);
    if (d.shape == Shape::Ground) out_.hasGround = true;
    else out_.bounds.extend(d.bounds);
    out_.drawables.push_back(std::move(d));
  }

  void object(const Object& o, int index) {
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

  void compound(const Compound& c, int index) {
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

  void light(const Light& src) {
    if (src.hiddenByGroup) return;
    RenderLight l;
    l.type = src.type == "point"  ? LightType::Point
             : src.type == "spot" ? LightType::Spot
             : src.type == "area" ? LightType::Area
                                  : LightType::Directional;
    l.direction = src.direction;
    l.position = src.position;
    float intensity = shade(src.negative ? -src.intensity : src.intensity);
    l.color = toF(Vector3d((rgb(src.color) * intensity).cast<double>()));
    l.attenuation = Vector3f(float(src.attenuationConstant), float(src.attenuationLinear), float(src.attenuationQuadratic));
    l.coneDegrees = float(src.coneAngle);
    l.innerConeDegrees = float(std::min(src.innerConeAngle, src.coneAngle));
    l.range = float(src.range);
    // An area light without a size is a 1 m square.
    Vector3d area = src.areaSize.head<2>().isZero() ? Vector3d(1, 1, 0) : src.areaSize;
    l.areaSize = Eigen::Vector2f(float(area.x()), float(area.y()));
    l.shadows = src.shadows;
    l.shadowResolution = int(std::clamp<std::int64_t>(src.shadowResolution, 0, 16384));
    l.shadowBias = float(src.shadowBias);
    l.shadowStrength = float(std::clamp(src.shadowStrength, 0.0, 1.0));
    l.shadowPcfRadius = float(std::max(src.shadowPcfRadius, 0.0));
    l.customShadowBox = src.shadowUseCustomPosition;
    l.shadowCenter = src.shadowCenter;
    l.shadowOrthoHalfSize = float(std::max(src.shadowOrthoHalfSize, 0.0));
    l.shadowNear = float(src.shadowNear);
    l.shadowFar = float(src.shadowFar);
    l.line = lineOf(src.recordIndex);
    out_.lights.push_back(l);
  }

  void camera(Camera c) {
    if (!(c.nearPlane > 0)) c.nearPlane = 0.05;
    if (!(c.farPlane > c.nearPlane)) c.farPlane = c.nearPlane * 2000;
    out_.cameras.push_back(std::move(c));
  }

  void terrainColors() {
    for (const TerrainTexture& t : s_.terrainTextures) slotColors_[t.slot] = toF(t.color);
  }

  Vector4f slotColor(int slot) const {
    auto it = slotColors_.find(slot);
    if (it != slotColors_.end()) return it->second;
    return slotColors_.empty() ? Vector4f(0.5f, 0.5f, 0.5f, 1) : slotColors_.begin()->second;
  }

  // Whether every sample of `src` looks the same: one height, no holes,
  // no per-sample color.  Such a terrain is drawn as its 4 corners.
  static bool uniform(const Terrain& src) {
    std::size_t n = src.heights.size();
    if (src.vertexColors.size() == n) return false;
    if (src.textureSplatting) {
      if (src.texturePrimary.size() == n) return false;
      for (const TerrainSplatLayer& layer : src.splatLayers)
        if (layer.enabled && layer.weights.size() == n) return false;
    }
    for (double h : src.holes)
      if (h > 0.5) return false;
    return std::all_of(src.heights.begin(), src.heights.end(), [&](double h) { return h == src.heights.front(); });
  }

  // Sample indices drawn along an axis of `n` samples: every `step`-th,
  // and always the last, so the drawn terrain keeps its extent.
  static std::vector<int> axisSamples(int n, int step) {
    std::vector<int> out;
    for (int i = 0; i < n - 1; i += step) out.push_back(i);
    out.push_back(n - 1);
    return out;
  }

  void terrain(const Terrain& src) {
    if (!src.visible || src.hiddenByGroup) return;
    std::size_t n = std::size_t(src.xSamples) * std::size_t(src.ySamples);
    if (src.xSamples < 2 || src.ySamples < 2 || src.heights.size() != n) return;  // the view reported it
    // The grid drawn: all samples up to limits_.maxTerrainVertices, else
    // every step-th one; a uniform terrain needs only its corners.
    int step = 1;
    while (std::uint64_t((src.xSamples - 2) / step + 2) * std::uint64_t((src.ySamples - 2) / step + 2) >
           std::max<std::uint64_t>(limits_.maxTerrainVertices, 4))
      ++step;
    if (uniform(src)) step = std::max(src.xSamples, src.ySamples);
    std::vector<int> xs = axisSamples(src.xSamples, step), ys = axisSamples(src.ySamples, step);
    TerrainMesh t;
    t.segment = segment("terrain_region", src.recordIndex, src.path, src.id, "", -1);
    t.xSamples = int(xs.size());
    t.ySamples = int(ys.size());
    std::size_t drawn = xs.size() * ys.size();
    t.material = materialIndex(src.material);
    t.castShadow = src.castShadow;
    t.receiveShadow = src.receiveShadow;
    t.positions.resize(drawn);
    t.colors.assign(drawn, slotColor(src.baseTexture));
    t.holes.assign(drawn, false);
    bool splatting = src.textureSplatting;
    const auto& primary = src.texturePrimary;
    const auto& secondary = src.textureSecondary;
    const auto& blend = src.textureBlend;
    std::vector<const TerrainSplatLayer*> layers;
    for (const TerrainSplatLayer& layer : src.splatLayers)
      if (splatting && layer.enabled && layer.weights.size() == n) layers.push_back(&layer);
    for (std::size_t yi = 0; yi < ys.size(); ++yi)
      for (std::size_t xi = 0; xi < xs.size(); ++xi) {
        int x = xs[xi], y = ys[yi];
        std::size_t i = std::size_t(y) * std::size_t(src.xSamples) + std::size_t(x);  // in the source grid
        std::size_t o = yi * xs.size() + xi;                                          // in the drawn grid
        t.positions[o] = src.samplePosition(x, y).cast<float>();
        Vector4f& c = t.colors[o];
        if (splatting && primary.size() == n) {
          Vector4f a = slotColor(int(primary[i]));
          Vector4f b = secondary.size() == n ? slotColor(int(secondary[i])) : a;
          float w = blend.size() == n ? std::clamp(float(blend[i]), 0.f, 1.f) : 0.f;
          c = a * (1 - w) + b * w;
        }
        for (const TerrainSplatLayer* layer : layers) {
          float k = std::clamp(float(layer->weights[i]), 0.f, 1.f) * std::clamp(float(layer->strength), 0.f, 1.f);
          c = c * (1 - k) + slotColor(layer->slot) * k;
        }
        if (src.vertexColors.size() == n)
          for (int k = 0; k < 3; ++k) c[k] *= float(src.vertexColors[i][k]);
        if (src.holes.size() == n) t.holes[o] = src.holes[i] > 0.5;
        t.bounds.extend(t.positions[o].cast<double>());
      }
    out_.bounds.extend(t.bounds);
    out_.terrains.push_back(std::move(t));
  }

  // Indices a record draws: every stride-th (stride < 1 counts as 1), at
  // most `max` of them when max > 0.
  static std::size_t drawnCount(std::size_t total, std::int64_t max, std::int64_t stride) {
    std::size_t s = std::size_t(std::max<std::int64_t>(stride, 1));
    std::size_t n = (total + s - 1) / s;
    return max > 0 ? std::min(n, std::size_t(max)) : n;
  }

  void instanced(const InstancedVisual& v) {
    if (!v.enabled || v.hiddenByGroup || v.instances.empty()) return;
    Instanced b;
    b.line = lineOf(v.recordIndex);
    b.segment = segment("instanced_visual", v.recordIndex, v.path, v.id, "", -1);
    b.shape = shapeOf(v.primitive);
    if (b.shape == Shape::Ground) b.shape = Shape::Box;
    if (b.shape == Shape::Capsule) b.shape = Shape::Cylinder;  // an instanced capsule is drawn as its cylinder
    if (b.shape == Shape::Mesh) {
      b.meshPath = v.meshPath;
      b.meshColumn = columnOf(v.recordIndex, "meshPath");
    }
    // A grass patch draws blades unless it names a mesh (its own blades).
    if (v.grassPatch && b.shape != Shape::Mesh) b.shape = Shape::GrassBlade;
    b.doubleSided = b.shape == Shape::GrassBlade;
    b.castShadow = v.castShadows;
    Vector3d unit = unitScale(b.shape, v.size);
    const Terrain* bound = boundTerrain(v);
    Vector4f colorA = toF(v.colorA), colorB = toF(v.colorB);
    std::size_t stride = std::size_t(std::max<std::int64_t>(v.renderedStride, 1));
    std::size_t count = drawnCount(v.instances.size(), v.maxRendered, v.renderedStride);
    b.generated = v.instances.size();
    // Checked before anything per instance is allocated.
    if (!reserveInstances(count, b.line, "instanced_visual")) return;
    b.worlds.reserve(count);
    b.colors.reserve(count);
    b.instanceBounds.reserve(count);
    for (std::size_t k = 0; k < count; ++k) {
      std::size_t i = k * stride;
      const Instance& in = v.instances[i];
      Vector3d position = in.position;
      if (bound) position = onTerrain(*bound, position);
      Affine3d m = Eigen::Translation3d(position) * in.orientation * Eigen::Scaling(in.scale.cwiseProduct(unit));
      b.worlds.push_back(m);
      float w = i < v.colorWeights.size() ? std::clamp(float(v.colorWeights[i]), 0.f, 1.f) : 0.f;
      b.colors.push_back(colorA * (1 - w) + colorB * w);
      b.instanceBounds.push_back(transformBox(m, unitShapeBounds(b.shape)));
      b.bounds.extend(b.instanceBounds.back());
    }
    out_.bounds.extend(b.bounds);
    out_.instanced.push_back(std::move(b));
  }

  // The unit shape's scale for a primitive of extent `size`: box sides and
  // mesh scale as written, sphere/cylinder diameters halved to radii, a
  // grass blade's width, lean and height as written.
  static Vector3d unitScale(Shape shape, const Vector3d& size) {
    Vector3d unit = shape == Shape::Box || shape == Shape::Mesh || shape == Shape::GrassBlade ? size : Vector3d(size / 2);
    if (shape == Shape::Cylinder) unit.z() = size.z();
    return unit;
  }

  // Room for `count` more instances under limits_.maxInstances, taken; else
  // RS9014 on the record that asks for them.
  bool reserveInstances(std::uint64_t count, std::uint32_t line, const std::string& kind) {
    std::uint64_t left = limits_.maxInstances - std::min(instancesDrawn_, limits_.maxInstances);
    if (count <= left) {
      instancesDrawn_ += count;
      return true;
    }
    Diagnostic d;
    d.severity = Severity::Error;
    d.code = rs::RS9014;
    d.line = line;
    d.column = line ? 1 : 0;
    d.message = kind + " draws " + std::to_string(count) + " instances, more than the " + std::to_string(left) +
                " left of --max-instances " + std::to_string(limits_.maxInstances);
    d.hint = "set maxRenderedInstances or renderedInstanceStride on the record, or raise --max-instances";
    diags_.push_back(std::move(d));
    ok_ = false;
    return false;
  }

  // The terrain an instanced_visual's terrainBinding names (id or path).
  const Terrain* boundTerrain(const InstancedVisual& v) const {
    if (v.terrainBinding.empty()) return nullptr;
    for (const Terrain& t : s_.terrains)
      if (t.id == v.terrainBinding || t.path == v.terrainBinding) return TerrainSurface(t).valid() ? &t : nullptr;
    return nullptr;
  }

  // terrainBinding: an instance over the terrain stands on its surface,
  // its z an offset above it; one beyond the terrain's rectangle keeps its
  // position.
  static Vector3d onTerrain(const Terrain& t, Vector3d p) {
    TerrainSurface surface(t);
    if (surface.contains(p.x(), p.y())) p.z() += surface.at(p.x(), p.y()).z;
    return p;
  }

  static Shape foliageShape(const std::string& primitive) {
    if (primitive == "box" || primitive == "cube") return Shape::Box;
    if (primitive == "sphere") return Shape::Sphere;
    if (primitive == "cylinder" || primitive == "capsule") return Shape::Cylinder;
    if (primitive == "mesh") return Shape::Mesh;
    return Shape::GrassBlade;
  }

  // Every enabled terrain_foliage_layer of a drawn terrain, scattered
  // (render_foliage.hpp): visual only, so sensors do not see it.
  void foliage(const Terrain& t) {
    if (!t.visible || t.hiddenByGroup) return;
    for (std::size_t k = 0; k < t.foliageLayers.size(); ++k) {
      const FoliageLayer& l = t.foliageLayers[k];
      if (!l.enabled) continue;
      Instanced b;
      b.kind = "terrain_foliage_layer";
      b.line = lineOf(l.recordIndex);
      b.shape = foliageShape(l.primitive);
      static const char* const known[] = {"grass_blade", "grass", "box", "cube", "sphere", "cylinder", "capsule", "mesh", ""};
      if (std::find(std::begin(known), std::end(known), l.primitive) == std::end(known)) {
        Diagnostic d;
        d.severity = Severity::Warning;
        d.code = rs::RS9072;
        d.line = b.line;
        d.column = b.line ? 1 : 0;
        d.message = "terrain_foliage_layer primitive '" + l.primitive + "' is drawn as grass_blade";
        d.hint = "use grass_blade, box, sphere, cylinder, or mesh with meshPath";
        diags_.push_back(std::move(d));
      }
      FoliageScatter sc = countFoliage(t, l);
      b.generated = sc.generated;
      if (sc.drawn == 0) continue;
      if (!reserveInstances(sc.drawn, b.line, "terrain_foliage_layer")) continue;
      std::string name = !l.id.empty() ? l.id : !l.name.empty() ? l.name : "foliage" + std::to_string(k);
      b.segment = segment("terrain_foliage_layer", l.recordIndex, t.path + "#" + name, l.id, "", -1);
      if (b.shape == Shape::Mesh) {
        b.meshPath = l.meshPath;
        b.meshColumn = columnOf(l.recordIndex, "meshPath");
      }
      b.doubleSided = b.shape == Shape::GrassBlade;
      b.castShadow = l.castShadows;
      // A flat blade (a zero lean) or a zero size would make the normal
      // matrix singular: every axis keeps a sliver.
      Vector3d unit = unitScale(b.shape, l.size).unaryExpr([](double v) { return std::isfinite(v) ? std::max(v, 1e-4) : 1e-4; });
      Vector4f colorA = toF(l.colorA), colorB = toF(l.colorB);
      std::vector<FoliageInstance> placed = scatterFoliage(t, l, sc);
      b.worlds.reserve(placed.size());
      b.colors.reserve(placed.size());
      b.instanceBounds.reserve(placed.size());
      Eigen::AlignedBox3d unitBounds = unitShapeBounds(b.shape);
      for (const FoliageInstance& f : placed) {
        Affine3d m = Eigen::Translation3d(f.position) * f.rotation * Eigen::Scaling(Vector3d(unit * f.scale));
        b.worlds.push_back(m);
        b.colors.push_back(colorA * (1 - f.colorWeight) + colorB * f.colorWeight);
        b.instanceBounds.push_back(transformBox(m, unitBounds));
        b.bounds.extend(b.instanceBounds.back());
      }
      out_.bounds.extend(b.bounds);
      out_.instanced.push_back(std::move(b));
    }
  }

  // The bounds of a mesh file in its own frame (empty when it cannot be
  // read: the renderer reports that, with the same cache).
  Eigen::AlignedBox3d meshBounds(const std::string& path) {
    Eigen::AlignedBox3d box;
    std::string err;
    if (path.empty()) return box;
    if (std::shared_ptr<const asset::Mesh> mesh = assets().mesh(path, asset::MeshContent::Surface, &err))
      for (const asset::MeshPart& p : mesh->parts)
        for (std::size_t i = 0; i < p.vertexCount(); ++i)
          box.extend(Vector3d(p.positions[i * 3], p.positions[i * 3 + 1], p.positions[i * 3 + 2]));
    return box;
  }

  // deformable: its mesh at rest (the format stores no deformed state), at
  // its pose and scale, in its material.  An OBJ is drawn from its surface
  // in file order (deformed_surface.hpp): the vertices rscene-sim moves, so
  // trajectory frames can replace them.  Any other mesh, or an OBJ that is
  // no usable surface, goes through assimp as other meshes do; a missing
  // mesh is then the renderer's RS5001 (a placeholder box of the record's
  // scale with --allow-missing-assets).
  void deformable(const Deformable& src, std::size_t index) {
    if (!src.visible || src.hiddenByGroup) return;
    Drawable d;
    d.shape = Shape::Mesh;
    d.meshPath = src.meshPath;
    d.line = lineOf(src.recordIndex);
    d.meshColumn = columnOf(src.recordIndex, "meshPath");
    d.material = materialIndex(src.material);
    d.segment = segment("deformable", src.recordIndex, src.path, src.id, "", -1);
    d.worldObject = true;  // a body of the world, as sensors see it
    d.world = affine(src.world) * Eigen::Scaling(src.scale);
    // A sheet of cloth is seen from both sides; a closed volume's back
    // faces are hidden anyway.
    d.doubleSided = src.kind == "cloth";
    if (objSurface(src, index, d)) return;
    addDrawable(std::move(d), meshBounds(src.meshPath));
  }

  // Draws `d` from the OBJ surface of a deformable, when its mesh is one
  // that reads; false (and `d` untouched) otherwise.
  bool objSurface(const Deformable& src, std::size_t index, Drawable& d) {
    std::string ext = std::filesystem::path(src.meshPath).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    asset::ObjSurface obj;
    // Regular files only (a FIFO would block the read): anything else is
    // the assimp path's to report.
    const FileSystem& fs = assets().fileSystem();
    if (ext != ".obj" || fs.stat(src.meshPath).kind != FileKind::Regular ||
        !asset::loadObjSurface(fs, src.meshPath, obj, nullptr))
      return false;
    DeformedSurface surface = surfaceFromObj(obj, d.world);
    surface.mayFill = src.kind != "cloth" && src.kind != "mass_spring";
    // Its positions are world positions (trajectory frames replace them),
    // and a mirroring scale turns a closed surface's winding inside out.
    d.doubleSided = d.doubleSided || d.world.linear().determinant() < 0;
    d.world = Eigen::Affine3d::Identity();
    d.surface = int(out_.surfaces.size());
    surface.drawable = out_.drawables.size();
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3f& p : surface.positions) box.extend(p.cast<double>());
    out_.deformableSurfaces[index] = d.surface;
    out_.surfaces.push_back(std::move(surface));
    addDrawable(std::move(d), box);
    return true;
  }

  // granular: its particles (box fill or explicit) as spheres of their
  // radii in the record's frame, sand-colored: materialId names the
  // particles' contact material, not a look.
  void granular(const Granular& g, std::size_t index) {
    if (!g.visible || g.hiddenByGroup) return;
    std::uint64_t left = limits_.maxInstances - std::min(instancesDrawn_, limits_.maxInstances);
    std::vector<Vector3d> positions;
    std::vector<double> radii;
    std::string why = granularParticles(g, left, positions, radii);
    if (!why.empty()) {
      // A record whose grains cannot be made at all is the scene model's
      // finding (checkScene(): RS7082 at its key, as validate and sim say);
      // what is left is this renderer's own cap, --max-instances.
      std::vector<Vector3d> p;
      std::vector<double> r;
      if (!granularParticles(g, kMaxGranularParticles, p, r).empty()) {
        ok_ = false;
        return;
      }
      Diagnostic d;
      d.severity = Severity::Error;
      d.code = rs::RS9070;
      d.line = lineOf(g.recordIndex);
      d.column = d.line ? 1 : 0;
      d.message = why;
      d.hint = "maxParticles is " + std::to_string(g.maxParticles) + "; " + std::to_string(left) + " of --max-instances " +
               std::to_string(limits_.maxInstances) + " are left: fill a smaller box, space the particles wider, or raise "
               "--max-instances";
      diags_.push_back(std::move(d));
      ok_ = false;
      return;
    }
    if (positions.empty()) return;
    instancesDrawn_ += positions.size();
    Instanced b;
    b.kind = "granular";
    b.generated = positions.size();
    b.shape = Shape::Sphere;
    b.line = lineOf(g.recordIndex);
    b.segment = segment("granular", g.recordIndex, g.path, g.id, "", -1);
    b.worldObject = true;
    Affine3d frame = affine(g.world);
    const Vector4f sand(0.76f, 0.64f, 0.45f, 1.0f);
    b.worlds.reserve(positions.size());
    b.colors.assign(positions.size(), sand);
    b.instanceBounds.reserve(positions.size());
    b.radii.reserve(positions.size());
    for (std::size_t i = 0; i < positions.size(); ++i) {
      double r = std::isfinite(radii[i]) ? std::max(radii[i], 0.0) : 0.0;
      b.radii.push_back(r);
      Affine3d m = frame * Eigen::Translation3d(positions[i]) * Eigen::Scaling(r);
      b.worlds.push_back(m);
      b.instanceBounds.push_back(transformBox(m, unitShapeBounds(Shape::Sphere)));
      b.bounds.extend(b.instanceBounds.back());
    }
    out_.bounds.extend(b.bounds);
    out_.granularBatches[index] = int(out_.instanced.size());
    out_.instanced.push_back(std::move(b));
  }

  // The link whose frame is RaiSim's body `body` of robot `robot` (as
  // rscene-sim attaches a wire: body 0 the root, body k the child link of
  // the k-th movable joint in RaiSim's order, fixed links merged away), or
  // -1 when the robot did not load or has no such body.
  int robotBodyLink(std::size_t robot, int body) const {
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

  // Where a wire end is attached: the body `ref` names (id or path; its
  // record frame, or a robot's link localIndex), or the world when `ref` is
  // empty.  False when it names nothing that is drawn at a known pose.
  bool wireEnd(const std::string& ref, int record, int localIndex, const Vector3d& point, Attachment& at,
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

  // wire: a dark cylinder of visualizationWidth between its two attachment
  // points, recomputed from both ends when bodies move (poseScene()).  An
  // end that names nothing drawable (the validator's RS3012, a robot
  // without that link) leaves the wire undrawn, counted as skipped.
  void wire(const Wire& w) {
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

  void points(const PointCloud& src) {
    if (!src.enabled || src.hiddenByGroup || src.points.empty()) return;
    PointBatch pc;
    pc.segment = segment("point_cloud", src.recordIndex, src.path, src.id, "", -1);
    pc.pointSize = float(std::clamp(src.pointSize, 1.0, 64.0));
    std::size_t stride = std::size_t(std::max<std::int64_t>(src.renderedStride, 1));
    std::size_t count = drawnCount(src.points.size(), src.maxRendered, src.renderedStride);
    pc.points.reserve(count);
    pc.colors.reserve(count);
    for (std::size_t k = 0; k < count; ++k) {
      std::size_t i = k * stride;
      pc.points.push_back(src.points[i].cast<float>());
      pc.colors.push_back(i < src.colors.size() ? toF(src.colors[i]) : Vector4f(1, 1, 1, 1));
      pc.bounds.extend(src.points[i]);
    }
    out_.bounds.extend(pc.bounds);
    out_.pointClouds.push_back(std::move(pc));
  }

  // Every visible articulated system at the state its record gives
  // (robot::makeInstance, as sim and validate read it); one load per robot
  // file and one read per mesh file, however many robots share them.
  void robots() {
    if (s_.articulated.empty()) return;
    RobotDrawer drawer(out_, assets());
    robot::ModelCache models;
    out_.robotModels.assign(s_.articulated.size(), nullptr);
    robotLinks_.assign(s_.articulated.size(), {});
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
      robot::InstanceOptions io;
      io.allowMissingMeshes = limits_.allowMissingAssets;
      if (!robot::makeInstance(doc_, a, models, r, diags_, io)) ok_ = false;
      if (!r.model) continue;
      out_.robotModels[i] = r.model;
      robotLinks_[i] = robot::linkPoses(r);
      if (!a.visible || a.hiddenByGroup) continue;
      int seg = segment("articulated", a.recordIndex, a.path, a.id, a.semanticClass, -1);
      if (drawer.add(*r.model, robot::linkPoses(r), static_cast<int>(i), seg) == 0) {
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

  asset::AssetCache& assets() { return assets_ ? *assets_ : ownAssets_ ? *ownAssets_ : ownAssets_.emplace(); }

  const Document& doc_;
  const Scene& s_;
  RenderScene& out_;
  Diagnostics& diags_;
  const DrawLimits& limits_;
  asset::AssetCache* assets_;
  std::uint64_t instancesDrawn_ = 0;
  std::optional<asset::AssetCache> ownAssets_;  // when prepareScene was given none
  std::vector<std::vector<Pose>> robotLinks_;   // per Scene::articulated: link poses at its record's state
  int wireMaterial_ = -1;
  bool ok_ = true;
  std::unordered_map<std::string, int> materialByRef_;
  std::unordered_map<int, int> segmentOf_;  // record index -> RenderScene::segments
  std::map<int, Vector4f> slotColors_;
};

}  // namespace

Eigen::AlignedBox3d transformBox(const Affine3d& m, const Eigen::AlignedBox3d& local) {
  Eigen::AlignedBox3d b;
  if (local.isEmpty()) return b;
  for (int i = 0; i < 8; ++i) b.extend(m * local.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)));
  return b;
}

Eigen::AlignedBox3d unitShapeBounds(Shape s, double capsuleR, double capsuleH) {
  switch (s) {
    case Shape::Sphere: return {Vector3d(-1, -1, -1), Vector3d(1, 1, 1)};
    case Shape::Cylinder: return {Vector3d(-1, -1, -0.5), Vector3d(1, 1, 0.5)};
    case Shape::Capsule:
      return {Vector3d(-capsuleR, -capsuleR, -capsuleH / 2 - capsuleR), Vector3d(capsuleR, capsuleR, capsuleH / 2 + capsuleR)};
    case Shape::Ground: return {Vector3d(-0.5, -0.5, 0), Vector3d(0.5, 0.5, 0)};
    default: return {Vector3d::Constant(-0.5), Vector3d::Constant(0.5)};
  }
}

void segmentColor(const std::optional<Eigen::Vector4d>& written, std::int64_t instanceId,
                  const std::string& semanticClass, const std::string& path, std::uint8_t rgb[3]) {
  if (written) {
    for (int k = 0; k < 3; ++k) rgb[k] = static_cast<std::uint8_t>(std::lround(std::clamp((*written)[k], 0.0, 1.0) * 255));
    if (rgb[0] || rgb[1] || rgb[2]) return;
    rgb[0] = rgb[1] = rgb[2] = 1;  // black is the background's: the nearest color that is not
    return;
  }
  // FNV-1a of what names the segment, so that a color never depends on the
  // order of the records or on the tool's version.
  // An instance id is counted within its class (instance 1 of "box" and of
  // "person" are two things), so the class is part of the key.
  std::string key = instanceId >= 0 ? "instance:" + semanticClass + ":" + std::to_string(instanceId)
                    : !semanticClass.empty() ? "class:" + semanticClass
                                             : "path:" + path;
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : key) h = (h ^ c) * 1099511628211ull;
  // Each channel in 32..255: bright enough to tell from the background.
  for (int k = 0; k < 3; ++k) rgb[k] = static_cast<std::uint8_t>(32 + (h >> (8 * k + 16)) % 224);
}

void poseScene(RenderScene& scene, const BodyPoseView& poses) {
  auto bodyPose = [&](const Attachment& a, Pose& out) {
    auto in = [](const auto* list, int i) { return list && i >= 0 && std::size_t(i) < list->size(); };
    switch (a.kind) {
      case Mount::Kind::Object:
        if (!in(poses.objects, a.index)) return false;
        out = (*poses.objects)[std::size_t(a.index)];
        return true;
      case Mount::Kind::Compound:
        if (!in(poses.compounds, a.index)) return false;
        out = (*poses.compounds)[std::size_t(a.index)];
        return true;
      case Mount::Kind::Articulated: {
        if (!in(poses.robotLinks, a.index)) return false;
        const std::vector<Pose>& links = (*poses.robotLinks)[std::size_t(a.index)];
        if (a.link < 0 || std::size_t(a.link) >= links.size()) return false;
        out = links[std::size_t(a.link)];
        return true;
      }
      case Mount::Kind::World: break;
    }
    return false;
  };
  // A wire follows both its ends: each moved end's point is its body's
  // pose times the attachment point.
  for (WireSpan& w : scene.wires) {
    Pose body;
    if (w.endA.kind != Mount::Kind::World && bodyPose(w.endA, body)) w.a = affine(body) * w.endA.local.translation();
    if (w.endB.kind != Mount::Kind::World && bodyPose(w.endB, body)) w.b = affine(body) * w.endB.local.translation();
    if (w.drawable >= scene.drawables.size()) continue;
    Drawable& d = scene.drawables[w.drawable];
    d.world = wireTransform(w.a, w.b, w.width);
    d.bounds = transformBox(d.world, d.localBounds);
  }
  if (poses.particles) poseParticles(scene, *poses.particles);
  Eigen::AlignedBox3d bounds;
  for (Drawable& d : scene.drawables) {
    Pose body;
    if (d.wire < 0 && d.attachment.kind != Mount::Kind::World && bodyPose(d.attachment, body)) {
      Affine3d world = affine(body) * d.attachment.local;
      if (d.placeholderWorld && std::abs(d.world.linear().determinant()) > 0)
        d.placeholderWorld = world * d.world.inverse() * *d.placeholderWorld;
      d.world = world;
      d.bounds = transformBox(d.world, d.localBounds);
    }
    if (d.shape != Shape::Ground) bounds.extend(d.bounds);
  }
  for (const TerrainMesh& t : scene.terrains) bounds.extend(t.bounds);
  for (const Instanced& b : scene.instanced) bounds.extend(b.bounds);
  for (const PointBatch& p : scene.pointClouds) bounds.extend(p.bounds);
  scene.bounds = bounds;
}

bool prepareScene(const Document& doc, const Scene& scene, RenderScene& out, Diagnostics& diags,
                  const DrawLimits& limits, asset::AssetCache* assets) {
  Preparer p(doc, scene, out, diags, limits, assets);
  p.run();
  prepareEffects(doc, scene, out);
  return p.ok();
}

bool buildRenderScene(const Document& doc, const SceneOptions& options, RenderScene& out, Diagnostics& diags,
                      const DrawLimits& limits, asset::AssetCache* assets) {
  Scene scene;
  return buildRenderScene(doc, options, scene, out, diags, limits, assets);
}

bool buildRenderScene(const Document& doc, const SceneOptions& options, Scene& scene, RenderScene& out,
                      Diagnostics& diags, const DrawLimits& limits, asset::AssetCache* assets) {
  scene = Scene{};
  // lib/core's verdict first, as validate gives it (scene/validate.hpp).
  // A document with errors goes no further: the model would read fallbacks.
  if (!robot::checkDocument(doc, options.baseDir.empty() ? options.sceneDir : options.baseDir, diags)) return false;
  bool ok = buildScene(doc, options, scene, diags);
  if (ok && limits.allowMissingAssets) robot::leaveOutMissingRobots(doc, scene, diags);  // as rscene-sim
  // The scene model's verdict, as in validate and sim; missing files are
  // the renderer's to report (RS9001, or placeholders when allowed).
  // A deformable is judged with its mesh, as sim judges it (a missing
  // file stays the renderer's: RS5001 or a placeholder).
  SceneCheckOptions check;
  check.readSurface = asset::objSurfaceReader(assets ? assets->fileSystem() : diskFileSystem());
  check.stepWarnings = false;  // nothing is stepped here
  // Every body and foliage mesh must read, as validate --check-files and
  // sim say (RS7007); read into the drawing's cache, so once.
  asset::AssetCache own;
  if (!limits.allowMissingAssets) {
    check.readMesh = (assets ? *assets : own).meshReader(asset::MeshContent::Surface);
    check.visualAssets = true;
  }
  ok = checkScene(doc, scene, check, diags) && ok;
  return prepareScene(doc, scene, out, diags, limits, assets) && ok;
}

}  // namespace rscene::render
