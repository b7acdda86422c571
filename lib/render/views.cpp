#include "render/views.hpp"

#include <algorithm>
#include <optional>

#include "core/schema.hpp"
#include "core/text.hpp"
#include "scene/reader.hpp"

namespace rscene::render {
namespace {

// A sensor of a robot's sensor set may leave a number out (0); it then has
// the sensor record's default, read from the schema table (the one place
// that knows them).
double sensorDefault(const char* key) {
  const KindDef* kind = Schema::get().kind("sensor");
  const FieldDef* f = kind ? kind->key(key) : nullptr;
  std::optional<double> v = f && f->defaultValue ? parseNumber(*f->defaultValue) : std::nullopt;
  return v.value_or(0);
}

void addPass(std::vector<Pass>& passes, Pass p) {
  for (Pass q : passes)
    if (q == p) return;
  passes.push_back(p);
}

View sensorView(const robot::SensorSpec& s, int index) {
  View v;
  v.name = s.name;
  v.id = s.id;
  v.sensor = true;
  v.recordIndex = s.recordIndex;
  v.sensorIndex = index;
  const SensorParams& p = s.params;
  Camera& c = v.camera;
  c.recordIndex = s.recordIndex;
  c.path = s.name;
  c.id = s.id;
  c.width = p.width > 0 ? p.width : static_cast<int>(sensorDefault("width"));
  c.height = p.height > 0 ? p.height : static_cast<int>(sensorDefault("height"));
  // A sensor set gives RaiSim's horizontal_fov; horizontalFov > 0 wins.
  c.verticalFov = p.verticalFov > 0 ? p.verticalFov : sensorDefault("verticalFov");
  c.horizontalFov = p.horizontalFov;
  c.nearPlane = p.nearPlane > 0 ? p.nearPlane : sensorDefault("nearPlane");
  c.farPlane = p.farPlane > c.nearPlane ? p.farPlane : std::max(sensorDefault("farPlane"), c.nearPlane * 2);
  c.renderMode = s.kindName;
  c.projection = "perspective";
  c.enabled = s.enabled;
  c.outputPath = s.outputPath;
  c.mount = s.mount;
  // The calibration when the record gives one (sensor_check.hpp: all four
  // written, fx and fy positive); all four written as 0 means none.
  if (p.fx > 0 && p.fy > 0) {
    v.fx = p.fx;
    v.fy = p.fy;
    v.cx = p.cx;
    v.cy = p.cy;
  }
  v.noiseMean = p.noiseMean;
  v.noiseStddev = p.noiseStddev;
  v.noiseSeed = p.noiseSeed;
  v.outputPath = s.outputPath;
  switch (s.kind) {
    case robot::SensorKind::Rgb:
      v.passes = {Pass::Color};
      break;
    case robot::SensorKind::Depth:
      v.passes = {Pass::Depth};
      break;
    case robot::SensorKind::Segmentation:
      v.passes = {Pass::Segmentation};
      break;
    case robot::SensorKind::RgbDepth:
      v.passes = {Pass::Color, Pass::Depth};
      break;
    default:
      v.passes = {Pass::Color};
      break;
  }
  if (p.segmentation) addPass(v.passes, Pass::Segmentation);
  return v;
}

// The rest pose of the body a camera record rides on (its root link for a
// robot); nullopt for the world.
std::optional<Pose> bodyPose(const Mount& m, const RenderScene& rs, const robot::BodyPoses& poses) {
  auto at = [](const auto& list, int i) -> decltype(&list[0]) {
    return i >= 0 && static_cast<std::size_t>(i) < list.size() ? &list[static_cast<std::size_t>(i)] : nullptr;
  };
  switch (m.kind) {
    case Mount::Kind::Object:
      if (auto p = at(poses.objects, m.index)) return *p;
      break;
    case Mount::Kind::Compound:
      if (auto p = at(poses.compounds, m.index)) return *p;
      break;
    case Mount::Kind::Articulated: {
      auto links = at(poses.robotLinks, m.index);
      auto model = at(rs.robotModels, m.index);
      if (links && model && *model)
        if (auto p = at(*links, (*model)->root)) return *p;
      break;
    }
    case Mount::Kind::World:
      break;
  }
  return std::nullopt;
}

}  // namespace

bool passesOfRenderMode(const std::string& mode, std::vector<Pass>& out) {
  out.clear();
  if (mode == "rgb")
    out = {Pass::Color};
  else if (mode == "depth")
    out = {Pass::Depth};
  else if (mode == "segmentation")
    out = {Pass::Segmentation};
  else if (mode == "rgb_depth")
    out = {Pass::Color, Pass::Depth};
  else {
    out = {Pass::Color};
    return false;
  }
  return true;
}

std::vector<View> collectViews(const Document& doc, const Scene& scene, const RenderScene& rs,
                               const std::vector<robot::SensorSpec>& sensors, const robot::BodyPoses& rest,
                               Diagnostics& diagnostics) {
  std::vector<View> views;
  // A camera or sensor riding on a robot --allow-missing-assets left out
  // gives no view, whoever asks (robot::leaveOutMissingRobots warned).
  auto onLeftOut = [&](const Mount& m) {
    return m.kind == Mount::Kind::Articulated && m.index >= 0 &&
           static_cast<std::size_t>(m.index) < scene.articulated.size() &&
           scene.articulated[static_cast<std::size_t>(m.index)].leftOut;
  };
  for (std::size_t i = 0; i < scene.cameras.size() && i < rs.cameras.size(); ++i) {
    if (onLeftOut(scene.cameras[i].mount)) continue;
    View v;
    v.camera = rs.cameras[i];  // near/far made usable
    v.name = v.camera.path;
    v.id = v.camera.id;
    v.recordIndex = v.camera.recordIndex;
    v.outputPath = v.camera.outputPath;
    if (!passesOfRenderMode(v.camera.renderMode, v.passes) && v.camera.recordIndex >= 0) {
      RecordReader r(doc, static_cast<std::size_t>(v.camera.recordIndex), diagnostics);
      r.error("renderMode", code::kRenderMode,
              "renderMode '" + v.camera.renderMode + "' is not one rscene-render draws; the color image is drawn",
              "use rgb, depth, segmentation or rgb_depth", Severity::Warning);
    }
    views.push_back(std::move(v));
  }
  for (std::size_t i = 0; i < sensors.size(); ++i)
    if (robot::cameraLike(sensors[i].kind) && !onLeftOut(sensors[i].mount))
      views.push_back(sensorView(sensors[i], static_cast<int>(i)));
  poseViews(views, scene, rs, sensors, rest, rest);
  return views;
}

void poseViews(std::vector<View>& views, const Scene& scene, const RenderScene& rs,
               const std::vector<robot::SensorSpec>& sensors, const robot::BodyPoses& rest,
               const robot::BodyPoses& poses) {
  for (View& v : views) {
    if (v.sensorIndex >= 0 && static_cast<std::size_t>(v.sensorIndex) < sensors.size()) {
      v.camera.world = robot::sensorPose(sensors[static_cast<std::size_t>(v.sensorIndex)], scene, poses);
      continue;
    }
    // A camera record: its world pose in the file, carried by its body.
    const Camera* record = nullptr;
    for (const Camera& c : scene.cameras)
      if (c.recordIndex == v.recordIndex) record = &c;
    if (!record) continue;
    std::optional<Pose> from = bodyPose(record->mount, rs, rest), to = bodyPose(record->mount, rs, poses);
    // A body where the file puts it leaves the camera where the file puts
    // it, to the last bit (the pose a single camera has always had).
    bool moved =
        from && to && (from->position != to->position || from->orientation.coeffs() != to->orientation.coeffs());
    v.camera.world = moved ? *to * (from->inverse() * record->world) : record->world;
  }
}

int findView(const std::vector<View>& views, const std::string& selector) {
  std::vector<int> all = findViews(views, selector);
  return all.empty() ? -1 : all.front();
}

std::vector<int> findViews(const std::vector<View>& views, const std::string& selector) {
  std::vector<int> found;
  if (selector.empty()) return found;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const std::string& n = views[i].name;
    bool samePath = n == selector || (!n.empty() && n[0] == '/' && n.compare(1, std::string::npos, selector) == 0);
    if (samePath || (!views[i].id.empty() && views[i].id == selector)) found.push_back(static_cast<int>(i));
  }
  return found;
}

