// Which views rscene-render draws, at what size, and which images
// (view_select.hpp).
#include "render/view_select.hpp"

#include <algorithm>
#include <string_view>

#include "core/codes.hpp"
#include "core/suggest.hpp"
#include "render/camera.hpp"
#include "render/limits.hpp"
#include "render/views.hpp"
#include "scene/reader.hpp"

namespace rscene::render {
namespace {

std::string ambiguous(const std::vector<View>& all, const std::vector<int>& found, const ViewRequest& request,
                      const ViewSources& sources) {
  std::string list;
  for (int i : found) {
    const View& v = all[static_cast<std::size_t>(i)];
    list += (list.empty() ? "" : "; ") + std::string("'") + v.name + "'" + (v.id.empty() ? "" : " (id " + v.id + ")") +
            ", " + declaredAt(v, sources);
  }
  return "--camera '" + request.camera + "' names " + std::to_string(found.size()) + " views: " + list +
         "; select one by its record's id, or rename the record";
}

// No view by that name: a sensor that is no view (a LiDAR, an IMU) says
// so; else the closest view's name, or the views there are.
std::string unknownView(const std::vector<View>& all, const ViewRequest& request, const ViewSources& sources) {
  const std::string& selector = request.camera;
  std::string message = "no camera or camera-like sensor with path or id '" + selector + "'";
  for (const robot::SensorSpec& s : sources.sensors) {
    bool named = s.name == selector || (!s.id.empty() && s.id == selector) ||
                 (!s.name.empty() && s.name[0] == '/' && s.name.compare(1, std::string::npos, selector) == 0);
    if (named && !robot::cameraLike(s.kind)) {
      message = "'" + s.name + "' is a sensor of kind " + s.kindName +
                ", not a view (rscene-render draws cameras and camera-like sensors; rscene-sim --sensors records it)";
      break;
    }
  }
  if (all.empty()) return message + "; the scene has no view (leave out --camera, or use --camera auto)";
  // Paths compare by their last part: a shared /World/ is no likeness.
  auto last = [](std::string_view p) { return p.substr(p.rfind('/') + 1); };
  const bool isPath = selector.find('/') != std::string::npos;
  std::vector<std::string_view> names;
  for (const View& v : all) names.push_back(isPath ? last(v.name) : std::string_view(v.id));
  std::string near = closestName(isPath ? last(selector) : std::string_view(selector), names);
  if (!near.empty() && message[0] != '\'') {
    const View& v = all[static_cast<std::size_t>(std::find(names.begin(), names.end(), near) - names.begin())];
    return message + "; did you mean '" + (isPath ? v.name : v.id) + "'?";
  }
  std::string list;
  for (std::size_t i = 0; i < all.size() && i < 8; ++i) list += (i ? ", " : "") + all[i].name;
  return message + "; the views of the scene: " + list + (all.size() > 8 ? ", ..." : "");
}

bool has(const View& v, Pass p) { return std::find(v.passes.begin(), v.passes.end(), p) != v.passes.end(); }

}  // namespace

std::string declaredAt(const View& v, const ViewSources& sources) {
  const std::string what = v.sensor ? "sensor" : "camera";
  const Document& doc = sources.document;
  if (v.recordIndex >= 0 && static_cast<std::size_t>(v.recordIndex) < doc.records.size())
    return "the " + what + " record at " + sources.display + ":" +
           std::to_string(doc.records[static_cast<std::size_t>(v.recordIndex)].line);
  if (v.sensorIndex >= 0 && static_cast<std::size_t>(v.sensorIndex) < sources.sensors.size()) {
    const robot::SensorSpec& s = sources.sensors[static_cast<std::size_t>(v.sensorIndex)];
    std::string robot;
    for (const Articulated& a : sources.scene.articulated)
      if (a.recordIndex == s.robotRecord) robot = " of robot '" + a.path + "'";
    return "a URDF sensor" + robot + " (" + s.file + ":" + std::to_string(s.line) + ")";
  }
  return "a " + what;
}

std::vector<View> selectViews(std::vector<View> all, const ViewRequest& request, const ViewSources& sources,
                              ViewFindings& findings) {
  std::vector<View> views;
  if (request.allCameras) {
    for (View& v : all)
      if (v.camera.enabled) views.push_back(std::move(v));
    if (views.empty()) findings.error = "--all-cameras: the scene has no enabled camera or camera-like sensor";
    return views;
  }
  int chosen = -1;
  if (request.lookAt) {
    ImageSize size = cameraImageSize(Camera{}, request.width, request.height);
    View v;
    v.camera = lookAtCamera(request.lookFrom, request.lookTo, request.lookFov, size.width, size.height);
    v.name = "look-at";
    v.passes = {Pass::Color};
    views.push_back(std::move(v));
    return views;
  }
  if (request.camera.empty()) {
    for (std::size_t i = 0; i < all.size() && chosen < 0; ++i)
      if (!all[i].sensor && all[i].camera.enabled) chosen = static_cast<int>(i);
  } else if (request.camera != "auto") {
    std::vector<int> found = findViews(all, request.camera);
    if (found.size() != 1) {
      findings.error = found.empty() ? unknownView(all, request, sources) : ambiguous(all, found, request, sources);
      return views;
    }
    chosen = found[0];
  }
  if (chosen >= 0) {
    views.push_back(std::move(all[static_cast<std::size_t>(chosen)]));
    return views;
  }
  View v;  // the automatic three-quarter view: no size of its own
  ImageSize size = cameraImageSize(Camera{}, request.width, request.height);
  v.camera = autoCamera(sources.renderScene, double(size.width) / size.height);
  v.camera.width = size.width;
  v.camera.height = size.height;
  v.camera.enabled = true;
  v.name = "auto";
  v.passes = {Pass::Color};
  views.push_back(std::move(v));
  return views;
}

void sizeViews(std::vector<View>& views, const ViewRequest& request, const ViewSources& sources,
               ViewFindings& findings) {
  const bool flags = request.width > 0 || request.height > 0;
  for (View& v : views) {
    if (v.sensor) {
      if (flags)
        findings.warnings.push_back("--width/--height: sensor '" + v.name + "' keeps its own size, " +
                                    std::to_string(v.camera.width) + "x" + std::to_string(v.camera.height) +
                                    " (its intrinsics are written for it)");
      std::string problem = imageSizeProblem(v.camera.width, v.camera.height, request.maxPixels);
      if (problem.empty()) continue;
      if (v.recordIndex < 0) {
        // A robot's sensor-set sensor: at its <sensor> element.
        Diagnostic d;
        d.severity = Severity::Error;
        d.code = rs::RS9013;
        d.message = "sensor '" + v.name + "': image " + problem;
        d.hint = "raise --max-pixels, or give the sensor a smaller resolution";
        if (v.sensorIndex >= 0 && static_cast<std::size_t>(v.sensorIndex) < sources.sensors.size()) {
          const robot::SensorSpec& spec = sources.sensors[static_cast<std::size_t>(v.sensorIndex)];
          d.file = spec.file;
          d.line = spec.line > 0 ? static_cast<std::uint32_t>(spec.line) : 0;
        }
        findings.diagnostics.push_back(std::move(d));
        continue;
      }
      RecordReader r(sources.document, static_cast<std::size_t>(v.recordIndex), findings.diagnostics);
      r.error("width", rs::RS9013, "sensor image " + problem);
      continue;
    }
    ImageSize size = cameraImageSize(v.camera, request.width, request.height);
    // A size the flags gave is a usage error, one the record gave an error
    // at its width field.
    if (request.width > 0 && request.height > 0) {
      if (std::string problem = imageSizeProblem(size.width, size.height, request.maxPixels); !problem.empty()) {
        findings.error = "--width/--height: " + problem;
        return;
      }
    } else if (!checkCameraImageSize(sources.document, v.camera, size.width, size.height, request.maxPixels,
                                     findings.diagnostics)) {
      continue;
    }
    v.camera.width = size.width;
    v.camera.height = size.height;
  }
}

std::string keepOneImage(View& v, bool reference) {
  if (reference) {
    if (v.sensor)
      return "--reference compares a camera record's color image; '" + v.name +
             "' is a sensor: write its images with -o and compare those files";
    if (!has(v, Pass::Color))
      return "--reference compares a color image; camera '" + v.name + "' has renderMode " + v.camera.renderMode +
             ", which makes none: write its images with -o and compare those files";
  }
  if (v.passes.size() > 1 && has(v, Pass::Color)) v.passes = {Pass::Color};
  return {};
}

std::vector<std::string> unseenViewWarnings(const std::vector<View>& views, const RenderScene& scene) {
  std::vector<std::string> out;
  for (const View& v : views) {
    if (!viewProblem(v).empty()) continue;
    Eigen::Matrix4d m = viewProjection(v);
    auto seen = [&](const auto& list) {
      return std::any_of(list.begin(), list.end(), [&](const auto& x) { return boxInFrustum(m, x.bounds); });
    };
    if (seen(scene.drawables) || seen(scene.terrains) || seen(scene.instanced) || seen(scene.pointClouds)) continue;
    out.push_back(std::string(v.sensor ? "sensor '" : "camera '") + v.name + "' sees none of the scene's geometry");
  }
  return out;
}

}  // namespace rscene::render
