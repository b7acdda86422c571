// PNG, JPEG and HDR decoding through lib/asset: round trips, caps checked
// before allocation, hostile headers refused.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <chrono>

#include "asset/image.hpp"
#include "test_images.hpp"

using namespace rscene;
using namespace rscene::asset;
using rscene::test::solidImage;

namespace {

// Peak resident memory of this process so far, in MiB.
long peakMiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024;
}

Image halves() {  // left half red, right half blue, 16 x 8
  Image im = solidImage(16, 8, 255, 0, 0);
  for (int y = 0; y < 8; ++y)
    for (int x = 8; x < 16; ++x) im.pixel(x, y)[0] = 0, im.pixel(x, y)[2] = 255;
  return im;
}

}  // namespace

TEST(Png, RoundTripsAndIsDeterministic) {
  Image a = solidImage(3, 2, 10, 20, 30, 40);
  a.pixel(2, 1)[0] = 200;
  std::string png = encodePng(a);
  EXPECT_EQ(png, encodePng(a));
  Image b;
  std::string err;
  ASSERT_TRUE(decodePng(png, b, &err)) << err;
  EXPECT_EQ(b.width, 3);
  EXPECT_EQ(b.height, 2);
  EXPECT_EQ(b.rgba, a.rgba);
}

// rscene-render writes a PNG per frame: a fast deflate level (zlib's
// header says "fast", levels 2-5), not the default 6 that cost 0.08 s of a
// 1280x720 frame's ~0.9 s.
TEST(Png, IsDeflatedAtAFastLevel) {
  std::string png = encodePng(solidImage(64, 64, 10, 20, 30));
  // Signature (8), IHDR (4 + 4 + 13 + 4), then IDAT's length and type.
  ASSERT_GT(png.size(), 43u);
  ASSERT_EQ(png.substr(37, 4), "IDAT");
  auto cmf = std::uint8_t(png[41]), flg = std::uint8_t(png[42]);
  EXPECT_EQ(cmf & 0x0f, 8);   // deflate
  EXPECT_EQ(flg >> 6, 1) << "FLEVEL";  // 1: fast (2: default, 3: best)
}

TEST(Png, RejectsGarbageAndTruncation) {
  Image out;
  std::string err;
  EXPECT_FALSE(decodePng("not a png", out, &err));
  EXPECT_EQ(err, "not a png file");
  std::string png = encodePng(solidImage(4, 4, 1, 2, 3));
  EXPECT_FALSE(decodePng(png.substr(0, png.size() / 2), out, &err));
  EXPECT_TRUE(out.rgba.empty());
}

TEST(Png, BombHeaderIsRefusedBeforeAllocating) {
  // 16384 x 16384 declared (3.5 GB of RGBA once decoded and staged).
  std::string bomb = test::pngDeclaring(16384, 16384, 1 << 20);
  long before = peakMiB();
  auto t0 = std::chrono::steady_clock::now();
  Image out;
  std::string err;
  EXPECT_FALSE(decodePng(bomb, out, &err));
  EXPECT_EQ(err, "png image too large: 16384x16384 pixels (limit 67108864)");
  // Under a raised cap, the file is still too small to hold what it claims.
  ImageLimits generous;
  generous.maxPixels = std::uint64_t{1} << 30;
  EXPECT_FALSE(decodePng(bomb, out, &err, generous));
  EXPECT_NE(err.find("more than its"), std::string::npos) << err;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
  EXPECT_LT(peakMiB() - before, 32);
}

TEST(Png, ALimitCanBeLowered) {
  ImageLimits tiny;
  tiny.maxPixels = 1000;
  Image out;
  std::string err;
  EXPECT_FALSE(decodePng(encodePng(solidImage(64, 64, 1, 2, 3)), out, &err, tiny));
  EXPECT_EQ(err, "png image too large: 64x64 pixels (limit 1000)");
}

TEST(Jpeg, DecodesWhatLibjpegEncoded) {
  std::string jpeg = test::encodeJpeg(halves());
  EXPECT_EQ(imageFormat(jpeg), ImageFormat::Jpeg);
  Image im;
  std::string err;
  ASSERT_TRUE(decodeJpeg(jpeg, im, &err)) << err;
  ASSERT_EQ(im.width, 16);
  ASSERT_EQ(im.height, 8);
  // JPEG is lossy and subsamples colour: compare away from the edge, within 24/255.
  const std::uint8_t* red = im.pixel(2, 4);
  const std::uint8_t* blue = im.pixel(13, 4);
  EXPECT_NEAR(red[0], 255, 24);
  EXPECT_NEAR(red[2], 0, 24);
  EXPECT_NEAR(blue[0], 0, 24);
  EXPECT_NEAR(blue[2], 255, 24);
  EXPECT_EQ(red[3], 255);
}

