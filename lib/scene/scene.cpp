// buildScene (scene.hpp): drives the builder (scene_builder.hpp).
#include "scene/scene.hpp"

#include "scene/scene_builder.hpp"

namespace rscene::scene_build {

void Builder::run() {
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
  if (!opt_.bodiesOnly) resolveWorld();
  else resolveBodyPoses();  // checkScene() needs the objects' world poses only
  resolveWires();
}

std::string Builder::asset(const std::string& path) const {
  if (path.empty()) return path;
  std::string out = resolveAsset(opt_.baseDir.empty() ? opt_.sceneDir : opt_.baseDir, opt_.project, doc_.version, s_.assetRoot, path,
                                 opt_.exists);
  for (std::size_t at; (at = out.find("/./")) != std::string::npos;) out.erase(at, 2);  // "dir/./x" -> "dir/x"
  return out;
}

void Builder::indexNodes() const {
  indexed_ = true;
  for (std::size_t i = 1; i < doc_.records.size(); ++i) {
    const Record& rec = doc_.records[i];
    if (!rec.kind || rec.kind->role != Role::Node) continue;
    std::string id = nodeId(doc_, rec), path = nodePath(doc_, rec);
    if (!id.empty()) byId_.emplace(id, i);
    if (!path.empty()) byPath_.emplace(path, i);
  }
}

int Builder::lookup(const std::string& ref) const {
  if (ref.empty()) return -1;
  if (!indexed_) indexNodes();
  if (auto it = byId_.find(ref); it != byId_.end()) return static_cast<int>(it->second);
  if (auto it = byPath_.find(ref); it != byPath_.end()) return static_cast<int>(it->second);
  return -1;
}

AssetPath Builder::assetFn() const {
  return [this](const std::string& p) { return asset(p); };
}

std::string Builder::assetDirectory(const std::string& path) const {
  if (path.empty()) return path;
  auto isDir = [](const std::string& p) { return DiskFileSystem().stat(p).kind == FileKind::Directory; };
  std::string out = resolveAsset(opt_.baseDir.empty() ? opt_.sceneDir : opt_.baseDir, opt_.project, doc_.version, s_.assetRoot, path,
                                 isDir);
  for (std::size_t at; (at = out.find("/./")) != std::string::npos;) out.erase(at, 2);
  return out;
}

std::vector<std::string> Builder::splitList(const std::string& text) {
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

void Builder::orphan(const RecordReader& r, const std::string& parentTag) {
  r.error("", rs::RS3015, r.record().kind->tag + " has no " + parentTag + " record before it");
}

void Builder::defaults() {
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

}  // namespace rscene::scene_build

namespace rscene {

using scene_build::Builder;


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

