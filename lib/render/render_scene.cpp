#include "render/render_scene.hpp"

#include <cmath>
#include <set>
#include <unordered_map>

#include "core/assets.hpp"
#include "core/text.hpp"
#include "render/record_view.hpp"

namespace rscene::render {
namespace {

using Eigen::Affine3d;
using Eigen::Vector3d;
using Eigen::Vector3f;
using Eigen::Vector4d;
using Eigen::Vector4f;

constexpr double kPi = 3.14159265358979323846;
constexpr double kMinGroundSize = 200;  // metres: the ground reads as "large" from any camera

// Kinds the renderer draws or consumes; every other node or child kind
// present is reported as skipped.
const std::set<std::string, std::less<>> kHandledKinds = {
    "group", "terrain_region", "terrain_splat_layer", "light", "camera",
    "object", "compound", "compound_child", "point_cloud", "instanced_visual"};

Vector4f toF(const Vector4d& v) { return v.cast<float>(); }
Vector3f rgb(const Vector4d& v) { return v.head<3>().cast<float>(); }

Shape shapeOf(const std::string& primitive) {
  if (primitive == "sphere") return Shape::Sphere;
  if (primitive == "cylinder") return Shape::Cylinder;
  if (primitive == "capsule") return Shape::Capsule;
  if (primitive == "mesh") return Shape::Mesh;
  if (primitive == "ground" || primitive == "half_space") return Shape::Ground;
  return Shape::Box;
}

// Unit shape -> local frame at physical size (compat-notes.md "Sizes").
Eigen::Vector3d shapeScale(Shape s, const Vector3d& scale, double radius, double height, const Vector3d& boxSize) {
  switch (s) {
    case Shape::Box: return boxSize;
    case Shape::Sphere: return Vector3d::Constant(radius * scale.x());
    case Shape::Cylinder: return {radius * scale.x(), radius * scale.x(), height * scale.z()};
    case Shape::Mesh: return scale;
    default: return Vector3d::Ones();
  }
}

Eigen::AlignedBox3d worldBounds(const Affine3d& m, const Eigen::AlignedBox3d& local) {
  Eigen::AlignedBox3d b;
  for (int i = 0; i < 8; ++i) b.extend(m * local.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)));
  return b;
}

Eigen::AlignedBox3d unitBounds(Shape s, double capsuleR = 0, double capsuleH = 0) {
  switch (s) {
    case Shape::Sphere:
    case Shape::Cylinder: return {Vector3d(-1, -1, s == Shape::Cylinder ? -0.5 : -1), Vector3d(1, 1, s == Shape::Cylinder ? 0.5 : 1)};
    case Shape::Capsule:
      return {Vector3d(-capsuleR, -capsuleR, -capsuleH / 2 - capsuleR), Vector3d(capsuleR, capsuleR, capsuleH / 2 + capsuleR)};
    case Shape::Ground: return {Vector3d(-0.5, -0.5, 0), Vector3d(0.5, 0.5, 0)};
    default: return {Vector3d::Constant(-0.5), Vector3d::Constant(0.5)};
  }
}

class Builder {
 public:
  Builder(const Document& doc, const SceneOptions& opt, RenderScene& out, Diagnostics& diags)
      : doc_(doc), opt_(opt), out_(out), diags_(diags) {}

  void run() {
    out_ = RenderScene{};
    Material base;
    base.id = "engine_default";
    out_.materials.push_back(base);
    assetRoot_ = assetRootOf(doc_);
    collectNodes();
    for (const Record& r : doc_.records) {
      if (!r.kind) continue;
      const std::string& tag = r.kind->tag;
      RecordView v(doc_, r);
      if (tag == "material") material(v);
      else if (tag == "terrain_texture") terrainTexture(v);
      else if (tag == "environment") environment(v);
      else if (tag == "weather") weather(v);
      else if (tag == "rayrai_render") renderSettings(v);
      else if (tag == "scene_graph") inherit_ = v.flag("inheritedTransforms", true);
      else if ((r.kind->isNode() || r.kind->role == Role::Child) && !kHandledKinds.count(tag)) ++out_.skipped[tag];
    }
    if (terrainColors_.empty()) {
      terrainColors_[0] = {0.28f, 0.43f, 0.20f, 1};
      terrainColors_[1] = {0.42f, 0.40f, 0.36f, 1};
    }
    finishEnvironment();
    for (std::size_t i = 0; i < doc_.records.size(); ++i) {
      const Record& r = doc_.records[i];
      if (!r.kind) continue;
      const std::string& tag = r.kind->tag;
      RecordView v(doc_, r);
      if (tag == "object") object(v);
      else if (tag == "compound") compound(i);
      else if (tag == "light") light(v);
      else if (tag == "camera") camera(v);
      else if (tag == "terrain_region") terrain(i);
      else if (tag == "instanced_visual") instanced(v);
      else if (tag == "point_cloud") pointCloud(v);
    }
  }

