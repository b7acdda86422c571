// Views: validity, projection and depth noise (view.hpp).
#include "render/view.hpp"

#include <cmath>

#include "render/camera.hpp"

namespace rscene::render {

const char* passName(Pass p) {
  switch (p) {
    case Pass::Color:
      return "rgb";
    case Pass::Depth:
      return "depth";
    case Pass::Segmentation:
      return "segmentation";
  }
  return "rgb";
}

namespace {
// Focal lengths make a calibration; the principal point may be anywhere
// (0 or negative for a crop), only finite.
bool hasIntrinsics(const View& v) { return v.fx != 0 || v.fy != 0; }
bool usesIntrinsics(const View& v) { return hasIntrinsics(v) && v.camera.projection != "orthographic"; }
}  // namespace

std::string viewProblem(const View& v) {
  const Camera& c = v.camera;
  if (c.width < 1 || c.height < 1 || c.width > kMaxImageSide || c.height > kMaxImageSide)
    return "image size " + std::to_string(c.width) + "x" + std::to_string(c.height) + " is not within 1.." +
           std::to_string(kMaxImageSide) + " on each side";
  if (v.passes.empty()) return "no image to render (rgb, depth or segmentation)";
  if (!(std::isfinite(c.nearPlane) && std::isfinite(c.farPlane) && c.nearPlane > 0 && c.nearPlane < c.farPlane))
    return "near and far planes must satisfy 0 < near < far";
  if (hasIntrinsics(v)) {
    for (double x : {v.fx, v.fy})
      if (!std::isfinite(x) || x <= 0) return "intrinsics fx and fy must both be positive (or both 0: none)";
    for (double x : {v.cx, v.cy})
      if (!std::isfinite(x)) return "intrinsics cx and cy must be finite";
  }
  return {};
}

Eigen::Matrix4d viewProjection(const View& v) {
  const Camera& c = v.camera;
  Eigen::Matrix4d p = usesIntrinsics(v)
                          ? intrinsicProjection(v.fx, v.fy, v.cx, v.cy, c.width, c.height, c.nearPlane, c.farPlane)
                          : projectionMatrix(c, double(c.width) / double(c.height));
  return p * viewMatrix(c);
}

namespace {
std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}
// A uniform double in (0, 1]: the top 53 bits plus one, never 0 (log(0)).
double unit(std::uint64_t bits) { return double((bits >> 11) + 1) * 0x1.0p-53; }
}  // namespace

void addDepthNoise(std::vector<float>& depth, double mean, double stddev, std::uint64_t seed) {
  if (mean == 0 && stddev == 0) return;
  constexpr double kTwoPi = 6.283185307179586;
  std::uint64_t key = splitmix64(seed);
  for (std::size_t i = 0; i < depth.size(); ++i) {
    if (!std::isfinite(depth[i])) continue;
    // Two independent draws per pixel from its own counter: the noise of a
    // pixel does not depend on which other pixels hit something.
    std::uint64_t a = splitmix64(key ^ (2 * std::uint64_t(i))), b = splitmix64(key ^ (2 * std::uint64_t(i) + 1));
    double n = std::sqrt(-2 * std::log(unit(a))) * std::cos(kTwoPi * unit(b));
    depth[i] = float(double(depth[i]) + mean + stddev * n);
  }
}

}  // namespace rscene::render
