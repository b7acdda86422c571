// rscene-render's one drawing pipeline, the part that decides: which views
// a run draws, at what size, and which of their images.  A single camera
// (the scene's first enabled camera record, --camera NAME, the automatic
// view) is a view like those of --all-cameras: its renderMode, its own
// size and its outputPath follow the same rules however it was chosen.
//
// Nothing here prints or exits: errors and warnings come back as values
// for the driver to print.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "render/render_scene.hpp"
#include "render/renderer.hpp"
#include "render/view.hpp"
#include "robot/sensors.hpp"
#include "scene/scene.hpp"

namespace rscene::render {

// What the flags ask for.
struct ViewRequest {
  bool allCameras = false;    // every enabled view
  std::string camera;         // "": the first enabled camera record, else auto; "auto"; a path or id
  int width = 0, height = 0;  // --width/--height, 0 when not given: camera records and auto only
  std::uint64_t maxPixels = kDefaultMaxPixels;
  // The look-at form (--camera-position --look-at --fov): a view named
  // "look-at" drawn like the automatic one from lookAtCamera(); camera and
  // allCameras are then empty (the driver refuses both with it).
  bool lookAt = false;
  Eigen::Vector3d lookFrom = Eigen::Vector3d::Zero(), lookTo = Eigen::Vector3d::UnitX();
  double lookFov = 50;
};

// The scene the views come from, for choosing them and for messages.
struct ViewSources {
  const Document& document;
  const Scene& scene;
  const RenderScene& renderScene;
  const std::vector<robot::SensorSpec>& sensors;  // robot::collectSensors()
  std::string display;                            // the scene's name in messages ("s.rscene", "<stdin>")
};

// What a step found: a usage error (the tool's own message), warnings of
// the same kind, and findings at a record's field (file:line:col).
struct ViewFindings {
  std::string error;
  std::vector<std::string> warnings;
  Diagnostics diagnostics;
  bool ok() const { return error.empty() && !hasErrors(diagnostics); }
};

// The views to draw, from every view of the scene (collectViews()): every
// enabled one with allCameras (none is an error); else the one
// request.camera names (a disabled one or a sensor too; a name two views
// share is an error listing both); else the first enabled camera record;
// else, with request.lookAt, the look-at view; else, or with "auto", the automatic three-quarter view (autoCamera()) at
// cameraImageSize() of the request, drawing its color image.  Empty with
// findings.error set when none can be chosen.
std::vector<View> selectViews(std::vector<View> all, const ViewRequest& request, const ViewSources& sources,
                              ViewFindings& findings);

// Gives every view its image size: a camera record (and the automatic
// view) cameraImageSize(), checked against request.maxPixels (a size the
// flags gave is a usage error, one the record gave RS9013 at its width); a
// sensor keeps its own, which its intrinsics are written for (a warning
// when the flags give one; too large is RS9013 at its record, or an error
// for a URDF sensor).  Views stay unsized where a finding refuses them.
void sizeViews(std::vector<View>& views, const ViewRequest& request, const ViewSources& sources,
               ViewFindings& findings);

// Narrows the passes of a single view to the one image a single file
// holds, for -o FILE (no fields) and --reference: a view making several
// images among them the color image (renderMode rgb_depth) keeps the color
// image.  With `reference` the color image is required: a sensor, or a
// camera whose renderMode makes none (depth, segmentation), is an error
// (returned; "" when fine).  A view of one image keeps it: a depth
// camera's -o FILE is its 16-bit depth PNG (and the .npy beside it), as
// --all-cameras writes it.
std::string keepOneImage(View& view, bool reference);

// "camera '/World/Cam' sees none of the scene's geometry" for each sized
// view whose frustum holds no drawable, terrain, instance batch or point
// cloud (a sensor is called one).
std::vector<std::string> unseenViewWarnings(const std::vector<View>& views, const RenderScene& scene);

// Where a view is declared, for messages: "the camera record at
// s.rscene:5", "a URDF sensor of robot '/World/A' (sensors/cam.xml:3)".
std::string declaredAt(const View& view, const ViewSources& sources);

}  // namespace rscene::render
