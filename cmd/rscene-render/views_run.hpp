// rscene-render's many-view run: --all-cameras, a sensor chosen by
// --camera, an output pattern or the records' outputPath, and --trajectory
// frames.  The scene is built and uploaded once; every selected view is
// drawn for every frame.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "common/cli.hpp"
#include "core/document.hpp"
#include "render/gl_context.hpp"
#include "render/render_scene.hpp"
#include "render/renderer.hpp"

namespace rscene::render_cli {

struct ViewsOptions {
  bool allCameras = false;
  std::string camera;      // --camera: a camera's or sensor's path or id, "auto", or "" (the first enabled camera)
  std::string output;      // -o pattern; "" = each record's outputPath
  std::string trajectory;  // --trajectory FILE, "-" = standard input; "" = the scene's own state
  std::uint64_t every = 1;
  int width = 0, height = 0;  // --width/--height: camera records only (a sensor's intrinsics fix its size)
  std::uint64_t maxPixels = 0;
  std::string backend = "auto";
  bool verbose = false;
  bool reference = false;  // --reference given: a sensor view cannot take it (one camera record's color image)
};

// Whether the flags ask for the many-view run rather than the single
// colour image of one camera record (today's behaviour, which --reference
// and -o FILE keep): --all-cameras, --trajectory, an -o pattern, no -o
// (the records' outputPath), or a --camera that is no camera record (a
// sensor: `cameraRecord` false).
bool wantsViews(const ViewsOptions& options, bool referenceGiven, bool cameraRecord);

// The scene read and built by main.cpp's run(), and how to report.
struct Prepared {
  const cli::Input& input;
  const Document& document;
  const Scene& scene;
  render::RenderScene& renderScene;
  render::RenderOptions renderOptions;
  std::string baseDir;
  bool color = false;
};

int renderViews(const ViewsOptions& options, Prepared& prepared);

// False, with the error printed, when --camera names more than one view (a
// camera record and a sensor of the same path, or a path that is another's
// id): the single-image path must not pick one silently.
bool cameraUnique(const ViewsOptions& options, Prepared& prepared);

// The OpenGL context of --backend; prints the error (and with --verbose the
// device) itself.  Null on failure.
std::unique_ptr<render::GlContext> openContext(const std::string& backend, bool verbose);

}  // namespace rscene::render_cli