 private:
  struct NodeInfo {
    const Record* record = nullptr;
    bool isGroup = false;
  };

  std::string resolve(const std::string& written) const {
    return written.empty() ? std::string() : resolveAsset(opt_.sceneDir, assetRoot_, written);
  }

  void warn(const Record& r, std::string message) {
    Diagnostic d;
    d.severity = Severity::Warning;
    d.code = "RS9101";
    d.line = r.line;
    d.column = r.line ? 1 : 0;
    d.message = std::move(message);
    d.tag = std::string(doc_.tag(r));
    diags_.push_back(std::move(d));
  }

  void collectNodes() {
    for (const Record& r : doc_.records) {
      if (!r.kind || !r.kind->isNode()) continue;
      NodeInfo info{&r, r.kind->tag == "group"};
      std::string path = nodePath(doc_, r), id = nodeId(doc_, r);
      if (!path.empty()) nodes_[path] = info;
      if (!id.empty()) nodes_[id] = info;
    }
  }

  const NodeInfo* node(const std::string& ref) const {
    auto it = nodes_.find(ref);
    return it == nodes_.end() ? nullptr : &it->second;
  }

  // Hidden by an invisible ancestor group.
  bool hiddenByParents(const RecordView& v, int depth = 0) const {
    if (depth > 64) return false;
    std::string parent = v.has("parentGroupId") ? v.text("parentGroupId") : v.text("parentId");
    if (parent.empty()) return false;
    const NodeInfo* n = node(parent);
    if (!n || n->record == &v.record()) return false;
    RecordView pv(doc_, *n->record);
    if (n->isGroup && !pv.flag("visible", true)) return true;
    return hiddenByParents(pv, depth + 1);
  }

  Affine3d localPose(const RecordView& v) const {
    Affine3d m = Affine3d::Identity();
    m.translate(v.vec3("position"));
    m.rotate(v.quat("orientation"));
    return m;
  }

  // World pose of a node: its own pose, under a non-group parent's pose
  // when scene_graph inherits transforms.
  Affine3d worldPose(const RecordView& v, int depth = 0) const {
    Affine3d local = localPose(v);
    if (!inherit_ || depth > 64) return local;
    std::string parent = v.text("parentGroupId");
    const NodeInfo* n = parent.empty() ? nullptr : node(parent);
    if (!n || n->isGroup || n->record == &v.record()) return local;
    RecordView pv(doc_, *n->record);
    return worldPose(pv, depth + 1) * local;
  }

  int materialIndex(const std::string& ref) const {
    if (ref.empty()) return 0;
    auto it = materialByRef_.find(ref);
    return it == materialByRef_.end() ? 0 : it->second;
  }

  void material(const RecordView& v) {
    Material m;
    std::string name = v.text("name");
    m.id = nodeId(doc_, v.record());
    m.color = toF(v.color("color", Vector4d(0.55, 0.62, 0.72, 1)));
    m.metallic = float(v.number("metallic", 0));
    m.roughness = float(std::clamp(v.number("roughness", 0.55), 0.03, 1.0));
    m.emissive = rgb(v.color("emissive", Vector4d::Zero())) * float(v.number("emissiveStrength", 0));
    m.doubleSided = v.flag("doubleSided", false);
    m.blend = v.name("alphaMode", "opaque") == "blend" || m.color.w() < 0.999f;
    m.albedoTexture = resolve(v.text("albedoTexture"));
    m.line = v.line();
    m.isDefault = name == "engine_default";
    int index = static_cast<int>(out_.materials.size());
    if (m.isDefault) {  // redefines the default in place
      index = 0;
      out_.materials[0] = m;
    } else {
      out_.materials.push_back(m);
    }
    materialByRef_[name] = index;
    if (!m.id.empty()) materialByRef_[m.id] = index;
  }

