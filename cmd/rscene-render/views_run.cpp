#include "rscene-render/views_run.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
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

#include "core/suggest.hpp"
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

  // Whether --camera names one view only (the single-image path picks a
  // camera record by itself; a sensor of the same name makes it ambiguous).
  bool selectorUnique() {
    Diagnostics diags;  // what collectViews warns of is printed by no run of this one
    sensors_ = robot::collectSensors(p_.document, p_.scene, p_.renderScene.robotModels, diags);
    rest_ = robot::restPoses(p_.scene, p_.renderScene.robotModels);
    std::vector<View> all = render::collectViews(p_.document, p_.scene, p_.renderScene, sensors_, rest_, diags);
    std::vector<int> found = render::findViews(all, opt_.camera);
    if (found.size() <= 1) return true;
    cli::error(ambiguous(all, found));
    return false;
  }

  int run() {
    std::unique_ptr<std::istream> trajectoryStream;
    std::optional<robot::TrajectoryReader> reader;
    std::string trajectoryName = opt_.trajectory == "-" ? "<stdin>" : opt_.trajectory;
    if (!opt_.trajectory.empty()) {
      if (opt_.trajectory != "-") {
        // A directory opens as a stream and throws on the first read.
        std::error_code ec;
        if (std::filesystem::is_directory(opt_.trajectory, ec)) {
          cli::error(opt_.trajectory + ": is a directory");
          return cli::kTrouble;
        }
        auto file = std::make_unique<std::ifstream>(opt_.trajectory, std::ios::binary);
        if (!*file) {
          cli::error("cannot open trajectory '" + opt_.trajectory + "': " + std::strerror(errno));
          return cli::kTrouble;
        }
        trajectoryStream = std::move(file);
      }
      struct stat in {};
      if (opt_.trajectory == "-" && ::fstat(0, &in) == 0 && S_ISDIR(in.st_mode)) {
        cli::error("--trajectory -: standard input is a directory");  // reads would only say "empty"
        return cli::kTrouble;
      }
      // Lines as long as the scene's largest particle record needs.
      reader.emplace(trajectoryStream ? *trajectoryStream : std::cin, trajectoryName,
                     render::trajectoryLimits(p_.renderScene));
    }

    // After the trajectory opened: a folder of -o is made only for a run that can start.
    if (!selectViews() || !checkSizes() || !planOutputs()) return cli::kTrouble;

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

    robot::TrajectoryPoser poser(p_.scene, p_.renderScene.robotModels, render::particleCounts(p_.renderScene));
    robot::BodyPoses poses = rest_;
    robot::ParticlePositions particles;
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
        if (!poser.apply(frame, trajectoryName, poses, diags, &particles)) {
          print(diags);
          return cli::kTrouble;
        }
        render::poseScene(p_.renderScene, {&poses.objects, &poses.compounds, &poses.robotLinks, &particles});
        renderer->updatePoses();
        render::poseViews(views_, p_.scene, p_.renderScene, sensors_, rest_, poses);
        std::vector<Camera> cameras;
        for (const View& v : views_) cameras.push_back(v.camera);
        renderer->setParticleViews(cameras);
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
      std::vector<int> found = render::findViews(all, opt_.camera);
      if (found.size() > 1) {
        cli::error(ambiguous(all, found));
        return false;
      }
      if (found.empty()) {
        cli::error(unknownView(all));
        return false;
      }
      chosen = found[0];
    }
    if (chosen >= 0) {
      views_.push_back(std::move(all[static_cast<std::size_t>(chosen)]));
      if (opt_.reference && views_[0].sensor) {
        cli::error("--reference compares a camera record's color image; '" + views_[0].name +
                   "' is a sensor: write its images with -o and compare those files");
        return false;
      }
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

  // Where a view is declared, for messages: "the camera record at s.rscene:5",
  // "a URDF sensor of robot '/World/A' (sensors/cam.xml:3)".
  std::string declaredAt(const View& v) const {
    const std::string what = v.sensor ? "sensor" : "camera";
    if (v.recordIndex >= 0 && static_cast<std::size_t>(v.recordIndex) < p_.document.records.size())
      return "the " + what + " record at " + p_.input.display + ":" +
             std::to_string(p_.document.records[static_cast<std::size_t>(v.recordIndex)].line);
    if (v.sensorIndex >= 0 && static_cast<std::size_t>(v.sensorIndex) < sensors_.size()) {
      const robot::SensorSpec& s = sensors_[static_cast<std::size_t>(v.sensorIndex)];
      std::string robot;
      for (const Articulated& a : p_.scene.articulated)
        if (a.recordIndex == s.robotRecord) robot = " of robot '" + a.path + "'";
      return "a URDF sensor" + robot + " (" + s.file + ":" + std::to_string(s.line) + ")";
    }
    return "a " + what;
  }

  std::string ambiguous(const std::vector<View>& all, const std::vector<int>& found) const {
    std::string list;
    for (int i : found) {
      const View& v = all[static_cast<std::size_t>(i)];
      list += (list.empty() ? "" : "; ") + std::string("'") + v.name + "'" + (v.id.empty() ? "" : " (id " + v.id + ")") +
              ", " + declaredAt(v);
    }
    return "--camera '" + opt_.camera + "' names " + std::to_string(found.size()) + " views: " + list +
           "; select one by its record's id, or rename the record";
  }

  // No view by that name: a sensor that is no view (a LiDAR, an IMU) says
  // so; else the closest view's name, or the views there are.
  std::string unknownView(const std::vector<View>& all) const {
    std::string message = "no camera or camera-like sensor with path or id '" + opt_.camera + "'";
    for (const robot::SensorSpec& s : sensors_) {
      bool named = s.name == opt_.camera || (!s.id.empty() && s.id == opt_.camera) ||
                   (!s.name.empty() && s.name[0] == '/' && s.name.compare(1, std::string::npos, opt_.camera) == 0);
      if (named && !robot::cameraLike(s.kind)) {
        message = "'" + s.name + "' is a sensor of kind " + s.kindName +
                  ", not a view (rscene-render draws cameras and camera-like sensors; rscene-sim --sensors records it)";
        break;
      }
    }
    if (all.empty()) return message + "; the scene has no view (leave out --camera, or use --camera auto)";
    // Paths compare by their last part: a shared /World/ is no likeness.
    auto last = [](std::string_view p) { return p.substr(p.rfind('/') + 1); };
    const bool isPath = opt_.camera.find('/') != std::string::npos;
    std::vector<std::string_view> names;
    for (const View& v : all) names.push_back(isPath ? last(v.name) : std::string_view(v.id));
    std::string near = closestName(isPath ? last(opt_.camera) : std::string_view(opt_.camera), names);
    if (!near.empty() && message[0] != '\'') {
      const View& v = all[static_cast<std::size_t>(std::find(names.begin(), names.end(), near) - names.begin())];
      return message + "; did you mean '" + (isPath ? v.name : v.id) + "'?";
    }
    std::string list;
    for (std::size_t i = 0; i < all.size() && i < 8; ++i) list += (i ? ", " : "") + all[i].name;
    return message + "; the views of the scene: " + list + (all.size() > 8 ? ", ..." : "");
  }

  // Camera records take --width/--height (else their own size, else
  // 1280x720); a sensor keeps its own, which its intrinsics are written for.
  bool checkSizes() {
    Diagnostics diags;
    for (View& v : views_) {
      if (v.sensor && (opt_.width > 0 || opt_.height > 0))
        cli::warning("--width/--height: sensor '" + v.name + "' keeps its own size, " + std::to_string(v.camera.width) +
                     "x" + std::to_string(v.camera.height) + " (its intrinsics are written for it)");
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
      // Frames have increasing times: {time} names each one once too.
      if (frames && !render::patternHas(opt_.output, "frame") && !render::patternHas(opt_.output, "time")) {
        cli::error("-o '" + opt_.output +
                   "' has no {frame} or {time}: every frame of --trajectory would write the same file");
        return false;
      }
    }
    Diagnostics diags;
    for (std::size_t i = 0; i < views_.size(); ++i) {
      const View& v = views_[i];
      std::string pattern = opt_.output;
      if (pattern.empty()) {
        if (v.outputPath.empty() || v.outputPath == "-") {
          cli::error("nothing to write: '" + v.name + "' has no outputPath; give -o FILE (-o - for standard output)" +
                     (v.sensor ? std::string() : ", --reference FILE") + " or -o PATTERN such as '{name}.{kind}.png'");
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
    std::map<std::string, std::size_t> owners;  // path -> the output (index) writing it
    for (std::size_t k = 0; k < outputs_.size(); ++k) {
      const Output& o = outputs_[k];
      std::string path, err;
      if (!render::expandPattern(o.pattern, fieldsOf(views_[o.view], o.pass, 0, 0), path, &err)) {
        cli::error(err);
        return false;
      }
      if (std::string why = render::imageExtensionProblem(path); !why.empty()) {
        if (!opt_.output.empty()) {
          cli::error("-o '" + opt_.output + "': " + why + "; end -o with .png");
          return false;
        }
        if (views_[o.view].recordIndex < 0) {
          cli::error("'" + views_[o.view].name + "': " + why);
          return false;
        }
        RecordReader r(p_.document, static_cast<std::size_t>(views_[o.view].recordIndex), diags);
        r.error("outputPath", render::code::kOutputPath, "outputPath: " + why, "end outputPath with .png");
        return print(diags);
      }
      for (const std::string& file : filesOf(path, o.pass)) {
        auto [it, added] = owners.emplace(file, k);
        if (!added) {
          cli::error(collision(file, outputs_[it->second], o));
          return false;
        }
        named.push_back({"-o", file});
      }
    }
    for (const auto& [file, who] : owners) makeParentFolder(file);
    return cli::checkOutputs(named);
  }

  // Why two images would go to one file, and what to change: one view's
  // several passes, two views of one name, or a pattern without {name}.
  std::string collision(const std::string& file, const Output& first, const Output& second) const {
    const View& a = views_[first.view];
    const View& b = views_[second.view];
    std::string head = "two images would go to '" + file + "': ";
    if (&first == &second)  // the image and the .npy or .json written beside it
      return head + "the " + std::string(render::passName(first.pass)) + " image of '" + a.name +
             "' is PNG and its companion file goes beside it under the same name; end the pattern with .png [RS9048]";
    if (first.view == second.view) {
      std::string kinds;
      for (Pass p : a.passes) kinds += (kinds.empty() ? "" : ", ") + std::string(render::passName(p));
      return head + "view '" + a.name + "' makes several images (" + kinds + "); put {kind} in -o, such as '" +
             render::outputPathPattern(first.pattern, true, false) + "' [RS9048]";
    }
    if (a.name == b.name) {
      bool ids = !a.id.empty() || !b.id.empty();
      return head + "two views are named '" + a.name + "': " + declaredAt(a) + " and " + declaredAt(b) +
             "; rename the record" + (ids && !render::patternHas(opt_.output, "id") ? ", or use {id} in -o" : "") +
             " [RS9048]";
    }
    std::string fix = opt_.output.empty() ? "give the records different outputPath, or -o PATTERN with {name}"
                                          : "use {name} and {kind} in -o, or give the records different outputPath";
    return head + "'" + a.name + "' (" + render::passName(first.pass) + ") and '" + b.name + "' (" +
           render::passName(second.pass) + "); " + fix + " [RS9048]";
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
      View v = views_[i];
      // Sensor noise is drawn anew at each frame, as a real sensor's is:
      // frame k uses the seed plus k times an odd constant, so frame 0 is
      // the record's seed and the same seed gives the same sequence.
      v.noiseSeed += frame * 0x9E3779B97F4A7C15ull;
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
                  "per view per frame, post-processing %.3f s of it); on %u thread(s) beside it: encoding %.3f s, "
                  "writing %.3f s\n",
                  cli::toolName().c_str(), views_.size(), (unsigned long long)frames, writer.filesWritten(), seconds,
                  t.uploadSeconds, drawSeconds_, perView, t.postSeconds, writer.threads(), writer.encodeSeconds(),
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

bool cameraUnique(const ViewsOptions& options, Prepared& prepared) {
  if (options.camera.empty() || options.camera == "auto") return true;
  return ViewsRun(options, prepared).selectorUnique();
}

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
