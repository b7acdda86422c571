#include "render/render_foliage.hpp"

#include <algorithm>
#include <cmath>

namespace rscene::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

// splitmix64 (Steele, Lea, Flood 2014): tiny, fast, and the same numbers
// on every platform and standard library (std distributions are not).
struct SplitMix {
  std::uint64_t s;
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  double between(double a, double b) { return a + (b - a) * uniform(); }
};

// The generator of one cell: the seed and the cell index mixed, so that a
// cell's instances do not depend on the cells before it.
SplitMix cellGenerator(std::int64_t seed, std::size_t cell) {
  SplitMix mix{std::uint64_t(seed) ^ (std::uint64_t(cell) * 0xd1b54a32d192ed03ull)};
  return SplitMix{mix.next()};
}

double finiteOr(double v, double fallback) { return std::isfinite(v) ? v : fallback; }

// Walks every candidate of `layer` in a fixed order, calling `accept` with
// each accepted instance until it returns false or the layer's maximum is
// reached.  Both countFoliage() and scatterFoliage() walk the same
// candidates, so they agree on the numbering without keeping them all.
template <typename Accept>
std::uint64_t walk(const Terrain& t, const FoliageLayer& l, Accept&& accept) {
  TerrainSurface surface(t);
  if (!surface.valid() || !l.enabled || !(l.densityPerSquareMeter > 0)) return 0;
  std::size_t nx = std::size_t(t.xSamples), ny = std::size_t(t.ySamples), n = nx * ny;
  bool hasDensity = l.density.size() == n;
  double dx = t.xSize / double(nx - 1), dy = t.ySize / double(ny - 1);
  double x0 = t.center.x() - t.xSize / 2, y0 = t.center.y() - t.ySize / 2;
  auto cellSide = [](std::size_t i, std::size_t count, double step) { return i == 0 || i + 1 == count ? step / 2 : step; };
  auto weight = [&](std::size_t i) { return hasDensity ? std::clamp(finiteOr(l.density[i], 0), 0.0, 1.0) : 1.0; };
  std::uint64_t cap = l.maxInstances > 0 ? std::min<std::uint64_t>(std::uint64_t(l.maxInstances), kMaxFoliageGenerated)
                                         : kMaxFoliageGenerated;
  // Expected total first: a cap scales every cell alike.  Compared as
  // densities, so that a density of 1e308 is capped, not infinite.
  double area = 0;  // weighted by density
  for (std::size_t i = 0; i < n; ++i) area += weight(i) * cellSide(i % nx, nx, dx) * cellSide(i / nx, ny, dy);
  if (!(area > 0) || !std::isfinite(area)) return 0;
  double perArea = std::min(l.densityPerSquareMeter, double(cap) / area);
  double minScale = finiteOr(l.minScale, 1), maxScale = std::max(finiteOr(l.maxScale, 1), minScale);
  double yawMax = finiteOr(l.randomYawDegrees, 0) * kPi / 180, pitchMax = finiteOr(l.randomPitchDegrees, 0) * kPi / 180,
         rollMax = finiteOr(l.randomRollDegrees, 0) * kPi / 180;
  std::uint64_t accepted = 0;
  for (std::size_t i = 0; i < n && accepted < cap; ++i) {
    double w = weight(i);
    if (w <= 0) continue;
    std::size_t ix = i % nx, iy = i / nx;
    double cx = x0 + double(ix) * dx, cy = y0 + double(iy) * dy;
    double xa = std::max(cx - dx / 2, x0), xb = std::min(cx + dx / 2, x0 + t.xSize);
    double ya = std::max(cy - dy / 2, y0), yb = std::min(cy + dy / 2, y0 + t.ySize);
    double e = w * perArea * (xb - xa) * (yb - ya);
    SplitMix rng = cellGenerator(l.seed, i);
    double whole = std::floor(e);
    std::uint64_t count = std::uint64_t(whole) + (rng.uniform() < e - whole ? 1 : 0);
    for (std::uint64_t k = 0; k < count && accepted < cap; ++k) {
      double x = rng.between(xa, xb), y = rng.between(ya, yb);
      double s = rng.between(minScale, maxScale);
      double yaw = rng.between(-yawMax, yawMax), pitch = rng.between(-pitchMax, pitchMax),
             roll = rng.between(-rollMax, rollMax);
      float colorWeight = float(rng.uniform());
      TerrainSurface::Point p = surface.at(x, y);
      if (p.hole || p.height < l.minHeight || p.height > l.maxHeight) continue;
      double slope = std::acos(std::clamp(p.normal.z(), -1.0, 1.0)) * 180 / kPi;
      if (slope < l.minSlopeDegrees || slope > l.maxSlopeDegrees) continue;
      FoliageInstance in;
      in.position = {x, y, p.z};
      in.scale = s;
      in.colorWeight = colorWeight;
      if (!accept(accepted, p, yaw, pitch, roll, in)) return accepted + 1;
      ++accepted;
    }
  }
  return accepted;
}

}  // namespace

