// GLSL of what volumes do to a surface (surface program): projected
// decals paint it, irradiance volumes add indirect light, fog (global,
// height, local spheres) veils it.  Appended to the surface fragment's
// prelude (shaders.cpp).  The fog part (kFogGlsl) is also the post pass's:
// the sky behind a fog sphere or under height fog is veiled too.
//
// The records of the view (gl_volumes.cpp, VolumeEffects::bind) come in one
// RGBA32F buffer texture, so any number fits and a view with none costs a
// loop that does not run:
//   decals      8 texels each from 0: world -> unit cube rows (3), color
//               (linear rgb, alpha x distance fade), texture layers
//               (albedo, emission, normal, orm; -1 none), uv scale and
//               offset, (albedoMix, emissionEnergy, normalStrength,
//               ormStrength), (edgeFade, normalFade, upperFade, lowerFade)
//   irradiance  5 texels each from uIrradianceBase: world -> unit cube
//               rows (3), (linear color x strength, edgeFade), (half
//               sizes in metres, normalBias)
//   fog spheres 3 texels each from uFogBase: (eye - centre, |eye -
//               centre|^2 - R^2), (linear color, density), (R^2 - (R (1 -
//               edgeFade))^2, noiseScale, noiseStrength, 0)
//
// Each kind is compiled in only when the scene has it (RSCENE_DECALS,
// RSCENE_DECAL_ALBEDO, _EMISSION, _NORMAL, _ORM (a texture slot some
// decal uses), RSCENE_IRRADIANCE, RSCENE_FOG_SPHERES,
// RSCENE_FOG_NOISE, RSCENE_HEIGHT_FOG: VolumeEffects::configure): llvmpipe runs both sides
// of every branch and one pass of a loop that does not run, so code
// skipped at run time is still paid for by every fragment.
#include "render/shaders.hpp"

namespace rscene::render::shaders {

// Before kVolumesGlsl in the surface program (surfaceFragment()), after the
// sky in the post program (postFragment()).
const char* const kFogGlsl = R"(
#if defined(RSCENE_DECALS) || defined(RSCENE_IRRADIANCE) || defined(RSCENE_FOG_SPHERES)
uniform samplerBuffer uVolumeData;
vec4 volumeTexel(int i) { return texelFetch(uVolumeData, i); }
#endif
uniform int uFogCount;
uniform int uFogBase;
uniform vec3 uFogEye;           // the eye the fog spheres' data is relative to
uniform vec4 uHeightFog;        // density, base height, falloff
uniform vec3 uHeightFogColor;   // linear

#ifdef RSCENE_FOG_NOISE
float hash13(vec3 p) {
  p = fract(p * 0.1031);
  p += dot(p, p.zyx + 31.32);
  return fract((p.x + p.y) * p.z);
}

// Smooth value noise in [0, 1].
float valueNoise(vec3 p) {
  vec3 i = floor(p), f = fract(p);
  f = f * f * (3.0 - 2.0 * f);
  float a = mix(mix(hash13(i), hash13(i + vec3(1, 0, 0)), f.x),
                mix(hash13(i + vec3(0, 1, 0)), hash13(i + vec3(1, 1, 0)), f.x), f.y);
  float b = mix(mix(hash13(i + vec3(0, 0, 1)), hash13(i + vec3(1, 0, 1)), f.x),
                mix(hash13(i + vec3(0, 1, 1)), hash13(i + vec3(1, 1, 1)), f.x), f.y);
  return mix(a, b, f.z);
}

#endif

// Optical depth of the height fog along o + t d (unit d), t in [0, len]:
// the integral of density * exp(-falloff (z - base)), in closed form.
float heightFogDepth(vec3 o, vec3 d, float len) {
#ifndef RSCENE_HEIGHT_FOG
  return 0.0;
#else
  float start = uHeightFog.x * exp(clamp(-uHeightFog.z * (o.z - uHeightFog.y), -80.0, 80.0));
  float k = uHeightFog.z * d.z;
  if (abs(k) < 1e-6) return start * len;
  return start * (1.0 - exp(clamp(-k * len, -80.0, 80.0))) / k;
#endif
}

// Integral over [0, u] (u >= 0, both ends of a chord at once) of a fog
// sphere's density profile along a chord, per unit density: 1 where
// u <= inner, (outer2 - s^2) / ramp beyond (s from the chord's middle;
// ramp = R^2 - (R (1 - edgeFade))^2).
vec2 chordIntegral(vec2 u, float inner, float outer2, float ramp) {
  vec2 beyond = inner + (outer2 * (u - inner) - (u * u * u - inner * inner * inner) / 3.0) / ramp;
  return mix(u, beyond, step(inner, u));
}

// `c` seen through the fog spheres crossed by eye + t d, t in [0, len].
// Density is uniform inside and falls to 0 over the outer edgeFade of the
// radius (linearly in r^2, so that the path integral has a closed form),
// modulated by value noise at the middle of the path through it.  No
// sampling loop: llvmpipe would run it for every sample on screen.
vec3 localFogs(vec3 c, vec3 d, float len) {
#ifdef RSCENE_FOG_SPHERES
  int k = 0;
  if (uFogCount > 0) do {
    int b = uFogBase + 3 * k;
    vec4 eyeFromCentre = volumeTexel(b);  // eye - centre, |eye - centre|^2 - R^2
    float tc = -dot(eyeFromCentre.xyz, d);  // the chord's middle
    float outer2 = tc * tc - eyeFromCentre.w;  // half chord, squared
    if (outer2 <= 0.0) continue;
    float outer = sqrt(outer2);
    vec2 s = vec2(max(tc - outer, 0.0), min(tc + outer, len)) - tc;  // the part in [0, len]
    if (s.y <= s.x) continue;
    vec4 colorDensity = volumeTexel(b + 1);
    vec4 shape = volumeTexel(b + 2);  // ramp (R^2 units), noiseScale, noiseStrength
    float ramp = max(shape.x, 1e-6);
    vec2 g = sign(s) * chordIntegral(abs(s), sqrt(max(outer2 - ramp, 0.0)), outer2, ramp);
    float tau = (g.y - g.x) * colorDensity.w;
#ifdef RSCENE_FOG_NOISE
    tau *= 1.0 + shape.z * (2.0 * valueNoise((uFogEye + d * (tc + 0.5 * (s.x + s.y))) * shape.y) - 1.0);
#endif
    c = mix(c, colorDensity.rgb, 1.0 - exp(-max(tau, 0.0)));
  } while (++k < uFogCount);
#endif
  return c;
}

// The background seen along d from the eye: height fog and fog spheres
// out to infinity (post pass).
vec3 backgroundFog(vec3 c, vec3 d) {
#if defined(RSCENE_HEIGHT_FOG) || defined(RSCENE_FOG_SPHERES)
  float tau = heightFogDepth(uFogEye, d, 1e30);
  if (tau > 0.0) c = mix(c, uHeightFogColor, 1.0 - exp(-tau));
  c = localFogs(c, d, 1e30);
#endif
  return c;
}
)";

