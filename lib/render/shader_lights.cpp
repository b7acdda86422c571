// GLSL of the direct light (surface program): every light, its
// attenuation and cone, and its shadow.  Appended to the surface
// fragment's prelude (shaders.cpp); owns the uniforms LightEffects sets
// (gl_lights.cpp): the light buffer (kLightTexels texels per light, laid
// out as LightEffects::writeLightBuffer says), the per-tile light lists
// and the shadow atlas.  Also the shadow maps' vertex shader.
#include "render/shaders.hpp"

namespace rscene::render::shaders {

const char* const kShadowMapVertex = R"(#version 330 core
layout(location = 0) in vec3 aPos;
layout(location = 4) in vec4 iM0;
layout(location = 5) in vec4 iM1;
layout(location = 6) in vec4 iM2;
layout(location = 7) in vec4 iM3;
uniform mat4 uViewProj;
void main() { gl_Position = uViewProj * (mat4(iM0, iM1, iM2, iM3) * vec4(aPos, 1.0)); }
)";

const char* const kLightsGlsl = R"(
uniform samplerBuffer uLights;       // 13 texels per light, directional ones first
uniform isamplerBuffer uLightGrid;   // per tile: offset, count, unshadowed count; then light indices
uniform int uDirectionalCount;       // lights [0, n): directional, they reach every pixel
uniform int uTileSize;
uniform int uTilesX;
uniform int uTilesY;
uniform bool uHasLocalLights;        // false: no tile lists to read (a sun alone costs nothing more)
uniform sampler2DShadow uShadowAtlas;
uniform float uAtlasTexel;           // 1 / atlas side

const int kLightTexels = 13;
// The first directional lights' texels also sit in uniforms, read by
// their own loop (sunLight): llvmpipe runs both sides of a branch on a
// per-pixel value, so one function choosing between uniform and buffer
// would pay for both.
const int kHeadLights = 8;
uniform vec4 uLightHead[kHeadLights * kLightTexels];
uniform int uHeadCount;              // directional lights in uLightHead

vec4 lightTexel(int i, int k) { return texelFetch(uLights, i * kLightTexels + k); }
vec4 headTexel(int i, int k) { return uLightHead[i * kLightTexels + k]; }

// Four bilinear comparisons spread over the filter radius: a tent as soft
// as nine point taps at under half their cost (the lit pass's largest part
// on llvmpipe), kept inside the map's cell of the atlas.
float shadowFilter(vec2 uv, float z, vec4 cell, float radius) {
  float spread = clamp(radius, 1.0, 3.0) * 0.5 * uAtlasTexel;
  float sum = 0.0;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x)
      sum += texture(uShadowAtlas, vec3(clamp(uv + (vec2(x, y) * 2.0 - 1.0) * spread, cell.xy, cell.zw), z));
  return sum * 0.25;
}

