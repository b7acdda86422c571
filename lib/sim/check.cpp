// What the simulator refuses before building a world (world.hpp): the
// scene model's checks (scene/check.hpp, the same rscene-validate runs), and
// the records it keeps without simulating.
#include <set>

#include "asset/obj_surface.hpp"
#include "scene/check.hpp"
#include "sim/world.hpp"

namespace rscene::sim {

bool checkPhysics(const Document& doc, const Scene& scene, Diagnostics& diagnostics, const FileSystem& files,
                  const MeshReader& readMesh) {
  SceneCheckOptions options;
  options.checkFiles = true;  // Bullet needs every collision mesh
  options.exists = [&files](const std::string& path) { return files.stat(path).kind == FileKind::Regular; };
  options.readSurface = asset::objSurfaceReader(files);  // a deformable's particles are its mesh's
  options.readMesh = readMesh;  // RS7007 as validate --check-files says it
  return checkScene(doc, scene, options, diagnostics);
}

std::optional<Diagnostic> unsupportedWarning(const Scene& scene) {
  std::string list;
  std::set<std::string> seen;
  // Scene records with physics this simulator does not model; purely
  // visual ones (decals, probes, fog volumes ...) are not worth a warning.
  auto physical = [](const std::string& tag) { return tag == "sensor"; };
  for (const SkippedRecord& s : scene.skipped) {
    if (!physical(s.tag) || !seen.insert(s.tag).second) continue;
    std::size_t n = 0;
    for (const SkippedRecord& t : scene.skipped) n += t.tag == s.tag;
    list += (list.empty() ? "" : ", ") + s.tag + " (" + std::to_string(n) + ")";
  }
  if (list.empty()) return std::nullopt;
  Diagnostic d;
  d.severity = Severity::Warning;
  d.code = scene_code::kUnsupported;
  d.message = "not simulated, kept unchanged: " + list;
  return d;
}

}  // namespace rscene::sim
