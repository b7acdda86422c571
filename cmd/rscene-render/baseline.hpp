// --reference handling: compare with a baseline PNG, or write the first
// baseline when it is missing.  Prints its findings; returns an exit code.
#pragma once
#include <string>

#include "render/image.hpp"

namespace rscene::render_cli {

struct BaselineOptions {
  std::string reference;
  std::string diffOutput;
  double threshold = 0.01;
  bool reportToStderr = false;  // stdout carries the PNG
};

int checkBaseline(const render::Image& image, const std::string& png, const BaselineOptions& opt);

}  // namespace rscene::render_cli