bool TerrainSurface::valid() const {
  return t_.xSamples >= 2 && t_.ySamples >= 2 && t_.heights.size() == std::size_t(t_.xSamples) * std::size_t(t_.ySamples) &&
         t_.xSize > 0 && t_.ySize > 0 && std::isfinite(t_.xSize) && std::isfinite(t_.ySize);
}

bool TerrainSurface::contains(double x, double y) const {
  return valid() && std::abs(x - t_.center.x()) <= t_.xSize / 2 && std::abs(y - t_.center.y()) <= t_.ySize / 2;
}

TerrainSurface::Point TerrainSurface::at(double x, double y) const {
  Point p;
  int nx = t_.xSamples, ny = t_.ySamples;
  double dx = t_.xSize / (nx - 1), dy = t_.ySize / (ny - 1);
  double fx = std::clamp((x - (t_.center.x() - t_.xSize / 2)) / dx, 0.0, double(nx - 1));
  double fy = std::clamp((y - (t_.center.y() - t_.ySize / 2)) / dy, 0.0, double(ny - 1));
  if (!std::isfinite(fx)) fx = 0;  // a terrain at 1e308: never an int of NaN
  if (!std::isfinite(fy)) fy = 0;
  int i = std::min(int(fx), nx - 2), j = std::min(int(fy), ny - 2);
  double tx = fx - i, ty = fy - j;
  auto idx = [&](int a, int b) { return std::size_t(b) * std::size_t(nx) + std::size_t(a); };
  double h00 = t_.heights[idx(i, j)], h10 = t_.heights[idx(i + 1, j)], h01 = t_.heights[idx(i, j + 1)],
         h11 = t_.heights[idx(i + 1, j + 1)];
  p.height = (h00 * (1 - tx) + h10 * tx) * (1 - ty) + (h01 * (1 - tx) + h11 * tx) * ty;
  p.z = t_.center.z() + p.height;
  double dhdx = ((h10 - h00) * (1 - ty) + (h11 - h01) * ty) / dx;
  double dhdy = ((h01 - h00) * (1 - tx) + (h11 - h10) * tx) / dy;
  Eigen::Vector3d n(-dhdx, -dhdy, 1);
  p.normal = std::isfinite(n.squaredNorm()) ? n.normalized() : Eigen::Vector3d::UnitZ();
  if (t_.holes.size() == t_.heights.size())
    for (std::size_t k : {idx(i, j), idx(i + 1, j), idx(i, j + 1), idx(i + 1, j + 1)})
      if (t_.holes[k] > 0.5) p.hole = true;
  return p;
}

FoliageScatter countFoliage(const Terrain& terrain, const FoliageLayer& layer) {
  FoliageScatter s;
  s.generated = walk(terrain, layer, [](std::uint64_t, const TerrainSurface::Point&, double, double, double,
                                        const FoliageInstance&) { return true; });
  s.stride = std::uint64_t(std::max<std::int64_t>(layer.renderedInstanceStride, 1));
  s.drawn = (s.generated + s.stride - 1) / s.stride;
  if (layer.maxRenderedInstances > 0 && s.drawn > std::uint64_t(layer.maxRenderedInstances)) {
    std::uint64_t max = std::uint64_t(layer.maxRenderedInstances);
    s.stride = (s.generated + max - 1) / max;
    s.drawn = std::min((s.generated + s.stride - 1) / s.stride, max);
  }
  return s;
}

std::vector<FoliageInstance> scatterFoliage(const Terrain& terrain, const FoliageLayer& layer,
                                            const FoliageScatter& scatter) {
  std::vector<FoliageInstance> out;
  if (scatter.drawn == 0) return out;
  out.reserve(scatter.drawn);
  std::uint64_t stride = std::max<std::uint64_t>(scatter.stride, 1);
  walk(terrain, layer,
       [&](std::uint64_t index, const TerrainSurface::Point& p, double yaw, double pitch, double roll,
           const FoliageInstance& in) {
         if (index % stride) return true;
         FoliageInstance f = in;
         Eigen::Quaterniond tilt = layer.alignToNormal ? Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), p.normal)
                                                       : Eigen::Quaterniond::Identity();
         f.rotation = tilt * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                      Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
         out.push_back(f);
         return out.size() < scatter.drawn;
       });
  return out;
}

}  // namespace rscene::render
