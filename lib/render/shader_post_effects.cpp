// GLSL of the post-processing passes (gl_post.cpp runs them, each a
// full-screen triangle of kPostVertex): ambient occlusion, the tone-mapping
// pass that adds bloom and depth of field, the bloom chain, the depth of
// field gather, the luminance of auto exposure and FXAA.  The post chain
// works in linear HDR (the composite of shader_post.cpp) until the final
// pass; FXAA runs on its display colors.
#include "render/shaders.hpp"

namespace rscene::render::shaders {
namespace {

// Distance along the view axis of a depth-buffer value: the eye-space z
// depends on the NDC depth alone in every projection the renderer makes
// (perspective, orthographic, intrinsics).
const char* const kViewDepthGlsl = R"(
uniform mat4 uInvProj;
float viewDepth(float z) {
  vec4 v = uInvProj * vec4(0.0, 0.0, z * 2.0 - 1.0, 1.0);
  return -v.z / v.w;
}
// Thin lens: uDof = (aperture x focal length in pixels / 2, 1 / focus distance, largest radius).
uniform vec3 uDof;
float cocRadius(float z) { return min(uDof.x * abs(uDof.y - 1.0 / max(viewDepth(z), 1e-6)), uDof.z); }
)";

const char* const kFinalMain = R"(
uniform sampler2D uHdrImage;  // the composite: linear HDR, coverage in alpha
uniform bool uHasBloom;
uniform sampler2D uBloom;     // the bloom chain's top level (exposed units)
uniform float uBloomGain;     // intensity / levels / exposure
uniform bool uHasDof;
uniform sampler2D uDofImage;  // the half-size gather
uniform sampler2D uDepth;

// The depth of field image at full size: of the four nearest half-size
// texels, those whose blur radius is close to this pixel's, so that a
// blurred background next to a sharp edge does not take its colour.
vec3 dofUpsampled(ivec2 p, float coc) {
  ivec2 size = textureSize(uDofImage, 0);
  vec2 h = (vec2(p) + 0.5) * 0.5 - 0.5;
  ivec2 base = ivec2(floor(h));
  vec2 f = h - vec2(base);
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  for (int k = 0; k < 4; ++k) {
    ivec2 o = ivec2(k & 1, k >> 1);
    vec4 d = texelFetch(uDofImage, clamp(base + o, ivec2(0), size - 1), 0);
    float w = mix(1.0 - f.x, f.x, float(o.x)) * mix(1.0 - f.y, f.y, float(o.y)) / (1e-3 + abs(d.a - coc));
    sum += d.rgb * w;
    weight += w;
  }
  return sum / max(weight, 1e-9);
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec2 uv = gl_FragCoord.xy / vec2(textureSize(uHdrImage, 0));
  vec4 c = texelFetch(uHdrImage, p, 0);
  vec3 lit = c.rgb;
  if (uHasDof) {
    float coc = cocRadius(texelFetch(uDepth, p, 0).r);
    float t = smoothstep(0.5, 1.5, coc);
    if (t > 0.0) lit = mix(lit, dofUpsampled(p, coc), t);
  }
  if (uHasBloom) lit += texture(uBloom, uv).rgb * uBloomGain;
  vec3 d = toneMap(lit);
  // A plain_color background shows as written (plus the glow on it).
  if (uMode == 0 && !uTransparent) d += (1.0 - c.a) * (uBackground - toneMap(uPlainLinear));
  fragColor = vec4(d, uTransparent ? c.a : 1.0);
}
)";

}  // namespace

std::string finalFragment() { return std::string(kPostPrelude) + kViewDepthGlsl + kFinalMain; }

// The depth buffer of a multisampled pass, one value per pixel: the
// nearest of its samples, so that a pixel an edge crosses takes the depth
// of the surface in front (whose colour it mostly shows) and depth of
// field keeps it with that surface.
const char* const kDepthResolveFragment = R"(#version 330 core
out vec4 fragColor;
uniform sampler2DMS uDepthMs;
uniform int uSamples;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float z = 1.0;
  for (int i = 0; i < uSamples; ++i) z = min(z, texelFetch(uDepthMs, p, i).r);
  fragColor = vec4(z);
}
)";

