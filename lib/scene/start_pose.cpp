#include "scene/start_pose.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/codes.hpp"
#include "scene/reader.hpp"

namespace rscene {

bool groundRuleBody(const Object& o) {
  return o.bodyMode == BodyMode::Dynamic &&
         (o.primitive == "box" || o.primitive == "sphere" || o.primitive == "capsule" || o.primitive == "cylinder");
}

bool groundRulePlane(const Object& o) {
  return o.bodyMode != BodyMode::VisualOnly && (o.primitive == "ground" || o.primitive == "half_space");
}

double depthBelow(const Object& o, double z) {
  Eigen::Quaterniond q = o.world.orientation;
  q = q.norm() > 1e-12 ? q.normalized() : Eigen::Quaterniond::Identity();
  const Eigen::Matrix3d r = q.toRotationMatrix();
  const double c = o.world.position.z();
  double reach = 0;  // how far the shape reaches below its centre
  if (o.primitive == "box") {
    const Eigen::Vector3d h = o.scale / 2;
    reach = std::abs(r(2, 0)) * h.x() + std::abs(r(2, 1)) * h.y() + std::abs(r(2, 2)) * h.z();
  } else if (o.primitive == "sphere") {
    reach = o.physicsRadius();
  } else {  // cylinder, capsule: along the body's z
    const double axis = std::abs(r(2, 2)), half = o.physicsHeight() / 2, radius = o.physicsRadius();
    reach = axis * half + (o.primitive == "capsule" ? radius : radius * std::sqrt(std::max(0.0, 1 - axis * axis)));
  }
  return z - (c - reach);
}

std::vector<GroundStart> groundStarts(const Scene& scene) {
  std::vector<GroundStart> out;
  std::vector<int> planes;
  for (std::size_t i = 0; i < scene.objects.size(); ++i)
    if (groundRulePlane(scene.objects[i])) planes.push_back(static_cast<int>(i));
  if (planes.empty()) return out;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& o = scene.objects[i];
    if (!groundRuleBody(o)) continue;
    for (int p : planes) {
      const Object& g = scene.objects[static_cast<std::size_t>(p)];
      // rscene-sim's filter: the pair meets when each group is in the other's mask.
      if ((o.collisionGroup & g.collisionMask) == 0 || (g.collisionGroup & o.collisionMask) == 0) continue;
      const double depth = depthBelow(o, g.world.position.z());
      if (std::isfinite(depth) && depth > kStartOverlapDepth) out.push_back({static_cast<int>(i), p, depth});
    }
  }
  return out;
}

Diagnostic startOverlapDiagnostic(const Document& doc, int bodyRecord, int otherRecord, double depth) {
  auto pathOf = [&](int recordIndex) -> std::string {
    if (recordIndex < 0 || static_cast<std::size_t>(recordIndex) >= doc.records.size()) return "a robot's link";
    Diagnostics unused;
    RecordReader r(doc, static_cast<std::size_t>(recordIndex), unused);
    return "'" + r.text("path").value_or("") + "'";
  };
  char text[48];
  std::snprintf(text, sizeof text, "%.3g m", depth);
  Diagnostics one;
  reportAt(&doc, bodyRecord, "position", rs::RS7013,
           "dynamic body " + pathOf(bodyRecord) + " starts " + text + " inside " + pathOf(otherRecord) +
               "; the solver pushes it out over the first steps, which moves it and what it touches",
           one, Severity::Warning, "place it clear of what it starts inside");
  return one.front();  // reportAt() reports at the record, or bare
}

void checkGroundStarts(const Document& doc, const Scene& scene, Diagnostics& diagnostics) {
  for (const GroundStart& s : groundStarts(scene))
    diagnostics.push_back(startOverlapDiagnostic(doc, scene.objects[static_cast<std::size_t>(s.body)].recordIndex,
                                                 scene.objects[static_cast<std::size_t>(s.ground)].recordIndex,
                                                 s.depth));
}

}  // namespace rscene
