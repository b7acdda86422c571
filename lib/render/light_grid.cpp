// Light reach, light boxes and the per-view light grid (light_grid.hpp).
#include "render/light_grid.hpp"

#include <algorithm>
#include <cmath>

#include "render/camera.hpp"

namespace rscene::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Box of the points within `reach` of `apex` inside the cone of half angle
// `halfAngle` (<= 90 degrees) around unit `axis`.  A linear function is
// largest over that solid at the apex, on the rim circle, or at the
// sphere's own extreme point when the cone contains it.
Eigen::AlignedBox3d coneBox(const Eigen::Vector3d& apex, const Eigen::Vector3d& axis, double halfAngle, double reach) {
  Eigen::AlignedBox3d b(apex, apex);
  Eigen::Vector3d rimCentre = apex + axis * (reach * std::cos(halfAngle));
  double rimRadius = reach * std::sin(halfAngle);
  Eigen::Vector3d ext;
  for (int i = 0; i < 3; ++i) ext[i] = rimRadius * std::sqrt(std::max(0.0, 1 - axis[i] * axis[i]));
  b.extend(rimCentre - ext);
  b.extend(rimCentre + ext);
  double cosHalf = std::cos(halfAngle);
  for (int i = 0; i < 3; ++i)
    for (double sign : {-1.0, 1.0})
      if (sign * axis[i] >= cosHalf - 1e-12) {
        Eigen::Vector3d e = apex;
        e[i] += sign * reach;
        b.extend(e);
      }
  return b;
}

}  // namespace

void areaAxes(const RenderLight& l, Eigen::Vector3d& halfRight, Eigen::Vector3d& halfUp) {
  Eigen::Vector3d d = l.direction.norm() > 1e-12 ? l.direction.normalized() : Eigen::Vector3d(0, 0, -1);
  Eigen::Vector3d right = Eigen::Vector3d::UnitX() - d * d.x();
  if (right.norm() < 1e-6) right = Eigen::Vector3d::UnitY() - d * d.y();
  right.normalize();
  halfRight = right * (0.5 * std::max(double(l.areaSize.x()), 0.0));
  halfUp = right.cross(d) * (0.5 * std::max(double(l.areaSize.y()), 0.0));
}

float lightReach(const RenderLight& l) {
  if (l.type == LightType::Directional) return kMaxLightReach;
  double intensity = l.color.cwiseAbs().maxCoeff();
  double c = l.attenuation.x(), lin = l.attenuation.y(), q = l.attenuation.z();
  // intensity / (c + lin d + q d^2) < cutoff  <=>  c + lin d + q d^2 > intensity / cutoff
  double need = intensity / kLightCutoff;
  double reach = kMaxLightReach;
  if (!(intensity > 0)) {
    reach = 0;
  } else if (q > 0) {
    double disc = lin * lin + 4 * q * (need - c);
    reach = disc <= 0 ? 0 : (-lin + std::sqrt(disc)) / (2 * q);
  } else if (lin > 0) {
    reach = (need - c) / lin;
  } else if (c > 0 && c >= need) {
    reach = 0;
  }
  if (l.range > 0) reach = std::min(reach, double(l.range));
  if (!std::isfinite(reach)) reach = kMaxLightReach;
  return float(std::clamp(reach, 0.0, double(kMaxLightReach)));
}

Eigen::AlignedBox3d lightBounds(const RenderLight& l, float reach) {
  const double big = kMaxLightReach * 10;
  if (l.type == LightType::Directional)
    return Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-big), Eigen::Vector3d::Constant(big));
  Eigen::Vector3d p = l.position, axis = l.direction;
  if (!(axis.norm() > 1e-9)) axis = -Eigen::Vector3d::UnitZ();
  axis.normalize();
  if (l.type == LightType::Spot) {
    double half = std::clamp(double(l.coneDegrees), 0.0, 90.0) * kPi / 180;
    return coneBox(p, axis, half, reach);
  }
  if (l.type == LightType::Area) {
    // The front half-sphere around every point of the rectangle.
    Eigen::AlignedBox3d b = coneBox(p, axis, kPi / 2, reach);
    Eigen::Vector3d halfRight, halfUp;
    areaAxes(l, halfRight, halfUp);
    Eigen::Vector3d grow = halfRight.cwiseAbs() + halfUp.cwiseAbs();
    return Eigen::AlignedBox3d(b.min() - grow, b.max() + grow);
  }
  return Eigen::AlignedBox3d(p - Eigen::Vector3d::Constant(reach), p + Eigen::Vector3d::Constant(reach));
}

