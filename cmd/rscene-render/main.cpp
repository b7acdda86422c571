// rscene-render: headless EGL render of a scene's views (one camera, every
// camera and camera-like sensor; RGB, depth, segmentation) to PNG, at rest
// or along a trajectory, with an optional comparison of one color image
// against a baseline: the flags and the scene here, the one drawing
// pipeline in views_run.cpp and lib/render (view_select.hpp).
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <chrono>
#include <csignal>
#include <optional>
#include <cstdio>
#include <filesystem>
#include <map>

#include "common/batch.hpp"
#include "common/cli.hpp"
#include "core/assets.hpp"
#include "core/loader.hpp"
#include "core/project.hpp"
#include "core/scene_pattern.hpp"
#include "render/camera.hpp"
#include "render/limits.hpp"
#include "render/render_scene.hpp"
#include "render/views.hpp"
#include "render/renderer.hpp"
#include "rscene-render/baseline.hpp"
#include "rscene-render/views_run.hpp"

namespace {

using namespace rscene;
using Clock = std::chrono::steady_clock;

struct Options {
  std::vector<std::string> files;
  std::string file = "-", output, stdinName, baseDir, camera, backend = "auto";
  std::string cameraPosition, lookAt;  // --camera-position, --look-at: "X,Y,Z"
  double fov = 50;
  int width = 0, height = 0, samples = 4;
  std::uint64_t maxPixels = render::kDefaultMaxPixels;
  render::DrawLimits limits;
  std::uint64_t maxTexturePixels = render::RenderOptions{}.maxTexturePixels;
  bool transparent = false, allowMissing = false, verbose = false, noPost = false;
  render_cli::BaselineOptions baseline;
  render_cli::ViewsOptions views;
};

// "X,Y,Z" of --camera-position and --look-at: three numbers (finite or
// not: lookAtProblem() says which is wrong).  False when it is not three.
bool parsePoint(const std::string& text, Eigen::Vector3d& out) {
  std::size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    std::size_t end = text.find(',', start);
    if ((end == std::string::npos) != (i == 2)) return false;
    std::string part = text.substr(start, end == std::string::npos ? std::string::npos : end - start);
    char* stop = nullptr;
    errno = 0;
    out[i] = std::strtod(part.c_str(), &stop);
    if (part.empty() || *stop != '\0' || std::isspace(static_cast<unsigned char>(part[0]))) return false;
    start = end + 1;
  }
  return true;
}

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::string skippedLine(const std::map<std::string, int>& skipped) {
  std::string s;
  for (const auto& [kind, n] : skipped) s += (s.empty() ? "" : ", ") + kind + " (" + std::to_string(n) + ")";
  return s;
}

// Without errors, `diags` less its warnings and notes (a batch's second
// pass: the first printed them).
void keepErrors(Diagnostics& diags, bool quiet) {
  if (!quiet) return;
  diags.erase(std::remove_if(diags.begin(), diags.end(), [](const Diagnostic& d) { return d.severity != Severity::Error; }),
              diags.end());
}

// One scene: read, built and drawn (or with views.planOnly, its outputs
// planned).  The views options are the run's, with a batch's -o expanded.
int run(const Options& opt, const render_cli::ViewsOptions& views) {
  bool color = cli::colorFor(2);
  cli::Input in;
  if (!cli::readInput(opt.file, opt.stdinName, in)) return cli::kTrouble;
  std::string text = in.text;
  LoadResult loaded = parse(std::move(text));
  keepErrors(loaded.diagnostics, views.quiet);
  cli::printDiagnostics(loaded.diagnostics, in.display, in.text, color);
  if (!loaded.ok()) return cli::kTrouble;

  auto tBuild = Clock::now();
  SceneOptions so;
  so.sceneDir = in.path.empty() ? "." : directoryOf(in.path);
  so.project = cli::projectPlace(in, opt.baseDir);
  so.baseDir = opt.baseDir;
  render::RenderOptions ro;
  ro.maxTexturePixels = opt.maxTexturePixels;
  // One cache for the scene's preparation (robot meshes, for their bounds)
  // and the drawing: every mesh and texture file is read once.
  asset::AssetCache assets(diskFileSystem(), render::assetLimits(ro));
  ro.assets = &assets;
  render::RenderScene scene;
  Scene model;
  Diagnostics diags;
  render::DrawLimits limits = opt.limits;
  limits.allowMissingAssets = opt.allowMissing;
  bool built = render::buildRenderScene(loaded.document, so, model, scene, diags, limits, &assets);
  cli::hintStdinPaths(in, opt.baseDir, diags);
  keepErrors(diags, views.quiet);
  cli::printDiagnostics(diags, in.display, in.text, color);
  if (!built) return cli::kTrouble;
  if (!scene.skipped.empty() && !views.quiet) cli::warning("skipped records it does not draw yet: " + skippedLine(scene.skipped));

  ro.samples = opt.samples;
  ro.transparent = opt.transparent;
  ro.allowMissingAssets = opt.allowMissing;
  ro.post = !opt.noPost;
  render_cli::Prepared prepared{in, loaded.document, model, scene, ro, opt.baseDir, color, since(tBuild)};
  return render_cli::renderViews(views, prepared);
}

