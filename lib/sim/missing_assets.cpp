// rscene-sim --allow-missing-assets (world.hpp): bodies whose collision
// mesh cannot be read are left out, as rscene-render draws a placeholder.
#include <map>
#include <set>
#include <vector>

#include "scene/left_out.hpp"
#include "scene/reader.hpp"
#include "sim/world.hpp"

namespace rscene::sim {
namespace {

// Why `path` gives no collision mesh ("does not exist", or the reader's
// reason), with its code; empty when it does.
std::pair<std::string, const char*> meshProblem(const std::string& path, asset::AssetCache& assets) {
  if (path.empty()) return {"no mesh file", scene_code::kNoMesh};
  // Not a regular file (missing, a folder, a device, a FIFO) is RS5001, as
  // in checkScene() and rscene-validate --check-files.
  switch (assets.fileSystem().stat(path).kind) {
    case FileKind::Regular: break;
    case FileKind::Missing: return {"mesh file '" + path + "' does not exist", scene_code::kMissingFile};
    case FileKind::Directory: return {"mesh file '" + path + "' is a directory, not a file", scene_code::kMissingFile};
    case FileKind::Other: return {"mesh file '" + path + "' is not a regular file", scene_code::kMissingFile};
  }
  std::string why;
  if (!assets.mesh(path, asset::MeshContent::Geometry, &why))
    return {"cannot read mesh '" + path + "': " + why, scene_code::kBadMesh};
  return {};
}

}  // namespace

int skipBodiesWithMissingMeshes(const Document& doc, Scene& scene, asset::AssetCache& assets,
                                Diagnostics& diagnostics) {
  // One warning per mesh file, at the first body that names it (a city of
  // 136 street lamps gives one line, as in rscene-render).
  struct Missing {
    std::string problem;
    const char* code;
    int recordIndex;
    const char* field;
    std::string firstBody;
    int bodies = 0;
  };
  std::vector<Missing> missing;
  std::map<std::string, std::size_t> byPath;
  std::set<int> skipped;  // record indices
  int count = 0;
  auto skip = [&](auto& body, const std::string& path, int recordIndex, const char* field) {
    auto [it, fresh] = byPath.try_emplace(path, missing.size());
    if (fresh) {
      auto [problem, code] = meshProblem(path, assets);
      missing.push_back({problem, code, recordIndex, field, body.path});
    }
    ++missing[it->second].bodies;
    body.bodyMode = BodyMode::VisualOnly;
    skipped.insert(body.recordIndex);
    ++count;
  };
  for (Object& o : scene.objects) {
    if (o.bodyMode == BodyMode::VisualOnly || o.primitive != "mesh") continue;
    if (meshProblem(o.collisionMeshPath, assets).first.empty()) continue;
    RecordReader fields(doc, static_cast<std::size_t>(o.recordIndex), diagnostics);
    skip(o, o.collisionMeshPath, o.recordIndex, fields.has("collisionMeshPath") ? "collisionMeshPath" : "meshPath");
  }
  for (Compound& c : scene.compounds) {
    if (c.bodyMode == BodyMode::VisualOnly) continue;
    for (const CompoundChild& ch : c.children)
      if (ch.primitive == "mesh" && !meshProblem(ch.meshPath, assets).first.empty()) {
        skip(c, ch.meshPath, ch.recordIndex, "meshPath");
        break;
      }
  }
  for (const Missing& m : missing) {
    std::string who = m.bodies == 1 ? "body '" + m.firstBody + "' is"
                                    : "bodies '" + m.firstBody + "' and " + std::to_string(m.bodies - 1) +
                                          (m.bodies == 2 ? " other are" : " others are");
    reportAt(&doc, m.recordIndex, m.field, m.code, m.problem + "; " + who + " not simulated", diagnostics,
             Severity::Warning);
  }
  detachFromLeftOut(doc, scene, skipped, false, "for its mesh", diagnostics);
  return count;
}

}  // namespace rscene::sim
