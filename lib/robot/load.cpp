// loadModel: one read of the robot file, dispatched by its root element;
// scaleModel; ModelCache.
#include <cmath>

#include "robot/load.hpp"

#include "scene/limits.hpp"
#include "robot/urdf_reader.hpp"
#include "robot/xml_file.hpp"

namespace rscene::robot {
namespace {

bool validScale(const Eigen::Vector3d& s) { return s.allFinite() && (s.array() > 0).all(); }

// How much a unit length along each axis of a frame rotated by `r` (in the
// link frame) grows when the link frame is scaled by `s`.
Eigen::Vector3d axisFactors(const Eigen::Vector3d& s, const Eigen::Quaterniond& r) {
  Eigen::Matrix3d m = s.asDiagonal() * r.toRotationMatrix();
  return m.colwise().norm().transpose();
}

void scaleGeometry(Geometry& g, const Eigen::Vector3d& s, const Eigen::Quaterniond& r) {
  Eigen::Vector3d f = axisFactors(s, r);
  switch (g.kind) {
    case GeometryKind::Box: g.size = g.size.cwiseProduct(f); break;
    case GeometryKind::Sphere: g.radius *= std::cbrt(s.prod()); break;  // stays a sphere: same volume ratio
    case GeometryKind::Cylinder:
    case GeometryKind::Capsule:
      g.length *= f.z();
      g.radius *= std::sqrt(f.x() * f.y());
      break;
    case GeometryKind::Mesh: g.meshScale = g.meshScale.cwiseProduct(f); break;
  }
}

// A body scaled by S keeps its density: mass grows by det S, and the second
// moment of mass about the centre, Sigma = integral rho r r^T, becomes
// det(A) A Sigma A^T with A = S written in the inertia frame.  The inertia
// tensor is I = tr(Sigma) 1 - Sigma, so Sigma = tr(I)/2 1 - I.
void scaleInertial(Inertial& in, const Eigen::Vector3d& s) {
  double det = s.prod();
  Eigen::Matrix3d r = in.origin.orientation.toRotationMatrix();
  Eigen::Matrix3d a = r.transpose() * s.asDiagonal() * r;
  Eigen::Matrix3d sigma = 0.5 * in.inertia.trace() * Eigen::Matrix3d::Identity() - in.inertia;
  Eigen::Matrix3d scaled = det * a * sigma * a.transpose();
  in.inertia = scaled.trace() * Eigen::Matrix3d::Identity() - scaled;
  in.mass *= det;
  in.origin.position = in.origin.position.cwiseProduct(s);
}

}  // namespace

void scaleModel(Model& model, const Eigen::Vector3d& s) {
  for (Link& link : model.links) {
    scaleInertial(link.inertial, s);
    for (Visual& v : link.visuals) {
      v.origin.position = v.origin.position.cwiseProduct(s);
      scaleGeometry(v.geometry, s, v.origin.orientation);
    }
    for (Collision& c : link.collisions) {
      c.origin.position = c.origin.position.cwiseProduct(s);
      scaleGeometry(c.geometry, s, c.origin.orientation);
    }
  }
  model.baseStart.position = model.baseStart.position.cwiseProduct(s);  // the free body's place in the scaled file
  for (SensorDef& d : model.sensors) d.origin.position = d.origin.position.cwiseProduct(s);  // ride on the link frame
  for (Joint& j : model.joints) {
    j.origin.position = j.origin.position.cwiseProduct(s);
    if (j.type == JointType::Prismatic) {
      // A slide's travel is a length along its axis (in the parent frame).
      double f = (s.asDiagonal() * (j.origin.orientation * j.axis)).norm();
      j.lower *= f;
      j.upper *= f;
      for (double& m : j.springMount) m *= f;
      j.initial *= f;
    }
  }
}

// The numbers of a model no simulator can stand behind, refused as the
// scene model refuses them for bodies (scene/limits.hpp), so that validate
// --check-files says what rscene-sim would stop on: a mass outside
// 0..1e15 kg, an inertia not finite, with a negative diagonal or beyond
// 1e21 kg m^2, a length beyond 1e12 m, a joint coefficient negative or
// beyond 1e15.  RS7035 at the element's line.
bool checkModelLimits(const Model& model, Diagnostics& diagnostics) {
  bool ok = true;
  auto refuse = [&](const std::string& file, int line, const std::string& message) {
    diagnostics.push_back(robotDiagnostic(Severity::Error, code::kBadNumber, file.empty() ? model.sourceFile : file,
                                          line, message));
    ok = false;
  };
  auto tooLong = [](const Eigen::Vector3d& v) { return !(v.lpNorm<Eigen::Infinity>() <= kMaxLength); };
  for (const Link& l : model.links) {
    const Inertial& in = l.inertial;
    if (!(in.mass >= 0 && in.mass <= kMaxMass))
      refuse(l.file, l.line, "link '" + l.name + "' has mass " + std::to_string(in.mass) + ", outside 0..1e15 kg");
    if (!in.inertia.allFinite() || in.inertia.diagonal().minCoeff() < 0 ||
        in.inertia.cwiseAbs().maxCoeff() > kMaxMass * 1e6)
      refuse(l.file, l.line, "link '" + l.name + "' has an inertia that is not finite, has a negative diagonal "
                             "entry or is beyond 1e21 kg m^2");
    if (tooLong(in.origin.position)) refuse(l.file, l.line, "link '" + l.name + "': inertial origin beyond 1e12 m");
    for (const Visual& v : l.visuals)
      if (tooLong(v.origin.position) || tooLong(v.geometry.size) || !(v.geometry.radius <= kMaxLength) ||
          !(v.geometry.length <= kMaxLength))
        refuse(l.file, v.line, "link '" + l.name + "': a visual's origin or size is beyond 1e12 m");
    for (const Collision& c : l.collisions)
      if (tooLong(c.origin.position) || tooLong(c.geometry.size) || !(c.geometry.radius <= kMaxLength) ||
          !(c.geometry.length <= kMaxLength))
        refuse(l.file, c.line, "link '" + l.name + "': a collision's origin or size is beyond 1e12 m");
  }
  for (const Joint& j : model.joints) {
    if (tooLong(j.origin.position)) refuse(j.file, j.line, "joint '" + j.name + "': origin beyond 1e12 m");
    for (double v : {j.damping, j.friction, j.rotorInertia, j.stiffness})
      if (!(v >= 0 && v <= kMaxCoefficient)) {
        refuse(j.file, j.line, "joint '" + j.name + "': damping, friction, rotor_inertia or stiffness outside 0..1e15");
        break;
      }
  }
  return ok;
}

bool loadModel(const std::string& path, const LoadOptions& options, Model& out, Diagnostics& diagnostics) {
  if (!validScale(options.scale)) {
    diagnostics.push_back(robotDiagnostic(Severity::Error, code::kBadFile, path, 0,
                                          "robot scale must be three positive finite numbers"));
    return false;
  }
  tinyxml2::XMLDocument doc;
  if (!readXmlFile(options.fileSystem(), path, options.maxFileBytes, doc, diagnostics)) return false;
  const tinyxml2::XMLElement* root = doc.RootElement();
  std::string kind = root ? root->Name() : "";
  Model model;
  bool ok = false;
  if (kind == "robot") {
    ok = urdf::loadDocument(path, doc, options, model, diagnostics);
  } else if (kind == "mujoco") {
    doc.Clear();  // MuJoCo's compiler reads the file itself
    ok = loadMjcf(path, options, model, diagnostics);
  } else {
    diagnostics.push_back(robotDiagnostic(Severity::Error, code::kBadFile, path, root ? root->GetLineNum() : 0,
                                          "robot file's root element is <" + kind +
                                              ">, not <robot> (URDF) or <mujoco> (MJCF)"));
  }
  if (!ok) return false;
  if (options.scale != Eigen::Vector3d::Ones()) scaleModel(model, options.scale);
  if (!checkModelLimits(model, diagnostics)) return false;
  out = std::move(model);
  return true;
}

std::shared_ptr<const Model> ModelCache::get(const std::string& path, const LoadOptions& options,
                                             Diagnostics& diagnostics) {
  Key key{path, options.resourceDirectory, options.modules, options.scale.x(), options.scale.y(), options.scale.z(),
          options.allowMissingMeshes};
  auto found = models_.find(key);
  if (found != models_.end()) {
    Entry& e = found->second;
    if (e.reportedIn != scene_) {  // a later scene of a batch: said again, once
      diagnostics.insert(diagnostics.end(), e.diagnostics.begin(), e.diagnostics.end());
      e.reportedIn = scene_;
    }
    return e.model;
  }
  Entry e;
  Model m;
  if (loadModel(path, options, m, e.diagnostics)) e.model = std::make_shared<const Model>(std::move(m));
  e.reportedIn = scene_;
  diagnostics.insert(diagnostics.end(), e.diagnostics.begin(), e.diagnostics.end());
  std::shared_ptr<const Model> model = e.model;
  models_.emplace(std::move(key), std::move(e));  // a failed load is remembered too: reported once a scene
  return model;
}

}  // namespace rscene::robot
