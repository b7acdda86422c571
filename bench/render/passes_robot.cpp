// rscene-render-passes-bench: where a frame's time goes on a real robot,
// on tests/render/passes_robot_test's scene (anymal_passes.hpp: ANYmal C
// from ../shared at 640x480, a new pose each frame): RGB + depth +
// segmentation at the default samples, the same at one sample, color
// alone, depth + segmentation alone.  Prints seconds per frame, wall and
// CPU (llvmpipe's threads included: steadier on a shared machine), over
// frames 2..5 (the first compiles llvmpipe's shader variants), and the
// upload time; figures, never a verdict.  Skipped (exit 0) without
// ../shared; exit 1 when a frame does not render.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "anymal_passes.hpp"
#include "render/gl_context.hpp"

using namespace rscene;
using namespace rscene::render;

namespace {

double cpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

}  // namespace

int main() {
  if (!std::filesystem::exists(test::anymalUrdf())) {
    std::printf("render passes bench: no ../shared corpus; skipped\n");
    return 0;
  }
  std::string err;
  std::unique_ptr<GlContext> gl = GlContext::create(Backend::Cpu, &err);
  if (!gl) {
    std::fprintf(stderr, "render passes bench: no CPU EGL context: %s\n", err.c_str());
    return 1;
  }
  Diagnostics diags;
  std::unique_ptr<test::AnymalScene> s = test::makeAnymalScene(diags);
  if (!s) {
    std::fprintf(stderr, "render passes bench: the scene does not build: %s\n",
                 diags.empty() ? "" : diags.back().message.c_str());
    return 1;
  }
  const View all = test::anymalView();
  View oneSample = all;
  oneSample.samples = 1;
  View color = all;
  color.passes = {Pass::Color};
  View depthSeg = all;
  depthSeg.passes = {Pass::Depth, Pass::Segmentation};

  std::printf("== ANYmal C, 640x480, CPU backend (llvmpipe): seconds per frame over frames 2..5 ==\n");
  const int frames = 5;
  for (const View& view : {all, oneSample, color, depthSeg}) {
    double wall = 0, cpu = 0;
    for (int f = 0; f < frames; ++f) {
      auto t0 = std::chrono::steady_clock::now();
      double c0 = cpuSeconds();
      test::poseFrame(*s, f, frames);
      ViewImages im;
      if (!s->renderer->render(view, im, diags)) {
        std::fprintf(stderr, "render passes bench: %s\n", diags.empty() ? "render failed" : diags.back().message.c_str());
        return 1;
      }
      if (f > 0) {
        wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        cpu += cpuSeconds() - c0;
      }
    }
    std::string passes;
    for (Pass p : view.passes) passes += std::string(passes.empty() ? "" : " + ") + passName(p);
    std::printf("%-34s (color at %d samples): %.4f s per frame, %.4f s of CPU\n", passes.c_str(),
                view.samples ? view.samples : s->options.samples, wall / (frames - 1), cpu / (frames - 1));
  }
  std::printf("upload (create): %.3f s\n", s->renderer->timings().uploadSeconds);
  return 0;
}