std::string fileNameOf(const std::string& viewName) {
  std::string out;
  std::size_t start = viewName.find_first_not_of('/');
  if (start == std::string::npos) return "_";
  for (std::size_t i = start; i < viewName.size(); ++i) {
    unsigned char c = static_cast<unsigned char>(viewName[i]);
    bool keep =
        (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '-';
    out += keep ? static_cast<char>(c) : '_';
  }
  if (out.find_first_not_of('.') == std::string::npos) out.assign(out.size(), '_');  // never "." or ".."
  return out;
}

bool patternHas(const std::string& pattern, const char* field) {
  return pattern.find("{" + std::string(field) + "}") != std::string::npos;
}

bool expandPattern(const std::string& pattern, const OutputFields& f, std::string& out, std::string* error) {
  out.clear();
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    char c = pattern[i];
    if (c == '}') {
      if (i + 1 < pattern.size() && pattern[i + 1] == '}') {
        out += '}';
        ++i;
        continue;
      }
      if (error) *error = "unmatched '}' in output pattern '" + pattern + "' (write }} for a brace)";
      return false;
    }
    if (c != '{') {
      out += c;
      continue;
    }
    if (i + 1 < pattern.size() && pattern[i + 1] == '{') {
      out += '{';
      ++i;
      continue;
    }
    std::size_t end = pattern.find('}', i);
    if (end == std::string::npos) {
      if (error) *error = "unmatched '{' in output pattern '" + pattern + "' (write {{ for a brace)";
      return false;
    }
    std::string field = pattern.substr(i + 1, end - i - 1);
    if (field == "name")
      out += f.name;
    else if (field == "id")
      out += f.id.empty() ? f.name : f.id;
    else if (field == "kind")
      out += f.kind;
    else if (field == "time")
      out += f.time;
    else if (field == "frame") {
      std::string n = std::to_string(f.frame);
      if (n.size() < 6) out += std::string(6 - n.size(), '0');
      out += n;
    } else {
      if (error) *error = "unknown field {" + field + "} in output pattern (fields: {name} {id} {kind} {frame} {time})";
      return false;
    }
    i = end;
  }
  return true;
}


std::string outputPathPattern(const std::string& path, bool severalKinds, bool severalFrames) {
  std::string suffix;
  if (severalKinds && !patternHas(path, "kind")) suffix += ".{kind}";
  if (severalFrames && !patternHas(path, "frame") && !patternHas(path, "time")) suffix += ".{frame}";
  if (suffix.empty()) return path;
  std::size_t slash = path.find_last_of('/');
  std::size_t dot = path.find_last_of('.');
  // No extension: ".png", else "noext.{kind}" would read as a file of kind "rgb".
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash) || dot == slash + 1)
    return path + suffix + ".png";
  return path.substr(0, dot) + suffix + path.substr(dot);
}

}  // namespace rscene::render
