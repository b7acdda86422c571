// terrain_foliage_layer scattering: where the instances of a foliage layer
// stand on its terrain_region, deterministic from the layer's seed.  Pure
// functions of the scene model (no GL), so that the tests can count and
// place what the renderer will draw.
#pragma once
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "scene/scene.hpp"

namespace rscene::render {

// The surface a terrain_region draws: heights bilinear between samples,
// the normal of that bilinear patch, holes per quad (a quad with a hole at
// any corner is not drawn, so nothing stands on it).
class TerrainSurface {
 public:
  explicit TerrainSurface(const Terrain& t) : t_(t) {}
  // Whether the terrain has a usable grid (2+ samples per axis, heights).
  bool valid() const;
  // Whether world (x, y) lies over the terrain's rectangle.
  bool contains(double x, double y) const;
  struct Point {
    double height = 0;  // the heightfield's value: above the terrain's centre
    double z = 0;       // world
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    bool hole = false;
  };
  // At world (x, y), clamped to the rectangle.
  Point at(double x, double y) const;

 private:
  const Terrain& t_;
};

// One scattered instance: its origin on the surface, its rotation (the
// surface's tilt when alignToNormal, then yaw about z, pitch about y, roll
// about x), its uniform scale factor (times the layer's size) and where its
// color lies between colorA (0) and colorB (1).
struct FoliageInstance {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  double scale = 1;
  float colorWeight = 0;
};

// What a layer scatters and which of it is drawn.
struct FoliageScatter {
  std::uint64_t generated = 0;  // accepted instances (at most maxInstances)
  std::uint64_t stride = 1;     // every stride-th of them is drawn ...
  std::uint64_t drawn = 0;      // ... up to this many
};

// Scattered instances a layer generates at most, whatever its maxInstances
// says: bounds the time spent (about 0.1 us each), not memory (only drawn
// instances are kept).
constexpr std::uint64_t kMaxFoliageGenerated = std::uint64_t{1} << 24;

// Counts what `layer` scatters over `terrain` and chooses what is drawn.
//
// The terrain's samples are the centres of its cells (dx by dy, halved at
// the edges).  A cell expects density[i] (1 when the layer has no density)
// x densityPerSquareMeter x its area instances: the whole part always, one
// more with the probability of the fraction.  When the expected total
// exceeds maxInstances (or kMaxFoliageGenerated), every cell's expectation
// is scaled down alike, so a capped layer still covers its whole terrain;
// generation also stops at that count.  Each instance draws its position
// in the cell, scale in [minScale, maxScale], yaw/pitch/roll within
// +-random*Degrees and its color weight from a generator seeded by `seed`
// and the cell (splitmix64), so a layer's pattern depends on nothing else.
// It is rejected over a hole, where the heightfield's value is outside
// [minHeight, maxHeight] or the slope outside [minSlopeDegrees,
// maxSlopeDegrees].
//
// Drawn: every renderedInstanceStride-th accepted instance; when that
// leaves more than maxRenderedInstances (> 0), the stride grows until it
// does not, so the drawn ones spread over the whole terrain rather than
// filling its first rows.
FoliageScatter countFoliage(const Terrain& terrain, const FoliageLayer& layer);

// The drawn instances of countFoliage(): exactly `scatter.drawn` of them.
std::vector<FoliageInstance> scatterFoliage(const Terrain& terrain, const FoliageLayer& layer,
                                            const FoliageScatter& scatter);

}  // namespace rscene::render