TEST(Jpeg, HugeDeclaredSizeIsRefusedBeforeAllocating) {
  std::string jpeg = test::encodeJpeg(solidImage(8, 8, 9, 9, 9));
  // SOF0 (FF C0): length (2), precision (1), height (2), width (2).
  std::size_t sof = jpeg.find("\xff\xc0");
  ASSERT_NE(sof, std::string::npos);
  jpeg[sof + 5] = jpeg[sof + 7] = '\xea', jpeg[sof + 6] = jpeg[sof + 8] = '\x60';  // 60000 x 60000
  Image out;
  std::string err;
  long before = peakMiB();
  EXPECT_FALSE(decodeJpeg(jpeg, out, &err));
  EXPECT_EQ(err, "jpeg image too large: 60000x60000 pixels (limit 67108864)");
  EXPECT_LT(peakMiB() - before, 32);
}

TEST(Jpeg, GarbageAndTruncationFailCleanly) {
  Image out;
  std::string err;
  EXPECT_FALSE(decodeJpeg("\xff\xd8\xff garbage", out, &err));
  EXPECT_EQ(err.rfind("invalid jpeg: ", 0), 0u) << err;
  EXPECT_FALSE(decodeJpeg("GIF89a", out, &err));
  EXPECT_EQ(err, "not a jpeg file");
  std::string jpeg = test::encodeJpeg(halves());
  EXPECT_FALSE(decodeJpeg(jpeg.substr(0, 20), out, &err));
  EXPECT_TRUE(out.rgba.empty());
}

TEST(Hdr, DecodesFlatRgbe) {
  // 2 x 1: (1, 0.5, 0.25) as RGBE mantissas 128, 64, 32 with exponent 129; then black.
  std::string hdr = std::string("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n") +
                    std::string("\x80\x40\x20\x81\x00\x00\x00\x00", 8);
  FloatImage im;
  std::string err;
  ASSERT_TRUE(decodeHdr(hdr, im, &err)) << err;
  ASSERT_EQ(im.width, 2);
  EXPECT_NEAR(im.rgb[0], 1.0, 0.01);
  EXPECT_NEAR(im.rgb[1], 0.5, 0.01);
  EXPECT_NEAR(im.rgb[2], 0.25, 0.01);
  EXPECT_EQ(im.rgb[3], 0);
}

TEST(Hdr, RefusesBadHeadersAndSizesItsBytesCannotHold) {
  FloatImage im;
  std::string err;
  EXPECT_FALSE(decodeHdr("#?RADIANCE\n\n-Y 99999 +X 99999\n", im, &err));
  EXPECT_EQ(err, "hdr image too large: 99999x99999 pixels (limit 67108864)");
  long before = peakMiB();
  EXPECT_FALSE(decodeHdr("#?RADIANCE\n\n-Y 8000 +X 8000\n\x02\x02", im, &err));  // 768 MB claimed in 2 bytes
  EXPECT_EQ(err, "truncated hdr pixels");
  EXPECT_LT(peakMiB() - before, 32);
  EXPECT_FALSE(decodeHdr("P6 1 1", im, &err));
  EXPECT_TRUE(im.rgb.empty());
}

TEST(Decode, TellsTheFormatByContent) {
  Image im;
  std::string err;
  ASSERT_TRUE(decodeImage(encodePng(solidImage(2, 2, 1, 2, 3)), im, &err)) << err;
  ASSERT_TRUE(decodeImage(test::encodeJpeg(solidImage(8, 8, 200, 200, 200)), im, &err)) << err;
  EXPECT_EQ(im.width, 8);
  EXPECT_FALSE(decodeImage("#?RADIANCE\n", im, &err));
  EXPECT_EQ(err, "hdr images have no 8-bit form");
  EXPECT_FALSE(decodeImage("BM....", im, &err));
  EXPECT_EQ(err, "not a png, jpeg or hdr image");
}

TEST(Decode, FloatImagesOfPngAreLinear) {
  FloatImage f;
  std::string err;
  ASSERT_TRUE(decodeFloatImage(encodePng(solidImage(1, 1, 255, 128, 0)), f, &err)) << err;
  EXPECT_FLOAT_EQ(f.rgb[0], 1.0f);
  EXPECT_NEAR(f.rgb[1], 0.2158, 1e-3);  // sRGB 128 in linear light
  EXPECT_FLOAT_EQ(f.rgb[2], 0.0f);
}

TEST(Decode, EveryTruncationAndByteFlipEndsCleanly) {
  // Either a whole image of the declared size or a failure with nothing
  // kept; never a crash (this also runs under ASan/UBSan).
  Image src = halves();
  for (const std::string& file : {encodePng(src), test::encodeJpeg(src)}) {
    auto check = [&](const std::string& bytes) {
      Image out;
      std::string err;
      if (decodeImage(bytes, out, &err)) {
        EXPECT_EQ(out.rgba.size(), std::size_t(out.width) * std::size_t(out.height) * 4);
      } else {
        EXPECT_TRUE(out.rgba.empty());
        EXPECT_FALSE(err.empty());
      }
    };
    for (std::size_t n = 0; n < file.size(); ++n) check(file.substr(0, n));
    for (std::size_t i = 0; i < file.size(); ++i) {
      std::string flipped = file;
      flipped[i] = static_cast<char>(flipped[i] ^ 0x5a);
      check(flipped);
    }
  }
}
