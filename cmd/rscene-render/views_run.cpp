#include "rscene-render/views_run.hpp"

#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <thread>

#include "core/text.hpp"
#include "render/camera.hpp"
#include "render/limits.hpp"
#include "render/view.hpp"
#include "render/view_output.hpp"
#include "render/views.hpp"
#include "robot/trajectory_read.hpp"
#include "rscene-render/image_writer.hpp"
#include "scene/reader.hpp"
#include "scene/sensor_check.hpp"

namespace rscene::render_cli {
namespace {

using Clock = std::chrono::steady_clock;
using render::Pass;
using render::View;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

volatile std::sig_atomic_t interrupted = 0;

// One image a view writes per frame: the pattern its path comes from.
struct Output {
  std::size_t view = 0;
  Pass pass = Pass::Color;
  std::string pattern;
};

render::OutputFields fieldsOf(const View& v, Pass pass, std::uint64_t frame, double time) {
  render::OutputFields f;
  f.name = render::fileNameOf(v.name);
  f.id = v.id.empty() ? "" : render::fileNameOf(v.id);
  f.kind = render::passName(pass);
  f.frame = frame;
  appendNumber(f.time, time);
  return f;
}

class ViewsRun {
 public:
  ViewsRun(const ViewsOptions& o, Prepared& p) : opt_(o), p_(p) {}

  int run() {
    if (!selectViews() || !checkSizes() || !planOutputs()) return cli::kTrouble;
    std::unique_ptr<std::istream> trajectoryStream;
    std::optional<robot::TrajectoryReader> reader;
    std::string trajectoryName = opt_.trajectory == "-" ? "<stdin>" : opt_.trajectory;
    if (!opt_.trajectory.empty()) {
      if (opt_.trajectory != "-") {
        auto file = std::make_unique<std::ifstream>(opt_.trajectory, std::ios::binary);
        if (!*file) {
          cli::error("cannot open trajectory '" + opt_.trajectory + "': " + std::strerror(errno));
          return cli::kTrouble;
        }
        trajectoryStream = std::move(file);
      }
      reader.emplace(trajectoryStream ? *trajectoryStream : std::cin, trajectoryName);
    }

    auto context = openContext(opt_.backend, opt_.verbose);
    if (!context) return cli::kTrouble;
    Diagnostics diags;
    // One frame: round shapes tessellated for these views, as a single
    // camera's render is (same pixels).  Along a trajectory the views move:
    // create() tessellates for any view.
    std::vector<Camera> lod;
    for (const View& v : views_) lod.push_back(v.camera);
    auto renderer = reader ? render::Renderer::create(p_.renderScene, p_.renderOptions, diags)
                           : render::createRenderer(p_.renderScene, p_.renderOptions, diags, std::move(lod));
    if (!print(diags) || !renderer) return cli::kTrouble;
    cli::stopOnInterrupt(&interrupted);
    // Encoding and writing overlap drawing; llvmpipe draws on the other cores.
    unsigned cores = std::max(2u, std::thread::hardware_concurrency());
    ImageWriter writer(std::min(cores - 1, 8u), render::segmentationLegendJson(p_.renderScene));
    auto tRun = Clock::now();

    robot::TrajectoryPoser poser(p_.scene, p_.renderScene.robotModels);
    robot::BodyPoses poses = rest_;
    robot::TrajectoryFrame frame;
    std::uint64_t written = 0;
    bool progress = !opt_.verbose && isatty(2);
    for (;;) {
      if (interrupted) {
        writer.finish();
        return cli::kInterrupted;
      }
      double time = 0;
      if (reader) {
        if (!reader->next(frame, diags)) {
          if (!print(diags) || reader->failed()) return cli::kTrouble;
          break;
        }
        if (frame.index % opt_.every != 0) continue;
        time = frame.time;
        if (!poser.apply(frame, trajectoryName, poses, diags)) {
          print(diags);
          return cli::kTrouble;
        }
        render::poseScene(p_.renderScene, {&poses.objects, &poses.compounds, &poses.robotLinks});
        renderer->updatePoses();
        render::poseViews(views_, p_.scene, p_.renderScene, sensors_, rest_, poses);
      }
      if (!drawFrame(*renderer, writer, written, time)) {
        writer.finish();
        return cli::kTrouble;
      }
      ++written;
      if (progress) std::fprintf(stderr, "\r%s: frame %llu", cli::toolName().c_str(), (unsigned long long)written);
      if (!reader) break;
    }
    bool ok = writer.finish();
    if (progress) std::fputc('\n', stderr);
    if (opt_.verbose) report(*renderer, writer, written, since(tRun));
    return ok ? cli::kSuccess : cli::kTrouble;
  }

 private:
  bool print(Diagnostics& diags) {
    cli::hintStdinPaths(p_.input, p_.baseDir, diags);
    cli::printDiagnostics(diags, p_.input.display, p_.input.text, p_.color);
    bool ok = !hasErrors(diags);
    diags.clear();
    return ok;
  }

