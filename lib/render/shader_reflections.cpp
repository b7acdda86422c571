// GLSL of the indirect light: the surface program's indirectLight() (the
// scene's ambient colour, the environment's image-based light, reflection
// probes) and the cube-face programs that build what it samples
// (gl_reflections.cpp): the environment or a probe's capture into a cube,
// and its GGX prefiltering by roughness.
#include "render/reflection_shaders.hpp"
#include "render/shaders.hpp"

namespace rscene::render::shaders {

// Surface program.  uEnvSh and uProbeSh: irradiance / pi as nine
// spherical harmonics each (environment_light.hpp's IrradianceSh).  The
// probes' code is there only when surfaceFragment(true) defines
// RSCENE_REFLECTION_PROBES and the cube map arrays they sample exist (GL
// 4.0 or ARB_texture_cube_map_array; without, gl_reflections.cpp warns,
// RS9060).
const char* const kReflectionsGlsl = R"(
uniform vec3 uAmbient;
uniform samplerCube uEnvSpecular;  // GGX-prefiltered radiance, mip = roughness x uEnvLods
uniform sampler2D uBrdfLut;        // split-sum scale and bias by (n.v, roughness)
uniform float uEnvLods;
uniform float uEnvIntensity;
uniform vec3 uEnvSh[9];
#if defined(RSCENE_REFLECTION_PROBES) && defined(GL_ARB_texture_cube_map_array)
#define PROBES 1
uniform samplerCubeArray uProbeCubes;
uniform int uProbeCount;
uniform float uProbeLods;
uniform vec4 uProbeSphere[8];  // capture position, radius of influence
uniform vec4 uProbeBoxMin[8];  // w: 1 for box projection
uniform vec4 uProbeBoxMax[8];  // w: strength
uniform vec3 uProbeSh[72];     // 9 a probe, as uEnvSh
#endif

// Irradiance / pi along n from nine harmonics (environment_light.hpp),
// passed as values so that the environment's are read at constant indices.
vec3 shIrradiance(vec3 c0, vec3 c1, vec3 c2, vec3 c3, vec3 c4, vec3 c5, vec3 c6, vec3 c7, vec3 c8, vec3 n) {
  vec3 e = 0.282095 * c0 + 0.488603 * (c1 * n.y + c2 * n.z + c3 * n.x) +
           1.092548 * (c4 * (n.x * n.y) + c5 * (n.y * n.z) + c7 * (n.x * n.z)) +
           0.315392 * c6 * (3.0 * n.z * n.z - 1.0) + 0.546274 * c8 * (n.x * n.x - n.y * n.y);
  return max(e, vec3(0.0));
}

#ifdef PROBES
// Parallax correction: where the reflected ray from P meets the probe's
// box, seen from the capture point, so that the walls of a room reflect
// where they are rather than as if infinitely far.
vec3 probeDirection(int i, vec3 P, vec3 R) {
  vec3 lo = uProbeBoxMin[i].xyz, hi = uProbeBoxMax[i].xyz;
  // A room's walls lie on its box: a margin keeps their points inside,
  // where rounding would otherwise flip them in and out in stripes.
  vec3 margin = 1e-3 * (hi - lo) + 1e-4;
  if (uProbeBoxMin[i].w < 0.5 || any(lessThan(P, lo - margin)) || any(greaterThan(P, hi + margin))) return R;
  vec3 r = mix(R, vec3(1e-6), equal(R, vec3(0.0)));
  vec3 far = max((hi - P) / r, (lo - P) / r);
  float t = min(min(far.x, far.y), far.z);
  return P + R * t - uProbeSphere[i].xyz;
}
#endif

// Light from the surroundings at s: diffuse (irradiance / pi along s.N)
// and specular (prefiltered radiance along R for s.rough).  Probes whose
// sphere holds s.P replace the environment, fading over the outer fifth
// of their radius; where several overlap they are averaged by weight.
void surroundings(Surface s, vec3 R, out vec3 diffuse, out vec3 specular) {
  diffuse = vec3(0.0);
  specular = vec3(0.0);
  float total = 0.0;
#ifdef PROBES
  for (int i = 0; i < 8; ++i) {
    if (i >= uProbeCount) break;
    vec4 sphere = uProbeSphere[i];
    float dist = length(s.P - sphere.xyz);
    if (dist >= sphere.w) continue;
    float w = 1.0 - smoothstep(0.8 * sphere.w, sphere.w, dist);
    float strength = uProbeBoxMax[i].w;
    vec3 dir = probeDirection(i, s.P, R);
    specular += (w * strength) * textureLod(uProbeCubes, vec4(dir, float(i)), s.rough * uProbeLods).rgb;
    int b = 9 * i;
    diffuse += (w * strength) * shIrradiance(uProbeSh[b], uProbeSh[b + 1], uProbeSh[b + 2], uProbeSh[b + 3],
                                             uProbeSh[b + 4], uProbeSh[b + 5], uProbeSh[b + 6], uProbeSh[b + 7],
                                             uProbeSh[b + 8], s.N);
    total += w;
  }
  if (total >= 1.0) {
    diffuse /= total;
    specular /= total;
    return;
  }
#endif
  float env = (1.0 - total) * uEnvIntensity;
  if (env <= 0.0) return;
  diffuse += env * shIrradiance(uEnvSh[0], uEnvSh[1], uEnvSh[2], uEnvSh[3], uEnvSh[4], uEnvSh[5], uEnvSh[6],
                                uEnvSh[7], uEnvSh[8], s.N);
  specular += env * textureLod(uEnvSpecular, R, s.rough * uEnvLods).rgb;
}

// Diffuse and specular light from the surroundings (the scene's ambient
// colour, the environment, reflection probes); `irradiance` is extra
// diffuse light arriving at s.P (irradiance volumes).
vec3 indirectLight(Surface s, vec3 irradiance) {
  vec3 f0 = mix(vec3(0.04), s.base.rgb, s.metallic);
  vec3 diffuseColor = s.base.rgb * (1.0 - s.metallic);
  float nv = clamp(dot(s.N, s.V), 1e-4, 1.0);
  vec2 ab = texture(uBrdfLut, vec2(nv, s.rough)).rg;
  vec3 specularColor = f0 * ab.x + ab.y;
  vec3 envDiffuse, envSpecular;
  surroundings(s, reflect(-s.V, s.N), envDiffuse, envSpecular);
  vec3 ambient = toLinear(uAmbient) * (0.75 + 0.25 * s.N.z);
  // Specular occlusion by the main light's shadow (gSunVisibility,
  // shader_lights.cpp): what lies in its shadow mirrors the object above it
  // more than the sky.
  float occlusion = mix(1.0, gSunVisibility, 0.6);
  return (diffuseColor + f0 * 0.5) * ambient + diffuseColor * irradiance +
         diffuseColor * (1.0 - specularColor) * envDiffuse + specularColor * envSpecular * occlusion;
}
)";

