#include "xml/to_xml_robot.hpp"

#include "core/codes.hpp"
#include "robot/instance.hpp"
#include "robot/kinematics.hpp"
#include "scene/reader.hpp"

namespace rscene::xml {

namespace {

constexpr const char* kRobotUnread = rs::RS8131;

// `v` (laid out by `from`) in the layout of `to`: the base entries stay,
// each movable joint's entries move to where `to` puts that joint.
std::vector<double> reorder(const robot::Model& model, const robot::Coordinates& from, const robot::Coordinates& to,
                            const std::vector<double>& v, bool velocity) {
  std::vector<double> out(v);  // the base entries (first 7 / 6) stay where they are
  for (int j : from.joints) {
    const robot::Joint& joint = model.joints[static_cast<std::size_t>(j)];
    int n = velocity ? joint.velocityDim() : joint.coordinateDim();
    int a = velocity ? from.velocityIndex[static_cast<std::size_t>(j)] : from.coordinateIndex[static_cast<std::size_t>(j)];
    int b = velocity ? to.velocityIndex[static_cast<std::size_t>(j)] : to.coordinateIndex[static_cast<std::size_t>(j)];
    for (int k = 0; k < n; ++k) out[static_cast<std::size_t>(b + k)] = v[static_cast<std::size_t>(a + k)];
  }
  return out;
}

bool atOrigin(const Pose& p) { return p.position.isZero(0) && p.orientation.coeffs() == Eigen::Quaterniond::Identity().coeffs(); }

}  // namespace

RobotExport exportRobotState(const Document& doc, const Articulated& a, robot::ModelCache& cache) {
  RobotExport out;
  robot::RobotInstance instance;
  Diagnostics found;
  bool ok = robot::makeInstance(doc, a, cache, instance, found);
  if (a.sourcePath.empty()) {  // no robot file at all: refused, as rscene-sim refuses it (RS7034)
    out.diagnostics = std::move(found);
    return out;
  }
  if (!instance.model) {
    // The robot file cannot be read: urdf_path is still exported, with the
    // state as the record writes it (nothing else can be known).
    std::string why;
    for (const Diagnostic& d : found)
      if (d.severity == Severity::Error) {
        why = d.message;
        break;
      }
    if (a.hasCoordinate) out.qpos = a.generalizedCoordinate;
    if (a.hasVelocity) out.qvel = a.generalizedVelocity;
    RecordReader r(doc, static_cast<std::size_t>(a.recordIndex), out.diagnostics);
    r.error("resource", kRobotUnread,
            "articulated system '" + a.path + "': its robot file cannot be read" + (why.empty() ? "" : " (" + why + ")") +
                "; urdf_path is exported" +
                (a.hasCoordinate ? ", qpos as written" : ", without a state (the model's sizes are unknown)"),
            {}, Severity::Warning);
    return out;
  }
  out.modelLoaded = true;
  out.diagnostics = std::move(found);
  if (!ok) return out;  // a length or jointOrder the model refuses: the errors say which
  const robot::Model& model = *instance.model;
  robot::Coordinates raisim;
  robot::makeCoordinates(model, {}, raisim);
  std::vector<double> q = a.hasCoordinate ? a.generalizedCoordinate
                                          : std::vector<double>(instance.q.data(), instance.q.data() + instance.q.size());
  out.qpos = reorder(model, instance.coordinates, raisim, q, false);
  // qvel only when the record writes generalizedVelocity: from-xml reads an
  // absent qvel as no key, so a written zero qvel would add one.
  if (a.hasVelocity) out.qvel = reorder(model, instance.coordinates, raisim, a.generalizedVelocity, true);
  // A fixed base sits at the record's pose; RaiSim's XML fixes it at the
  // origin (there is no pose attribute for it).
  if (!model.floatingBase && !atOrigin(a.world)) out.losses.push_back("articulated " + a.path + ": fixed-base pose");
  return out;
}

}  // namespace rscene::xml
