// What the passes' images become as files (view_output.hpp): the 16-bit
// depth PNG decodes with libpng to the millimetres, the .npy header parses
// as NPY 1.0 and its data round-trips bit for bit, the legend is valid,
// escaped JSON.
#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "render/view_output.hpp"

using namespace rscene;
using namespace rscene::render;

namespace {

struct Gray16 {
  int width = 0, height = 0, bitDepth = 0, colorType = -1;
  std::vector<std::uint16_t> values;
};

// libpng's own reader, not ours: what any PNG tool sees.
Gray16 decodeGray16(const std::string& bytes) {
  Gray16 out;
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  // The simplified API hides the bit depth: read the header by hand.
  if (bytes.size() < 33) return out;
  auto be32 = [&](std::size_t at) {
    return std::uint32_t(std::uint8_t(bytes[at])) << 24 | std::uint32_t(std::uint8_t(bytes[at + 1])) << 16 |
           std::uint32_t(std::uint8_t(bytes[at + 2])) << 8 | std::uint32_t(std::uint8_t(bytes[at + 3]));
  };
  out.width = int(be32(16));
  out.height = int(be32(20));
  out.bitDepth = std::uint8_t(bytes[24]);
  out.colorType = std::uint8_t(bytes[25]);
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) return out;
  image.format = PNG_FORMAT_LINEAR_Y;  // 16-bit gray, host order, no gamma change for linear data
  out.values.resize(PNG_IMAGE_SIZE(image) / 2);
  if (!png_image_finish_read(&image, nullptr, out.values.data(), 0, nullptr)) out.values.clear();
  return out;
}

// The reader a C++ user writes for our .npy (the 20 lines view_output.hpp promises).
bool readNpy(const std::string& b, int& rows, int& cols, std::vector<float>& data, std::string& header) {
  if (b.size() < 10 || b.compare(0, 6, "\x93NUMPY") != 0 || b[6] != 1 || b[7] != 0) return false;
  std::size_t len = std::uint8_t(b[8]) | std::size_t(std::uint8_t(b[9])) << 8;
  if (b.size() < 10 + len) return false;
  header = b.substr(10, len);
  if (header.find("'descr': '<f4'") == std::string::npos || header.find("'fortran_order': False") == std::string::npos)
    return false;
  if (std::sscanf(header.c_str() + header.find("'shape': (") + 10, "%d, %d", &rows, &cols) != 2) return false;
  std::size_t n = std::size_t(rows) * std::size_t(cols);
  if (b.size() != 10 + len + 4 * n) return false;
  data.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t bits = 0;
    for (int k = 0; k < 4; ++k) bits |= std::uint32_t(std::uint8_t(b[10 + len + 4 * i + k])) << (8 * k);
    std::memcpy(&data[i], &bits, 4);
  }
  return true;
}

const float kNan = std::numeric_limits<float>::quiet_NaN();

}  // namespace

TEST(PassOutput, MillimetreRule) {
  EXPECT_EQ(depthMillimetres(kNan), 0);
  EXPECT_EQ(depthMillimetres(std::numeric_limits<float>::infinity()), 0);
  EXPECT_EQ(depthMillimetres(5.0f), 5000);
  EXPECT_EQ(depthMillimetres(1.2344f), 1234);
  EXPECT_EQ(depthMillimetres(1.2346f), 1235);
  EXPECT_EQ(depthMillimetres(0.0001f), 1);   // a return is never 0
  EXPECT_EQ(depthMillimetres(-0.3f), 1);     // noise below 0 too
  EXPECT_EQ(depthMillimetres(65.535f), 65535);
  EXPECT_EQ(depthMillimetres(1000.0f), 65535);  // saturates
}

TEST(PassOutput, DepthPngDecodesToMillimetres) {
  std::vector<float> depth = {5.0f, kNan, 0.05f, 65.534f, 100.0f, 1.0005f};  // 3 x 2
  std::string png = encodeDepthPng16(depth, 3, 2);
  ASSERT_FALSE(png.empty());
  Gray16 g = decodeGray16(png);
  EXPECT_EQ(g.width, 3);
  EXPECT_EQ(g.height, 2);
  EXPECT_EQ(g.bitDepth, 16);
  EXPECT_EQ(g.colorType, PNG_COLOR_TYPE_GRAY);
  ASSERT_EQ(g.values.size(), 6u);
  std::vector<std::uint16_t> want = {5000, 0, 50, 65534, 65535, 1000};  // 1.0005 rounds to even: 1000 or 1001
  for (std::size_t i = 0; i < 6; ++i)
    if (i != 5) {
      EXPECT_EQ(g.values[i], want[i]) << i;
    }
  EXPECT_NEAR(g.values[5], 1000.5, 0.5);
  EXPECT_EQ(encodeDepthPng16(depth, 4, 2), "");  // wrong size
  EXPECT_EQ(png, encodeDepthPng16(depth, 3, 2));  // deterministic
}

