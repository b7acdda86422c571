// Numbers a simulator cannot stand behind (limits.hpp): refused up front by
// every tool that reads the scene model, so rscene-validate reports what
// rscene-sim would refuse.
#include "scene/limits.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <unordered_map>

#include "core/codes.hpp"
#include "core/text.hpp"
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

// RS7090 at inertiaDiagonal when a moment is not a normal positive double
// up to kMaxInertia (0 or a denormal has an infinite inverse).
void checkInertia(const RecordReader& r, const Eigen::Vector3d& d, const std::string& what) {
  for (int i = 0; i < 3; ++i)
    if (!(d[i] >= DBL_MIN && d[i] <= kMaxInertia)) {
      r.error("inertiaDiagonal", scene_code::kBadInertia,
              "inertia diagonal of " + what + " has " + number(d[i]) + ", which cannot be simulated",
              "each principal moment must lie between 2.2250738585072014e-308 and " + number(kMaxInertia) +
                  " kg m^2");
      return;
    }
}

bool tooLarge(double v) { return !(std::abs(v) <= kMaxLength); }
bool tooLarge(const Eigen::Vector3d& v) { return !(v.lpNorm<Eigen::Infinity>() <= kMaxLength); }

// RS7026 at `field` when `value` is beyond kMaxLength (or not finite).
template <class T>
void checkLength(const RecordReader& r, const char* field, const T& value, const std::string& what) {
  if (tooLarge(value))
    r.error(field, scene_code::kHugeValue, what + " is larger than " + number(kMaxLength) + " in magnitude",
            "lengths, coordinates and accelerations must stay within 1e12 (m, m/s^2) for double precision to resolve them");
}

// RS7027 at `field` when the coefficient is negative, above
// kMaxCoefficient or not finite.
void checkCoefficient(const RecordReader& r, const char* field, double v, const std::string& what) {
  if (!(v >= 0 && v <= kMaxCoefficient))
    r.error(field, scene_code::kBadCoefficient, what + " is " + number(v) + ", outside 0.." + number(kMaxCoefficient),
            "a negative coefficient has no meaning, and a larger one overflows forces");
}

// The records validate's bodies-only scene does not build, read here from
// the document: solver, contact materials, cameras, terrains.
void checkRecords(const Document& doc, const Scene& scene, Diagnostics& diagnostics) {
  // A full build has parsed each terrain's heights already; a bodies-only
  // one (validate) has not, and they are read here once.
  std::unordered_map<int, const std::vector<double>*> parsedHeights;
  for (const Terrain& t : scene.terrains)
    if (!t.heights.empty()) parsedHeights.emplace(t.recordIndex, &t.heights);
  for (std::size_t i = 1; i < doc.records.size(); ++i) {
    const Record& rec = doc.records[i];
    if (!rec.kind) continue;
    const std::string& tag = rec.kind->tag;
    if (tag == "solver") {
      RecordReader r(doc, i, diagnostics);
      for (const char* field : {"iterations", "contactMaxIterations"}) {
        std::int64_t n = r.integer(field);
        if (n < 0 || n > kMaxSolverIterations)
          r.error(field, scene_code::kBadCoefficient,
                  std::string("solver ") + field + " is " + std::to_string(n) + ", outside 0.." +
                      std::to_string(kMaxSolverIterations),
                  "each iteration visits every contact of every step");
      }
      for (const char* field : {"defaultFriction", "defaultRestitution", "defaultStaticFriction",
                                "defaultRollingFriction", "defaultSpinningFriction"})
        checkCoefficient(r, field, r.number(field), std::string("solver ") + field);
    } else if (tag == "contact_material") {
      RecordReader r(doc, i, diagnostics);
      for (const char* field : {"friction", "restitution", "staticFriction", "rollingFriction", "spinningFriction"})
        if (r.has(field)) checkCoefficient(r, field, r.number(field, 0), std::string("contact ") + field);
    } else if (tag == "sensor" || tag == "camera") {
      // Poses as bodies have them: a sensor's readings and a view's
      // matrices are computed from it, and 1.5e308 makes them inf or NaN.
      RecordReader r(doc, i, diagnostics);
      if (tooLarge(r.vec3("position", Eigen::Vector3d::Zero())))
        r.error("position", scene_code::kBadPose,
                tag + " '" + r.text("path").value_or("") + "': position is more than " + number(kMaxLength) +
                    " m from its frame's origin");
      if (tag == "sensor") continue;
      for (const char* field : {"width", "height"}) {
        std::int64_t n = r.integer(field, 0);
        if (n < 0 || n > kMaxCameraSide)
          r.error(field, scene_code::kBadCameraSize,
                  std::string("camera ") + field + " is " + std::to_string(n) + ", outside 0.." +
                      std::to_string(kMaxCameraSide),
                  "0 lets rscene-render choose; it draws at most 16384 pixels per side");
      }
    } else if (tag == "terrain_region") {
      RecordReader r(doc, i, diagnostics);
      checkLength(r, "xSize", r.number("xSize", 0), "terrain xSize");
      checkLength(r, "ySize", r.number("ySize", 0), "terrain ySize");
      checkLength(r, "center", r.vec3("center", Eigen::Vector3d::Zero()), "terrain center");
      std::vector<double> read;
      auto it = parsedHeights.find(static_cast<int>(i));
      const std::vector<double>* heights = it != parsedHeights.end() ? it->second : nullptr;
      if (!heights && r.has("heights") && r.numbers("heights", read)) heights = &read;
      if (heights) {
        double largest = 0;
        for (double h : *heights) largest = std::isnan(h) ? h : std::max(largest, std::abs(h));
        checkLength(r, "heights", largest, "a terrain height");
      }
    }
  }
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
  checkRecords(doc, scene, diagnostics);
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
    if (o.bodyMode == BodyMode::Dynamic && o.hasInertia) checkInertia(r, o.inertiaDiagonal, "body '" + o.path + "'");
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
    if (c.bodyMode == BodyMode::Dynamic && c.hasInertia)
      checkInertia(r, c.inertiaDiagonal, "compound '" + c.path + "'");
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
    if (w.length < 0)  // lib/core's finding, in its words
      r.error("length", rs::RS4011, "length is negative (" + numberText(w.length) + ")");
    else
      checkLength(r, "length", w.length, "length of wire '" + w.path + "'");
    checkCoefficient(r, "stiffness", w.stiffness, "stiffness of wire '" + w.path + "'");
    checkCoefficient(r, "damping", w.damping, "damping of wire '" + w.path + "'");
    checkCoefficient(r, "compliance", w.compliance, "compliance of wire '" + w.path + "'");
    checkLength(r, "localPositionA", w.localPositionA, "localPositionA of wire '" + w.path + "'");
    checkLength(r, "localPositionB", w.localPositionB, "localPositionB of wire '" + w.path + "'");
  }
  for (std::size_t i = before; i < diagnostics.size(); ++i)
    if (diagnostics[i].severity == Severity::Error) return false;
  return true;
}

}  // namespace rscene
