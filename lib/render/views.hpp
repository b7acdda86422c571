// Which views rscene-render draws: one per camera record and one per
// camera-like sensor (sensor records and the sensor sets of the robots'
// URDFs), each with its passes, intrinsics, noise and pose; and where their
// images go (output patterns, the records' outputPath).
//
// A view rides on what its record names: a camera on the body its
// parentGroupId is (an object, compound or robot), a sensor on its
// parentObject/parentLink (robot::sensorPose).  poseViews() moves the views
// with the bodies along a trajectory.
#pragma once
#include "core/codes.hpp"
#include "scene/sensor_check.hpp"
#include <cstdint>
#include <string>
#include <vector>

#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "render/render_scene.hpp"
#include "render/view.hpp"
#include "robot/sensors.hpp"
#include "scene/scene.hpp"

namespace rscene::render {

namespace code {
inline constexpr const char* kRenderMode = rs::RS9045;  // camera renderMode not drawn as written (colour instead)
inline constexpr const char* kOutputPath = rs::RS9048;  // outputPath a scene may not write (absolute, '..')
}  // namespace code

// The passes of a camera record's renderMode (canonical, as the schema
// reads it): rgb -> Color, depth -> Depth, segmentation -> Segmentation,
// rgb_depth -> Color + Depth.  False for any other value (Color then).
bool passesOfRenderMode(const std::string& renderMode, std::vector<Pass>& out);

// Every camera record (in file order, disabled ones too: View::camera.enabled
// says) then every camera-like sensor (robot::cameraLike; in the order of
// `sensors`), placed at `rest` (robot::restPoses(): the poses the scene
// file gives, which camera records' poses are written against).  `scene` and `renderScene` are the same
// build (RenderScene::cameras has one entry per Scene::cameras).  A camera
// whose renderMode has no passes of its own gets Color and a RS9045
// warning at that field.
std::vector<View> collectViews(const Document& doc, const Scene& scene, const RenderScene& renderScene,
                               const std::vector<robot::SensorSpec>& sensors, const robot::BodyPoses& rest,
                               Diagnostics& diagnostics);

// Moves each view to the pose of what it rides on at `poses` (`scene`,
// `sensors` and `rest` as collectViews() had them).  A camera record on a
// body keeps its offset from the body at `rest`; a robot's camera rides on
// the robot's root link.
void poseViews(std::vector<View>& views, const Scene& scene, const RenderScene& renderScene,
               const std::vector<robot::SensorSpec>& sensors, const robot::BodyPoses& rest,
               const robot::BodyPoses& poses);

// The view `selector` names: a camera's or sensor's path ("<robot>/<set>/
// <sensor>" for a URDF sensor, with or without the leading '/'), or a
// record id.  -1 when none.
int findView(const std::vector<View>& views, const std::string& selector);

// Every view `selector` names, in order: more than one when a sensor
// record's path is also a URDF sensor's "<robot>/<set>/<sensor>" name, or
// one view's path is another's id (the caller says which are ambiguous).
std::vector<int> findViews(const std::vector<View>& views, const std::string& selector);

// --- Output names -------------------------------------------------------

// The fields of an output pattern (-o, outputPath).
struct OutputFields {
  std::string name;         // View::name without its leading '/', '/' -> '_', unsafe bytes -> '_'
  std::string id;           // the record id; the {name} when it has none
  std::string kind;         // rgb, depth, segmentation
  std::uint64_t frame = 0;  // rendered frame number, from 0, printed with 6 digits
  std::string time;         // simulated time, shortest round-trip ("0", "0.25")
};

// The {name} of a view name: no leading '/', every byte other than
// [A-Za-z0-9._-] replaced by '_', never "." or "..".
std::string fileNameOf(const std::string& viewName);

// Whether `pattern` uses field `field` ("frame" for "{frame}").
bool patternHas(const std::string& pattern, const char* field);

// `pattern` with {name}, {id}, {kind}, {frame} and {time} replaced; "{{"
// and "}}" are literal braces.  False with `error` on an unknown field or an
// unmatched brace.
bool expandPattern(const std::string& pattern, const OutputFields& fields, std::string& out, std::string* error);

// Why an image file name does not suit (.png or no extension): the scene
// model's rule (scene/sensor_check.hpp), which validate applies to every
// camera's outputPath too.
using rscene::imageExtensionProblem;

// The pattern a record's outputPath stands for, for a view with several
// passes or frames: ".{kind}" before the extension when `severalKinds` and
// it has no {kind}, ".{frame}" likewise when `severalFrames` and it has
// neither {frame} nor {time} (a trajectory's frames have increasing times,
// so {time} names each frame once) ("cam.png" ->
// "cam.{kind}.{frame}.png").  Non-colour passes of a one-pass view keep
// the path as written.  A path with no extension gains ".png" with the
// suffix ("noext" -> "noext.{kind}.png"): its images are PNG files.
std::string outputPathPattern(const std::string& outputPath, bool severalKinds, bool severalFrames);

}  // namespace rscene::render