TEST(PassOutput, NpyHeaderParsesAndDataRoundTrips) {
  std::vector<float> depth(7 * 5);
  for (std::size_t i = 0; i < depth.size(); ++i) depth[i] = 0.1f * float(i) + 0.0123f;
  depth[3] = kNan;
  std::string npy = encodeDepthNpy(depth, 7, 5);
  int rows = 0, cols = 0;
  std::vector<float> back;
  std::string header;
  ASSERT_TRUE(readNpy(npy, rows, cols, back, header));
  EXPECT_EQ(rows, 5);  // shape (height, width)
  EXPECT_EQ(cols, 7);
  const std::string dict = "{'descr': '<f4', 'fortran_order': False, 'shape': (5, 7), }";
  EXPECT_EQ(header.substr(0, dict.size()), dict);
  EXPECT_EQ((10 + header.size()) % 64, 0u);  // data aligned to 64 bytes
  EXPECT_EQ(header.back(), '\n');
  EXPECT_EQ(header.find_first_not_of(' ', dict.size()), header.size() - 1);  // spaces, then the newline
  ASSERT_EQ(back.size(), depth.size());
  EXPECT_TRUE(std::isnan(back[3]));
  for (std::size_t i = 0; i < depth.size(); ++i)
    if (i != 3) {
      EXPECT_EQ(back[i], depth[i]);
    }
  // The bytes of 1.0f little-endian, where the data starts.
  std::string one = encodeDepthNpy({1.0f}, 1, 1);
  ASSERT_EQ(one.size(), 128u + 4u);  // magic, version, length and a 59-byte dict: two 64-byte blocks
  EXPECT_EQ(one.substr(128), std::string("\x00\x00\x80\x3f", 4));
  EXPECT_EQ(encodeDepthNpy(depth, 7, 4), "");
}

TEST(PassOutput, LegendListsSegmentsWithEscapedText) {
  RenderScene scene;
  Segment a;
  a.rgb[0] = 255, a.rgb[1] = 16, a.rgb[2] = 1;
  a.kind = "object";
  a.path = "/World/Crate \"A\"\\\n";
  a.id = "crate";
  a.semanticClass = "box\x01";
  a.instanceId = 7;
  Segment b;
  b.rgb[0] = 32, b.rgb[1] = 33, b.rgb[2] = 34;
  b.kind = "articulated";
  b.path = "/World/Caf\xc3\xa9";     // UTF-8: kept as is
  b.semanticClass = "";
  Segment c = b;
  c.path = "/World/bad\xff%";        // not UTF-8: percent-encoded
  scene.segments = {a, b, c};
  std::string json = segmentationLegendJson(scene);
  EXPECT_EQ(json,
            "{\n"
            "  \"background\": {\"color\": [0, 0, 0], \"hex\": \"#000000\"},\n"
            "  \"segments\": [\n"
            "    {\"color\": [255, 16, 1], \"hex\": \"#ff1001\", \"kind\": \"object\", \"path\": \"/World/Crate "
            "\\\"A\\\"\\\\\\n\", \"id\": \"crate\", \"semanticClass\": \"box\\u0001\", \"instanceId\": 7},\n"
            "    {\"color\": [32, 33, 34], \"hex\": \"#202122\", \"kind\": \"articulated\", \"path\": "
            "\"/World/Caf\xc3\xa9\", \"id\": null, \"semanticClass\": null, \"instanceId\": null},\n"
            "    {\"color\": [32, 33, 34], \"hex\": \"#202122\", \"kind\": \"articulated\", \"path\": "
            "\"/World/bad%FF%25\", \"id\": null, \"semanticClass\": null, \"instanceId\": null}\n"
            "  ]\n"
            "}\n");
  EXPECT_EQ(segmentationLegendJson(RenderScene{}),
            "{\n  \"background\": {\"color\": [0, 0, 0], \"hex\": \"#000000\"},\n  \"segments\": []\n}\n");
}
