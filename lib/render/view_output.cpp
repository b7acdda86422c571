// Depth PNG/NPY and the segmentation legend (view_output.hpp).
#include "render/view_output.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "asset/image.hpp"
#include "core/json_value.hpp"

namespace rscene::render {

std::uint16_t depthMillimetres(float metres) {
  if (!std::isfinite(metres)) return 0;
  double mm = std::nearbyint(double(metres) * 1000.0);
  if (mm < 1) return 1;
  if (mm > 65535) return 65535;
  return static_cast<std::uint16_t>(mm);
}

std::string encodeDepthPng16(const std::vector<float>& depth, int width, int height) {
  if (width < 1 || height < 1 || depth.size() != std::size_t(width) * std::size_t(height)) return {};
  std::vector<std::uint16_t> mm(depth.size());
  for (std::size_t i = 0; i < depth.size(); ++i) mm[i] = depthMillimetres(depth[i]);
  return asset::encodePngGray16(width, height, mm);
}

std::string encodeDepthNpy(const std::vector<float>& depth, int width, int height) {
  if (width < 1 || height < 1 || depth.size() != std::size_t(width) * std::size_t(height)) return {};
  std::string dict = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(height) + ", " +
                     std::to_string(width) + "), }";
  // magic (6) + version (2) + length (2) + dict + padding + '\n' = 64k.
  std::size_t unpadded = 10 + dict.size() + 1;
  dict.append((64 - unpadded % 64) % 64, ' ');
  dict.push_back('\n');
  std::string out("\x93NUMPY\x01\x00", 8);
  out.push_back(char(dict.size() & 0xff));
  out.push_back(char(dict.size() >> 8));
  out += dict;
  out.reserve(out.size() + depth.size() * 4);
  for (float f : depth) {
    std::uint32_t bits;
    std::memcpy(&bits, &f, 4);
    for (int k = 0; k < 4; ++k) out.push_back(char((bits >> (8 * k)) & 0xff));  // little-endian on any host
  }
  return out;
}

namespace {

void appendText(std::string& out, const std::string& s) {
  if (json::validUtf8(s)) {
    json::appendString(out, s);
    return;
  }
  std::string encoded;
  for (unsigned char c : s) {
    if (c >= 0x80 || c == '%') {
      char b[4];
      std::snprintf(b, sizeof b, "%%%02X", c);
      encoded += b;
    } else {
      encoded.push_back(char(c));
    }
  }
  json::appendString(out, encoded);
}

void appendColor(std::string& out, const std::uint8_t rgb[3]) {
  char b[64];
  std::snprintf(b, sizeof b, "\"color\": [%d, %d, %d], \"hex\": \"#%02x%02x%02x\"", rgb[0], rgb[1], rgb[2], rgb[0],
                rgb[1], rgb[2]);
  out += b;
}

}  // namespace

std::string segmentationLegendJson(const RenderScene& scene) {
  std::string out = "{\n  \"background\": {";
  const std::uint8_t black[3] = {0, 0, 0};
  appendColor(out, black);
  out += "},\n  \"segments\": [";
  for (std::size_t i = 0; i < scene.segments.size(); ++i) {
    const Segment& g = scene.segments[i];
    out += i ? ",\n    {" : "\n    {";
    appendColor(out, g.rgb);
    out += ", \"kind\": ";
    appendText(out, g.kind);
    out += ", \"path\": ";
    appendText(out, g.path);
    out += ", \"id\": ";
    if (g.id.empty()) out += "null";
    else appendText(out, g.id);
    out += ", \"semanticClass\": ";
    if (g.semanticClass.empty()) out += "null";
    else appendText(out, g.semanticClass);
    out += ", \"instanceId\": ";
    out += g.instanceId >= 0 ? std::to_string(g.instanceId) : "null";
    out += "}";
  }
  out += scene.segments.empty() ? "]\n}\n" : "\n  ]\n}\n";
  return out;
}

}  // namespace rscene::render
