#include "scene/scene_builder.hpp"

namespace rscene::scene_build {

void Builder::readArticulatedResource(const RecordReader& r, int idx) {
  ArticulatedResource a;
  a.recordIndex = idx;
  a.id = r.str("id");
  a.name = r.str("name");
  a.path = asset(r.str("path"));
  a.resourceDirectory = assetDirectory(r.str("resourceDirectory"));
  a.modules = splitList(r.str("modules"));
  a.jointOrder = splitList(r.str("jointOrder"));
  a.doNotCollideWithParent = r.flag("doNotCollideWithParent");
  a.convexifyCollisionMeshes = r.flag("convexifyCollisionMeshes");
  s_.articulatedResources.push_back(std::move(a));
}

void Builder::readSensor(const RecordReader& r, int idx) {
  Sensor v;
  v.recordIndex = idx;
  v.path = nodePath(doc_, r.record());
  v.id = nodeId(doc_, r.record());
  v.kind = r.name("kind");
  v.parentObject = r.str("parentObject");
  if (v.parentObject == "-") v.parentObject.clear();
  v.parentLink = r.str("parentLink");
  if (v.parentLink == "-") v.parentLink.clear();
  v.local = readPose(r, "position", "orientation");
  SensorParams& p = v.params;
  p.width = pixelCount(r, "width");
  p.height = pixelCount(r, "height");
  p.updateRate = r.number("updateRate");
  p.verticalFov = r.number("verticalFov");
  p.horizontalFov = r.number("horizontalFov");
  p.nearPlane = r.number("nearPlane");
  p.farPlane = r.number("farPlane");
  p.lidarChannels = static_cast<int>(std::clamp<std::int64_t>(r.integer("lidarChannels"), 0, INT32_MAX));
  p.lidarSamples = static_cast<int>(std::clamp<std::int64_t>(r.integer("lidarSamples"), 0, INT32_MAX));
  p.lidarMinRange = r.number("lidarMinRange");
  p.lidarMaxRange = r.number("lidarMaxRange");
  // lidarVerticalFov: a span centred on the horizon.
  p.lidarMaxPitch = r.number("lidarVerticalFov") / 2;
  p.lidarMinPitch = -p.lidarMaxPitch;
  p.segmentation = r.flag("segmentation");
  p.fx = r.number("calibrationFx");
  p.fy = r.number("calibrationFy");
  p.cx = r.number("calibrationCx");
  p.cy = r.number("calibrationCy");
  p.noiseMean = r.number("noiseMean");
  p.noiseStddev = r.number("noiseStddev");
  p.noiseSeed = static_cast<std::uint64_t>(r.integer("noiseSeed"));
  v.enabled = r.flag("enabled");
  v.outputPath = r.str("outputPath");
  parentOf_[idx] = r.str("parentGroupId");
  s_.sensors.push_back(std::move(v));
}

void Builder::readArticulated(const RecordReader& r, int idx) {
  Articulated a;
  a.recordIndex = idx;
  a.path = nodePath(doc_, r.record());
  a.id = nodeId(doc_, r.record());
  a.parentId = r.str("parentGroupId");
  a.resourceRef = r.str("resource");
  // Fields the record writes; the rest come from its resource once every
  // resource is read (resolveArticulated: a resource is scene-global).
  Written w;
  w.source = r.has("sourcePath");
  w.directory = r.has("resourceDirectory");
  w.modules = r.has("modules");
  w.order = r.has("jointOrder");
  w.noParent = r.has("doNotCollideWithParent");
  w.convexify = r.has("convexifyCollisionMeshes");
  a.sourcePath = asset(r.str("sourcePath"));
  a.resourceDirectory = assetDirectory(r.str("resourceDirectory"));
  a.modules = splitList(r.str("modules"));
  a.jointOrder = splitList(r.str("jointOrder"));
  a.doNotCollideWithParent = r.flag("doNotCollideWithParent");
  a.convexifyCollisionMeshes = r.flag("convexifyCollisionMeshes");
  written_.push_back(w);
  a.local = readPose(r, "position", "orientation");
  a.positionToken = r.positionalToken("position");
  a.scale = r.vec3("scale");
  a.visible = r.flag("visible");
  a.collidable = r.flag("collidable");
  a.collisionGroup = r.group("collisionGroup");
  a.collisionMask = r.group("collisionMask");
  // An empty list (`-` or nothing after `=`) gives no state, like no key.
  a.hasCoordinate = r.has("generalizedCoordinate") && r.numbers("generalizedCoordinate", a.generalizedCoordinate) &&
                    !a.generalizedCoordinate.empty();
  a.hasVelocity = r.has("generalizedVelocity") && r.numbers("generalizedVelocity", a.generalizedVelocity) &&
                  !a.generalizedVelocity.empty();
  a.semanticClass = r.str("semanticClass");
  parentOf_[idx] = a.parentId;
  s_.articulated.push_back(std::move(a));
}

void Builder::resolveArticulated() {
  for (std::size_t n = 0; n < s_.articulated.size(); ++n) {
    Articulated& a = s_.articulated[n];
    const Written& w = written_[n];
    for (std::size_t i = 0; i < s_.articulatedResources.size(); ++i)  // the last of that id or name
      if (s_.articulatedResources[i].id == a.resourceRef || s_.articulatedResources[i].name == a.resourceRef)
        a.resource = static_cast<int>(i);
    if (a.resource < 0) continue;
    const ArticulatedResource& res = s_.articulatedResources[static_cast<std::size_t>(a.resource)];
    a.resourceRecord = res.recordIndex;
    if (!w.source) a.sourcePath = res.path;
    if (!w.directory) a.resourceDirectory = res.resourceDirectory;
    if (!w.modules) a.modules = res.modules;
    if (!w.order) a.jointOrder = res.jointOrder;
    if (!w.noParent) a.doNotCollideWithParent = res.doNotCollideWithParent;
    if (!w.convexify) a.convexifyCollisionMeshes = res.convexifyCollisionMeshes;
  }
}

void Builder::readArticulatedIk(const RecordReader& r, int idx) {
  std::string ref = r.str("articulated");
  Articulated* owner = lastNamed(s_.articulated, ref);
  if (!owner) {
    orphan(r, "articulated");
    return;
  }
  ArticulatedIk k;
  k.recordIndex = idx;
  k.frame = r.str("frame");
  k.target = r.vec3("target", Eigen::Vector3d::Zero());
  k.enabled = r.flag("enabled");
  k.useOrientation = r.flag("useOrientation");
  Eigen::Quaterniond q = toQuat(r.quat("orientation"));
  k.orientation = q.norm() > 1e-12 ? q.normalized() : Eigen::Quaterniond::Identity();
  k.maxIterations = static_cast<int>(r.integer("maxIterations"));
  k.positionTolerance = r.number("positionTolerance");
  k.orientationTolerance = r.number("orientationTolerance");
  k.orientationWeight = r.number("orientationWeight");
  k.damping = r.number("damping");
  k.stepSize = r.number("stepSize");
  k.maxStep = r.number("maxStep");
  k.svdTolerance = r.number("svdTolerance");
  k.finiteDifferenceStep = r.number("finiteDifferenceStep");
  k.transposeGain = r.number("transposeGain");
  k.applyBestOnFailure = r.flag("applyBestOnFailure");
  k.enforceJointLimits = r.flag("enforceJointLimits");
  k.inverseMethod = r.name("inverseMethod");
  owner->ik.push_back(std::move(k));
}

}  // namespace rscene::scene_build