// Several scenes (more than one operand, a folder, a project): each one's
// outputs named by -o with {stem}/{dir}; every output of every scene
// planned and checked before anything is drawn; then drawn one by one on
// one OpenGL context (its programs compiled once).  A scene that fails is
// named and the others go on; exit 2 when one failed.  A stop signal ends
// the batch after the scene being drawn (its frames whole), saying how far
// it got.
int runBatch(Options& opt, const std::vector<std::string>& scenes, bool operandsRead) {
  auto patternOf = [&](const std::string& file) { return withSceneFields(opt.output, sceneFields(file)); };
  std::vector<char> failed(scenes.size(), 0);
  auto fail = [&](std::size_t i) {
    failed[i] = 1;
    cli::error(scenes[i] + ": not rendered");
  };
  // First pass: the views and outputs of every scene, nothing drawn; then
  // every output checked as rscene-sim's batch checks its own (one rule in
  // cmd/common/batch.cpp): none is one of the scenes (by file identity, so
  // a hard link too; a pattern such as 'scenes/{stem}.rscene' would put
  // images where the scenes are), no two scenes write one file, and each
  // file is one a single run could write; their folders are made first.
  std::vector<cli::SceneOutputs> planned(scenes.size());
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    planned[i].scene = scenes[i];
    planned[i].file = scenes[i];
    render_cli::ViewsOptions views = opt.views;
    views.output = patternOf(scenes[i]);
    std::vector<std::string> files;
    views.planOnly = &files;
    Options one = opt;
    one.file = scenes[i];
    if (run(one, views) != cli::kSuccess) {
      fail(i);
      continue;
    }
    for (const std::string& f : files) planned[i].outputs.push_back({"-o", f});
  }
  // "" for checkBatchOutputs' in-place flag: an image never writes its
  // scene back.
  if (!cli::checkBatchOutputs(planned, {{"-o", opt.output}}, "")) return cli::kTrouble;  // nothing drawn
  // Second pass: drawn, on one context; the first pass printed the warnings.
  std::unique_ptr<render::GlContext> context;
  std::size_t done = 0, finished = 0, total = scenes.size();
  volatile std::sig_atomic_t& stop = render_cli::stopFlag();
  cli::stopOnInterrupt(&stop);
  {
    std::optional<cli::BatchProgress> progress;
    if (!opt.verbose) progress.emplace(total);
    for (std::size_t i = 0; i < scenes.size() && !stop; ++i) {
      if (failed[i]) {
        ++finished;
        continue;
      }
      if (progress) progress->scene(i);
      cli::batchReached(finished, total);
      render_cli::ViewsOptions views = opt.views;
      views.output = patternOf(scenes[i]);
      views.quiet = true;
      views.context = &context;
      views.returnOnSignal = true;
      Options one = opt;
      one.file = scenes[i];
      int rc = run(one, views);
      if (rc == cli::kInterrupted) break;  // the scenes drawn before it stay
      ++finished;
      if (rc == cli::kSuccess)
        ++done;
      else
        fail(i);
      if (stop) break;  // a signal after this scene's images were written
    }
  }
  cli::batchReached(total, total);
  if (stop) {
    cli::batchStopped(finished, total);
    return cli::endBySignal(stop);
  }
  std::vector<std::string> bad;
  for (std::size_t i = 0; i < scenes.size(); ++i)
    if (failed[i]) bad.push_back(scenes[i]);
  cli::batchSummary(total, done, bad, operandsRead ? 0 : 1, "rendered");
  return bad.empty() && operandsRead ? cli::kSuccess : cli::kTrouble;
}