// How much of light `base`'s light reaches s.P past its casters (1 lit).
float shadowVisibility(int i, vec3 lightPos, Surface s, vec3 l) {
  vec4 sh = lightTexel(i, 4);    // strength, bias (m), radius (texels), texel size
  vec4 map = lightTexel(i, 5);   // origin (uv), side (uv), kind
  vec4 nf = lightTexel(i, 6);    // near, far, cube face scale
  int kind = int(map.w + 0.5);
  float nl = clamp(dot(s.N, l), 0.0, 1.0);
  // Normal offset of one to three texels (more where the light grazes):
  // the surface does not shadow itself.
  float texel = kind == 1 ? sh.w : sh.w * length(s.P - lightPos);
  vec3 Q = s.P + s.N * texel * (1.0 + 2.0 * (1.0 - nl));
  vec2 uv;
  float depth;
  vec4 cell;
  if (kind == 3) {
    // The face of the largest axis, as shadow_fit.hpp's kCubeForward and
    // kCubeRight (up = right x forward), written out: no array indexing,
    // which llvmpipe pays per pixel.
    vec3 d = Q - lightPos;
    vec3 a = abs(d);
    float face;
    vec2 st;
    if (a.x >= a.y && a.x >= a.z) {
      float sx = d.x >= 0.0 ? 1.0 : -1.0;
      face = sx > 0.0 ? 0.0 : 1.0;
      depth = a.x;
      st = vec2(sx * d.y, -d.z);
    } else if (a.y >= a.z) {
      float sy = d.y >= 0.0 ? 1.0 : -1.0;
      face = sy > 0.0 ? 2.0 : 3.0;
      depth = a.y;
      st = vec2(-sy * d.x, -d.z);
    } else {
      float sz = d.z >= 0.0 ? 1.0 : -1.0;
      face = sz > 0.0 ? 4.0 : 5.0;
      depth = a.z;
      st = vec2(d.x, -sz * d.y);
    }
    vec2 ndc = st * nf.z / max(depth, 1e-6);
    vec2 origin = map.xy + vec2(mod(face, 3.0), floor(face / 3.0)) * map.z;
    uv = origin + (ndc * 0.5 + 0.5) * map.z;
    cell = vec4(origin, origin + map.z);
  } else {
    vec4 q = vec4(Q, 1.0);
    vec4 c = vec4(dot(lightTexel(i, 7), q), dot(lightTexel(i, 8), q),
                  dot(lightTexel(i, 9), q), dot(lightTexel(i, 10), q));
    if (c.w <= 0.0) return 1.0;
    vec3 ndc = c.xyz / c.w;
    if (abs(ndc.x) >= 1.0 || abs(ndc.y) >= 1.0) return 1.0;  // outside the map: nothing shadows it
    uv = map.xy + (ndc.xy * 0.5 + 0.5) * map.z;
    depth = kind == 1 ? ndc.z : c.w;
    cell = vec4(map.xy, map.xy + map.z);
  }
  float n = nf.x, f = nf.y, z;
  if (kind == 1) {
    z = depth * 0.5 + 0.5 - sh.y / (f - n);
  } else {
    float biased = max(depth - sh.y, n);
    z = 0.5 * ((f + n) / (f - n) - 2.0 * f * n / ((f - n) * biased)) + 0.5;
  }
  // Beyond the map's far plane: still behind whatever the map holds.
  z = min(z, 0.99999);
  cell += vec4(0.5, 0.5, -0.5, -0.5) * uAtlasTexel;
  return mix(1.0, shadowFilter(uv, z, cell, sh.z), sh.x);
}

// Light of radiance `light` arriving from direction l, reflected towards the eye (GGX).
vec3 brdf(Surface s, vec3 l, float nl, vec3 light, vec3 f0, vec3 diffuse, float a2, float rough, float nv) {
  vec3 h = normalize(l + s.V);
  float nh = max(dot(s.N, h), 0.0);
  float dn = nh * nh * (a2 - 1.0) + 1.0;
  float D = a2 / (PI * dn * dn);
  float k = (rough + 1.0) * (rough + 1.0) / 8.0;
  float G = nv / (nv * (1.0 - k) + k) * nl / (nl * (1.0 - k) + k);
  // Clamped: pow() of a negative base is undefined (NaN, a black pixel
  // where a light lies exactly between the eye and the surface).
  vec3 F = f0 + (1.0 - f0) * pow(clamp(1.0 - dot(h, s.V), 0.0, 1.0), 5.0);
  vec3 spec = D * G * F / max(4.0 * nv * nl, 1e-4);
  return ((1.0 - F) * diffuse / PI + spec) * light * nl;
}

// The first directional light's shadow at this pixel (1: lit), for
// indirectLight(): its shadow also dims the environment's reflection, or a
// metallic floor (lit mostly by the sky it mirrors) shows no shadow and a
// robot on it seems to float.
float gSunVisibility = 1.0;

// Directional light `i` (< uHeadCount) from the uniforms; its shadow map
// is orthographic.
vec3 sunLight(int i, Surface s, vec3 f0, vec3 diffuse, float a2, float rough, float nv) {
  vec4 t0 = headTexel(i, 0);
  vec3 l = -headTexel(i, 1).xyz;
  float nl = dot(s.N, l);
  if (nl <= 0.0) return vec3(0.0);
  float vis = 1.0;
  if (t0.w >= 4.0 && s.receiveShadow) {
    vec4 sh = headTexel(i, 4);
    vec4 map = headTexel(i, 5);
    vec4 nf = headTexel(i, 6);
    vec4 q = vec4(s.P + s.N * sh.w * (1.0 + 2.0 * (1.0 - clamp(nl, 0.0, 1.0))), 1.0);
    vec3 c = vec3(dot(headTexel(i, 7), q), dot(headTexel(i, 8), q), dot(headTexel(i, 9), q));
    if (abs(c.x) < 1.0 && abs(c.y) < 1.0) {
      vec2 uv = map.xy + (c.xy * 0.5 + 0.5) * map.z;
      float z = min(c.z * 0.5 + 0.5 - sh.y / (nf.y - nf.x), 0.99999);
      vec4 cell = vec4(map.xy, map.xy + map.z) + vec4(0.5, 0.5, -0.5, -0.5) * uAtlasTexel;
      vis = mix(1.0, shadowFilter(uv, z, cell, sh.z), sh.x);
    }
  }
  if (i == 0) gSunVisibility = vis;
  return brdf(s, l, nl, headTexel(i, 2).rgb * vis, f0, diffuse, a2, rough, nv);
}

