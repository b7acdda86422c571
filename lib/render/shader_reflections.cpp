// GLSL of the indirect light (surface program): ambient, sky and
// environment reflections.  Appended to the surface fragment's prelude
// (shaders.cpp).
#include "render/shaders.hpp"

namespace rscene::render::shaders {

const char* const kReflectionsGlsl = R"(
uniform vec3 uAmbient;
uniform vec3 uSkyAmbient;   // linear light from the procedural sky or HDR, 0 for plain color

// Diffuse and specular light from the surroundings (ambient, sky, HDR,
// reflection probes); `irradiance` is extra diffuse light arriving at s.P
// (irradiance volumes).
vec3 indirectLight(Surface s, vec3 irradiance) {
  vec3 f0 = mix(vec3(0.04), s.base.rgb, s.metallic);
  vec3 diffuse = s.base.rgb * (1.0 - s.metallic);
  // Ambient: brighter from the sky side.
  vec3 light = toLinear(uAmbient) * (0.75 + 0.25 * s.N.z) + uSkyAmbient * (0.6 + 0.4 * s.N.z);
  return (diffuse + f0 * 0.5) * light + diffuse * irradiance;
}
)";

}  // namespace rscene::render::shaders
