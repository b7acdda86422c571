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

// The local measure of --fail-pixels/--pixel-threshold (as OpenImageIO's
// idiff -fail): a change is found when more than N pixels differ by more
// than T/255 in some channel.  The fraction above catches broad changes
// (lighting, exposure, a camera moved) and forgives a few strong pixels;
// this one catches a small object moved or added, whose few hundred
// pixels are far under 1 % of the image.  Defaults: T = 32, N = 50.
inline constexpr int kLocalPixelThreshold = 32;
inline constexpr std::uint64_t kLocalFailPixels = 50;

struct Comparison {
  bool sameSize = false;
  // Pixels by their largest channel difference, 0..255: histogram[d] is
  // how many pixels differ by exactly d (pixelsOver() reads it).
  std::vector<std::uint64_t> histogram;
  // Pixels whose largest channel difference exceeds t/255.
  std::uint64_t pixelsOver(int t) const;
  double differingFraction = 1;  // 0..1, the value compared with T
  double meanAbsoluteError = 1;  // mean |a-b| over all channels, 0..1
  int maxChannelDifference = 255;
  Image diff;  // differing pixels red, the rest a dimmed gray of the reference
};

Comparison compareImages(const Image& render, const Image& reference);

}  // namespace rscene::render