// Light `i` from the buffer, any type, arriving at s and reflected towards
// the eye; its shadow only when `withShadow` (a constant at each call, so
// the loop of lights without maps carries no shadow code at all).
vec3 lightFrom(int i, Surface s, vec3 f0, vec3 diffuse, float a2, float rough, float nv, bool withShadow) {
  vec4 t0 = lightTexel(i, 0);       // position, type (+4: has a shadow map)
  vec4 t1 = lightTexel(i, 1);   // direction, cos(outer cone)
  vec4 t2 = lightTexel(i, 2);   // color, cos(inner cone)
  int code = int(t0.w + 0.5);
  int type = code & 3;
  vec3 l;
  float att = 1.0;
  if (type == 0) {
    l = -t1.xyz;
  } else {
    vec4 t3 = lightTexel(i, 3);  // attenuation, reach
    vec3 from = t0.xyz;
    if (type == 3) {
      // A rectangle: light comes from its point nearest the surface (a
      // representative point), so a long strip lights its whole length.
      vec3 r = lightTexel(i, 11).xyz, u = lightTexel(i, 12).xyz;
      vec3 o = s.P - from;
      from += r * clamp(dot(o, r) / max(dot(r, r), 1e-8), -1.0, 1.0) + u * clamp(dot(o, u) / max(dot(u, u), 1e-8), -1.0, 1.0);
    }
    vec3 d = from - s.P;
    float dist = length(d);
    l = d / max(dist, 1e-4);
    att = 1.0 / max(t3.x + t3.y * dist + t3.z * dist * dist, 1e-4);
    // Down to nothing at the reach, where the tiles stop listing the light.
    if (t3.w > 0.0) att *= clamp(1.0 - pow(dist / t3.w, 4.0), 0.0, 1.0);
    if (type == 2) {
      att *= smoothstep(t1.w, t2.w, dot(-l, t1.xyz));
    } else if (type == 3) {
      att *= max(dot(-l, t1.xyz), 0.0);  // one-sided emitter
    }
  }
  float nl = dot(s.N, l);
  if (nl <= 0.0 || att <= 0.0) return vec3(0.0);
  if (withShadow && code >= 4 && s.receiveShadow) att *= shadowVisibility(i, t0.xyz, s, l);
  return brdf(s, l, nl, t2.rgb * att, f0, diffuse, a2, rough, nv);
}

// Light arriving directly from the scene's lights, reflected towards the
// eye: the directional lights, then the local lights of this pixel's tile.
vec3 directLight(Surface s) {
  float rough = clamp(s.rough, 0.03, 1.0);
  float a2 = rough * rough * rough * rough;
  vec3 f0 = mix(vec3(0.04), s.base.rgb, s.metallic);
  vec3 diffuse = s.base.rgb * (1.0 - s.metallic);
  float nv = max(dot(s.N, s.V), 1e-4);
  vec3 color = vec3(0.0);
  for (int i = 0; i < uHeadCount; ++i) color += sunLight(i, s, f0, diffuse, a2, rough, nv);
#ifdef RSCENE_MANY_SUNS
  for (int i = uHeadCount; i < uDirectionalCount; ++i) color += lightFrom(i, s, f0, diffuse, a2, rough, nv, true);
#endif
#ifdef RSCENE_LOCAL_LIGHTS
  if (!uHasLocalLights) return color;
  ivec2 tile = min(ivec2(gl_FragCoord.xy) / uTileSize, ivec2(uTilesX - 1, uTilesY - 1));
  int cell = tile.y * uTilesX + tile.x;
  int offset = texelFetch(uLightGrid, 3 * cell).r, count = texelFetch(uLightGrid, 3 * cell + 1).r,
      plain = texelFetch(uLightGrid, 3 * cell + 2).r;
  for (int k = 0; k < plain; ++k)
    color += lightFrom(texelFetch(uLightGrid, offset + k).r, s, f0, diffuse, a2, rough, nv, false);
  for (int k = plain; k < count; ++k)
    color += lightFrom(texelFetch(uLightGrid, offset + k).r, s, f0, diffuse, a2, rough, nv, true);
#endif
  return color;
}
)";

}  // namespace rscene::render::shaders