// The many-view flags that do not go together; -1 when they do.
int checkViewFlags(const CLI::App& app, Options& opt) {
  render_cli::ViewsOptions& v = opt.views;
  auto refuse = [](const std::string& message) {
    cli::error(message);
    return static_cast<int>(cli::kTrouble);
  };
  if (v.allCameras && !opt.camera.empty()) return refuse("--all-cameras and --camera: give one of them");
  const bool lookAt = app.count("--look-at") || app.count("--camera-position");
  if (lookAt || app.count("--fov")) {
    if (!app.count("--look-at") || !app.count("--camera-position"))
      return refuse(std::string(app.count("--fov") && !lookAt ? "--fov" : app.count("--look-at") ? "--look-at" : "--camera-position") +
                    " needs --camera-position X,Y,Z and --look-at X,Y,Z together");
    if (!opt.camera.empty() || v.allCameras)
      return refuse(std::string("--camera-position/--look-at place a camera of their own: not with ") +
                    (v.allCameras ? "--all-cameras" : "--camera"));
    Eigen::Vector3d from, to;
    if (!parsePoint(opt.cameraPosition, from))
      return refuse("--camera-position '" + opt.cameraPosition + "': give three numbers X,Y,Z (metres, +z up)");
    if (!parsePoint(opt.lookAt, to)) return refuse("--look-at '" + opt.lookAt + "': give three numbers X,Y,Z (metres, +z up)");
    if (std::string why = render::lookAtProblem(from, to, opt.fov); !why.empty())
      return refuse("--camera-position/--look-at/--fov: " + why);
    v.lookAt = true;
    v.lookFrom = from;
    v.lookTo = to;
    v.lookFov = opt.fov;
  }
  if (app.count("--every") && v.trajectory.empty()) return refuse("--every needs --trajectory");
  if (v.trajectory == "-" && (opt.file == "-" || opt.file.empty()))
    return refuse("--trajectory - reads standard input, which the scene is read from: name the scene file");
  if (!opt.baseline.reference.empty() && (v.allCameras || !v.trajectory.empty()))
    return refuse("--reference compares one image: not with --all-cameras or --trajectory");
  v.camera = opt.camera;
  v.output = opt.output;
  v.width = opt.width;
  v.height = opt.height;
  v.maxPixels = opt.maxPixels;
  v.backend = opt.backend;
  v.verbose = opt.verbose;
  return -1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Render a .rscene scene headlessly (EGL, no window system) to a PNG image."};
  cli::setup(app, "rscene-render");
  Options opt;
  app.add_option("files", opt.files,
                 "Scene file; several, or folders to search for *.rscene (or Engine 2 projects), render a batch "
                 "(-o with {stem} or {dir}); none or - reads standard input")
      ->type_name("FILE");
  cli::addOutputOption(app, opt.output,
                       "Write the PNG to FILE (atomically; - writes standard output), or to a PATTERN with "
                       "{name} {id} {kind} {frame} {time} for many views and frames, {stem} {dir} for many scenes (default: each drawn record's outputPath)");
  app.add_option("--width", opt.width,
                 "Image width in pixels (default: the camera's, else " + std::to_string(render::kDefaultImageWidth) + ")")
      ->type_name("PIXELS")
      ->check(cli::range(1, render::kMaxImageSide));
  app.add_option("--height", opt.height,
                 "Image height in pixels (default: the camera's, else " + std::to_string(render::kDefaultImageHeight) +
                     ")")
      ->type_name("PIXELS")
      ->check(cli::range(1, render::kMaxImageSide));
  app.add_option("--samples", opt.samples, "Multisample anti-aliasing samples per pixel, 1 to 64 (default 4)")
      ->type_name("N")
      ->check(cli::range(1, 64));
  app.add_option("--max-pixels", opt.maxPixels,
                 "Largest image, width x height, before anything is drawn (default 16777216 = 4096x4096, at most 268435456)")
      ->type_name("N")
      ->check(cli::range(1, 1LL << 28));
  app.add_option("--max-instances", opt.limits.maxInstances,
                 "Most instances drawn in all: instanced_visual instances, terrain foliage and granular particles, "
                 "after maxRenderedInstances (default 1000000)")
      ->type_name("N")
      ->check(cli::range(0, 1LL << 32));
  app.add_option("--max-texture-pixels", opt.maxTexturePixels,
                 "Largest texture or HDR background decoded; a larger one is not drawn (default 67108864)")
      ->type_name("N")
      ->check(cli::range(1, 1LL << 28));
  app.add_flag("--transparent", opt.transparent, "Leave the background transparent (alpha 0)");
  app.add_flag("--no-post", opt.noPost,
               "Skip the post-processing the scene asks for (bloom, SSAO, FXAA, auto exposure, depth of field); "
               "exposure, tone mapping and gamma stay");
  app.add_option("--backend", opt.backend, "auto (GPU if one answers, else CPU), gpu (EGL device) or cpu (llvmpipe)")
      ->check(CLI::IsMember({"auto", "gpu", "cpu"}));
  app.add_option("--camera", opt.camera,
                 "Camera or camera-like sensor by path or id (ROBOT/SET/SENSOR for a URDF sensor), or auto for a "
                 "three-quarter view of everything")
      ->type_name("PATH|ID|auto");
  app.add_option("--camera-position", opt.cameraPosition,
                 "Draw from a camera at X,Y,Z (metres, +z up) looking at --look-at, instead of the scene's camera")
      ->type_name("X,Y,Z");
  app.add_option("--look-at", opt.lookAt, "With --camera-position, the point X,Y,Z the camera looks at (image centre)")
      ->type_name("X,Y,Z");
  app.add_option("--fov", opt.fov, "With --look-at, the vertical field of view in degrees (default 50)")
      ->type_name("DEG");
  app.add_flag("--all-cameras", opt.views.allCameras,
               "Render every enabled camera record and camera-like sensor (URDF sensor sets too), in all of its passes");
  app.add_option("--trajectory", opt.views.trajectory,
                 "Render every frame of what rscene-sim --trajectory wrote (JSON Lines or CSV); - reads standard input")
      ->type_name("FILE");
  app.add_option("--every", opt.views.every, "With --trajectory, render every K-th frame (default 1: all)")
      ->type_name("K")
      ->check(cli::range(1, 1LL << 40));
  cli::addStdinFilename(app, opt.stdinName, true);
  cli::addBaseDir(app, opt.baseDir, "Resolve relative asset paths against DIR instead of the scene's folder");
  app.add_flag("--allow-missing-assets", opt.allowMissing,
               "Warn instead of failing on a missing asset: a missing mesh is drawn as a magenta box, a missing "
               "texture left out");
  app.add_option("--reference", opt.baseline.reference,
                 "Compare with baseline PNG FILE; exit 1 above --threshold or --fail-pixels; a missing FILE is "
                 "written")
      ->type_name("FILE");
  app.add_option("--threshold", opt.baseline.threshold,
                 "Largest accepted fraction (0..1) of pixels differing by more than 16/255 (default 0.01)")
      ->check(cli::fraction());
  app.add_option("--fail-pixels", opt.baseline.failPixels,
                 "With --reference, exit 1 when more than N pixels differ by more than --pixel-threshold: a small "
                 "object moved (default " + std::to_string(render::kLocalFailPixels) + ")")
      ->type_name("N")
      ->check(cli::range(0, 1LL << 40));
  app.add_option("--pixel-threshold", opt.baseline.pixelThreshold,
                 "The difference, in 1/255 of any channel, past which a pixel counts for --fail-pixels (default " +
                     std::to_string(render::kLocalPixelThreshold) + ")")
      ->type_name("T")
      ->check(cli::range(0, 255));
  app.add_option("--diff-output", opt.baseline.diffOutput, "With --reference, write a difference image to FILE")
      ->type_name("FILE");
  app.add_flag("-v,--verbose", opt.verbose, "Print the EGL device, GL renderer and timings on standard error");
  if (int rc = cli::parseArgs(app, argc, argv); rc >= 0) return rc;

  // Several scenes: a batch (runBatch()); one keeps the single-scene run.
  // A project alone is its default scene, as for the other one-scene
  // tools, unless -o names scenes ({stem}, {dir}): then all its scenes.
  if (opt.files.empty()) opt.files.push_back("-");
  std::vector<std::string> scenes;
  bool operandsRead = true;
  bool scenePattern = false;  // -o named this one scene by {stem}/{dir}: a pattern still (its folders are made)
  bool batch = opt.files.size() > 1;
  if (!batch && opt.files[0] != "-") {
    std::string root;
    if (isProject(opt.files[0], diskFileSystem(), root))
      batch = hasSceneFields(opt.output);
    else {
      std::error_code ec;
      batch = std::filesystem::is_directory(opt.files[0], ec);
    }
  }
  if (batch) {
    if (std::count(opt.files.begin(), opt.files.end(), "-")) {
      cli::error("standard input cannot be one of several scenes: name the files");
      return cli::kTrouble;
    }
    if (!hasSceneFields(opt.output)) {
      cli::error("-o: several scenes need an output pattern naming each one, with {stem} or {dir} (such as "
                 "-o 'thumbs/{stem}.png')");
      return cli::kTrouble;
    }
    if (!opt.views.trajectory.empty() || !opt.baseline.reference.empty()) {
      cli::error(std::string(opt.views.trajectory.empty() ? "--reference" : "--trajectory") +
                 " belongs to one scene: not with several");
      return cli::kTrouble;
    }
    cli::Operands operands = cli::expandOperands(opt.files);
    operandsRead = operands.ok;  // an unreadable folder is said, and the others are drawn
    scenes = std::move(operands.files);
  } else {
    opt.file = opt.files[0];
    if (hasSceneFields(opt.output)) {
      opt.output = withSceneFields(opt.output, sceneFields(opt.file));
      scenePattern = true;
    }
  }

  if (int rc = checkViewFlags(app, opt); rc >= 0) return rc;
  // A size that no scene can take is said once, before any scene is read.
  if (opt.width > 0 && opt.height > 0)
    if (std::string problem = render::imageSizeProblem(opt.width, opt.height, opt.maxPixels); !problem.empty()) {
      cli::error("--width/--height: " + problem);
      return cli::kTrouble;
    }
  for (const char* flag : {"--diff-output", "--fail-pixels", "--pixel-threshold"})
    if (app.count(flag) && opt.baseline.reference.empty()) {
      cli::error(std::string(flag) + " needs --reference");
      return cli::kTrouble;
    }
  // A reference that exists is an input no output may replace; one that
  // does not is where this render goes.
  bool referenceWritten = !opt.baseline.reference.empty() && !fileExistsOnDisk(opt.baseline.reference);
  // An -o pattern is checked file by file once the views are known.
  bool pattern = scenePattern || opt.output.find('{') != std::string::npos;
  if (!cli::checkOutputs({{"-o", pattern ? std::string() : opt.output},
                          {"--diff-output", opt.baseline.diffOutput},
                          {"--reference", opt.baseline.reference, referenceWritten}}))
    return cli::kTrouble;
  // Images are PNG whatever the name says: a .jpg name is refused, not
  // filled with PNG bytes.  A pattern's files are checked once expanded.
  for (const auto& [flag, file] : {std::pair<const char*, std::string>{"-o", pattern ? "" : opt.output},
                                   {"--diff-output", opt.baseline.diffOutput}}) {
    if (file.empty() || file == "-") continue;
    if (std::string why = render::imageExtensionProblem(file); !why.empty()) {
      cli::error(std::string(flag) + ": " + why + "; end " + flag + " with .png");
      return cli::kTrouble;
    }
  }
  opt.baseline.reportToStderr = opt.output == "-";
  opt.views.baseline = opt.baseline;
  if (batch) return runBatch(opt, scenes, operandsRead);
  return run(opt, opt.views);
}
