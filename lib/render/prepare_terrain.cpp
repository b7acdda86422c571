#include "render/preparer.hpp"

namespace rscene::render::preparer_detail {

void Preparer::terrainColors() {
  for (const TerrainTexture& t : s_.terrainTextures) slotColors_[t.slot] = toF(t.color);
}

void Preparer::terrain(const Terrain& src) {
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

void Preparer::instanced(const InstancedVisual& v) {
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

bool Preparer::reserveInstances(std::uint64_t count, std::uint32_t line, const std::string& kind) {
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

void Preparer::foliage(const Terrain& t) {
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

}  // namespace rscene::render::preparer_detail