// The cube-face programs' common part: a full-screen triangle
// (kPostVertex) drawn into one face (uFace, GL order) of uSize texels.
// cubeDirection() is environment_light.hpp's cubeFaceDirection().
namespace {

const char* const kCubeFacePrelude = R"(#version 330 core
uniform int uFace;
uniform float uSize;
out vec4 fragColor;
const float PI = 3.14159265;
)";

const char* const kCubeFaceGlsl = R"(
vec3 cubeDirection(int face, vec2 uv) {
  float u = uv.x, v = uv.y;
  if (face == 0) return vec3(1.0, -v, -u);
  if (face == 1) return vec3(-1.0, -v, u);
  if (face == 2) return vec3(u, 1.0, v);
  if (face == 3) return vec3(u, -1.0, -v);
  if (face == 4) return vec3(u, -v, 1.0);
  return vec3(-u, -v, -1.0);
}
vec3 faceDirection() { return normalize(cubeDirection(uFace, gl_FragCoord.xy / uSize * 2.0 - 1.0)); }
)";

// The background's radiance along each texel's direction (plain colour,
// HDR, procedural sky, times uBackgroundScale); with uCapture, the lit
// image of a probe's face camera (premultiplied by coverage) over it.
const char* const kBackgroundFaceMain = R"(
uniform int uMode;            // 0 plain colour, 1 hdr, 2 sky
uniform vec3 uBackground;     // linear
uniform sampler2D uHdr;       // equirectangular, box-filtered to about the face's texel size
uniform float uBackgroundScale;
uniform bool uCapture;
uniform sampler2D uScene;
uniform mat4 uFaceViewProj;
uniform vec3 uProbePos;

