// Format dispatch and the size check every decoder shares.
#include <cmath>
#include <cstring>

#include "asset/image.hpp"
#include "asset/image_limits.hpp"

namespace rscene::asset {

ImageFormat imageFormat(std::string_view bytes) {
  if (bytes.size() >= 8 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0) return ImageFormat::Png;
  if (bytes.size() >= 3 && bytes.compare(0, 3, "\xff\xd8\xff") == 0) return ImageFormat::Jpeg;
  if (bytes.compare(0, 2, "#?") == 0) return ImageFormat::Hdr;
  return ImageFormat::Unknown;
}

const char* imageFormatName(ImageFormat f) {
  switch (f) {
    case ImageFormat::Png: return "png";
    case ImageFormat::Jpeg: return "jpeg";
    case ImageFormat::Hdr: return "hdr";
    case ImageFormat::Unknown: break;
  }
  return "unknown";
}

std::string sizeProblem(const char* format, std::uint64_t width, std::uint64_t height, const ImageLimits& limits) {
  if (width == 0 || height == 0) return std::string(format) + " image has no pixels";
  if (width * height > limits.maxPixels || width > 1u << 30 || height > 1u << 30)
    return std::string(format) + " image too large: " + std::to_string(width) + "x" + std::to_string(height) +
           " pixels (limit " + std::to_string(limits.maxPixels) + ")";
  return {};
}

bool decodeImage(const std::string& bytes, Image& out, std::string* error, const ImageLimits& limits) {
  switch (imageFormat(bytes)) {
    case ImageFormat::Png: return decodePng(bytes, out, error, limits);
    case ImageFormat::Jpeg: return decodeJpeg(bytes, out, error, limits);
    case ImageFormat::Hdr:
      if (error) *error = "hdr images have no 8-bit form";
      return false;
    case ImageFormat::Unknown: break;
  }
  if (error) *error = "not a png, jpeg or hdr image";
  return false;
}

bool decodeFloatImage(const std::string& bytes, FloatImage& out, std::string* error, const ImageLimits& limits) {
  if (imageFormat(bytes) == ImageFormat::Hdr) return decodeHdr(bytes, out, error, limits);
  Image im;
  if (!decodeImage(bytes, im, error, limits)) return false;
  float linear[256];
  for (int i = 0; i < 256; ++i) {
    float c = float(i) / 255.0f;
    linear[i] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
  }
  out.width = im.width;
  out.height = im.height;
  out.rgb.resize(std::size_t(im.width) * std::size_t(im.height) * 3);
  for (std::size_t p = 0, n = out.rgb.size() / 3; p < n; ++p)
    for (int k = 0; k < 3; ++k) out.rgb[p * 3 + std::size_t(k)] = linear[im.rgba[p * 4 + std::size_t(k)]];
  return true;
}

}  // namespace rscene::asset
