// Which lights reach which part of an image (CPU, no GL): a light's reach
// (where its attenuated intensity falls below 1/256, or its range), the
// world box it can light, and the per-view grid of 16x16-pixel tiles that
// lists the local lights whose box covers each tile.  The surface shader
// loops over its tile's list (shader_lights.cpp), so the cost of a pixel
// grows with the lights that reach it, not with the scene's light count.
#pragma once
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "render/render_scene.hpp"

namespace rscene::render {

// Linear light below which a light is not drawn: one step of an 8-bit
// channel at exposure 1.
inline constexpr float kLightCutoff = 1.0f / 256;
// Reach of any light, metres: a light without attenuation reaches this far.
inline constexpr float kMaxLightReach = 1e5f;

// The distance beyond which `l` adds less than kLightCutoff (its range
// when that is shorter); kMaxLightReach for directional lights.
float lightReach(const RenderLight& l);

// An area light's rectangle: half its width along `halfRight`, half its
// height along `halfUp`, across its direction (areaRight / areaUp are not
// in the scene model: width runs along world x made perpendicular to the
// direction, so a light facing down lies along x and y as the defaults).
void areaAxes(const RenderLight& l, Eigen::Vector3d& halfRight, Eigen::Vector3d& halfUp);

// The world box `l` can light within `reach`: a sphere's box for point
// lights, the cone's for spot lights, the front half-sphere's for area
// lights (one-sided emitters) grown by their rectangle; infinite for
// directional lights.
Eigen::AlignedBox3d lightBounds(const RenderLight& l, float reach);

// Tiles of tileSize x tileSize pixels, row 0 at the bottom (GL window
// coordinates, as gl_FragCoord).  `data` is what the shader reads: for
// each tile (row-major) its offset into `data`, its count and how many of
// its first lights cast no shadow, then the light indices of all tiles.
// The shader loops over the two parts apart: llvmpipe runs both sides of
// a per-pixel branch, so a light without a shadow would pay for one.
struct LightGrid {
  int tileSize = 16, tilesX = 0, tilesY = 0;
  std::vector<std::int32_t> data;
  std::int32_t count(int tx, int ty) const { return data[std::size_t(3 * (ty * tilesX + tx) + 1)]; }
  std::int32_t unshadowed(int tx, int ty) const { return data[std::size_t(3 * (ty * tilesX + tx) + 2)]; }
};

// Lists light `indices[i]` (whose world box is `bounds[i]`) in every tile
// its box covers on screen under clip-space matrix `viewProj`; a box that
// reaches behind the eye covers every tile.  Lights [firstShadowed, n) cast
// shadows (the caller orders them last); each tile lists them last.  False, with `out` untouched,
// when the lists would hold more than `maxEntries` indices (thousands of
// lights over a large image: the caller takes larger tiles).
bool buildLightGrid(const std::vector<Eigen::AlignedBox3d>& bounds, const std::vector<std::int32_t>& indices,
                    const Eigen::Matrix4d& viewProj, int width, int height, int tileSize, LightGrid& out,
                    std::size_t maxEntries = std::size_t(-1), std::size_t firstShadowed = std::size_t(-1));

}  // namespace rscene::render
