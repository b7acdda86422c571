#include "render/render_scene.hpp"

#include "render/preparer.hpp"

namespace rscene::render::preparer_detail {

void Preparer::run() {
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

std::uint32_t Preparer::lineOf(int recordIndex) const {
  return recordIndex >= 0 && std::size_t(recordIndex) < doc_.records.size() ? doc_.records[std::size_t(recordIndex)].line
                                                                            : 0;
}

std::uint32_t Preparer::columnOf(int recordIndex, std::string_view field) const {
  if (recordIndex < 0 || std::size_t(recordIndex) >= doc_.records.size()) return 0;
  Diagnostics unused;
  return RecordReader(doc_, std::size_t(recordIndex), unused).columnOf(field);
}

bool Preparer::hasField(int recordIndex, std::string_view field) const {
  Diagnostics unused;
  return recordIndex >= 0 && RecordReader(doc_, std::size_t(recordIndex), unused).has(field);
}

int Preparer::materialIndex(const std::string& ref) const {
  if (ref.empty()) return 0;
  auto it = materialByRef_.find(ref);
  return it == materialByRef_.end() ? 0 : it->second;
}

RenderMaterial Preparer::renderMaterial(const Material& src) const {
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

void Preparer::materials() {
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

void Preparer::look() {
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

int Preparer::segment(const char* kind, int recordIndex, const std::string& path, const std::string& id,
                      const std::string& semanticClass, std::int64_t instanceId,
                      const std::optional<Eigen::Vector4d>& color) {
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

void Preparer::attach(Drawable& d, Mount::Kind kind, int index, const Pose& body, int link) {
  d.attachment.kind = kind;
  d.attachment.index = index;
  d.attachment.link = link;
  d.attachment.local = affine(body).inverse() * d.world;
}

void Preparer::addDrawable(Drawable d, const std::optional<Eigen::AlignedBox3d>& local) {
  d.localBounds = local && !local->isEmpty() ? *local : unitShapeBounds(d.shape, d.capsuleRadius, d.capsuleHeight);
  d.bounds = transformBox(d.world, d.localBounds);
  if (d.shape == Shape::Ground) out_.hasGround = true;
  else out_.bounds.extend(d.bounds);
  out_.drawables.push_back(std::move(d));
}

void Preparer::light(const Light& src) {
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

void Preparer::camera(Camera c) {
  if (!(c.nearPlane > 0)) c.nearPlane = 0.05;
  if (!(c.farPlane > c.nearPlane)) c.farPlane = c.nearPlane * 2000;
  out_.cameras.push_back(std::move(c));
}

Vector4f Preparer::slotColor(int slot) const {
  auto it = slotColors_.find(slot);
  if (it != slotColors_.end()) return it->second;
  return slotColors_.empty() ? Vector4f(0.5f, 0.5f, 0.5f, 1) : slotColors_.begin()->second;
}

bool Preparer::uniform(const Terrain& src) {
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

std::vector<int> Preparer::axisSamples(int n, int step) {
  std::vector<int> out;
  for (int i = 0; i < n - 1; i += step) out.push_back(i);
  out.push_back(n - 1);
  return out;
}

std::size_t Preparer::drawnCount(std::size_t total, std::int64_t max, std::int64_t stride) {
  std::size_t s = std::size_t(std::max<std::int64_t>(stride, 1));
  std::size_t n = (total + s - 1) / s;
  return max > 0 ? std::min(n, std::size_t(max)) : n;
}

Vector3d Preparer::unitScale(Shape shape, const Vector3d& size) {
  Vector3d unit = shape == Shape::Box || shape == Shape::Mesh || shape == Shape::GrassBlade ? size : Vector3d(size / 2);
  if (shape == Shape::Cylinder) unit.z() = size.z();
  return unit;
}

const Terrain* Preparer::boundTerrain(const InstancedVisual& v) const {
  if (v.terrainBinding.empty()) return nullptr;
  for (const Terrain& t : s_.terrains)
    if (t.id == v.terrainBinding || t.path == v.terrainBinding) return TerrainSurface(t).valid() ? &t : nullptr;
  return nullptr;
}

Vector3d Preparer::onTerrain(const Terrain& t, Vector3d p) {
  TerrainSurface surface(t);
  if (surface.contains(p.x(), p.y())) p.z() += surface.at(p.x(), p.y()).z;
  return p;
}

Shape Preparer::foliageShape(const std::string& primitive) {
  if (primitive == "box" || primitive == "cube") return Shape::Box;
  if (primitive == "sphere") return Shape::Sphere;
  if (primitive == "cylinder" || primitive == "capsule") return Shape::Cylinder;
  if (primitive == "mesh") return Shape::Mesh;
  return Shape::GrassBlade;
}

Eigen::AlignedBox3d Preparer::meshBounds(const std::string& path) {
  Eigen::AlignedBox3d box;
  std::string err;
  if (path.empty()) return box;
  if (std::shared_ptr<const asset::Mesh> mesh = assets().mesh(path, asset::MeshContent::Surface, &err))
    for (const asset::MeshPart& p : mesh->parts)
      for (std::size_t i = 0; i < p.vertexCount(); ++i)
        box.extend(Vector3d(p.positions[i * 3], p.positions[i * 3 + 1], p.positions[i * 3 + 2]));
  return box;
}

}  // namespace rscene::render::preparer_detail

namespace rscene::render {

using namespace preparer_detail;


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

