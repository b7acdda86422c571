// Draws a RenderScene from one camera into an RGBA8 image with the current
// EGL context (gl_context.hpp): shadow map of the main light, an MSAA HDR
// pass, then background, exposure, tone mapping and gamma.  renderScene()
// is the one-view form of the Renderer in view.hpp (many views, depth and
// segmentation, one upload).
#pragma once
#include <cstdint>
#include <string>

#include "asset/cache.hpp"
#include "core/diagnostic.hpp"
#include "render/image.hpp"
#include "render/render_scene.hpp"

namespace rscene::render {

// The image size of a view that has none of its own (a camera record
// without width/height, the automatic view) and no --width/--height: the
// one default, which cameraImageSize() (limits.hpp) applies.
inline constexpr int kDefaultImageWidth = 1280, kDefaultImageHeight = 720;

struct RenderOptions {
  int width = kDefaultImageWidth, height = kDefaultImageHeight;
  int samples = 4;            // clamped to what the driver offers
  bool transparent = false;   // alpha 0 where no geometry covers a pixel
  bool allowMissingAssets = false;  // placeholder box + warning instead of an error
  // The post-processing the scene asks for (bloom, SSAO, FXAA, auto
  // exposure, depth of field); false: background, exposure, tone map and
  // gamma only (rscene-render --no-post).
  bool post = true;
  // Largest texture or HDR background decoded, in pixels; a larger one is
  // not drawn (RS9002 / RS9003 warnings).  8192 x 8192: 256 MiB as RGBA8.
  std::uint64_t maxTexturePixels = std::uint64_t{1} << 26;
  // Meshes and textures are read through this cache when given (the one
  // prepareScene read robot meshes through, built with assetLimits() of
  // these options), so that no file is read twice; null: one of its own.
  asset::AssetCache* assets = nullptr;
};

// What a texture or background image may cost under `options`
// (--max-texture-pixels): the limits of the asset cache the renderer reads through.
asset::AssetLimits assetLimits(const RenderOptions& options);

// The image size rscene-render allows by default (--max-pixels): 4096 x
// 4096, about 1 GiB of framebuffers with 4x MSAA (README, "Resource
// limits: rscene-render").  Each side is at most kMaxImageSide.
inline constexpr std::uint64_t kDefaultMaxPixels = std::uint64_t{1} << 24;
inline constexpr int kMaxImageSide = 16384;

struct RenderTimings {
  double uploadSeconds = 0;  // meshes, textures, instance buffers
  double shadowSeconds = 0;  // shadow map passes
  double drawSeconds = 0;    // the lit layers, depth and segmentation passes
  double postSeconds = 0;    // resolve, background, post-processing, tone map, color read-back
  // How the lit layers were drawn (passes.cpp, main_pass.hpp): views drawn
  // as jittered single-sample passes instead of MSAA, and instances left
  // out as hidden (behind opaque boxes, occlusion.hpp; in jittered views
  // also those no sample sees), summed over views.
  std::uint64_t jitteredViews = 0;
  std::uint64_t occludedInstances = 0;
  // Shadow map views drawn (a cube light's six faces count six): how often
  // the maps were redrawn for views that moved them.
  std::uint64_t shadowMapsDrawn = 0;
};

// Renders; false (with an error diagnostic naming the record's line) when
// an asset is missing or unreadable and !allowMissingAssets, or GL fails.
// `timings`: the upload and the drawing of this one view.
bool renderScene(const RenderScene& scene, const Camera& camera, const RenderOptions& options, Image& out,
                 Diagnostics& diags, RenderTimings* timings = nullptr);

}  // namespace rscene::render