// Ambient obscurance at half size: eye positions from the depth buffer,
// the normal from the neighbours on the flatter side (no smearing across
// silhouettes), 10 samples on a golden spiral rotated by a 4x4 Bayer
// pattern that the blur then averages out.  Each sample counts the cosine
// of its rise over the surface, faded by distance (0 past uRadius): the
// mean is bounded, where McGuire's 1/distance weight of scalable ambient
// obscurance went to black at contacts (issue 27's dark smudges).
// Writes (occlusion, view depth) for the depth-aware blur.  It reads the
// depth buffer itself (sample 0 of a multisampled one: ssaoFragment(true))
// unless depth of field had it resolved already.
const char* const kSsaoMain = R"(
out vec4 fragColor;
uniform DEPTH_SAMPLER uDepth;  // full size: texelFetch(uDepth, p, 0) is level 0 or sample 0
uniform ivec2 uDepthSize;
uniform mat4 uInvProj;
uniform float uPixelsPerMetre; // at 1 m (perspective) or anywhere (orthographic)
uniform bool uOrtho;
uniform float uRadius;         // metres
uniform float uIntensity;
uniform float uMaxPixels;
const int N = 10;
const float kBias = 0.1, kStrength = 4.0;

vec3 eyePos(ivec2 p, ivec2 size) {
  float z = texelFetch(uDepth, p, 0).r;
  vec2 ndc = (vec2(p) + 0.5) / vec2(size) * 2.0 - 1.0;
  vec4 v = uInvProj * vec4(ndc, z * 2.0 - 1.0, 1.0);
  return v.xyz / v.w;
}

void main() {
  ivec2 size = uDepthSize;
  ivec2 p = min(ivec2(gl_FragCoord.xy) * 2, size - 1);
  if (texelFetch(uDepth, p, 0).r >= 1.0) {  // nothing drawn: the background
    fragColor = vec4(1.0, 0.0, 0.0, 0.0);
    return;
  }
  vec3 P = eyePos(p, size);
  vec3 l = eyePos(max(p - ivec2(1, 0), ivec2(0)), size), r = eyePos(min(p + ivec2(1, 0), size - 1), size);
  vec3 b = eyePos(max(p - ivec2(0, 1), ivec2(0)), size), t = eyePos(min(p + ivec2(0, 1), size - 1), size);
  vec3 dx = abs(r.z - P.z) < abs(P.z - l.z) ? r - P : P - l;
  vec3 dy = abs(t.z - P.z) < abs(P.z - b.z) ? t - P : P - b;
  vec3 n = normalize(cross(dx, dy));
  float dist = uOrtho ? 1.0 : -P.z;
  float rPx = min(uRadius * uPixelsPerMetre / dist, uMaxPixels);
  if (rPx < 1.0) {
    fragColor = vec4(1.0, -P.z, 0.0, 0.0);
    return;
  }
  const float bayer[16] = float[16](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0, 3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);
  ivec2 cell = ivec2(gl_FragCoord.xy) & 3;
  float angle = (bayer[cell.y * 4 + cell.x] + 0.5) * (6.2831853 / 16.0);
  float r2 = uRadius * uRadius;
  float sum = 0.0;
  for (int i = 0; i < N; ++i) {
    float s = (float(i) + 0.5) / float(N);
    float a = angle + float(i) * 2.3999632;  // the golden angle
    ivec2 q = clamp(p + ivec2(round(vec2(cos(a), sin(a)) * (s * rPx))), ivec2(0), size - 1);
    vec3 v = eyePos(q, size) - P;
    float vv = dot(v, v);
    // How far above the surface's plane the sample rises (the cosine,
    // less a bias of ~6 degrees against depth noise), faded to nothing at
    // the radius: bounded, so that a sample next to a contact counts as
    // much as one further up the wall and a contact is not a black smudge.
    float falloff = max(1.0 - vv / r2, 0.0);
    float rise = dot(v, n) * inversesqrt(max(vv, 1e-8));
    sum += falloff * max(rise - kBias, 0.0);
  }
  float ao = clamp(1.0 - uIntensity * kStrength * sum / float(N), 0.0, 1.0);
  fragColor = vec4(ao, -P.z, 0.0, 0.0);
}
)";

std::string ssaoFragment(bool multisampled) {
  return std::string("#version 330 core\n#define DEPTH_SAMPLER ") + (multisampled ? "sampler2DMS" : "sampler2D") +
         "\n" + kSsaoMain;
}

