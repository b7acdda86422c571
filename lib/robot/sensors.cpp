#include "robot/sensors.hpp"

#include "core/suggest.hpp"
#include "robot/check.hpp"
#include "robot/kinematics.hpp"
#include "scene/reader.hpp"

namespace rscene::robot {

SensorKind sensorKindOf(const std::string& k) {
  if (k == "rgb") return SensorKind::Rgb;
  if (k == "depth") return SensorKind::Depth;
  if (k == "segmentation") return SensorKind::Segmentation;
  if (k == "rgb_depth") return SensorKind::RgbDepth;
  if (k == "lidar") return SensorKind::Lidar;
  if (k == "imu") return SensorKind::Imu;
  return SensorKind::Other;
}

const char* sensorKindName(SensorKind k) {
  switch (k) {
    case SensorKind::Rgb: return "rgb";
    case SensorKind::Depth: return "depth";
    case SensorKind::Segmentation: return "segmentation";
    case SensorKind::RgbDepth: return "rgb_depth";
    case SensorKind::Lidar: return "lidar";
    case SensorKind::Imu: return "imu";
    case SensorKind::Other: break;
  }
  return "other";
}

BodyPoses restPoses(const Scene& scene, const std::vector<std::shared_ptr<const Model>>& models) {
  BodyPoses p;
  for (const Object& o : scene.objects) p.objects.push_back(o.world);
  for (const Compound& c : scene.compounds) p.compounds.push_back(c.world);
  p.robotLinks.resize(scene.articulated.size());
  for (std::size_t i = 0; i < scene.articulated.size() && i < models.size(); ++i) {
    if (!models[i]) continue;
    const Articulated& a = scene.articulated[i];
    Coordinates c;
    makeCoordinates(*models[i], a.jointOrder, c);
    Pose base = a.world;
    Eigen::VectorXd q = neutralCoordinate(*models[i], c, base);
    if (a.hasCoordinate && static_cast<int>(a.generalizedCoordinate.size()) == c.coordinateDim) {
      q = Eigen::Map<const Eigen::VectorXd>(a.generalizedCoordinate.data(), c.coordinateDim);
      for (int j : c.joints) {  // quaternions as makeInstance reads them: normalised
        const Joint& joint = models[i]->joints[static_cast<std::size_t>(j)];
        if (joint.type != JointType::Spherical) continue;
        int at = c.coordinateIndex[static_cast<std::size_t>(j)];
        double n = q.segment<4>(at).norm();
        q.segment<4>(at) = n > 1e-12 ? Eigen::Vector4d(q.segment<4>(at) / n) : Eigen::Vector4d(1, 0, 0, 0);
      }
      if (c.baseCoordinates == 7) {
        double n = q.segment<4>(3).norm();
        q.segment<4>(3) = n > 1e-12 ? Eigen::Vector4d(q.segment<4>(3) / n) : Eigen::Vector4d(1, 0, 0, 0);
      }
    }
    p.robotLinks[i] = linkPoses(*models[i], c, base, q);
  }
  return p;
}

std::vector<SensorSpec> collectSensors(const Document& doc, const Scene& scene,
                                       const std::vector<std::shared_ptr<const Model>>& models,
                                       Diagnostics& diagnostics) {
  std::vector<SensorSpec> out;
  auto modelOf = [&](const Mount& m) -> const Model* {
    if (m.kind != Mount::Kind::Articulated || m.index < 0 || std::size_t(m.index) >= models.size()) return nullptr;
    return models[static_cast<std::size_t>(m.index)].get();
  };
  for (const Sensor& v : scene.sensors) {
    SensorSpec s;
    s.name = v.path;
    s.id = v.id;
    s.kindName = v.kind;
    s.kind = sensorKindOf(v.kind);
    s.mount = v.mount;
    s.local = v.local;
    s.params = v.params;
    s.enabled = v.enabled;
    s.outputPath = v.outputPath;
    s.recordIndex = v.recordIndex;
    if (const Model* model = modelOf(v.mount)) {
      s.robotRecord = scene.articulated[static_cast<std::size_t>(v.mount.index)].recordIndex;
      s.link = model->root;
      if (!v.mount.link.empty()) {
        // A link by name, as validate's RS7045 check reads it.
        int link = model->findLink(v.mount.link);
        if (link >= 0) s.link = link;
        else  // the sensor stays on the root link
          reportUnknownSensorLink(doc, v.recordIndex, *model, v.mount.link,
                                  scene.articulated[static_cast<std::size_t>(v.mount.index)].path, diagnostics);
      }
    }
    out.push_back(std::move(s));
  }
  for (std::size_t i = 0; i < scene.articulated.size() && i < models.size(); ++i) {
    if (!models[i]) continue;
    const Articulated& a = scene.articulated[i];
    for (const SensorDef& d : models[i]->sensors) {
      SensorSpec s;
      s.name = a.path + "/" + d.set + "/" + d.name;
      s.kindName = d.kind;
      s.kind = sensorKindOf(d.kind);
      s.mount.kind = Mount::Kind::Articulated;
      s.mount.index = static_cast<int>(i);
      s.link = d.link >= 0 ? d.link : models[i]->root;
      s.local = d.origin;
      s.params = d.params;
      s.robotRecord = a.recordIndex;
      s.file = d.file;
      s.line = d.line;
      out.push_back(std::move(s));
    }
  }
  return out;
}

void reportUnknownSensorLink(const Document& doc, int record, const Model& model, const std::string& link,
                             const std::string& robotPath, Diagnostics& diagnostics) {
  std::string hint;
  if (int j = model.findJoint(link); j >= 0 && model.joints[static_cast<std::size_t>(j)].childLink >= 0) {
    hint = "'" + link + "' is a joint; its child link is '" +
           model.links[static_cast<std::size_t>(model.joints[static_cast<std::size_t>(j)].childLink)].name + "'";
  } else {
    std::vector<std::string_view> names;
    for (const Link& l : model.links) names.push_back(l.name);
    std::string best = closestName(link, names);
    if (!best.empty()) hint = "did you mean '" + best + "'?";
  }
  RecordReader r(doc, static_cast<std::size_t>(record), diagnostics);
  r.error("parentLink", code::kSensorLink,
          "parentLink '" + link + "' is no link of the model '" + model.name + "' of '" + robotPath + "'", hint);
}

Pose sensorPose(const SensorSpec& s, const Scene& scene, const BodyPoses& poses) {
  auto at = [](const auto& list, int i) { return i >= 0 && std::size_t(i) < list.size(); };
  const Mount& m = s.mount;
  switch (m.kind) {
    case Mount::Kind::Object:
      if (at(poses.objects, m.index)) return poses.objects[std::size_t(m.index)] * s.local;
      if (at(scene.objects, m.index)) return scene.objects[std::size_t(m.index)].world * s.local;
      break;
    case Mount::Kind::Compound:
      if (at(poses.compounds, m.index)) return poses.compounds[std::size_t(m.index)] * s.local;
      if (at(scene.compounds, m.index)) return scene.compounds[std::size_t(m.index)].world * s.local;
      break;
    case Mount::Kind::Articulated:
      if (at(poses.robotLinks, m.index)) {
        const std::vector<Pose>& links = poses.robotLinks[std::size_t(m.index)];
        if (!links.empty()) {
          if (at(links, s.link)) return links[std::size_t(s.link)] * s.local;
        }
      }
      if (at(scene.articulated, m.index)) return scene.articulated[std::size_t(m.index)].world * s.local;
      break;
    case Mount::Kind::World: break;
  }
  // In the world: the record's world pose (its parent folder's frame).
  if (s.recordIndex >= 0)
    for (const Sensor& v : scene.sensors)
      if (v.recordIndex == s.recordIndex) return v.world;
  return s.local;
}

}  // namespace rscene::robot
