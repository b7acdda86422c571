// 8-bit RGBA images: deterministic PNG encoding (fixed zlib level and
// filter, no time or text chunks), PNG decoding, and the baseline
// comparison rscene-render --reference uses.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace rscene::render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // rows top to bottom
  std::uint8_t* pixel(int x, int y) { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
  const std::uint8_t* pixel(int x, int y) const { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
};

// Linear float RGB image (Radiance .hdr), rows top to bottom.
struct FloatImage {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;
};

// Same image => same bytes.
std::string encodePng(const Image& image);
// Any PNG libpng reads (palette, gray, 16-bit are expanded to RGBA8).
// Refuses images over `maxPixels` so a hostile header cannot exhaust memory.
bool decodePng(const std::string& bytes, Image& out, std::string* error,
               std::uint64_t maxPixels = 1ull << 28);

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