// 4x4 depth-aware average of the raw occlusion: one period of the Bayer
// rotation, without mixing surfaces more than 5 % apart in depth.
const char* const kSsaoBlurFragment = R"(#version 330 core
out vec4 fragColor;
uniform sampler2D uAoRaw;  // (occlusion, view depth); depth 0: background
void main() {
  ivec2 size = textureSize(uAoRaw, 0);
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec2 c = texelFetch(uAoRaw, p, 0).rg;
  if (c.g <= 0.0) {
    fragColor = vec4(1.0);
    return;
  }
  float sum = 0.0, weight = 0.0;
  for (int y = -2; y < 2; ++y)
    for (int x = -2; x < 2; ++x) {
      vec2 s = texelFetch(uAoRaw, clamp(p + ivec2(x, y), ivec2(0), size - 1), 0).rg;
      float w = s.g > 0.0 ? max(0.0, 1.0 - abs(s.g - c.g) / (0.05 * c.g)) : 0.0;
      sum += s.r * w;
      weight += w;
    }
  fragColor = vec4(weight > 0.0 ? sum / weight : c.r);
}
)";

// Bloom, first level (half size): what is brighter than the threshold
// after exposure, with a soft knee (knee = threshold / 2) so that it does
// not start at a hard edge; 4 bilinear taps cover 4x4 pixels.  The source
// is clamped so that the sun's disk does not flood the image.
const char* const kBloomPrefilterFragment = R"(#version 330 core
out vec4 fragColor;
uniform sampler2D uSrc;
uniform vec2 uTargetTexel;
uniform float uExposure;
uniform float uThreshold;
uniform float uSourceClamp;
void main() {
  vec2 uv = gl_FragCoord.xy * uTargetTexel;
  vec2 h = 1.0 / vec2(textureSize(uSrc, 0));
  vec3 c = texture(uSrc, uv + vec2(-h.x, -h.y)).rgb + texture(uSrc, uv + vec2(h.x, -h.y)).rgb +
           texture(uSrc, uv + vec2(-h.x, h.y)).rgb + texture(uSrc, uv + vec2(h.x, h.y)).rgb;
  c = min(c * (0.25 * uExposure), vec3(uSourceClamp));
  float bright = max(c.r, max(c.g, c.b));
  float knee = 0.5 * uThreshold;
  float soft = clamp(bright - uThreshold + knee, 0.0, 2.0 * knee);
  soft = soft * soft / (4.0 * knee + 1e-5);
  float contribution = max(soft, bright - uThreshold) / max(bright, 1e-5);
  fragColor = vec4(c * contribution, 1.0);
}
)";

// Dual-filter (Kawase) halving: the centre and four diagonal taps,
// uSpread source texels out (bloomRadius / 4).
const char* const kBloomDownFragment = R"(#version 330 core
out vec4 fragColor;
uniform sampler2D uSrc;
uniform vec2 uTargetTexel;
uniform float uSpread;
void main() {
  vec2 uv = gl_FragCoord.xy * uTargetTexel;
  vec2 h = uSpread / vec2(textureSize(uSrc, 0));
  vec3 c = texture(uSrc, uv).rgb * 4.0 + texture(uSrc, uv - h).rgb + texture(uSrc, uv + h).rgb +
           texture(uSrc, uv + vec2(h.x, -h.y)).rgb + texture(uSrc, uv - vec2(h.x, -h.y)).rgb;
  fragColor = vec4(c / 8.0, 1.0);
}
)";

// Dual-filter doubling: a tent of eight taps, added (blending) onto the
// level above, so that the top level ends as the sum of every level.
const char* const kBloomUpFragment = R"(#version 330 core
out vec4 fragColor;
uniform sampler2D uSrc;
uniform vec2 uTargetTexel;
uniform float uSpread;
void main() {
  vec2 uv = gl_FragCoord.xy * uTargetTexel;
  vec2 h = uSpread / vec2(textureSize(uSrc, 0));
  vec3 c = texture(uSrc, uv + vec2(-2.0 * h.x, 0.0)).rgb + texture(uSrc, uv + vec2(2.0 * h.x, 0.0)).rgb +
           texture(uSrc, uv + vec2(0.0, -2.0 * h.y)).rgb + texture(uSrc, uv + vec2(0.0, 2.0 * h.y)).rgb +
           2.0 * (texture(uSrc, uv + vec2(-h.x, h.y)).rgb + texture(uSrc, uv + vec2(h.x, h.y)).rgb +
                  texture(uSrc, uv + vec2(h.x, -h.y)).rgb + texture(uSrc, uv + vec2(-h.x, -h.y)).rgb);
  fragColor = vec4(c / 12.0, 1.0);
}
)";

