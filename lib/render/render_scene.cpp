#include "render/render_scene.hpp"
#include "render/render_effects.hpp"

#include "scene/reader.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "render/robot_drawables.hpp"
#include "robot/instance.hpp"
#include "core/assets.hpp"
#include "scene/check.hpp"
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
    for (const InstancedVisual& v : s_.instancedVisuals) instanced(v);
    for (const PointCloud& p : s_.pointClouds) points(p);
    robots();
    for (const SkippedRecord& r : s_.skipped) ++out_.skipped[r.tag];
    if (!s_.wires.empty()) out_.skipped["wire"] += static_cast<int>(s_.wires.size());  // not drawn yet
    // Modelled but not drawn yet (each line goes when its record is drawn).
    auto notDrawn = [&](const char* tag, std::size_t n) {
      if (n) out_.skipped[tag] += static_cast<int>(n);
    };
    notDrawn("projected_decal", s_.decals.size());
    notDrawn("local_fog", s_.localFogs.size());
    notDrawn("irradiance_volume", s_.irradianceVolumes.size());
    notDrawn("deformable", s_.deformables.size());
    notDrawn("granular", s_.granulars.size());
    for (const Terrain& t : s_.terrains) notDrawn("terrain_foliage_layer", t.foliageLayers.size());
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
    e.fogDensity = float(std::max(0.0, env.fogDensity));
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

  void addDrawable(Drawable d) {
    d.localBounds = unitShapeBounds(d.shape, d.capsuleRadius, d.capsuleHeight);
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
    b.castShadow = v.castShadows;
    // size is the primitive's extent: box sides, sphere/cylinder diameter.
    Vector3d unit = b.shape == Shape::Box || b.shape == Shape::Mesh ? v.size : Vector3d(v.size / 2);
    if (b.shape == Shape::Cylinder) unit.z() = v.size.z();
    Vector4f colorA = toF(v.colorA), colorB = toF(v.colorB);
    std::size_t stride = std::size_t(std::max<std::int64_t>(v.renderedStride, 1));
    std::size_t count = drawnCount(v.instances.size(), v.maxRendered, v.renderedStride);
    // Checked before anything per instance is allocated.
    if (count > limits_.maxInstances - std::min(instancesDrawn_, limits_.maxInstances)) {
      Diagnostic d;
      d.severity = Severity::Error;
      d.code = "RS9014";
      d.line = b.line;
      d.column = b.line ? 1 : 0;
      d.message = "instanced_visual draws " + std::to_string(count) + " instances, more than the " +
                  std::to_string(limits_.maxInstances - std::min(instancesDrawn_, limits_.maxInstances)) +
                  " left of --max-instances " + std::to_string(limits_.maxInstances);
      d.hint = "set maxRenderedInstances or renderedInstanceStride on the record, or raise --max-instances";
      diags_.push_back(std::move(d));
      ok_ = false;
      return;
    }
    instancesDrawn_ += count;
    b.worlds.reserve(count);
    b.colors.reserve(count);
    b.instanceBounds.reserve(count);
    for (std::size_t k = 0; k < count; ++k) {
      std::size_t i = k * stride;
      const Instance& in = v.instances[i];
      Affine3d m = Eigen::Translation3d(in.position) * in.orientation * Eigen::Scaling(in.scale.cwiseProduct(unit));
      b.worlds.push_back(m);
      float w = i < v.colorWeights.size() ? std::clamp(float(v.colorWeights[i]), 0.f, 1.f) : 0.f;
      b.colors.push_back(colorA * (1 - w) + colorB * w);
      b.instanceBounds.push_back(transformBox(m, unitShapeBounds(b.shape)));
      b.bounds.extend(b.instanceBounds.back());
    }
    out_.bounds.extend(b.bounds);
    out_.instanced.push_back(std::move(b));
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
    std::optional<asset::AssetCache> own;
    asset::AssetCache& assets = assets_ ? *assets_ : own.emplace();
    RobotDrawer drawer(out_, assets);
    robot::ModelCache models;
    out_.robotModels.assign(s_.articulated.size(), nullptr);
    for (std::size_t i = 0; i < s_.articulated.size(); ++i) {
      const Articulated& a = s_.articulated[i];
      if (!robot::checkRobotFile(doc_, a, diags_)) {
        ok_ = false;
        continue;
      }
      robot::RobotInstance r;
      // An error (a model that does not load, a coordinate of the wrong
      // length) fails the render; what could be read is still drawn.
      if (!robot::makeInstance(doc_, a, models, r, diags_)) ok_ = false;
      if (!r.model) continue;
      out_.robotModels[i] = r.model;
      if (!a.visible || a.hiddenByGroup) continue;
      int seg = segment("articulated", a.recordIndex, a.path, a.id, a.semanticClass, -1);
      if (drawer.add(*r.model, robot::linkPoses(r), static_cast<int>(i), seg) == 0) {
        // Not an error (a collision-only model simulates), but an empty
        // picture needs a reason.
        Diagnostic d;
        d.severity = Severity::Warning;
        d.code = "RS9030";
        d.line = lineOf(a.recordIndex);
        d.column = d.line ? 1 : 0;
        d.message = "articulated system '" + a.path + "' draws nothing: its model '" + r.model->name +
                    "' has no visual elements";
        diags_.push_back(std::move(d));
      }
      ++out_.robots;
    }
  }

  const Document& doc_;
  const Scene& s_;
  RenderScene& out_;
  Diagnostics& diags_;
  const DrawLimits& limits_;
  asset::AssetCache* assets_;
  std::uint64_t instancesDrawn_ = 0;
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
  Eigen::AlignedBox3d bounds;
  for (Drawable& d : scene.drawables) {
    Pose body;
    if (d.attachment.kind != Mount::Kind::World && bodyPose(d.attachment, body)) {
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
  bool ok = buildScene(doc, options, scene, diags);
  // The scene model's verdict, as in validate and sim; missing files are
  // the renderer's to report (RS9001, or placeholders when allowed).
  ok = checkScene(doc, scene, SceneCheckOptions{}, diags) && ok;
  return prepareScene(doc, scene, out, diags, limits, assets) && ok;
}

}  // namespace rscene::render
