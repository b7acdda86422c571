#include "scene/left_out.hpp"

#include "scene/mounted_node.hpp"

#include "scene/reader.hpp"

namespace rscene {

void detachFromLeftOut(const Document& doc, Scene& scene, const std::set<int>& records, bool sensors,
                       const std::string& why, Diagnostics& diagnostics) {
  if (records.empty()) return;
  auto warn = [&](int recordIndex, const char* field, const std::string& message) {
    RecordReader(doc, static_cast<std::size_t>(recordIndex), diagnostics)
        .error(field, scene_code::kMissingFile, message, {}, Severity::Warning);
  };
  for (Wire& w : scene.wires) {
    if (!w.enabled) continue;
    bool a = records.count(w.recordA) > 0;
    if (!a && !records.count(w.recordB)) continue;
    const std::string& body = a ? w.bodyA : w.bodyB;
    warn(w.recordIndex, a ? "bodyA" : "bodyB",
         "wire '" + w.path + "' is not attached: '" + body + "' was left out " + why);
    w.enabled = false;
  }
  // A robot left out is not posed: its IK targets are not solved.
  for (Articulated& a : scene.articulated) {
    if (!records.count(a.recordIndex)) continue;
    for (ArticulatedIk& ik : a.ik) {
      if (!ik.enabled) continue;
      warn(ik.recordIndex, "frame",
           "IK target of frame '" + ik.frame + "' is not solved: '" + a.path + "' was left out " + why);
      ik.enabled = false;
    }
  }
  if (!sensors) return;
  auto mountRecord = [&](const Mount& m) { return mountedNode(scene, m).recordIndex; };
  for (Sensor& s : scene.sensors) {
    if (!s.enabled || !records.count(mountRecord(s.mount))) continue;
    warn(s.recordIndex, "parentObject",
         "sensor '" + s.path + "' is not used: '" + s.parentObject + "' was left out " + why);
    s.enabled = false;
  }
  for (Camera& c : scene.cameras) {
    if (!c.enabled || !records.count(mountRecord(c.mount))) continue;
    warn(c.recordIndex, "parentGroupId", "camera '" + c.path + "' is not used: the body it rides on was left out " + why);
    c.enabled = false;
  }
}

}  // namespace rscene
