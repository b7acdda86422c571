// Images made inside the tests (no binary fixtures): a JPEG through
// libjpeg's encoder and PNG chunks with their CRC, for hostile headers.
#pragma once
#include <cstdio>  // jpeglib.h needs FILE
#include <jpeglib.h>
#include <zlib.h>

#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "asset/image.hpp"

namespace rscene::test {

inline asset::Image solidImage(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a = 255) {
  asset::Image im;
  im.width = w, im.height = h;
  for (int i = 0; i < w * h; ++i) im.rgba.insert(im.rgba.end(), {r, g, b, a});
  return im;
}

// Baseline JPEG of the RGB channels of `im`.
inline std::string encodeJpeg(const asset::Image& im, int quality = 95) {
  jpeg_compress_struct c{};
  jpeg_error_mgr err{};
  c.err = jpeg_std_error(&err);
  jpeg_create_compress(&c);
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&c, &buffer, &size);
  c.image_width = static_cast<JDIMENSION>(im.width);
  c.image_height = static_cast<JDIMENSION>(im.height);
  c.input_components = 3;
  c.in_color_space = JCS_RGB;
  jpeg_set_defaults(&c);
  jpeg_set_quality(&c, quality, TRUE);
  jpeg_start_compress(&c, TRUE);
  std::vector<unsigned char> row(static_cast<std::size_t>(im.width) * 3);
  while (c.next_scanline < c.image_height) {
    const std::uint8_t* src = im.pixel(0, static_cast<int>(c.next_scanline));
    for (int x = 0; x < im.width; ++x)
      for (int k = 0; k < 3; ++k) row[std::size_t(x * 3 + k)] = src[x * 4 + k];
    JSAMPROW rows[1] = {row.data()};
    jpeg_write_scanlines(&c, rows, 1);
  }
  jpeg_finish_compress(&c);
  jpeg_destroy_compress(&c);
  std::string out(reinterpret_cast<const char*>(buffer), size);
  std::free(buffer);
  return out;
}

inline void putBigEndian(std::string& s, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) s.push_back(static_cast<char>((v >> shift) & 0xff));
}

inline std::string pngChunk(const std::string& type, const std::string& data) {
  std::string c;
  putBigEndian(c, static_cast<std::uint32_t>(data.size()));
  std::string body = type + data;
  c += body;
  putBigEndian(c, static_cast<std::uint32_t>(
                      crc32(0, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size()))));
  return c;
}

// A PNG whose header declares `w` x `h` 8-bit gray pixels, followed by
// `zeroBytes` zeros deflated: the shape of a decompression bomb.
inline std::string pngDeclaring(std::uint32_t w, std::uint32_t h, std::size_t zeroBytes) {
  std::string ihdr;
  putBigEndian(ihdr, w);
  putBigEndian(ihdr, h);
  ihdr += std::string("\x08\x00\x00\x00\x00", 5);  // depth 8, gray, deflate, filter 0, no interlace
  std::string zeros(zeroBytes, '\0');
  uLongf size = compressBound(static_cast<uLong>(zeros.size()));
  std::string idat(size, '\0');
  compress2(reinterpret_cast<Bytef*>(idat.data()), &size, reinterpret_cast<const Bytef*>(zeros.data()),
            static_cast<uLong>(zeros.size()), 9);
  idat.resize(size);
  return std::string("\x89PNG\r\n\x1a\n", 8) + pngChunk("IHDR", ihdr) + pngChunk("IDAT", idat) +
         pngChunk("IEND", "");
}

}  // namespace rscene::test
