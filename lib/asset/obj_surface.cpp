#include "asset/obj_surface.hpp"

#include <charconv>
#include <cmath>
#include <string_view>

namespace rscene::asset {
namespace {

bool fail(std::string* error, std::string message) {
  if (error) *error = std::move(message);
  return false;
}

std::string_view nextToken(std::string_view& rest) {
  std::size_t b = rest.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) {
    rest = {};
    return {};
  }
  std::size_t e = rest.find_first_of(" \t\r", b);
  std::string_view t = rest.substr(b, e == std::string_view::npos ? std::string_view::npos : e - b);
  rest = e == std::string_view::npos ? std::string_view{} : rest.substr(e);
  return t;
}

bool toDouble(std::string_view t, double& v) {
  auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  return ec == std::errc() && p == t.data() + t.size() && std::isfinite(v);
}

}  // namespace

bool parseObjSurface(const std::string& text, ObjSurface& out, std::string* error, const ObjLimits& limits) {
  out = {};
  std::string_view all(text);
  std::size_t lineNo = 0;
  std::vector<std::uint32_t> polygon;
  while (!all.empty()) {
    ++lineNo;
    std::size_t nl = all.find('\n');
    std::string_view line = all.substr(0, nl);
    all = nl == std::string_view::npos ? std::string_view{} : all.substr(nl + 1);
    std::string_view rest = line;
    std::string_view tag = nextToken(rest);
    auto at = [&](const std::string& what) { return "line " + std::to_string(lineNo) + ": " + what; };
    if (tag == "v") {
      if (out.vertices.size() >= limits.maxVertices)
        return fail(error, at("more than " + std::to_string(limits.maxVertices) + " vertices"));
      std::array<double, 3> p{};
      for (int k = 0; k < 3; ++k)
        if (!toDouble(nextToken(rest), p[k])) return fail(error, at("a vertex needs three finite numbers"));
      out.vertices.push_back(p);  // a fourth (w) or colour values are ignored, as RaiSim does
    } else if (tag == "f") {
      polygon.clear();
      for (std::string_view t = nextToken(rest); !t.empty(); t = nextToken(rest)) {
        std::string_view v = t.substr(0, t.find('/'));  // v/vt/vn: the position index only
        long long index = 0;
        auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), index);
        if (ec != std::errc() || p != v.data() + v.size() || index == 0)
          return fail(error, at("face index '" + std::string(t) + "' is not a vertex number"));
        long long n = static_cast<long long>(out.vertices.size());
        long long resolved = index > 0 ? index - 1 : n + index;  // negative: relative to the last vertex
        if (resolved < 0 || resolved >= n)
          return fail(error, at("face index " + std::to_string(index) + " is not one of the " + std::to_string(n) +
                                " vertices before it"));
        polygon.push_back(static_cast<std::uint32_t>(resolved));
      }
      if (polygon.size() < 3) return fail(error, at("a face needs at least three vertices"));
      for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
        std::array<std::uint32_t, 3> t{polygon[0], polygon[k], polygon[k + 1]};
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;  // degenerate: no area, no constraint
        if (out.triangles.size() >= limits.maxTriangles)
          return fail(error, at("more than " + std::to_string(limits.maxTriangles) + " triangles"));
        out.triangles.push_back(t);
      }
    }
    // Anything else (vn, vt, o, g, s, usemtl, mtllib, comments) carries no geometry for particles.
  }
  if (out.triangles.empty()) return fail(error, "no triangles (an OBJ surface needs 'v' and 'f' lines)");
  return true;
}

bool loadObjSurface(const FileSystem& fs, const std::string& path, ObjSurface& out, std::string* error,
                    const ObjLimits& limits) {
  std::string text;
  if (!fs.read(path, text, error, limits.maxBytes)) return false;
  if (text.find('\0') != std::string::npos) return fail(error, "not an OBJ file (it holds binary data)");
  return parseObjSurface(text, out, error, limits);
}

SurfaceReader objSurfaceReader(const FileSystem& fs) {
  return [&fs](const std::string& path, TriangleSurface& out, std::string& error) {
    return loadObjSurface(fs, path, out, &error);
  };
}

}  // namespace rscene::asset