  // The views to draw: every enabled one (--all-cameras), or the one
  // --camera names (a sensor too), or the first enabled camera, or auto.
  bool selectViews() {
    Diagnostics diags;
    sensors_ = robot::collectSensors(p_.document, p_.scene, p_.renderScene.robotModels, diags);
    rest_ = robot::restPoses(p_.scene, p_.renderScene.robotModels);
    std::vector<View> all = render::collectViews(p_.document, p_.scene, p_.renderScene, sensors_, rest_, diags);
    if (!print(diags)) return false;
    if (opt_.allCameras) {
      for (View& v : all)
        if (v.camera.enabled) views_.push_back(std::move(v));
      if (views_.empty()) {
        cli::error("--all-cameras: the scene has no enabled camera or camera-like sensor");
        return false;
      }
      return true;
    }
    int chosen = -1;
    if (opt_.camera.empty()) {
      for (std::size_t i = 0; i < all.size() && chosen < 0; ++i)
        if (!all[i].sensor && all[i].camera.enabled) chosen = static_cast<int>(i);
    } else if (opt_.camera != "auto") {
      chosen = render::findView(all, opt_.camera);
      if (chosen < 0) {
        std::string err;
        Camera unused;
        render::chooseCamera(p_.renderScene, opt_.camera, unused, &err);  // its "did you mean" for cameras
        cli::error(err);
        return false;
      }
    }
    if (chosen >= 0) {
      views_.push_back(std::move(all[static_cast<std::size_t>(chosen)]));
      return true;
    }
    View v;  // the automatic three-quarter view of today's rscene-render
    int w = opt_.width > 0 ? opt_.width : 1280, h = opt_.height > 0 ? opt_.height : 720;
    v.camera = render::autoCamera(p_.renderScene, double(w) / h);
    v.camera.width = w;
    v.camera.height = h;
    v.camera.enabled = true;
    v.name = "auto";
    v.passes = {Pass::Color};
    views_.push_back(std::move(v));
    return true;
  }

  // Camera records take --width/--height (else their own size, else
  // 1280x720); a sensor keeps its own, which its intrinsics are written for.
  bool checkSizes() {
    Diagnostics diags;
    for (View& v : views_) {
      if (v.sensor) {
        std::string problem = render::imageSizeProblem(v.camera.width, v.camera.height, opt_.maxPixels);
        if (problem.empty()) continue;
        if (v.recordIndex >= 0) {
          RecordReader r(p_.document, static_cast<std::size_t>(v.recordIndex), diags);
          r.error("width", "RS9013", "sensor image " + problem);
        } else {
          cli::error("sensor '" + v.name + "': image " + problem);
          return false;
        }
        continue;
      }
      int w = opt_.width > 0 ? opt_.width : v.camera.width > 0 ? v.camera.width : 1280;
      int h = opt_.height > 0 ? opt_.height : v.camera.height > 0 ? v.camera.height : 720;
      if (opt_.width > 0 && opt_.height > 0) {
        if (std::string problem = render::imageSizeProblem(w, h, opt_.maxPixels); !problem.empty()) {
          cli::error("--width/--height: " + problem);
          return false;
        }
      } else if (!render::checkCameraImageSize(p_.document, v.camera, w, h, opt_.maxPixels, diags)) {
        continue;
      }
      v.camera.width = w;
      v.camera.height = h;
    }
    return print(diags);
  }

  // Every image's pattern, then every file of the first frame checked
  // before anything is drawn: no two the same, none writeOutput() would
  // refuse, none a scene's outputPath may not name.
  bool planOutputs() {
    const bool frames = !opt_.trajectory.empty();
    if (!opt_.output.empty()) {
      if (frames && !render::patternHas(opt_.output, "frame")) {
        cli::error("-o '" + opt_.output + "' has no {frame}: every frame of --trajectory would write the same file");
        return false;
      }
    }
    Diagnostics diags;
    for (std::size_t i = 0; i < views_.size(); ++i) {
      const View& v = views_[i];
      std::string pattern = opt_.output;
      if (pattern.empty()) {
        if (v.outputPath.empty() || v.outputPath == "-") {
          cli::error("nothing to write: give -o FILE (-o - for standard output), -o PATTERN or --reference FILE ('" +
                     v.name + "' has no outputPath)");
          return false;
        }
        if (std::string why = outputPathProblem(v.outputPath); !why.empty()) {
          RecordReader r(p_.document, static_cast<std::size_t>(v.recordIndex), diags);
          r.error("outputPath", render::code::kOutputPath,
                  "outputPath '" + v.outputPath + "' " + why + ": a scene may only write below the current folder",
                  "give -o PATTERN to write elsewhere");
          continue;
        }
        pattern = render::outputPathPattern(v.outputPath, v.passes.size() > 1, frames);
      }
      for (Pass pass : v.passes) outputs_.push_back({i, pass, pattern});
    }
    if (!print(diags)) return false;
    if (opt_.output == "-" && (outputs_.size() != 1 || outputs_[0].pass != Pass::Color)) {
      cli::error("-o - writes one color image; these views make " + std::to_string(outputs_.size()) +
                 " images and their files: give -o PATTERN such as 'out/{name}.{kind}.png'");
      return false;
    }
    std::vector<cli::NamedOutput> named;
    std::map<std::string, std::string> owners;  // path -> the view and kind writing it
    for (const Output& o : outputs_) {
      std::string path, err;
      if (!render::expandPattern(o.pattern, fieldsOf(views_[o.view], o.pass, 0, 0), path, &err)) {
        cli::error(err);
        return false;
      }
      std::string who = "'" + views_[o.view].name + "' (" + render::passName(o.pass) + ")";
      for (const std::string& file : filesOf(path, o.pass)) {
        auto [it, added] = owners.emplace(file, who);
        if (!added) {
          cli::error("two views would write '" + file + "': " + it->second + " and " + who +
                     "; use {name} and {kind} in -o, or give the records different outputPath [RS9048]");
          return false;
        }
        named.push_back({"-o", file});
      }
    }
    for (const auto& [file, who] : owners) makeParentFolder(file);
    return cli::checkOutputs(named);
  }

