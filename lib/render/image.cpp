#include "render/image.hpp"

#include <png.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

namespace rscene::render {
namespace {

void appendBytes(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::string*>(png_get_io_ptr(png));
  out->append(reinterpret_cast<const char*>(data), length);
}
void noFlush(png_structp) {}

struct ReadCursor {
  const std::string* bytes;
  std::size_t offset;
};

void readBytes(png_structp png, png_bytep data, png_size_t length) {
  auto* c = static_cast<ReadCursor*>(png_get_io_ptr(png));
  if (c->offset + length > c->bytes->size()) png_error(png, "truncated png");
  std::memcpy(data, c->bytes->data() + c->offset, length);
  c->offset += length;
}

void onError(png_structp png, png_const_charp message) {
  auto* err = static_cast<std::string*>(png_get_error_ptr(png));
  if (err) *err = message;
  png_longjmp(png, 1);
}
void onWarning(png_structp, png_const_charp) {}

}  // namespace

std::string encodePng(const Image& image) {
  std::string out;
  std::string err;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &err, onError, onWarning);
  if (!png) return {};
  png_infop info = png_create_info_struct(png);
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return {};
  }
  png_set_write_fn(png, &out, appendBytes, noFlush);
  png_set_compression_level(png, 6);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
               PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
  for (int y = 0; y < image.height; ++y)
    rows[static_cast<std::size_t>(y)] = const_cast<png_bytep>(image.pixel(0, y));
  png_set_rows(png, info, rows.data());
  png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

bool decodePng(const std::string& bytes, Image& out, std::string* error, std::uint64_t maxPixels) {
  if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8) != 0) {
    if (error) *error = "not a png file";
    return false;
  }
  std::string err = "invalid png";
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &err, onError, onWarning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  ReadCursor cursor{&bytes, 0};
  std::vector<png_bytep> rows;
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    if (error) *error = err;
    return false;
  }
  png_set_read_fn(png, &cursor, readBytes);
  png_read_info(png, info);
  png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
  if (static_cast<std::uint64_t>(w) * h > maxPixels || w == 0 || h == 0) {
    err = "png image too large";
    png_longjmp(png, 1);
  }
  png_set_expand(png);
  png_set_strip_16(png);
  png_set_gray_to_rgb(png);
  png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  out.width = static_cast<int>(w);
  out.height = static_cast<int>(h);
  out.rgba.assign(static_cast<std::size_t>(w) * h * 4, 0);
  rows.resize(h);
  for (png_uint_32 y = 0; y < h; ++y) rows[y] = out.pixel(0, static_cast<int>(y));
  png_read_image(png, rows.data());
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

Comparison compareImages(const Image& render, const Image& reference) {
  Comparison c;
  c.sameSize = render.width == reference.width && render.height == reference.height;
  if (!c.sameSize) return c;
  c.diff.width = render.width;
  c.diff.height = render.height;
  c.diff.rgba.resize(render.rgba.size());
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

}  // namespace rscene::render
