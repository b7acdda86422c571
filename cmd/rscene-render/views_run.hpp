// rscene-render's one drawing pipeline: the views chosen (--all-cameras,
// --camera, the scene's first enabled camera, the automatic view: a single
// camera is one view, render/view_select.hpp), their images written to -o
// (a file or a pattern) or the records' outputPath, --trajectory frames, and
// the --reference comparison.  The scene is built and uploaded once; every
// selected view is drawn for every frame.
#pragma once
#include <Eigen/Core>
#include <csignal>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "core/document.hpp"
#include "render/gl_context.hpp"
#include "render/render_scene.hpp"
#include "render/renderer.hpp"
#include "rscene-render/baseline.hpp"

namespace rscene::render_cli {

struct ViewsOptions {
  bool allCameras = false;
  std::string camera;      // --camera: a camera's or sensor's path or id, "auto", or "" (the first enabled camera)
  std::string output;      // -o FILE or PATTERN; "" = each record's outputPath
  std::string trajectory;  // --trajectory FILE, "-" = standard input; "" = the scene's own state
  std::uint64_t every = 1;
  bool lookAt = false;  // --camera-position/--look-at/--fov (render::ViewRequest)
  Eigen::Vector3d lookFrom = Eigen::Vector3d::Zero(), lookTo = Eigen::Vector3d::UnitX();
  double lookFov = 50;
  int width = 0, height = 0;  // --width/--height: camera records only (a sensor's intrinsics fix its size)
  std::uint64_t maxPixels = 0;
  std::string backend = "auto";
  bool verbose = false;
  BaselineOptions baseline;  // reference "" = no --reference; else one camera record's color image is compared
  // A batch of scenes (main.cpp): its first pass only plans, the files
  // each scene would write put here, nothing drawn and no folder made;
  // its second pass prints errors only (quiet) and draws on the one
  // context kept here (opened by the first scene that draws).
  std::vector<std::string>* planOnly = nullptr;
  bool quiet = false;
  std::unique_ptr<render::GlContext>* context = nullptr;
  // A stop signal returns cli::kInterrupted (stopFlag() holds the signal)
  // instead of ending the tool: a batch says how far it got first.
  bool returnOnSignal = false;
};

// The flag a stop signal sets while views are drawn (cli::stopOnInterrupt).
volatile std::sig_atomic_t& stopFlag();

// The scene read and built by main.cpp's run(), and how to report.
struct Prepared {
  const cli::Input& input;
  const Document& document;
  const Scene& scene;
  render::RenderScene& renderScene;
  render::RenderOptions renderOptions;
  std::string baseDir;
  bool color = false;
  double buildSeconds = 0;  // reading and building the scene, for --verbose
};

// Draws what the options select; returns the exit status (the messages
// printed).
int renderViews(const ViewsOptions& options, Prepared& prepared);

// The OpenGL context of --backend; prints the error (and with --verbose the
// device) itself.  Null on failure.
std::unique_ptr<render::GlContext> openContext(const std::string& backend, bool verbose);

}  // namespace rscene::render_cli