vec3 background(vec3 d) {
  if (uMode == 0) return uBackground;
  if (uMode == 1) {
    vec2 uv = vec2(atan(d.y, d.x) / (2.0 * PI) + 0.5, acos(clamp(d.z, -1.0, 1.0)) / PI);
    return textureLod(uHdr, uv, 0.0).rgb;
  }
  return sky(d);
}

void main() {
  vec3 d = faceDirection();
  vec3 bg = uBackgroundScale > 0.0 ? background(d) * uBackgroundScale : vec3(0.0);
  if (!uCapture) {
    fragColor = vec4(bg, 1.0);
    return;
  }
  vec4 p = uFaceViewProj * vec4(uProbePos + d, 1.0);
  ivec2 size = textureSize(uScene, 0);
  ivec2 texel = clamp(ivec2((p.xy / p.w * 0.5 + 0.5) * vec2(size)), ivec2(0), size - 1);
  vec4 s = texelFetch(uScene, texel, 0);
  fragColor = vec4(s.rgb + bg * (1.0 - s.a), 1.0);
}
)";

// GGX prefiltering of uSource for roughness uRough, V = N = R (Karis
// 2013), with filtered importance sampling (Colbert and Krivanek 2007):
// each sample reads the source mip whose texels match its solid angle, so
// a few dozen samples give a smooth result.  uRough 0: a copy at uCopyLod.
const char* const kPrefilterMain = R"(
uniform samplerCube uSource;  // with its mipmaps
uniform float uSourceSize;
uniform float uRough;
uniform float uCopyLod;
uniform int uSamples;

float radicalInverse(uint bits) {
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return float(bits) * 2.3283064365386963e-10;
}

void main() {
  vec3 N = faceDirection();
  if (uRough <= 0.0) {
    fragColor = vec4(textureLod(uSource, N, uCopyLod).rgb, 1.0);
    return;
  }
  float a = uRough * uRough, a2 = a * a;
  vec3 up = abs(N.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
  vec3 T = normalize(cross(up, N));
  vec3 B = cross(N, T);
  float texelSolidAngle = 4.0 * PI / (6.0 * uSourceSize * uSourceSize);
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  for (int i = 0; i < uSamples; ++i) {
    float phi = 2.0 * PI * (float(i) + 0.5) / float(uSamples);
    float xi = radicalInverse(uint(i));
    float cosT = sqrt((1.0 - xi) / (1.0 + (a2 - 1.0) * xi));
    float sinT = sqrt(max(1.0 - cosT * cosT, 0.0));
    vec3 H = T * (sinT * cos(phi)) + B * (sinT * sin(phi)) + N * cosT;
    vec3 L = 2.0 * cosT * H - N;
    float nl = dot(N, L);
    if (nl <= 0.0) continue;
    float d = cosT * cosT * (a2 - 1.0) + 1.0;
    float pdf = a2 / (PI * d * d) / 4.0;  // D(h) n.h / (4 v.h), and v.h = n.h here
    float lod = 0.5 * log2(1.0 / (float(uSamples) * pdf * texelSolidAngle)) + 1.0;
    sum += textureLod(uSource, L, max(lod, 0.0)).rgb * nl;
    weight += nl;
  }
  fragColor = vec4(sum / max(weight, 1e-4), 1.0);
}
)";

}  // namespace

std::string backgroundFaceFragment() {
  return std::string(kCubeFacePrelude) + kSkyGlsl + kCubeFaceGlsl + kBackgroundFaceMain;
}

std::string prefilterFragment() { return std::string(kCubeFacePrelude) + kCubeFaceGlsl + kPrefilterMain; }

}  // namespace rscene::render::shaders
