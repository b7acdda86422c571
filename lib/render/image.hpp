// The baseline comparison rscene-render --reference uses.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "asset/image.hpp"

namespace rscene::render {

// The renderer's images and PNG codec are lib/asset's (8-bit RGBA rows top
// to bottom, linear float RGB); named here too because every user of
// rscene-render's output (drivers, baselines) speaks of render::Image.
using asset::decodePng;
using asset::encodePng;
using asset::FloatImage;
using asset::Image;

// The per-pixel metric of --threshold: a pixel differs when any channel
// (alpha included) differs by more than kPixelTolerance (of 255).  T is the
// fraction of differing pixels, 0..1.
inline constexpr int kPixelTolerance = 16;

struct Comparison {
  bool sameSize = false;
  double differingFraction = 1;  // 0..1, the value compared with T
  double meanAbsoluteError = 1;  // mean |a-b| over all channels, 0..1
  int maxChannelDifference = 255;
  Image diff;  // differing pixels red, the rest a dimmed gray of the reference
};

Comparison compareImages(const Image& render, const Image& reference);

}  // namespace rscene::render