// Depth of field at half size: a gather over a disk of the pixel's own
// blur radius (24 samples on a golden spiral), writing the radius in
// alpha for finalFragment's upsampling.  Each half-size texel stands for
// one full-size pixel (its colour and depth together, never a mix of a
// sharp edge and what lies behind it).  A sample counts where its own blur
// circle reaches this pixel; one behind the pixel is limited to twice the
// pixel's radius, so that a blurred background does not spill over a sharp
// subject (Gustafsson's single-pass bokeh).
const char* const kDofMain = R"(
out vec4 fragColor;
uniform sampler2D uHdrImage;
uniform sampler2D uDepth;
const int N = 24;
void main() {
  ivec2 size = textureSize(uHdrImage, 0);
  ivec2 c = min(ivec2(gl_FragCoord.xy) * 2 + 1, size - 1);
  float z = texelFetch(uDepth, c, 0).r;
  float centreDepth = viewDepth(z), centreCoc = cocRadius(z);
  vec3 sum = texelFetch(uHdrImage, c, 0).rgb;
  float weight = 1.0;
  for (int i = 0; i < N; ++i) {
    float a = float(i) * 2.3999632;
    vec2 off = vec2(cos(a), sin(a)) * (sqrt((float(i) + 0.5) / float(N)) * centreCoc);
    ivec2 q = clamp(c + ivec2(round(off)), ivec2(0), size - 1);
    float zs = texelFetch(uDepth, q, 0).r;
    float cs = cocRadius(zs);
    if (viewDepth(zs) > centreDepth) cs = min(cs, 2.0 * centreCoc);
    float w = clamp(cs - length(off) + 1.0, 0.0, 1.0);
    sum += texelFetch(uHdrImage, q, 0).rgb * w;
    weight += w;
  }
  fragColor = vec4(sum / weight, centreCoc);
}
)";

std::string dofFragment() { return std::string("#version 330 core\n") + kViewDepthGlsl + kDofMain; }

// Auto exposure: the log of the luminance of a 1/16 downsample (4 bilinear
// taps per 16x16 block), read back and averaged on the CPU.
const char* const kLuminanceFragment = R"(#version 330 core
out vec4 fragColor;
uniform sampler2D uSrc;
uniform vec2 uTargetTexel;
void main() {
  vec2 uv = gl_FragCoord.xy * uTargetTexel;
  vec2 h = 4.0 / vec2(textureSize(uSrc, 0));
  const vec3 w = vec3(0.2126, 0.7152, 0.0722);
  float s = log(max(dot(texture(uSrc, uv + vec2(-h.x, -h.y)).rgb, w), 1e-4)) +
            log(max(dot(texture(uSrc, uv + vec2(h.x, -h.y)).rgb, w), 1e-4)) +
            log(max(dot(texture(uSrc, uv + vec2(-h.x, h.y)).rgb, w), 1e-4)) +
            log(max(dot(texture(uSrc, uv + vec2(h.x, h.y)).rgb, w), 1e-4));
  fragColor = vec4(0.25 * s);
}
)";

// FXAA 3.11, quality preset 12 (Lottes 2011; the structure of McNopper's
// GLSL port): on display colors, luma from rgb, 5 search steps along the
// edge (1, 1.5, 2, 4, 12 pixels), subpixel blending 0.75.
const char* const kFxaaFragment = R"(#version 330 core
out vec4 fragColor;
uniform sampler2D uLdr;  // display colors, linear filtering
const float EDGE_MIN = 0.0312, EDGE_MAX = 0.125, SUBPIXEL = 0.75;
const int STEPS = 5;  // FXAA_QUALITY__PRESET 12, the default of FXAA 3.11
const float QUALITY[5] = float[5](1.0, 1.5, 2.0, 4.0, 12.0);

