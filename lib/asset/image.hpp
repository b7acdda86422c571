// Images: PNG and JPEG to 8-bit RGBA, Radiance HDR to linear float RGB,
// through one decoder that tells the format by content, plus the
// deterministic PNG encoder the renderer writes with.
//
// Every decoder reads the declared size first and refuses an image over
// ImageLimits::maxPixels before allocating anything for its pixels, so a
// small hostile file cannot claim gigabytes.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace rscene::asset {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // rows top to bottom
  std::uint8_t* pixel(int x, int y) { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
  const std::uint8_t* pixel(int x, int y) const { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
};

// Linear float RGB, rows top to bottom.
struct FloatImage {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;
};

struct ImageLimits {
  // 8192 x 8192: 256 MiB as RGBA8, 768 MiB as float RGB.
  std::uint64_t maxPixels = std::uint64_t{1} << 26;
};

enum class ImageFormat { Unknown, Png, Jpeg, Hdr };
ImageFormat imageFormat(std::string_view bytes);  // by signature, not by name
const char* imageFormatName(ImageFormat f);

// Each returns false with `error` set ("png image too large: 16384x16384
// pixels (limit 67108864)", "not a jpeg file", ...) and leaves `out` empty.
bool decodePng(const std::string& bytes, Image& out, std::string* error, const ImageLimits& limits = {});
bool decodeJpeg(const std::string& bytes, Image& out, std::string* error, const ImageLimits& limits = {});
bool decodeHdr(const std::string& bytes, FloatImage& out, std::string* error, const ImageLimits& limits = {});

// PNG or JPEG, by content.  HDR is refused here: it has no 8-bit form.
bool decodeImage(const std::string& bytes, Image& out, std::string* error, const ImageLimits& limits = {});
// HDR as is; PNG and JPEG converted from sRGB to linear.
bool decodeFloatImage(const std::string& bytes, FloatImage& out, std::string* error, const ImageLimits& limits = {});

// Same image => same bytes (fixed zlib level and filter, no time or text
// chunks).  Empty on failure.
std::string encodePng(const Image& image);
// A 16-bit grayscale PNG (depth images): `values` width*height, rows top
// to bottom; deterministic like encodePng.  Empty on failure or when
// values.size() != width*height.
std::string encodePngGray16(int width, int height, const std::vector<std::uint16_t>& values);

}  // namespace rscene::asset