  void terrainTexture(const RecordView& v) {
    terrainColors_[static_cast<int>(v.number("slot", 0))] = toF(v.color("color", Vector4d(0.5, 0.5, 0.5, 1)));
  }

  void environment(const RecordView& v) {
    Environment& e = out_.environment;
    e.background = rgb(v.color("background", Vector4d(0.38, 0.38, 0.38, 1)));
    e.ambient = rgb(v.color("ambient", Vector4d(0.15, 0.16, 0.2, 1)));
    e.fogDensity = float(std::max(0.0, v.number("fogDensity", 0)));
    e.fogColor = rgb(v.color("fogColor", Vector4d(0.66, 0.78, 0.96, 1)));
    e.shadows = v.flag("shadows", true);
    e.exposure = float(v.number("exposure", 1));
    e.gamma = float(v.number("gamma", 2.2));
    if (!(e.gamma > 0.1f)) e.gamma = 2.2f;
    std::string mode = v.name("backgroundMode", "rayrai_sky");
    e.mode = mode == "plain_color" ? Background::PlainColor : mode == "hdr" ? Background::Hdr : Background::Sky;
    e.hdrPath = resolve(v.text("envMapPath"));
    e.hdrLine = v.line();
    if (v.has("colorMode") && !v.text("colorMode").empty()) colorMode_ = v.name("colorMode");
  }

  void renderSettings(const RecordView& v) {
    if (colorMode_.empty() && !v.text("colorMode").empty()) colorMode_ = v.name("colorMode");
  }

