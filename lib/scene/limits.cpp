// Numbers a simulator cannot stand behind (limits.hpp): refused up front by
// every tool that reads the scene model, so rscene-validate reports what
// rscene-sim would refuse.
#include "scene/limits.hpp"

#include <cfloat>
#include <cmath>
#include <cstdio>

#include "scene/reader.hpp"

namespace rscene {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// What is wrong with a pose for Bullet, and the field to point at; empty
// when nothing is.  The scene view normalises orientations, so a quaternion
// whose norm overflowed (1e308 1e308 0 0) arrives here as zero or NaN.
std::pair<std::string, const char*> poseProblem(const Pose& p) {
  if (!p.position.allFinite()) return {"position is not finite", "position"};
  if (!(p.position.lpNorm<Eigen::Infinity>() <= kMaxLength))
    return {"position is more than " + number(kMaxLength) + " m from its frame's origin", "position"};
  const Eigen::Vector4d q = p.orientation.coeffs();
  if (!q.allFinite() || !(std::abs(q.norm() - 1) < 1e-6))
    return {"orientation does not normalise to a unit quaternion", "orientation"};
  return {};
}

// A dynamic mass Bullet can invert and move: a normal double up to
// kMaxMass.  mass <= 0 is checkScene()'s RS4008.
bool badMass(double mass) { return mass > 0 && !(mass >= DBL_MIN && mass <= kMaxMass); }

const std::string kMassHint = "a dynamic mass must lie between 2.2250738585072014e-308 and " + number(kMaxMass) + " kg";

bool tooLarge(double v) { return !(std::abs(v) <= kMaxLength); }
bool tooLarge(const Eigen::Vector3d& v) { return !(v.lpNorm<Eigen::Infinity>() <= kMaxLength); }

// RS7026 at `field` when `value` is beyond kMaxLength (or not finite).
template <class T>
void checkLength(const RecordReader& r, const char* field, const T& value, const std::string& what) {
  if (tooLarge(value))
    r.error(field, scene_code::kHugeValue, what + " is larger than " + number(kMaxLength) + " in magnitude",
            "lengths, coordinates and accelerations must stay within 1e12 (m, m/s^2) for double precision to resolve them");
}

}  // namespace

bool checkNumericLimits(const Document& doc, const Scene& scene, Diagnostics& diagnostics) {
  std::size_t before = diagnostics.size();
  for (std::size_t i = 1; i < doc.records.size(); ++i) {
    const Record& rec = doc.records[i];
    if (!rec.kind || rec.kind->tag != "time_step") continue;
    RecordReader r(doc, i, diagnostics);
    double dt = r.number("dt", scene.timeStep);
    if (dt > 0 && !(std::isfinite(dt) && dt >= kMinTimeStep))  // dt <= 0 is RS7008
      r.error("dt", scene_code::kTinyTimeStep,
              "time_step " + number(dt) + " is below the smallest simulated step, " + number(kMinTimeStep) + " s",
              "a smaller step would need more than 10^9 steps per simulated second");
    else if (dt > kMaxTimeStep)
      r.error("dt", scene_code::kTinyTimeStep,
              "time_step " + number(dt) + " is above the longest simulated step, " + number(kMaxTimeStep) + " s",
              "a step longer than a second resolves no contact");
  }
  for (std::size_t i = 1; i < doc.records.size(); ++i) {
    const Record& rec = doc.records[i];
    if (!rec.kind || rec.kind->tag != "gravity") continue;
    RecordReader r(doc, i, diagnostics);
    checkLength(r, "gravity", r.vec3("gravity"), "gravity");
  }
  for (const Object& o : scene.objects) {
    if (o.bodyMode == BodyMode::VisualOnly) continue;
    RecordReader r(doc, static_cast<std::size_t>(o.recordIndex), diagnostics);
    if (o.bodyMode == BodyMode::Dynamic && badMass(o.mass))
      r.error("mass", scene_code::kBadMassValue, "dynamic body '" + o.path + "' has mass " + number(o.mass) +
                                                     ", which cannot be simulated", kMassHint);
    checkLength(r, "scale", o.scale, "scale of body '" + o.path + "'");
    checkLength(r, "radius", o.radius, "radius of body '" + o.path + "'");
    checkLength(r, "height", o.height, "height of body '" + o.path + "'");
    if (o.primitive == "ground" || o.primitive == "half_space") {  // only position.z is used
      if (!std::isfinite(o.local.position.z()) || tooLarge(o.local.position.z()))
        r.error("position", scene_code::kBadPose, "plane '" + o.path + "' is more than " + number(kMaxLength) +
                                                      " m from its frame's origin (or not finite)");
      continue;
    }
    auto [problem, field] = poseProblem(o.local);  // as written: bodiesOnly builds resolve no world poses
    if (!problem.empty()) r.error(field, scene_code::kBadPose, "body '" + o.path + "': " + problem);
  }
  for (const Compound& c : scene.compounds) {
    if (c.bodyMode == BodyMode::VisualOnly) continue;
    RecordReader r(doc, static_cast<std::size_t>(c.recordIndex), diagnostics);
    if (c.bodyMode == BodyMode::Dynamic && badMass(c.mass))
      r.error("mass", scene_code::kBadMassValue, "dynamic compound '" + c.path + "' has mass " + number(c.mass) +
                                                     ", which cannot be simulated", kMassHint);
    auto [problem, field] = poseProblem(c.local);
    if (!problem.empty()) r.error(field, scene_code::kBadPose, "compound '" + c.path + "': " + problem);
    checkLength(r, "scale", c.scale, "scale of compound '" + c.path + "'");
    for (const CompoundChild& ch : c.children) {
      RecordReader cr(doc, static_cast<std::size_t>(ch.recordIndex), diagnostics);
      checkLength(cr, "scale", ch.scale, "scale of a child of compound '" + c.path + "'");
      checkLength(cr, "size", ch.size, "size of a child of compound '" + c.path + "'");
      checkLength(cr, "radius", ch.radius, "radius of a child of compound '" + c.path + "'");
      checkLength(cr, "height", ch.height, "height of a child of compound '" + c.path + "'");
      auto [childProblem, childField] = poseProblem(ch.local);
      if (!childProblem.empty())
        cr.error(childField, scene_code::kBadPose, "child of compound '" + c.path + "': " + childProblem);
    }
  }
  for (const Wire& w : scene.wires) {
    RecordReader r(doc, static_cast<std::size_t>(w.recordIndex), diagnostics);
    checkLength(r, "length", w.length, "length of wire '" + w.path + "'");
    checkLength(r, "localPositionA", w.localPositionA, "localPositionA of wire '" + w.path + "'");
    checkLength(r, "localPositionB", w.localPositionB, "localPositionB of wire '" + w.path + "'");
  }
  for (std::size_t i = before; i < diagnostics.size(); ++i)
    if (diagnostics[i].severity == Severity::Error) return false;
  return true;
}

}  // namespace rscene
