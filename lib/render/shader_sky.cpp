// GLSL of the procedural sky (rayrai_sky): used by the post pass for the
// background and by the surface program for the light of the sky.  It is
// continuous across the horizon: below it the sky's colour there (glow and
// clouds included) fades into the ground haze.
#include "render/shaders.hpp"

namespace rscene::render::shaders {

const char* const kSkyGlsl = R"(
uniform vec3 uSunDir;
uniform float uCloud;
uniform bool uNight;

vec3 sky(vec3 d) {
  vec3 sun = normalize(uSunDir);
  float sunHeight = clamp(sun.z, -0.2, 1.0);
  float day = smoothstep(-0.15, 0.2, sunHeight);
  vec3 zenith = mix(vec3(0.005, 0.008, 0.02), vec3(0.10, 0.28, 0.72), day);
  vec3 horizon = mix(vec3(0.02, 0.025, 0.04), mix(vec3(0.85, 0.55, 0.35), vec3(0.60, 0.75, 0.95), smoothstep(0.0, 0.35, sunHeight)), day);
  // Horizon to zenith: pow(z, 0.45) eased near the horizon (offset 0.03)
  // so that its slope there is finite: no bright seam in the first rows.
  float up = max(d.z, 0.0);
  const float e = 0.03;
  float rise = (pow(up + e, 0.45) - pow(e, 0.45)) / (pow(1.0 + e, 0.45) - pow(e, 0.45));
  vec3 c = mix(horizon, zenith, rise);
  float mu = max(dot(d, sun), 0.0);
  c += vec3(1.0, 0.85, 0.6) * pow(mu, 8.0) * 0.25 * day;              // glow around the sun
  c += vec3(40.0, 36.0, 30.0) * smoothstep(0.99985, 0.99995, mu) * day;  // the disk
  vec3 cloud = vec3(0.62, 0.64, 0.68) * mix(0.05, 1.0, day);
  c = mix(c, cloud, clamp(uCloud, 0.0, 1.0) * 0.85);
  if (d.z < 0.0) {  // below the horizon: the sky at the horizon fading into a dim ground haze (no step)
    vec3 ground = vec3(0.18, 0.17, 0.16) * mix(0.05, 1.0, day);
    c = mix(c, ground, smoothstep(0.0, 0.25, -d.z));
  }
  if (uNight) c = c * 0.05 + vec3(0.002, 0.003, 0.008);
  return c;
}
)";

}  // namespace rscene::render::shaders