const char* const kVolumesGlsl = R"(
uniform float uFogDensity;
uniform vec3 uFogColorLinear;
uniform int uDecalCount;
uniform int uIrradianceCount;
uniform int uIrradianceBase;
#if defined(RSCENE_DECAL_ALBEDO) || defined(RSCENE_DECAL_EMISSION) || defined(RSCENE_DECAL_NORMAL) || defined(RSCENE_DECAL_ORM)
uniform sampler2DArray uDecalTextures;
#endif

#if defined(RSCENE_DECALS) || defined(RSCENE_IRRADIANCE)
// World point -> the unit cube of the box whose rows start at texel b.
vec3 boxLocal(int b, vec3 P) {
  vec4 p = vec4(P, 1.0);
  return vec3(dot(volumeTexel(b), p), dot(volumeTexel(b + 1), p), dot(volumeTexel(b + 2), p));
}
#endif

// Projected decals: may change the surface's color, normal, roughness,
// metallic and emission.  A decal projects along its box's local -z; its
// image is upright seen from +z with local +y up.
void applyDecals(inout Surface s) {
#ifdef RSCENE_DECALS
  // Texture gradients from the position's: the loop is non-uniform flow.
  vec3 dPdx = dFdx(s.P), dPdy = dFdy(s.P);
  vec3 geometric = s.N;
  // A cheap pass finds the range of decals whose boxes hold P; the full
  // work runs over that range only (llvmpipe pays for a loop's body once
  // per pass for every fragment, so the expensive body must not run once
  // per decal in view).  Loops are do-whiles behind an if: a while loop
  // costs llvmpipe one more (masked) pass of its body than it runs.
  int first = uDecalCount, last = -1;
  int k = 0;
  if (uDecalCount > 0) do {
    if (all(lessThanEqual(abs(boxLocal(8 * k, s.P)), vec3(1.0)))) {
      first = min(first, k);
      last = k;
    }
  } while (++k < uDecalCount);
  k = first;
  if (first <= last) do {
    int b = 8 * k;
    vec3 q = boxLocal(b, s.P);
    if (any(greaterThan(abs(q), vec3(1.0)))) continue;
    vec4 color = volumeTexel(b + 3);
    vec4 layers = volumeTexel(b + 4);
    vec4 uvst = volumeTexel(b + 5);
    vec4 mixes = volumeTexel(b + 6);  // albedoMix, emissionEnergy, normalStrength, ormStrength
    vec4 fades = volumeTexel(b + 7);  // edgeFade, normalFade, upperFade, lowerFade
    vec3 ax = volumeTexel(b).xyz, ay = volumeTexel(b + 1).xyz, az = volumeTexel(b + 2).xyz;
    float fade = 1.0;
    if (fades.x > 0.0) fade *= clamp(min(1.0 - abs(q.x), 1.0 - abs(q.y)) / fades.x, 0.0, 1.0);
    float zFade = q.z > 0.0 ? fades.z : fades.w;
    if (zFade > 0.0) fade *= pow(max(1.0 - abs(q.z), 0.0), zFade);
    if (fades.y > 0.0) fade *= smoothstep(fades.y, 1.0, dot(geometric, normalize(az)) * 0.5 + 0.5);
    if (fade <= 0.0) continue;
    vec2 uv = vec2(q.x * 0.5 + 0.5, 0.5 - q.y * 0.5) * uvst.xy + uvst.zw;
#if defined(RSCENE_DECAL_ALBEDO) || defined(RSCENE_DECAL_EMISSION) || defined(RSCENE_DECAL_NORMAL) || defined(RSCENE_DECAL_ORM)
    // One untiled image (the default uvScale and uvOffset): kept half a texel
    // inside, so that filtering does not wrap the opposite edge in.
    if (uvst == vec4(1.0, 1.0, 0.0, 0.0)) {
      vec2 inset = 0.5 / vec2(textureSize(uDecalTextures, 0).xy);
      uv = clamp(uv, inset, 1.0 - inset);
    }
#endif
    vec2 gx = vec2(dot(ax, dPdx), -dot(ay, dPdx)) * 0.5 * uvst.xy;
    vec2 gy = vec2(dot(ax, dPdy), -dot(ay, dPdy)) * 0.5 * uvst.xy;
    vec4 albedo = color;
    vec3 glow = albedo.rgb;
#ifdef RSCENE_DECAL_ALBEDO
    if (layers.x >= 0.0) {
      vec4 t = textureGrad(uDecalTextures, vec3(uv, layers.x), gx, gy);
      albedo *= vec4(toLinear(t.rgb), t.a);
    }
    glow = albedo.rgb;
#endif
#ifdef RSCENE_DECAL_EMISSION
    // Emission: the emission texture's, else the decal's own color, x emissionEnergy.
    if (layers.y >= 0.0) glow = toLinear(textureGrad(uDecalTextures, vec3(uv, layers.y), gx, gy).rgb);
#endif
    float w = clamp(albedo.a * fade, 0.0, 1.0);
    s.base.rgb = mix(s.base.rgb, albedo.rgb, w * mixes.x);
    s.emissive += glow * mixes.y * w;
#ifdef RSCENE_DECAL_NORMAL
    if (layers.z >= 0.0) {
      vec3 n = textureGrad(uDecalTextures, vec3(uv, layers.z), gx, gy).xyz * 2.0 - 1.0;
      vec3 nw = normalize(normalize(ax) * n.x + normalize(ay) * n.y + normalize(az) * n.z);
      s.N = normalize(mix(s.N, nw, clamp(w * mixes.z, 0.0, 1.0)));
    }
#endif
#ifdef RSCENE_DECAL_ORM
    if (layers.w >= 0.0) {
      // Occlusion darkens the color: the Surface carries no separate
      // occlusion term for the indirect light alone.
      vec3 orm = textureGrad(uDecalTextures, vec3(uv, layers.w), gx, gy).xyz;
      float m = clamp(w * mixes.w, 0.0, 1.0);
      s.base.rgb *= mix(1.0, orm.r, m);
      s.rough = clamp(mix(s.rough, orm.g, m), 0.03, 1.0);
      s.metallic = mix(s.metallic, orm.b, m);
    }
#endif
  } while (++k <= last);
#endif
}