float luma(vec4 c) { return dot(c.rgb, vec3(0.299, 0.587, 0.114)); }
float lumaAt(vec2 uv) { return luma(textureLod(uLdr, uv, 0.0)); }

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec2 inv = 1.0 / vec2(textureSize(uLdr, 0));
  vec2 uv = gl_FragCoord.xy * inv;
  vec4 centre = texelFetch(uLdr, p, 0);
  float lC = luma(centre);
  float lD = luma(texelFetchOffset(uLdr, p, 0, ivec2(0, -1))), lU = luma(texelFetchOffset(uLdr, p, 0, ivec2(0, 1)));
  float lL = luma(texelFetchOffset(uLdr, p, 0, ivec2(-1, 0))), lR = luma(texelFetchOffset(uLdr, p, 0, ivec2(1, 0)));
  float lMin = min(lC, min(min(lD, lU), min(lL, lR)));
  float lMax = max(lC, max(max(lD, lU), max(lL, lR)));
  float range = lMax - lMin;
  if (range < max(EDGE_MIN, lMax * EDGE_MAX)) {  // no edge here: most pixels stop at 5 fetches
    fragColor = centre;
    return;
  }
  float lDL = luma(texelFetchOffset(uLdr, p, 0, ivec2(-1, -1))), lUR = luma(texelFetchOffset(uLdr, p, 0, ivec2(1, 1)));
  float lUL = luma(texelFetchOffset(uLdr, p, 0, ivec2(-1, 1))), lDR = luma(texelFetchOffset(uLdr, p, 0, ivec2(1, -1)));
  float lDU = lD + lU, lLR = lL + lR;
  float lLeft = lDL + lUL, lDown = lDL + lDR, lRight = lDR + lUR, lUp = lUR + lUL;
  float edgeH = abs(-2.0 * lL + lLeft) + abs(-2.0 * lC + lDU) * 2.0 + abs(-2.0 * lR + lRight);
  float edgeV = abs(-2.0 * lU + lUp) + abs(-2.0 * lC + lLR) * 2.0 + abs(-2.0 * lD + lDown);
  bool horizontal = edgeH >= edgeV;
  float l1 = horizontal ? lD : lL, l2 = horizontal ? lU : lR;
  float g1 = l1 - lC, g2 = l2 - lC;
  bool steepest1 = abs(g1) >= abs(g2);
  float gScaled = 0.25 * max(abs(g1), abs(g2));
  float stepLength = horizontal ? inv.y : inv.x;
  float lLocal;
  if (steepest1) {
    stepLength = -stepLength;
    lLocal = 0.5 * (l1 + lC);
  } else {
    lLocal = 0.5 * (l2 + lC);
  }
  vec2 cur = uv;
  if (horizontal) cur.y += 0.5 * stepLength; else cur.x += 0.5 * stepLength;
  vec2 offset = horizontal ? vec2(inv.x, 0.0) : vec2(0.0, inv.y);
  vec2 uv1 = cur - offset * QUALITY[0], uv2 = cur + offset * QUALITY[0];
  float end1 = lumaAt(uv1) - lLocal, end2 = lumaAt(uv2) - lLocal;
  bool reached1 = abs(end1) >= gScaled, reached2 = abs(end2) >= gScaled;
  if (!reached1) uv1 -= offset * QUALITY[1];
  if (!reached2) uv2 += offset * QUALITY[1];
  for (int i = 2; i < STEPS && !(reached1 && reached2); ++i) {
    if (!reached1) end1 = lumaAt(uv1) - lLocal;
    if (!reached2) end2 = lumaAt(uv2) - lLocal;
    reached1 = abs(end1) >= gScaled;
    reached2 = abs(end2) >= gScaled;
    if (!reached1) uv1 -= offset * QUALITY[i];
    if (!reached2) uv2 += offset * QUALITY[i];
  }
  float d1 = horizontal ? uv.x - uv1.x : uv.y - uv1.y;
  float d2 = horizontal ? uv2.x - uv.x : uv2.y - uv.y;
  bool nearer1 = d1 < d2;
  float pixelOffset = -min(d1, d2) / (d1 + d2) + 0.5;
  bool correct = ((nearer1 ? end1 : end2) < 0.0) != (lC < lLocal);
  float finalOffset = correct ? pixelOffset : 0.0;
  float lAverage = (1.0 / 12.0) * (2.0 * (lDU + lLR) + lLeft + lRight);
  float sub1 = clamp(abs(lAverage - lC) / range, 0.0, 1.0);
  float sub2 = (-2.0 * sub1 + 3.0) * sub1 * sub1;
  finalOffset = max(finalOffset, sub2 * sub2 * SUBPIXEL);
  vec2 fuv = uv;
  if (horizontal) fuv.y += finalOffset * stepLength; else fuv.x += finalOffset * stepLength;
  fragColor = textureLod(uLdr, fuv, 0.0);
}
)";

}  // namespace rscene::render::shaders
