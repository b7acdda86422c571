// What the post-processing of a color view does (gl_post.cpp draws it):
// which effects the environment and rayrai_render records ask for, and the
// few numbers the passes share with the CPU (auto exposure, the circle of
// confusion), kept here so they can be tested without a GL context.
#pragma once
#include <cstddef>

#include "render/render_scene.hpp"

namespace rscene::render {

struct PostPlan {
  bool bloom = false, ssao = false, fxaa = false, autoExposure = false, depthOfField = false;
  bool any() const { return bloom || ssao || fxaa || autoExposure || depthOfField; }
};

// The effects `look` asks for; none when !enabled (rscene-render --no-post).
// Bloom needs an intensity above 0, depth of field an aperture above 0.
PostPlan postPlan(const Look& look, bool enabled);

// Auto exposure: the factor that brings the geometric mean of the image's
// luminance to `key` (Reinhard's key value), from the natural logarithms of
// the luminance of a downsample.  Clamped to rayrai's default
// [autoExposureMinFactor, autoExposureMaxFactor] = [0.1, 6], so that a black
// frame is not amplified without bound; 1 when there is nothing to average.
inline constexpr float kAutoExposureMin = 0.1f, kAutoExposureMax = 6.0f;
float autoExposureFactor(const float* logLuminance, std::size_t count, float key);

// Depth of field (thin lens, `aperture` the lens diameter in metres,
// focused at `focusDistance` metres): the radius in pixels of the blur
// circle of a point `depth` metres along the view axis, for a lens of
// `focalPixels` focal length (image height / 2 / tan(vfov / 2)).  The
// shader computes the same, then clamps to maxCocPixels().
float cocRadiusPixels(float depth, float focusDistance, float aperture, float focalPixels);
float maxCocPixels(int imageHeight);

// Bloom: how many levels of the chain (half size, then halving) an image
// of this size gets: at most 5, none smaller than 2 pixels a side.
int bloomLevels(int width, int height);
// What the top level of the chain (the sum of `levels` levels, in exposed
// units) is multiplied by before it is added to the unexposed image:
// intensity / levels / exposure, finite for any exposure and intensity.
float bloomGain(float intensity, int levels, float exposure);

}  // namespace rscene::render
