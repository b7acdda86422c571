// Radiance .hdr (RGBE, flat or new-style run-length encoded), for
// equirectangular backgrounds.  Debian 12 has no small packaged reader.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "asset/image.hpp"
#include "asset/image_limits.hpp"

namespace rscene::asset {
namespace {

bool fail(std::string* error, const char* why) {
  if (error) *error = why;
  return false;
}

void rgbeToFloat(const unsigned char* e, float* rgb) {
  if (e[3] == 0) {
    rgb[0] = rgb[1] = rgb[2] = 0;
    return;
  }
  float f = std::ldexp(1.0f, int(e[3]) - (128 + 8));
  for (int k = 0; k < 3; ++k) rgb[k] = (float(e[k]) + 0.5f) * f;
}

bool decode(const std::string& bytes, FloatImage& out, std::string* error, const ImageLimits& limits) {
  if (bytes.rfind("#?", 0) != 0) return fail(error, "not a radiance hdr file");
  std::size_t pos = 0;
  // Header lines up to an empty line, then the resolution line.
  bool rgbe = true;
  for (;;) {
    std::size_t nl = bytes.find('\n', pos);
    if (nl == std::string::npos) return fail(error, "truncated hdr header");
    std::string line = bytes.substr(pos, nl - pos);
    pos = nl + 1;
    if (line.empty()) break;
    if (line.rfind("FORMAT=", 0) == 0 && line != "FORMAT=32-bit_rle_rgbe") rgbe = false;
  }
  if (!rgbe) return fail(error, "unsupported hdr pixel format (only 32-bit_rle_rgbe)");
  std::size_t nl = bytes.find('\n', pos);
  if (nl == std::string::npos) return fail(error, "missing hdr resolution line");
  int w = 0, h = 0;
  char ys[3] = {}, xs[3] = {};
  std::string res = bytes.substr(pos, nl - pos);
  if (std::sscanf(res.c_str(), "%2s %d %2s %d", ys, &h, xs, &w) != 4 || std::strcmp(ys, "-Y") != 0 ||
      std::strcmp(xs, "+X") != 0)
    return fail(error, "unsupported hdr orientation (only -Y H +X W)");
  if (std::string problem = sizeProblem("hdr", std::uint64_t(std::max(w, 0)), std::uint64_t(std::max(h, 0)), limits);
      !problem.empty()) {
    if (error) *error = problem;
    return false;
  }
  pos = nl + 1;
  // The smallest scanline is run-length encoded: a 4-byte header and, per
  // channel, one 2-byte run per 127 pixels.  Fewer bytes than h of those
  // cannot be this image: refused before the pixels are allocated.
  std::uint64_t minScanline = w >= 8 && w < 32768 ? 4 + 4 * 2 * ((std::uint64_t(w) + 126) / 127) : 4 * std::uint64_t(w);
  if (std::uint64_t(bytes.size() - pos) < minScanline * std::uint64_t(h)) return fail(error, "truncated hdr pixels");
  out.width = w;
  out.height = h;
  out.rgb.assign(std::size_t(w) * h * 3, 0.f);
  std::vector<unsigned char> scan(std::size_t(w) * 4);
  auto avail = [&](std::size_t n) { return pos + n <= bytes.size(); };
  auto byteAt = [&](std::size_t i) { return static_cast<unsigned char>(bytes[i]); };
  for (int y = 0; y < h; ++y) {
    if (!avail(4)) return fail(error, "truncated hdr pixels");
    bool rle = w >= 8 && w < 32768 && byteAt(pos) == 2 && byteAt(pos + 1) == 2 && !(byteAt(pos + 2) & 0x80);
    if (rle) {
      if (((byteAt(pos + 2) << 8) | byteAt(pos + 3)) != w) return fail(error, "bad hdr scanline length");
      pos += 4;
      for (int c = 0; c < 4; ++c) {
        int x = 0;
        while (x < w) {
          if (!avail(1)) return fail(error, "truncated hdr pixels");
          int count = byteAt(pos++);
          if (count > 128) {
            count -= 128;
            if (!avail(1) || x + count > w) return fail(error, "bad hdr run");
            unsigned char v = byteAt(pos++);
            for (int i = 0; i < count; ++i) scan[std::size_t(x++) * 4 + c] = v;
          } else {
            if (count == 0 || !avail(std::size_t(count)) || x + count > w) return fail(error, "bad hdr run");
            for (int i = 0; i < count; ++i) scan[std::size_t(x++) * 4 + c] = byteAt(pos++);
          }
        }
      }
    } else {
      if (!avail(std::size_t(w) * 4)) return fail(error, "truncated hdr pixels");
      std::memcpy(scan.data(), bytes.data() + pos, std::size_t(w) * 4);
      pos += std::size_t(w) * 4;
    }
    for (int x = 0; x < w; ++x) rgbeToFloat(&scan[std::size_t(x) * 4], &out.rgb[(std::size_t(y) * w + x) * 3]);
  }
  return true;
}

}  // namespace

bool decodeHdr(const std::string& bytes, FloatImage& out, std::string* error, const ImageLimits& limits) {
  out = FloatImage{};
  if (decode(bytes, out, error, limits)) return true;
  out = FloatImage{};
  return false;
}

}  // namespace rscene::asset