bool buildLightGrid(const std::vector<Eigen::AlignedBox3d>& bounds, const std::vector<std::int32_t>& indices,
                    const Eigen::Matrix4d& viewProj, int width, int height, int tileSize, LightGrid& out,
                    std::size_t maxEntries, std::size_t firstShadowed) {
  LightGrid g;
  g.tileSize = std::max(tileSize, 1);
  g.tilesX = std::max(1, (width + g.tileSize - 1) / g.tileSize);
  g.tilesY = std::max(1, (height + g.tileSize - 1) / g.tileSize);
  const int tiles = g.tilesX * g.tilesY;
  // Each light's tile rectangle [x0, x1) x [y0, y1), then counts, offsets, fill.
  struct Rect {
    int x0, y0, x1, y1;
  };
  std::vector<Rect> rects(bounds.size(), Rect{0, 0, 0, 0});
  for (std::size_t i = 0; i < bounds.size(); ++i) {
    const Eigen::AlignedBox3d& b = bounds[i];
    if (b.isEmpty() || !boxInFrustum(viewProj, b)) continue;
    double x0 = 1, y0 = 1, x1 = -1, y1 = -1;
    bool behind = false;
    for (int k = 0; k < 8 && !behind; ++k) {
      Eigen::Vector3d c = b.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k));
      Eigen::Vector4d h = viewProj * Eigen::Vector4d(c.x(), c.y(), c.z(), 1);
      if (!(h.w() > 1e-9)) {
        behind = true;
        break;
      }
      x0 = std::min(x0, h.x() / h.w()), x1 = std::max(x1, h.x() / h.w());
      y0 = std::min(y0, h.y() / h.w()), y1 = std::max(y1, h.y() / h.w());
    }
    if (behind) x0 = y0 = -1, x1 = y1 = 1;
    auto tileOf = [&](double ndc, int pixels, int count) {
      double px = (std::clamp(ndc, -1.0, 1.0) * 0.5 + 0.5) * pixels;
      return std::clamp(int(std::floor(px / g.tileSize)), 0, count - 1);
    };
    if (x1 < -1 || y1 < -1 || x0 > 1 || y0 > 1) continue;
    rects[i] = {tileOf(x0, width, g.tilesX), tileOf(y0, height, g.tilesY), tileOf(x1, width, g.tilesX) + 1,
                tileOf(y1, height, g.tilesY) + 1};
  }
  std::size_t entries = 0;
  for (const Rect& r : rects) entries += std::size_t(r.x1 - r.x0) * std::size_t(r.y1 - r.y0);
  if (entries > maxEntries) return false;
  std::vector<std::int32_t> counts(std::size_t(tiles), 0);
  for (const Rect& r : rects)
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) ++counts[std::size_t(y * g.tilesX + x)];
  g.data.assign(std::size_t(3 * tiles), 0);
  std::int32_t offset = 3 * tiles;
  for (int t = 0; t < tiles; ++t) {
    g.data[std::size_t(3 * t)] = offset;
    offset += counts[std::size_t(t)];
  }
  g.data.resize(std::size_t(offset), 0);
  // In input order: a tile's unshadowed lights come first.
  for (std::size_t i = 0; i < rects.size(); ++i) {
    const Rect& r = rects[i];
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) {
        auto t = std::size_t(y * g.tilesX + x);
        g.data[std::size_t(g.data[3 * t] + g.data[3 * t + 1]++)] = indices[i];
        if (i < firstShadowed) ++g.data[3 * t + 2];
      }
  }
  out = std::move(g);
  return true;
}

}  // namespace rscene::render
