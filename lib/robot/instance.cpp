#include "robot/instance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "core/suggest.hpp"
#include "core/assets.hpp"
#include "scene/limits.hpp"
#include "scene/left_out.hpp"
#include "scene/reader.hpp"

namespace rscene::robot {
namespace {

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// The generalizedCoordinate entries that are quaternions: the floating
// base's (at 3) and each spherical joint's.
std::vector<int> quaternionStarts(const Model& model, const Coordinates& c) {
  std::vector<int> at;
  if (model.floatingBase) at.push_back(3);
  for (int j : c.joints)
    if (model.joints[static_cast<std::size_t>(j)].type == JointType::Spherical)
      at.push_back(c.coordinateIndex[static_cast<std::size_t>(j)]);
  return at;
}

// "did you mean" among the model's movable joints.
std::string jointHint(const Model& model, const std::string& name) {
  std::vector<std::string_view> movable;
  for (const Joint& j : model.joints)
    if (j.type != JointType::Fixed) movable.push_back(j.name);
  std::string best = closestName(name, movable);
  return best.empty() ? std::string() : "did you mean '" + best + "'?";
}

void reportJointOrder(const Document& doc, const Articulated& a, const Model& model,
                      const std::vector<JointOrderProblem>& problems, Diagnostics& diags) {
  RecordReader r(doc, static_cast<std::size_t>(writtenBy(doc, a, "jointOrder").record), diags);
  std::vector<std::string> missing;
  for (const JointOrderProblem& p : problems) {
    switch (p.kind) {
      case JointOrderProblem::Unknown:
        r.error("jointOrder", code::kJointOrder, "jointOrder names '" + p.name + "', which is not a joint of the model",
                jointHint(model, p.name));
        break;
      case JointOrderProblem::Fixed:
        r.error("jointOrder", code::kJointOrder,
                "jointOrder names '" + p.name + "', a fixed joint (it has no coordinate)");
        break;
      case JointOrderProblem::Repeated:
        r.error("jointOrder", code::kJointOrder, "jointOrder names '" + p.name + "' twice");
        break;
      case JointOrderProblem::Missing: missing.push_back(p.name); break;
    }
  }
  if (!missing.empty())
    r.error("jointOrder", code::kJointOrder, "jointOrder leaves out movable joints: " + joinNames(missing));
}

}  // namespace

FieldSource writtenBy(const Document& doc, const Articulated& a, const char* field) {
  Diagnostics unused;  // has() reports nothing
  bool own = a.resourceRecord < 0 || RecordReader(doc, static_cast<std::size_t>(a.recordIndex), unused).has(field);
  if (own) return {a.recordIndex, field};
  return {a.resourceRecord, std::string_view(field) == "sourcePath" ? "path" : field};
}

bool checkRobotFile(const Document& doc, const Articulated& a, Diagnostics& diags) {
  if (a.sourcePath.empty() || fileExistsOnDisk(a.sourcePath)) return true;
  FieldSource at = writtenBy(doc, a, "sourcePath");
  RecordReader(doc, static_cast<std::size_t>(at.record), diags)
      .error(at.field, scene_code::kMissingFile, "robot file '" + a.sourcePath + "' " + whyNotAFile(a.sourcePath));
  return false;
}

int leaveOutMissingRobots(const Document& doc, Scene& scene, Diagnostics& diags) {
  // One warning per file, at the first record that names it, as for a
  // missing body mesh (sim/missing_assets.cpp).
  std::map<std::string, std::vector<const Articulated*>> byFile;
  std::vector<std::string> order;
  std::set<int> records;  // of the robots left out
  int count = 0;
  for (Articulated& a : scene.articulated) {
    if (a.sourcePath.empty() || fileExistsOnDisk(a.sourcePath)) continue;
    a.leftOut = true;
    ++count;
    records.insert(a.recordIndex);
    auto& robots = byFile[a.sourcePath];
    if (robots.empty()) order.push_back(a.sourcePath);
    robots.push_back(&a);
  }
  for (const std::string& file : order) {
    const std::vector<const Articulated*>& robots = byFile[file];
    const Articulated& first = *robots.front();
    std::size_t others = robots.size() - 1;
    std::string who = others == 0 ? "articulated system '" + first.path + "' is"
                                  : "articulated systems '" + first.path + "' and " + std::to_string(others) +
                                        (others == 1 ? " other are" : " others are");
    FieldSource at = writtenBy(doc, first, "sourcePath");
    RecordReader(doc, static_cast<std::size_t>(at.record), diags)
        .error(at.field, scene_code::kMissingFile,
               "robot file '" + file + "' " + whyNotAFile(file) + "; " + who + " left out (--allow-missing-assets)",
               {}, Severity::Warning);
  }
  detachFromLeftOut(doc, scene, records, true, "for its missing robot file", diags);
  return count;
}

LoadOptions loadOptionsOf(const Articulated& record, bool allowMissingMeshes) {
  LoadOptions o;
  o.resourceDirectory = record.resourceDirectory;
  o.modules = record.modules;
  o.scale = record.scale;
  o.allowMissingMeshes = allowMissingMeshes;
  return o;
}

namespace {

// RS7056: a start pose that puts a 1-dof joint outside its limits (the
// solver snaps it back in the first steps, a jolt the scene did not ask
// for).  At the record's coordinates when it writes them, else at the
// field naming the model whose own start (MJCF qpos0) it is.
void startLimits(RecordReader& r, const Articulated& a, const Model& model, const Coordinates& c,
                 const Eigen::VectorXd& q) {
  for (int j : c.joints) {
    const Joint& joint = model.joints[static_cast<std::size_t>(j)];
    if (!joint.hasLimits || joint.coordinateDim() != 1) continue;
    const int at = c.coordinateIndex[static_cast<std::size_t>(j)];
    if (at < 0 || at >= q.size()) continue;
    const double v = q[at], slack = 1e-9 * std::max(1.0, joint.upper - joint.lower);
    if (v >= joint.lower - slack && v <= joint.upper + slack) continue;
    char text[160];
    std::snprintf(text, sizeof text, "%g, outside its limits [%g, %g]", v, joint.lower, joint.upper);
    const bool written = a.hasCoordinate;
    r.error(written ? "generalizedCoordinate" : "resource", code::kStartLimits,
            "articulated system '" + a.path + "' starts with joint '" + joint.name + "' (entry " + std::to_string(at) +
                (written ? " of generalizedCoordinate" : ", the model's own start") + ") at " + text,
            "the solver pushes the joint back inside in the first steps", Severity::Warning);
  }
}

}  // namespace

bool makeInstance(const Document& doc, const Articulated& a, ModelCache& cache, RobotInstance& out,
                  Diagnostics& diags, const InstanceOptions& options) {
  out = RobotInstance{};
  out.record = &a;
  out.base = a.world;
  RecordReader r(doc, static_cast<std::size_t>(a.recordIndex), diags);
  if (a.sourcePath.empty()) {
    if (options.reportModel)
      r.error(a.resource < 0 ? "resource" : "sourcePath", code::kNoResource,
              a.resource < 0 ? "articulated system names no articulated_resource '" + a.resourceRef + "'"
                             : "articulated system has no robot file (its resource's path is empty)");
    return false;
  }
  Diagnostics loadDiags;
  out.model = cache.get(a.sourcePath, loadOptionsOf(a, options.allowMissingMeshes), loadDiags);
  if (options.reportModel) diags.insert(diags.end(), loadDiags.begin(), loadDiags.end());
  if (!out.model) return false;
  const Model& model = *out.model;

  bool ok = true;
  std::vector<JointOrderProblem> problems = makeCoordinates(model, a.jointOrder, out.coordinates);
  if (!problems.empty()) {
    reportJointOrder(doc, a, model, problems, diags);
    ok = false;
  }
  const Coordinates& c = out.coordinates;
  if (std::size_t bodies = c.joints.size() + 1; bodies > kMaxRobotBodies) {
    r.error("resource", code::kTooLarge,
            "articulated system '" + a.path + "' has " + std::to_string(bodies) + " bodies; rscene-sim simulates at most " +
                std::to_string(kMaxRobotBodies) + " per robot",
            "each movable joint adds a body; fixed joints merge into their parent");
    return false;
  }

  out.q = neutralCoordinate(model, c, a.world);
  if (a.hasCoordinate) {
    const std::vector<double>& gc = a.generalizedCoordinate;
    if (static_cast<int>(gc.size()) != c.coordinateDim) {
      r.error("generalizedCoordinate", code::kCoordinateLength,
              "generalizedCoordinate has " + std::to_string(gc.size()) + " numbers; the model '" + model.name +
                  "' has " + std::to_string(c.coordinateDim) +
                  (model.floatingBase ? " (7 for the floating base, then the joints)" : " (joints only: fixed base)"));
      ok = false;
    } else if (Eigen::Map<const Eigen::VectorXd> m(gc.data(), static_cast<Eigen::Index>(gc.size()));
               !(m.lpNorm<Eigen::Infinity>() <= kMaxLength)) {
      // As a body's position (RS7021): beyond it no simulator resolves the
      // state, and 1e308 was written back as is.
      r.error("generalizedCoordinate", code::kStateRange, "generalizedCoordinate holds a number beyond 1e12 in magnitude");
      ok = false;
    } else {
      out.q = Eigen::Map<const Eigen::VectorXd>(gc.data(), static_cast<Eigen::Index>(gc.size()));
      for (int at : quaternionStarts(model, c)) {
        Eigen::Vector4d v = out.q.segment<4>(at);
        double n = v.norm();
        if (!(n > 1e-12) || !std::isfinite(n)) {
          r.error("generalizedCoordinate", code::kQuaternion,
                  "generalizedCoordinate holds a zero quaternion at entries " + std::to_string(at) + ".." +
                      std::to_string(at + 3));
          out.q.segment<4>(at) << 1, 0, 0, 0;
          ok = false;
        } else {
          if (std::abs(n - 1) > 1e-3)
            r.error("generalizedCoordinate", code::kQuaternion,
                    "quaternion at entries " + std::to_string(at) + ".." + std::to_string(at + 3) +
                        " has length " + std::to_string(n) + "; it is normalised",
                    {}, Severity::Warning);
          out.q.segment<4>(at) = v / n;
        }
      }
    }
  }
  if (options.reportModel) startLimits(r, a, model, c, out.q);
  out.u = Eigen::VectorXd::Zero(c.velocityDim);
  if (a.hasVelocity) {
    const std::vector<double>& gv = a.generalizedVelocity;
    if (static_cast<int>(gv.size()) != c.velocityDim) {
      r.error("generalizedVelocity", code::kVelocityLength,
              "generalizedVelocity has " + std::to_string(gv.size()) + " numbers; the model '" + model.name +
                  "' has " + std::to_string(c.velocityDim));
      ok = false;
    } else if (Eigen::Map<const Eigen::VectorXd> m(gv.data(), static_cast<Eigen::Index>(gv.size()));
               !(m.lpNorm<Eigen::Infinity>() <= kMaxLength)) {
      r.error("generalizedVelocity", code::kStateRange, "generalizedVelocity holds a number beyond 1e12 in magnitude");
      ok = false;
    } else {
      out.u = Eigen::Map<const Eigen::VectorXd>(gv.data(), static_cast<Eigen::Index>(gv.size()));
    }
  }
  if (model.floatingBase) {
    out.base.position = out.q.head<3>();
    out.base.orientation = Eigen::Quaterniond(out.q[3], out.q[4], out.q[5], out.q[6]);
  }
  return ok;
}

}  // namespace rscene::robot
