#include "render/image.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

namespace rscene::render {

Comparison compareImages(const Image& render, const Image& reference) {
  Comparison c;
  c.sameSize = render.width == reference.width && render.height == reference.height;
  if (!c.sameSize) return c;
  c.diff.width = render.width;
  c.diff.height = render.height;
  c.diff.rgba.resize(render.rgba.size());
  c.histogram.assign(256, 0);
  std::size_t differing = 0;
  double sum = 0;
  int maxDiff = 0;
  for (std::size_t p = 0; p < render.rgba.size(); p += 4) {
    int worst = 0;
    for (int k = 0; k < 4; ++k) {
      int d = std::abs(int(render.rgba[p + k]) - int(reference.rgba[p + k]));
      worst = std::max(worst, d);
      sum += d;
    }
    maxDiff = std::max(maxDiff, worst);
    ++c.histogram[std::size_t(worst)];
    std::uint8_t* o = &c.diff.rgba[p];
    if (worst > kPixelTolerance) {
      ++differing;
      o[0] = 255, o[1] = 0, o[2] = 0;
    } else {
      auto gray = static_cast<std::uint8_t>(
          (reference.rgba[p] * 3 + reference.rgba[p + 1] * 6 + reference.rgba[p + 2]) / 10 / 3);
      o[0] = o[1] = o[2] = gray;
    }
    o[3] = 255;
  }
  std::size_t pixels = render.rgba.size() / 4;
  c.differingFraction = pixels ? double(differing) / double(pixels) : 0;
  c.meanAbsoluteError = pixels ? sum / (double(pixels) * 4 * 255) : 0;
  c.maxChannelDifference = maxDiff;
  return c;
}

std::uint64_t Comparison::pixelsOver(int t) const {
  std::uint64_t n = 0;
  for (std::size_t d = std::size_t(std::clamp(t + 1, 0, 256)); d < histogram.size(); ++d) n += histogram[d];
  return n;
}

}  // namespace rscene::render
