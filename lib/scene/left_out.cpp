#include "scene/left_out.hpp"

#include "scene/reader.hpp"

namespace rscene {

void detachFromLeftOut(const Document& doc, Scene& scene, const std::set<std::string>& names, bool sensors,
                       const std::string& why, Diagnostics& diagnostics) {
  if (names.empty()) return;
  auto warn = [&](int recordIndex, const char* field, const std::string& message) {
    RecordReader(doc, static_cast<std::size_t>(recordIndex), diagnostics)
        .error(field, scene_code::kMissingFile, message, {}, Severity::Warning);
  };
  for (Wire& w : scene.wires) {
    if (!w.enabled) continue;
    bool a = names.count(w.bodyA) > 0;
    if (!a && !names.count(w.bodyB)) continue;
    const std::string& body = a ? w.bodyA : w.bodyB;
    warn(w.recordIndex, a ? "bodyA" : "bodyB",
         "wire '" + w.path + "' is not attached: '" + body + "' was left out " + why);
    w.enabled = false;
  }
  if (!sensors) return;
  for (Sensor& s : scene.sensors) {
    if (!s.enabled || !names.count(s.parentObject)) continue;
    warn(s.recordIndex, "parentObject",
         "sensor '" + s.path + "' is not used: '" + s.parentObject + "' was left out " + why);
    s.enabled = false;
  }
}

}  // namespace rscene
