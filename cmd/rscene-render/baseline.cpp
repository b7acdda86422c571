#include "rscene-render/baseline.hpp"

#include <cstdio>
#include <iostream>

#include "common/cli.hpp"
#include "core/assets.hpp"
#include "core/io.hpp"

namespace rscene::render_cli {

int checkBaseline(const render::Image& image, const std::string& png, const BaselineOptions& opt) {
  std::ostream& report = opt.reportToStderr ? std::cerr : std::cout;
  auto writePng = [](const std::string& path, const std::string& bytes) {
    return cli::writeOutput(path, [&](Sink& s) {
      s.write(bytes);
      return true;
    });
  };
  if (!fileExistsOnDisk(opt.reference)) {
    if (!writePng(opt.reference, png)) return cli::kTrouble;
    cli::warning("reference '" + opt.reference + "' did not exist; wrote this render there");
    return cli::kFindings;
  }
  std::string bytes, err;
  render::Image reference;
  if (!readFile(opt.reference, bytes, &err) || !render::decodePng(bytes, reference, &err)) {
    cli::error("cannot read reference '" + opt.reference + "': " + err);
    return cli::kTrouble;
  }
  render::Comparison c = render::compareImages(image, reference);
  if (!c.sameSize) {
    report << "size differs: render " << image.width << "x" << image.height << ", reference " << reference.width
           << "x" << reference.height << '\n';
    return cli::kFindings;
  }
  std::uint64_t strong = c.pixelsOver(opt.pixelThreshold);
  char line[320];
  std::snprintf(line, sizeof line,
                "difference %.6f (pixels off by more than %d/255), threshold %g, mean error %.6f, max %d/255; "
                "%llu pixel(s) off by more than %d/255, fail pixels %llu",
                c.differingFraction, render::kPixelTolerance, opt.threshold, c.meanAbsoluteError,
                c.maxChannelDifference, (unsigned long long)strong, opt.pixelThreshold,
                (unsigned long long)opt.failPixels);
  report << line << '\n';
  if (!opt.diffOutput.empty() && !writePng(opt.diffOutput, render::encodePng(c.diff))) return cli::kTrouble;
  return c.differingFraction > opt.threshold || strong > opt.failPixels ? cli::kFindings : cli::kSuccess;
}

}  // namespace rscene::render_cli
