// GLSL of the post pass (full-screen triangle after the lit pass):
// background (plain color, HDR or the procedural sky of shader_sky.cpp),
// exposure, tone mapping and gamma.  postFragment() assembles it: without
// post effects it writes display color; with them (gl_post.cpp) the
// surface times ambient occlusion over the background in linear HDR, and
// finalFragment() tone maps that after bloom and depth of field.
#include "render/shaders.hpp"

namespace rscene::render::shaders {

const char* const kPostPrelude = R"(#version 330 core
in vec2 vNdc;
uniform sampler2D uScene;      // linear HDR, premultiplied by coverage
uniform mat4 uInvViewProj;
uniform vec3 uCameraPos;
uniform bool uOrtho;
uniform int uMode;             // 0 plain color, 1 hdr, 2 sky
uniform bool uTransparent;
uniform vec3 uBackground;      // display color of plain_color
uniform vec3 uPlainLinear;     // the same as linear light, for the post chain (gl_post.cpp)
uniform sampler2D uHdr;
uniform float uFogDensity;
uniform vec3 uFogColor;
uniform float uExposure;
uniform float uGamma;
uniform int uToneMap;          // 0 linear, 1 aces, 2 filmic, 3 agx, 4 unreal
out vec4 fragColor;
const float PI = 3.14159265;

vec3 aces(vec3 x) { return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }
vec3 filmic(vec3 x) {  // Hable / Uncharted 2, white point 11.2
  const float A = 0.15, B = 0.50, C = 0.10, D = 0.20, E = 0.02, F = 0.30;
  vec3 c = ((x * (A * x + C * B) + D * E) / (x * (A * x + B) + D * F)) - E / F;
  float w = 11.2;
  float cw = ((w * (A * w + C * B) + D * E) / (w * (A * w + B) + D * F)) - E / F;
  return clamp(c * 2.0 / cw, 0.0, 1.0);
}
vec3 agx(vec3 c) {  // AgX base contrast curve, fitted polynomial
  const mat3 inset = mat3(0.842479, 0.0423303, 0.0423743, 0.0784336, 0.878468, 0.0784336, 0.0792237, 0.0791661, 0.879142);
  const mat3 outset = mat3(1.19688, -0.0528969, -0.0529716, -0.0980209, 1.15190, -0.0980435, -0.0990297, -0.0989612, 1.15107);
  c = inset * max(c, vec3(1e-10));
  c = clamp((log2(c) + 12.47393) / 16.5, 0.0, 1.0);
  vec3 c2 = c * c, c4 = c2 * c2;
  c = 15.5 * c4 * c2 - 40.14 * c4 * c + 31.96 * c4 - 6.868 * c2 * c + 0.4298 * c2 + 0.1191 * c - 0.00232;
  c = outset * c;
  return clamp(pow(max(c, vec3(0.0)), vec3(2.2)), 0.0, 1.0);  // back to linear for the shared gamma step
}
vec3 toneMap(vec3 c) {
  c *= uExposure;
  if (uToneMap == 1) c = aces(c);
  else if (uToneMap == 2) c = filmic(c);
  else if (uToneMap == 3) c = agx(c);
  else if (uToneMap == 4) c = aces(c * 0.8);
  else c = clamp(c, 0.0, 1.0);
  return pow(c, vec3(1.0 / uGamma));
}

)";

const char* const kPostMain = R"(
uniform bool uLinearOut;  // write linear HDR for the post chain, not display color
uniform bool uHasAo;
uniform sampler2D uAo;    // ambient occlusion at half size, 1 where open

// Linear HDR background; plain_color is a display color, the others are
// light (tone mapped with the surfaces).  Height fog and fog spheres
// (backgroundFog, shader_volumes.cpp) veil it.
vec3 backgroundLinear(vec3 d) {
  vec3 c;
  if (uMode == 1) {
    vec2 uv = vec2(atan(d.y, d.x) / (2.0 * PI) + 0.5, acos(clamp(d.z, -1.0, 1.0)) / PI);
    c = texture(uHdr, uv).rgb;
  } else {
    c = sky(d);
  }
  if (uFogDensity > 0.0) c = mix(c, pow(uFogColor, vec3(2.2)), clamp(uFogDensity * 20.0, 0.0, 0.9));
  c = backgroundFog(c, d);  // height fog and fog spheres (shader_volumes.cpp)
  return c;
}

vec3 viewDir() {
  vec4 far = uInvViewProj * vec4(vNdc, 1.0, 1.0);
  vec4 near = uInvViewProj * vec4(vNdc, -1.0, 1.0);
  return normalize(far.xyz / far.w - near.xyz / near.w);
}

// The post chain's input: linear HDR with coverage in alpha, over the
// background unless transparent.  A plain_color background is a display
// color, not light: it goes in as uPlainLinear (its linear value) so that
// bloom and blur see it, and finalFragment() puts the exact color back.
void compositeLinear(vec4 s) {
  vec3 surface = s.a > 0.0 ? s.rgb / s.a : vec3(0.0);
  if (uHasAo) surface *= texture(uAo, gl_FragCoord.xy / vec2(textureSize(uScene, 0))).r;
  if (uTransparent || s.a >= 1.0) {
    fragColor = vec4(surface, s.a);
    return;
  }
  vec3 d = viewDir();
  vec3 bg = uMode == 0 ? backgroundFog(uPlainLinear, d) : backgroundLinear(d);
  fragColor = vec4(surface * s.a + bg * (1.0 - s.a), s.a);
}

// plain_color is a display color: fogged in linear, back to display.
vec3 background(vec3 d) {
  return uMode == 0 ? pow(backgroundFog(pow(uBackground, vec3(2.2)), d), vec3(1.0 / 2.2)) : toneMap(backgroundLinear(d));
}

void main() {
  vec4 s = texelFetch(uScene, ivec2(gl_FragCoord.xy), 0);
  if (uLinearOut) {
    compositeLinear(s);
    return;
  }
  vec3 surface = s.a > 0.0 ? toneMap(s.rgb / s.a) : vec3(0.0);
  // Fully covered (most pixels): no background to blend, no sky to compute.
  if (uTransparent || s.a >= 1.0) {
    fragColor = vec4(surface, uTransparent ? s.a : 1.0);
    return;
  }
  vec3 bg = background(viewDir());
  fragColor = vec4(surface * s.a + bg * (1.0 - s.a), 1.0);
}
)";

std::string postFragment() { return std::string(kPostPrelude) + kSkyGlsl + kFogGlsl + kPostMain; }

}  // namespace rscene::render::shaders
