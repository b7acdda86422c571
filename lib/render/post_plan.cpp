// PostPlan and the CPU side of the post-processing numbers (post_plan.hpp).
#include "render/post_plan.hpp"

#include <algorithm>
#include <cmath>

namespace rscene::render {

PostPlan postPlan(const Look& look, bool enabled) {
  PostPlan p;
  if (!enabled) return p;
  p.bloom = look.bloomIntensity > 0;
  p.ssao = look.ssao;
  p.fxaa = look.fxaa;
  p.autoExposure = look.autoExposure && look.autoExposureKey > 0;
  p.depthOfField = look.depthOfField && look.aperture > 0 && look.focusDistance > 0;
  return p;
}

float autoExposureFactor(const float* logLuminance, std::size_t count, float key) {
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < count; ++i)
    if (std::isfinite(logLuminance[i])) sum += logLuminance[i], ++n;
  if (n == 0 || !(key > 0)) return 1.0f;
  double factor = key / std::exp(sum / double(n));
  return float(std::clamp(factor, double(kAutoExposureMin), double(kAutoExposureMax)));
}

float cocRadiusPixels(float depth, float focusDistance, float aperture, float focalPixels) {
  if (!(depth > 0) || !(focusDistance > 0)) return 0;
  return 0.5f * aperture * focalPixels * std::abs(1.0f / focusDistance - 1.0f / depth);
}

// 16 px at 720 rows: a strong but bounded blur (the gather takes 24 samples).
float maxCocPixels(int imageHeight) { return std::clamp(float(imageHeight) / 45.0f, 2.0f, 32.0f); }

int bloomLevels(int width, int height) {
  int levels = 0;
  for (int w = width / 2, h = height / 2; levels < 5 && w >= 2 && h >= 2; w /= 2, h /= 2) ++levels;
  return levels;
}

float bloomGain(float intensity, int levels, float exposure) {
  if (!(intensity > 0)) return 0;
  return std::min(intensity, 1e3f) / float(std::max(levels, 1)) / std::max(exposure, 1e-6f);
}

}  // namespace rscene::render