// Indirect light from irradiance volumes around s.P (linear rgb; its
// diffuse response is the caller's): the point pushed off the surface by
// normalBias is tested, the light fading over edgeFade metres at the faces.
vec3 volumeIrradiance(Surface s) {
  vec3 sum = vec3(0.0);
#ifdef RSCENE_IRRADIANCE
  int k = 0;
  if (uIrradianceCount > 0) do {
    int b = uIrradianceBase + 5 * k;
    vec4 sizes = volumeTexel(b + 4);  // half sizes in metres, normalBias
    vec3 q = boxLocal(b, s.P + s.N * sizes.w);
    if (any(greaterThan(abs(q), vec3(1.0)))) continue;
    vec4 ce = volumeTexel(b + 3);
    float w = 1.0;
    if (ce.w > 0.0) {
      vec3 inside = (1.0 - abs(q)) * sizes.xyz;
      w = clamp(min(inside.x, min(inside.y, inside.z)) / ce.w, 0.0, 1.0);
    }
    sum += ce.rgb * w;
  } while (++k < uIrradianceCount);
#endif
  return sum;
}

// `color` seen through the fog between the eye and P: the global
// exponential fog and the height fog (one color), then the fog spheres.
vec3 applyFog(vec3 color, vec3 P, vec3 eye) {
#if defined(RSCENE_HEIGHT_FOG) || defined(RSCENE_FOG_SPHERES)
  vec3 d = P - eye;
  float len = max(length(d), 1e-6);
  d /= len;
  float tau = uFogDensity * len + heightFogDepth(eye, d, len);
  if (tau > 0.0) color = mix(color, uFogColorLinear, 1.0 - exp(-tau));
  return localFogs(color, d, len);
#else
  if (uFogDensity > 0.0) color = mix(color, uFogColorLinear, 1.0 - exp(-uFogDensity * length(eye - P)));
  return color;
#endif
}
)";

}  // namespace rscene::render::shaders
