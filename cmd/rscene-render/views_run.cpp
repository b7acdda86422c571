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

#include "core/text.hpp"
#include "render/image.hpp"
#include "render/output_plan.hpp"
#include "render/view.hpp"
#include "render/view_output.hpp"
#include "render/view_select.hpp"
#include "render/views.hpp"
#include "robot/trajectory_read.hpp"
#include "rscene-render/image_writer.hpp"
#include "scene/reader.hpp"
#include "scene/sensor_check.hpp"
#include "rscene-render/baseline.hpp"

namespace rscene::render_cli {
namespace {

using Clock = std::chrono::steady_clock;
using render::Pass;
using render::View;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

volatile std::sig_atomic_t interrupted = 0;

class ViewsRun {
 public:
  ViewsRun(const ViewsOptions& o, Prepared& p) : opt_(o), p_(p) {}

  // A stop signal: the tool ends by it, or a batch (returnOnSignal) says
  // how far it got first.
  int stopped() const { return opt_.returnOnSignal ? cli::kInterrupted : cli::endBySignal(interrupted); }

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
    if (opt_.planOnly) {
      *opt_.planOnly = plan_.files;
      return cli::kSuccess;
    }
    // A view that sees nothing at rest: a trajectory may still bring something into it.
    if (!reader && !opt_.quiet)
      for (const std::string& w : render::unseenViewWarnings(views_, p_.renderScene)) cli::warning(w);

    auto tStart = Clock::now();
    std::unique_ptr<render::GlContext> ownContext;
    std::unique_ptr<render::GlContext>& context = opt_.context ? *opt_.context : ownContext;
    if (!context) context = openContext(opt_.backend, opt_.verbose);
    if (!context) return cli::kTrouble;
    double startSeconds = since(tStart);
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
    bool progress = reader && !opt_.verbose && isatty(2);  // frames of a trajectory
    for (;;) {
      if (interrupted) {
        writer.finish();
        return stopped();
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
    // The frames written stay, each one whole.  A still whose images are
    // all written is done: in a batch it counts as finished.
    if (interrupted && (reader || !ok || !opt_.returnOnSignal)) return stopped();
    double encodeSeconds = writer.encodeSeconds();
    std::string referencePng;
    if (ok && reference()) {
      auto t = Clock::now();
      referencePng = render::encodePng(referenceImage_);
      encodeSeconds += since(t);
    }
    if (opt_.verbose) {
      if (views_.size() == 1 && !reader)
        reportOne(*renderer, startSeconds, encodeSeconds);
      else
        report(*renderer, writer, written, since(tRun));
    }
    if (!ok) return cli::kTrouble;
    if (!reference()) return cli::kSuccess;
    return checkBaseline(referenceImage_, referencePng, opt_.baseline);
  }

 private:
  bool print(Diagnostics& diags) {
    if (opt_.quiet)
      diags.erase(std::remove_if(diags.begin(), diags.end(),
                                 [](const Diagnostic& d) { return d.severity != Severity::Error; }),
                  diags.end());
    cli::hintStdinPaths(p_.input, p_.baseDir, diags);
    cli::printDiagnostics(diags, p_.input.display, p_.input.text, p_.color);
    bool ok = !hasErrors(diags);
    diags.clear();
    return ok;
  }

  bool reference() const { return !opt_.baseline.reference.empty(); }

  render::ViewRequest request() const {
    render::ViewRequest r;
    r.allCameras = opt_.allCameras;
    r.camera = opt_.camera;
    r.width = opt_.width;
    r.height = opt_.height;
    r.maxPixels = opt_.maxPixels;
    r.lookAt = opt_.lookAt;
    r.lookFrom = opt_.lookFrom;
    r.lookTo = opt_.lookTo;
    r.lookFov = opt_.lookFov;
    return r;
  }

  render::ViewSources sources() const {
    return {p_.document, p_.scene, p_.renderScene, sensors_, p_.input.display};
  }

  // Prints what a step found; false when it refuses the run.
  bool print(render::ViewFindings& found) {
    if (!opt_.quiet)
      for (const std::string& w : found.warnings) cli::warning(w);
    if (!found.error.empty()) {
      cli::error(found.error);
      return false;
    }
    return print(found.diagnostics);
  }

  // The views to draw (render::selectViews()).  A single view written to
  // one file (-o FILE, --reference) keeps the one image a file holds
  // (render::keepOneImage()).
  bool selectViews() {
    Diagnostics diags;
    sensors_ = robot::collectSensors(p_.document, p_.scene, p_.renderScene.robotModels, diags);
    rest_ = robot::restPoses(p_.scene, p_.renderScene.robotModels);
    std::vector<View> all = render::collectViews(p_.document, p_.scene, p_.renderScene, sensors_, rest_, diags);
    if (!print(diags)) return false;
    render::ViewFindings found;
    views_ = render::selectViews(std::move(all), request(), sources(), found);
    if (!print(found)) return false;
    const bool oneFile = !opt_.output.empty() && opt_.output.find('{') == std::string::npos;
    if (views_.size() == 1 && !opt_.allCameras && (oneFile || reference())) {
      if (std::string why = render::keepOneImage(views_[0], reference()); !why.empty()) {
        cli::error(why);
        return false;
      }
    }
    return true;
  }

  // Camera records take --width/--height (else their own size, else the
  // default); a sensor keeps its own (render::sizeViews()).
  bool checkSizes() {
    render::ViewFindings found;
    render::sizeViews(views_, request(), sources(), found);
    return print(found);
  }

  // Where every image goes (render::planOutputs()), checked before
  // anything is drawn; then the folders they go in, and the files as
  // writeOutput() would see them.
  bool planOutputs() {
    render::ViewFindings found;
    render::OutputRequest request{opt_.output, !opt_.trajectory.empty(), reference()};
    if (!render::planOutputs(views_, request, sources(), plan_, found)) {
      print(found);
      return false;
    }
    if (opt_.planOnly) return true;  // a batch's first pass: checked with the other scenes' (main.cpp)
    std::vector<cli::NamedOutput> named;
    for (const std::string& file : plan_.files) {
      makeParentFolder(file);
      named.push_back({"-o", file});
    }
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
      if (reference()) referenceImage_ = job.images.color;
      for (; next < plan_.outputs.size() && plan_.outputs[next].view == i; ++next) {
        const render::PlannedOutput& o = plan_.outputs[next];
        job.outputs.emplace_back(render::outputPathAt(o, v, frame, time), o.pass);
      }
      if (!writer.submit(std::move(job))) return false;
    }
    return true;
  }

