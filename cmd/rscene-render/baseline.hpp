// --reference handling: compare with a baseline PNG, or write the first
// baseline when it is missing.  Prints its findings; returns an exit code.
#pragma once
#include <cstdint>
#include <string>

#include "render/image.hpp"

namespace rscene::render_cli {

struct BaselineOptions {
  std::string reference;
  std::string diffOutput;
  double threshold = 0.01;
  // The local measure (render::kLocalPixelThreshold): fail when more than
  // failPixels pixels differ by more than pixelThreshold/255.
  int pixelThreshold = render::kLocalPixelThreshold;
  std::uint64_t failPixels = render::kLocalFailPixels;
  bool reportToStderr = false;  // stdout carries the PNG
};

int checkBaseline(const render::Image& image, const std::string& png, const BaselineOptions& opt);

}  // namespace rscene::render_cli
