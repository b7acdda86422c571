// GLSL of the direct light (surface program): every light, its
// attenuation and cone, and its shadow.  Appended to the surface
// fragment's prelude (shaders.cpp); owns the uLight* and uShadow* uniforms
// that the renderer sets (passes.cpp, colorPass).
#include "render/shaders.hpp"

namespace rscene::render::shaders {

const char* const kLightsGlsl = R"(
uniform int uLightCount;
uniform vec4 uLightPos[8];    // xyz, type (0 dir, 1 point, 2 spot, 3 area)
uniform vec4 uLightDir[8];    // travel direction, cos(outer cone)
uniform vec4 uLightColor[8];  // rgb x intensity, cos(inner cone)
uniform vec4 uLightAtt[8];    // constant, linear, quadratic, range
uniform int uShadowLight;     // index of the light with the shadow map, -1 none
uniform mat4 uLightViewProj;
uniform sampler2DShadow uShadowMap;
uniform float uShadowTexel;

float shadowFactor(vec3 P, vec3 n, vec3 l) {
  vec4 p = uLightViewProj * vec4(P, 1.0);
  vec3 s = p.xyz / p.w * 0.5 + 0.5;
  if (s.x <= 0.0 || s.x >= 1.0 || s.y <= 0.0 || s.y >= 1.0 || s.z >= 1.0) return 1.0;
  float bias = uShadowTexel * (1.5 + 3.0 * (1.0 - max(dot(n, l), 0.0)));
  // Four bilinear comparisons at half-texel offsets: a 3x3-texel tent,
  // as soft as nine point taps at a little under half their cost (the
  // largest part of the lit pass on llvmpipe).
  float sum = 0.0;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x)
      sum += texture(uShadowMap, vec3(s.xy + (vec2(x, y) - 0.5) * uShadowTexel, s.z - bias));
  return sum / 4.0;
}

// Light arriving directly from the scene's lights, reflected towards the eye.
vec3 directLight(Surface s) {
  float rough = clamp(s.rough, 0.03, 1.0);
  float a2 = rough * rough * rough * rough;
  vec3 f0 = mix(vec3(0.04), s.base.rgb, s.metallic);
  vec3 diffuse = s.base.rgb * (1.0 - s.metallic);
  float nv = max(dot(s.N, s.V), 1e-4);
  vec3 color = vec3(0.0);
  for (int i = 0; i < 8; ++i) {
    if (i >= uLightCount) break;
    int type = int(uLightPos[i].w + 0.5);
    vec3 l;
    float att = 1.0;
    if (type == 0) {
      l = -normalize(uLightDir[i].xyz);
    } else {
      vec3 d = uLightPos[i].xyz - s.P;
      float dist = length(d);
      l = d / max(dist, 1e-4);
      att = 1.0 / max(uLightAtt[i].x + uLightAtt[i].y * dist + uLightAtt[i].z * dist * dist, 1e-4);
      if (uLightAtt[i].w > 0.0) att *= clamp(1.0 - pow(dist / uLightAtt[i].w, 4.0), 0.0, 1.0);
      if (type == 2) {
        float c = dot(-l, normalize(uLightDir[i].xyz));
        att *= smoothstep(uLightDir[i].w, uLightColor[i].w, c);
      } else if (type == 3) {
        att *= max(dot(-l, normalize(uLightDir[i].xyz)), 0.0);  // one-sided emitter
      }
    }
    float nl = dot(s.N, l);
    if (nl <= 0.0) continue;
    if (i == uShadowLight && s.receiveShadow) att *= shadowFactor(s.P, s.N, l);
    vec3 h = normalize(l + s.V);
    float nh = max(dot(s.N, h), 0.0);
    float dn = nh * nh * (a2 - 1.0) + 1.0;
    float D = a2 / (PI * dn * dn);
    float k = (rough + 1.0) * (rough + 1.0) / 8.0;
    float G = nv / (nv * (1.0 - k) + k) * nl / (nl * (1.0 - k) + k);
    vec3 F = f0 + (1.0 - f0) * pow(1.0 - max(dot(h, s.V), 0.0), 5.0);
    vec3 spec = D * G * F / max(4.0 * nv * nl, 1e-4);
    color += ((1.0 - F) * diffuse / PI + spec) * uLightColor[i].rgb * att * nl;
  }
  return color;
}
)";

}  // namespace rscene::render::shaders
