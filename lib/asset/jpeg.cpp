// JPEG through libjpeg(-turbo): baseline and progressive, gray, RGB and
// CMYK-free YCbCr, to RGBA8.  Errors longjmp back here instead of exit().
#include <cstdio>  // jpeglib.h needs FILE
#include <csetjmp>

#include <jpeglib.h>

#include "asset/image.hpp"
#include "asset/image_limits.hpp"

namespace rscene::asset {
namespace {

// A progressive JPEG of a few kilobytes can hold thousands of scans, each
// a pass over the whole image; libjpeg-turbo's tools cap them the same way.
constexpr int kMaxScans = 1000;

struct ErrorManager {
  jpeg_error_mgr base;
  std::jmp_buf jump;
  std::string message;
};

void onError(j_common_ptr cinfo) {
  auto* e = reinterpret_cast<ErrorManager*>(cinfo->err);
  char text[JMSG_LENGTH_MAX];
  (*cinfo->err->format_message)(cinfo, text);
  e->message = text;
  std::longjmp(e->jump, 1);
}
void onMessage(j_common_ptr, int) {}  // warnings (e.g. premature end) keep what was decoded

struct ScanLimit {
  jpeg_progress_mgr base;
  std::string* message;
};

void onProgress(j_common_ptr cinfo) {
  auto* d = reinterpret_cast<j_decompress_ptr>(cinfo);
  if (d->is_decompressor && d->input_scan_number > kMaxScans) {
    auto* e = reinterpret_cast<ErrorManager*>(cinfo->err);
    e->message = "jpeg has more than " + std::to_string(kMaxScans) + " scans";
    std::longjmp(e->jump, 1);
  }
}

}  // namespace

bool decodeJpeg(const std::string& bytes, Image& out, std::string* error, const ImageLimits& limits) {
  out = Image{};
  if (imageFormat(bytes) != ImageFormat::Jpeg) {
    if (error) *error = "not a jpeg file";
    return false;
  }
  jpeg_decompress_struct cinfo{};
  ErrorManager err{};
  ScanLimit progress{};
  cinfo.err = jpeg_std_error(&err.base);
  err.base.error_exit = onError;
  err.base.emit_message = onMessage;
  // Everything below that can longjmp touches only these locals and `out`,
  // none of them with a destructor that must run between here and there.
  std::vector<std::uint8_t> row;
  if (setjmp(err.jump)) {
    jpeg_destroy_decompress(&cinfo);
    out = Image{};
    if (error) *error = "invalid jpeg: " + err.message;
    return false;
  }
  jpeg_create_decompress(&cinfo);
  progress.base.progress_monitor = onProgress;
  cinfo.progress = &progress.base;
  jpeg_mem_src(&cinfo, reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&cinfo, TRUE);
  std::string problem = sizeProblem("jpeg", cinfo.image_width, cinfo.image_height, limits);
  if (!problem.empty()) {
    jpeg_destroy_decompress(&cinfo);
    if (error) *error = problem;
    return false;
  }
  cinfo.out_color_space = JCS_RGB;  // gray and YCbCr both convert; CMYK/YCCK fail in start
  jpeg_start_decompress(&cinfo);
  out.width = static_cast<int>(cinfo.output_width);
  out.height = static_cast<int>(cinfo.output_height);
  out.rgba.assign(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height) * 4, 255);
  row.resize(static_cast<std::size_t>(out.width) * 3);
  while (cinfo.output_scanline < cinfo.output_height) {
    JSAMPROW rows[1] = {row.data()};
    int y = static_cast<int>(cinfo.output_scanline);
    if (jpeg_read_scanlines(&cinfo, rows, 1) != 1) break;
    std::uint8_t* dst = out.pixel(0, y);
    for (int x = 0; x < out.width; ++x) {
      dst[4 * x] = row[std::size_t(3 * x)];
      dst[4 * x + 1] = row[std::size_t(3 * x + 1)];
      dst[4 * x + 2] = row[std::size_t(3 * x + 2)];
    }
  }
  jpeg_finish_decompress(&cinfo);
  jpeg_destroy_decompress(&cinfo);
  return true;
}

}  // namespace rscene::asset