  void weather(const RecordView& v) {
    weatherSeen_ = true;
    weatherEnabled_ = v.flag("enabled", true);
    std::string preset = v.name("preset", "clear");
    Environment& e = out_.environment;
    e.overcast = preset == "overcast" || preset == "rain" || preset == "heavy_rain" || preset == "storm" ||
                 preset == "snow" || preset == "fog" || preset == "night_rain";
    e.night = preset == "night_clear" || preset == "night_rain";
    e.cloudCoverage = float(std::clamp(v.number("cloudCoverage", e.overcast ? 0.9 : 0.05), 0.0, 1.0));
    double azimuth, elevation;
    if (v.flag("useExplicitSunAngles", false)) {
      azimuth = v.number("sunAzimuthDegrees", 180);
      elevation = v.number("sunElevationDegrees", 42);
    } else {
      // Time of day without the astronomical solver: sunrise 6h in the
      // east, noon at 70 degrees in the south, sunset 18h in the west.
      double t = v.number("timeOfDay", 12);
      elevation = 70 * std::sin(kPi * (t - 6) / 12);
      azimuth = 90 + (t - 6) * 15;
    }
    if (e.night) elevation = -20;
    // Azimuth clockwise from north (+y) towards east (+x).
    double az = azimuth * kPi / 180, el = elevation * kPi / 180;
    e.sunDirection = Vector3d(std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)).normalized();
  }

  void finishEnvironment() {
    Environment& e = out_.environment;
    const std::string& c = colorMode_;
    e.toneMap = c == "fast_linear" ? ToneMap::Linear
                : c == "filmic_approx" ? ToneMap::Filmic
                : c == "agx_approx" ? ToneMap::AgX
                : c == "unreal_preview_approx" ? ToneMap::Unreal
                : ToneMap::Aces;
    if (!weatherSeen_) {
      double az = 180 * kPi / 180, el = 42 * kPi / 180;
      e.sunDirection = Vector3d(std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el));
    }
  }

  void addDrawable(Drawable d) {
    d.bounds = worldBounds(d.world, unitBounds(d.shape, d.capsuleRadius, d.capsuleHeight));
    if (d.shape == Shape::Ground) out_.hasGround = true;
    else out_.bounds.extend(d.bounds);
    out_.drawables.push_back(std::move(d));
  }

  void object(const RecordView& v) {
    if (!v.flag("visible", true) || hiddenByParents(v)) return;
    Drawable d;
    d.line = v.line();
    d.shape = shapeOf(v.name("primitive", "box"));
    d.material = materialIndex(v.text("material"));
    d.castShadow = v.flag("castShadow", true);
    Vector3d scale = v.vec3("scale", Vector3d::Ones());
    double radius = v.number("radius", 0.5), height = v.number("height", 1);
    Affine3d pose = worldPose(v);
    if (d.shape == Shape::Ground) {
      Vector3d p = pose.translation();
      d.world = Eigen::Translation3d(p) * Eigen::Scaling(std::max(scale.x(), kMinGroundSize),
                                                         std::max(scale.y(), kMinGroundSize), 1.0);
      d.castShadow = false;
    } else if (d.shape == Shape::Capsule) {
      d.capsuleRadius = radius * scale.x();
      d.capsuleHeight = height * scale.z();
      d.world = pose;
    } else {
      if (d.shape == Shape::Mesh) {
        std::string render = v.text("renderMeshPath");
        d.meshWritten = render.empty() ? v.text("meshPath") : render;
        d.meshPath = resolve(d.meshWritten);
      }
      d.world = pose * Eigen::Scaling(shapeScale(d.shape, scale, radius, height, scale));
    }
    addDrawable(std::move(d));
  }

  void compound(std::size_t index) {
    const Record& r = doc_.records[index];
    RecordView v(doc_, r);
    bool visible = v.flag("visible", true) && !hiddenByParents(v);
    Affine3d pose = worldPose(v);
    std::string compoundPath = nodePath(doc_, r);
    int fallbackMaterial = materialIndex(v.text("material"));
    for (std::size_t i = index + 1; i < doc_.records.size(); ++i) {
      const Record& c = doc_.records[i];
      if (!c.kind) continue;
      if (c.kind->tag != "compound_child") break;
      if (!visible) continue;
      RecordView cv(doc_, c);
      Drawable d;
      d.line = c.line;
      d.shape = shapeOf(cv.name("primitive", "box"));
      if (d.shape == Shape::Ground) d.shape = Shape::Box;
      std::string mat = cv.text("material");
      d.material = mat.empty() ? fallbackMaterial : materialIndex(mat);
      Vector3d scale = cv.vec3("scale", Vector3d::Ones());
      Vector3d size = cv.vec3("size", Vector3d::Ones());
      double radius = cv.number("radius", 0.5), height = cv.number("height", 1);
      Affine3d local = Eigen::Translation3d(cv.vec3("position")) * cv.quat("orientation");
      if (d.shape == Shape::Capsule) {
        d.capsuleRadius = radius * scale.x();
        d.capsuleHeight = height * scale.z();
        d.world = pose * local;
      } else {
        if (d.shape == Shape::Mesh) {
          d.meshWritten = cv.text("meshPath");
          d.meshPath = resolve(d.meshWritten);
        }
        d.world = pose * local * Eigen::Scaling(shapeScale(d.shape, scale, radius, height, size.cwiseProduct(scale)));
      }
      addDrawable(std::move(d));
    }
  }

  void light(const RecordView& v) {
    if (hiddenByParents(v)) return;
    Light l;
    std::string type = v.name("type", "directional");
    l.type = type == "point" ? LightType::Point
             : type == "spot" ? LightType::Spot
             : type == "area" ? LightType::Area
                              : LightType::Directional;
    Vector3d dir = v.vec3("direction", Vector3d(0, 0, -1));
    l.direction = dir.norm() > 1e-9 ? dir.normalized() : Vector3d(0, 0, -1);
    l.position = v.vec3("position", Vector3d(0, 0, 3));
    float intensity = float(v.number("intensity", 1));
    if (v.flag("negative", false)) intensity = -intensity;
    l.color = rgb(v.color("color", Vector4d(1, 1, 1, 1))) * intensity;
    l.attenuation = Vector3f(float(v.number("attenuationConstant", 1)), float(v.number("attenuationLinear", 0.04)),
                             float(v.number("attenuationQuadratic", 0.012)));
    l.coneDegrees = float(v.number("coneAngle", 30));
    l.innerConeDegrees = float(std::min(v.number("innerConeAngle", 18), double(l.coneDegrees)));
    l.range = float(v.number("range", 0));
    Vector3d area = v.vec3("areaSize", Vector3d(1, 1, 0));
    l.areaSize = Eigen::Vector2f(float(area.x()), float(area.y()));
    l.shadows = v.flag("shadows", false);
    out_.lights.push_back(l);
  }

  void camera(const RecordView& v) {
    Camera c;
    c.path = nodePath(doc_, v.record());
    c.id = v.text("id");
    Affine3d pose = worldPose(v);
    c.position = pose.translation();
    c.orientation = Eigen::Quaterniond(pose.rotation());
    c.verticalFov = std::clamp(v.number("verticalFov", 52), 1.0, 175.0);
    c.horizontalFov = v.number("horizontalFov", 0);
    c.nearPlane = v.number("nearPlane", 0.05);
    c.farPlane = v.number("farPlane", 100);
    if (!(c.nearPlane > 0)) c.nearPlane = 0.05;
    if (!(c.farPlane > c.nearPlane)) c.farPlane = c.nearPlane * 2000;
    c.width = int(v.number("width", 0));
    c.height = int(v.number("height", 0));
    c.orthographic = v.name("projection", "perspective") == "orthographic";
    c.orthoScale = v.number("orthoScale", 10);
    c.enabled = v.flag("enabled", true);
    c.line = v.line();
    out_.cameras.push_back(c);
  }

  Vector4f slotColor(int slot) const {
    auto it = terrainColors_.find(slot);
    if (it != terrainColors_.end()) return it->second;
    return terrainColors_.begin()->second;
  }

  void terrain(std::size_t index) {
    const Record& r = doc_.records[index];
    RecordView v(doc_, r);
    if (!v.flag("visible", true) || hiddenByParents(v)) return;
    Terrain t;
    t.xSamples = int(v.number("xSamples", 0));
    t.ySamples = int(v.number("ySamples", 0));
    double xSize = v.number("xSize", 0), ySize = v.number("ySize", 0);
    Vector3d center = v.vec3("center");
    std::size_t n = std::size_t(std::max(t.xSamples, 0)) * std::size_t(std::max(t.ySamples, 0));
    if (t.xSamples < 2 || t.ySamples < 2 || t.xSamples > 16384 || t.ySamples > 16384 || n > (64u << 20) ||
        !(xSize > 0) || !(ySize > 0)) {
      warn(r, "terrain is not drawn: it needs 2..16384 samples per axis and positive sizes");
      return;
    }
    std::vector<double> heights = v.numbers("heights");
    if (heights.size() != n) {
      if (!heights.empty() || v.name("sourceKind", "samples") == "samples")
        warn(r, "terrain heights have " + std::to_string(heights.size()) + " values, expected " + std::to_string(n) +
                    "; drawn flat");
      heights.assign(n, 0.0);
    }
    std::vector<double> primary = v.numbers("texturePrimary"), secondary = v.numbers("textureSecondary"),
                        blend = v.numbers("textureBlend"), holes = v.numbers("holes");
    std::vector<double> vertexColors = v.numbers("vertexColors");
    int base = int(v.number("baseTexture", 0));
    t.material = materialIndex(v.text("material"));
    t.positions.resize(n);
    t.colors.assign(n, slotColor(base));
    t.holes.assign(n, false);
    bool splatting = v.flag("textureSplattingEnabled", true);
    for (int y = 0; y < t.ySamples; ++y)
      for (int x = 0; x < t.xSamples; ++x) {
        std::size_t i = std::size_t(y) * t.xSamples + x;
        t.positions[i] = Vector3f(float(center.x() - xSize / 2 + x * xSize / (t.xSamples - 1)),
                                  float(center.y() - ySize / 2 + y * ySize / (t.ySamples - 1)),
                                  float(center.z() + heights[i]));
        if (splatting && primary.size() == n) {
          Vector4f a = slotColor(int(primary[i]));
          Vector4f b = secondary.size() == n ? slotColor(int(secondary[i])) : a;
          float w = blend.size() == n ? std::clamp(float(blend[i]), 0.f, 1.f) : 0.f;
          t.colors[i] = a * (1 - w) + b * w;
        }
        if (holes.size() == n) t.holes[i] = holes[i] > 0.5;
        t.bounds.extend(t.positions[i].cast<double>());
      }
    // Splat layers follow their region.
    for (std::size_t j = index + 1; splatting && j < doc_.records.size(); ++j) {
      const Record& c = doc_.records[j];
      if (!c.kind || c.kind->tag == "terrain_foliage_layer") continue;
      if (c.kind->tag != "terrain_splat_layer") break;
      RecordView cv(doc_, c);
      if (!cv.flag("enabled", true)) continue;
      std::vector<double> w = cv.numbers("weights");
      if (w.size() != n) continue;
      Vector4f color = slotColor(int(cv.number("slot", 0)));
      float strength = std::clamp(float(cv.number("strength", 1)), 0.f, 1.f);
      for (std::size_t i = 0; i < n; ++i) {
        float k = std::clamp(float(w[i]), 0.f, 1.f) * strength;
        t.colors[i] = t.colors[i] * (1 - k) + color * k;
      }
    }
    if (vertexColors.size() == n * 4 || vertexColors.size() == n * 3) {
      std::size_t stride = vertexColors.size() / n;
      for (std::size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) t.colors[i][k] *= float(vertexColors[i * stride + std::size_t(k)]);
    }
    out_.bounds.extend(t.bounds);
    out_.terrains.push_back(std::move(t));
  }

  void instanced(const RecordView& v) {
    if (!v.flag("enabled", true) || hiddenByParents(v)) return;
    Instanced b;
    b.line = v.line();
    b.shape = shapeOf(v.name("primitive", "box"));
    if (b.shape == Shape::Ground) b.shape = Shape::Box;
    if (b.shape == Shape::Capsule) b.shape = Shape::Cylinder;  // an instanced capsule is drawn as its cylinder
    if (b.shape == Shape::Mesh) b.meshPath = resolve(v.text("meshPath"));
    Vector3d size = v.vec3("size", Vector3d::Ones());
    // size is the primitive's extent: box sides, sphere/cylinder diameter.
    Vector3d unit = b.shape == Shape::Box || b.shape == Shape::Mesh ? size : Vector3d(size / 2);
    if (b.shape == Shape::Cylinder) unit.z() = size.z();
    Vector4f colorA = toF(v.color("colorA")), colorB = toF(v.color("colorB"));
    std::vector<double> xf = v.numbers("instances"), weights = v.numbers("colorWeights");
    std::size_t count = xf.size() / 10;
    b.worlds.reserve(count);
    b.colors.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
      const double* p = &xf[i * 10];
      Eigen::Quaterniond q(p[3], p[4], p[5], p[6]);
      q = q.norm() > 1e-12 ? q.normalized() : Eigen::Quaterniond::Identity();
      Affine3d m = Eigen::Translation3d(p[0], p[1], p[2]) * q *
                   Eigen::Scaling(Vector3d(p[7], p[8], p[9]).cwiseProduct(unit));
      b.worlds.push_back(m);
      float w = i < weights.size() ? std::clamp(float(weights[i]), 0.f, 1.f) : 0.f;
      b.colors.push_back(colorA * (1 - w) + colorB * w);
      b.bounds.extend(worldBounds(m, unitBounds(b.shape)));
    }
    if (count == 0) return;
    out_.bounds.extend(b.bounds);
    out_.instanced.push_back(std::move(b));
  }

  void pointCloud(const RecordView& v) {
    if (!v.flag("enabled", true) || hiddenByParents(v)) return;
    PointCloud pc;
    std::vector<double> pts = v.numbers("points"), cols = v.numbers("colors");
    std::size_t n = pts.size() / 3;
    std::size_t stride = n && cols.size() == n * 3 ? 3 : 4;
    pc.pointSize = float(std::clamp(v.number("pointSize", 1), 1.0, 64.0));
    for (std::size_t i = 0; i < n; ++i) {
      pc.points.emplace_back(float(pts[3 * i]), float(pts[3 * i + 1]), float(pts[3 * i + 2]));
      Vector4f c(1, 1, 1, 1);
      if (cols.size() >= (i + 1) * stride)
        for (std::size_t k = 0; k < stride; ++k) c[int(k)] = float(cols[i * stride + k]);
      pc.colors.push_back(c);
      pc.bounds.extend(pc.points.back().cast<double>());
    }
    if (n == 0) return;
    out_.bounds.extend(pc.bounds);
    out_.pointClouds.push_back(std::move(pc));
  }

  const Document& doc_;
  const SceneOptions& opt_;
  RenderScene& out_;
  Diagnostics& diags_;
  std::string assetRoot_;
  std::unordered_map<std::string, NodeInfo> nodes_;
  std::unordered_map<std::string, int> materialByRef_;
  std::map<int, Vector4f> terrainColors_;
  std::string colorMode_;
  bool inherit_ = true;
  bool weatherSeen_ = false;
  bool weatherEnabled_ = true;
};

}  // namespace

void buildRenderScene(const Document& doc, const SceneOptions& options, RenderScene& out, Diagnostics& diags) {
  Builder(doc, options, out, diags).run();
}

}  // namespace rscene::render