  void report(const render::Renderer& renderer, const ImageWriter& writer, std::uint64_t frames, double seconds) const {
    render::RenderTimings t = renderer.timings();
    double perView = frames && !views_.empty() ? drawSeconds_ / double(frames * views_.size()) : 0;
    char line[600];
    std::snprintf(line, sizeof line,
                  "%s: %zu view(s) x %llu frame(s), %zu files in %.3f s; upload %.3f s, drawing %.3f s (%.4f s "
                  "per view per frame, post-processing %.3f s of it; shadow passes %.3f s, lit layers %.3f s); "
                  "on %u thread(s) beside it: encoding %.3f s, writing %.3f s; %llu jittered view(s), %llu shadow "
                  "map(s) drawn, %llu instance(s) left out as hidden\n",
                  cli::toolName().c_str(), views_.size(), (unsigned long long)frames, writer.filesWritten(), seconds,
                  t.uploadSeconds, drawSeconds_, perView, t.postSeconds, t.shadowSeconds, t.drawSeconds,
                  writer.threads(), writer.encodeSeconds(), writer.writeSeconds(),
                  (unsigned long long)t.jitteredViews, (unsigned long long)t.shadowMapsDrawn,
                  (unsigned long long)t.occludedInstances);
    std::cerr << line;
  }

  // The one view's line: where the time of one image went (issue 13).
  void reportOne(const render::Renderer& renderer, double startSeconds, double encodeSeconds) const {
    render::RenderTimings t = renderer.timings();
    const Camera& c = views_[0].camera;
    char line[480];
    std::snprintf(line, sizeof line,
                  "%s: %dx%d, %zu objects, %zu robots; start-up %.3f s, scene build %.3f s, upload %.3f s, "
                  "shadow passes %.3f s, drawing %.3f s, post-processing %.3f s, png encoding %.3f s; %llu jittered "
                  "view(s), %llu shadow map(s) drawn, %llu instance(s) left out as hidden\n",
                  cli::toolName().c_str(), c.width, c.height, p_.renderScene.drawables.size(), p_.renderScene.robots,
                  startSeconds, p_.buildSeconds, t.uploadSeconds, t.shadowSeconds, t.drawSeconds, t.postSeconds,
                  encodeSeconds, (unsigned long long)t.jitteredViews, (unsigned long long)t.shadowMapsDrawn,
                  (unsigned long long)t.occludedInstances);
    std::cerr << line;
  }

  const ViewsOptions& opt_;
  Prepared& p_;
  std::vector<robot::SensorSpec> sensors_;
  robot::BodyPoses rest_;
  std::vector<View> views_;
  render::OutputPlan plan_;
  render::Image referenceImage_;  // the color image --reference compares
  double drawSeconds_ = 0;
};

}  // namespace

int renderViews(const ViewsOptions& options, Prepared& prepared) { return ViewsRun(options, prepared).run(); }

volatile std::sig_atomic_t& stopFlag() { return interrupted; }

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