  static void makeParentFolder(const std::string& file) {
    std::filesystem::path parent = std::filesystem::path(file).parent_path();
    std::error_code ec;
    if (!parent.empty()) std::filesystem::create_directories(parent, ec);  // writeOutput reports what fails
  }

  bool drawFrame(render::Renderer& renderer, ImageWriter& writer, std::uint64_t frame, double time) {
    Diagnostics diags;
    std::size_t next = 0;
    for (std::size_t i = 0; i < views_.size(); ++i) {
      const View& v = views_[i];
      ImageJob job;
      auto t = Clock::now();
      if (!renderer.render(v, job.images, diags)) {
        print(diags);
        return false;
      }
      if (!print(diags)) return false;
      drawSeconds_ += since(t);
      for (; next < outputs_.size() && outputs_[next].view == i; ++next) {
        const Output& o = outputs_[next];
        std::string path, err;
        render::expandPattern(o.pattern, fieldsOf(v, o.pass, frame, time), path, &err);  // checked by planOutputs
        job.outputs.emplace_back(std::move(path), o.pass);
      }
      if (!writer.submit(std::move(job))) return false;
    }
    return true;
  }

  void report(const render::Renderer& renderer, const ImageWriter& writer, std::uint64_t frames, double seconds) const {
    render::RenderTimings t = renderer.timings();
    double perView = frames && !views_.empty() ? drawSeconds_ / double(frames * views_.size()) : 0;
    char line[400];
    std::snprintf(line, sizeof line,
                  "%s: %zu view(s) x %llu frame(s), %zu files in %.3f s; upload %.3f s, drawing %.3f s (%.4f s "
                  "per view per frame); on %u thread(s) beside it: encoding %.3f s, writing %.3f s\n",
                  cli::toolName().c_str(), views_.size(), (unsigned long long)frames, writer.filesWritten(), seconds,
                  t.uploadSeconds, drawSeconds_, perView, writer.threads(), writer.encodeSeconds(),
                  writer.writeSeconds());
    std::cerr << line;
  }

  const ViewsOptions& opt_;
  Prepared& p_;
  std::vector<robot::SensorSpec> sensors_;
  robot::BodyPoses rest_;
  std::vector<View> views_;
  std::vector<Output> outputs_;  // grouped by view, in view order
  double drawSeconds_ = 0;
};

}  // namespace

bool wantsViews(const ViewsOptions& o, bool referenceGiven, bool cameraRecord) {
  if (o.allCameras || !o.trajectory.empty() || !cameraRecord) return true;
  if (referenceGiven) return false;
  return o.output.empty() || o.output.find('{') != std::string::npos;
}

int renderViews(const ViewsOptions& options, Prepared& prepared) { return ViewsRun(options, prepared).run(); }

std::unique_ptr<render::GlContext> openContext(const std::string& backend, bool verbose) {
  render::Backend b = backend == "gpu"   ? render::Backend::Gpu
                      : backend == "cpu" ? render::Backend::Cpu
                                         : render::Backend::Auto;
  std::string err;
  auto context = render::GlContext::create(b, &err);
  if (!context) {
    cli::error("cannot create an OpenGL context (--backend " + backend + "): " + err);
    return nullptr;
  }
  if (verbose) {
    const render::ContextInfo& i = context->info();
    std::cerr << cli::toolName() << ": backend " << i.backend << " via EGL " << i.platform
              << (i.device.empty() ? "" : " " + i.device) << ", EGL vendor " << i.eglVendor << ", GL vendor "
              << i.vendor << ", renderer " << i.renderer << ", " << i.version << '\n';
  }
  return context;
}

}  // namespace rscene::render_cli
