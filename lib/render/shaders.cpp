#include "render/shaders.hpp"

namespace rscene::render::shaders {

const char* const kSurfaceVertex = R"(#version 330 core
layout(location = 0) in vec3 aPos;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;
layout(location = 3) in vec4 aVertexColor;
layout(location = 4) in vec4 iM0;
layout(location = 5) in vec4 iM1;
layout(location = 6) in vec4 iM2;
layout(location = 7) in vec4 iM3;
layout(location = 8) in vec4 iColor;
layout(location = 9) in vec4 iPbr;       // metallic, roughness, checker, unlit
layout(location = 10) in vec4 iEmissive;
uniform mat4 uViewProj;
invariant gl_Position;  // the depth pre-pass and the lit pass must agree bit for bit
out vec3 vWorld;
out vec3 vNormal;
out vec2 vUv;
out vec4 vColor;
flat out vec4 vPbr;
flat out vec3 vEmissive;
void main() {
  mat4 m = mat4(iM0, iM1, iM2, iM3);
  vec4 w = m * vec4(aPos, 1.0);
  vWorld = w.xyz;
  vNormal = transpose(inverse(mat3(m))) * aNormal;
  vUv = aUv;
  vColor = iColor * aVertexColor;
  vPbr = iPbr;
  vEmissive = iEmissive.rgb;
  gl_Position = uViewProj * w;
}
)";

const char* const kSurfaceFragment = R"(#version 330 core
in vec3 vWorld;
in vec3 vNormal;
in vec2 vUv;
in vec4 vColor;
flat in vec4 vPbr;
flat in vec3 vEmissive;
uniform vec3 uCameraPos;
uniform int uLightCount;
uniform vec4 uLightPos[8];    // xyz, type (0 dir, 1 point, 2 spot, 3 area)
uniform vec4 uLightDir[8];    // travel direction, cos(outer cone)
uniform vec4 uLightColor[8];  // rgb x intensity, cos(inner cone)
uniform vec4 uLightAtt[8];    // constant, linear, quadratic, range
uniform int uShadowLight;     // index of the light with the shadow map, -1 none
uniform mat4 uLightViewProj;
uniform sampler2DShadow uShadowMap;
uniform float uShadowTexel;
uniform vec3 uAmbient;
uniform vec3 uSkyAmbient;   // linear light from the procedural sky or HDR, 0 for plain color
uniform float uFogDensity;
uniform vec3 uFogColor;
uniform sampler2D uAlbedo;
uniform bool uHasAlbedo;
uniform bool uDoubleSided;
out vec4 fragColor;
const float PI = 3.14159265;

vec3 toLinear(vec3 c) { return pow(max(c, vec3(0.0)), vec3(2.2)); }

float shadowFactor(vec3 n, vec3 l) {
  vec4 p = uLightViewProj * vec4(vWorld, 1.0);
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

float checker(vec2 p) {
  // Box-filtered 1 m checkerboard: fades to the mean far away instead of aliasing.
  vec2 w = max(fwidth(p), vec2(1e-4));
  vec2 i = 2.0 * (abs(fract((p - 0.5 * w) / 2.0) - 0.5) - abs(fract((p + 0.5 * w) / 2.0) - 0.5)) / w;
  return 0.5 - 0.5 * i.x * i.y;
}

void main() {
  vec4 base = vec4(toLinear(vColor.rgb), vColor.a);
  if (uHasAlbedo) {
    vec4 t = texture(uAlbedo, vUv);
    base *= vec4(toLinear(t.rgb), t.a);
  }
  // The ground: 1 m squares of its material color and a light neutral gray.
  if (vPbr.z > 0.5) base.rgb = mix(vec3(0.52), base.rgb, checker(vWorld.xy));
  vec3 n = normalize(vNormal);
  vec3 v = normalize(uCameraPos - vWorld);
  if (dot(n, v) < 0.0) {
    if (uDoubleSided) n = -n;
  }
  vec3 color;
  if (vPbr.w > 0.5) {
    color = base.rgb;
  } else {
    float metallic = clamp(vPbr.x, 0.0, 1.0);
    float rough = clamp(vPbr.y, 0.03, 1.0);
    float a2 = rough * rough * rough * rough;
    vec3 f0 = mix(vec3(0.04), base.rgb, metallic);
    vec3 diffuse = base.rgb * (1.0 - metallic);
    float nv = max(dot(n, v), 1e-4);
    color = vec3(0.0);
    for (int i = 0; i < 8; ++i) {
      if (i >= uLightCount) break;
      int type = int(uLightPos[i].w + 0.5);
      vec3 l;
      float att = 1.0;
      if (type == 0) {
        l = -normalize(uLightDir[i].xyz);
      } else {
        vec3 d = uLightPos[i].xyz - vWorld;
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
      float nl = dot(n, l);
      if (nl <= 0.0) continue;
      if (i == uShadowLight) att *= shadowFactor(n, l);
      vec3 h = normalize(l + v);
      float nh = max(dot(n, h), 0.0);
      float dn = nh * nh * (a2 - 1.0) + 1.0;
      float D = a2 / (PI * dn * dn);
      float k = (rough + 1.0) * (rough + 1.0) / 8.0;
      float G = nv / (nv * (1.0 - k) + k) * nl / (nl * (1.0 - k) + k);
      vec3 F = f0 + (1.0 - f0) * pow(1.0 - max(dot(h, v), 0.0), 5.0);
      vec3 spec = D * G * F / max(4.0 * nv * nl, 1e-4);
      color += ((1.0 - F) * diffuse / PI + spec) * uLightColor[i].rgb * att * nl;
    }
    // Ambient: brighter from the sky side.
    color += (diffuse + f0 * 0.5) * (toLinear(uAmbient) * (0.75 + 0.25 * n.z) + uSkyAmbient * (0.6 + 0.4 * n.z));
  }
  color += vEmissive;
  if (uFogDensity > 0.0) {
    float f = 1.0 - exp(-uFogDensity * length(uCameraPos - vWorld));
    color = mix(color, toLinear(uFogColor), f);
  }
  fragColor = vec4(color, base.a);
}
)";

const char* const kDepthFragment = R"(#version 330 core
void main() {}
)";

const char* const kPointVertex = R"(#version 330 core
layout(location = 0) in vec3 aPos;
layout(location = 1) in vec4 aColor;
uniform mat4 uViewProj;
uniform float uPointSize;
out vec4 vColor;
void main() {
  vColor = aColor;
  gl_Position = uViewProj * vec4(aPos, 1.0);
  gl_PointSize = uPointSize;
}
)";

const char* const kPointFragment = R"(#version 330 core
in vec4 vColor;
out vec4 fragColor;
void main() { fragColor = vec4(pow(max(vColor.rgb, vec3(0.0)), vec3(2.2)), vColor.a); }
)";

// The data pass: segmentation color and linear depth in one draw, 1
// sample, no lighting, blending, fog or tone mapping.  Depth is the
// distance along the view's forward axis, interpolated perspective-
// correctly from the vertices: exact for planar triangles (no 24-bit
// depth-buffer round trip).
const char* const kDataVertex = R"(#version 330 core
layout(location = 0) in vec3 aPos;
layout(location = 4) in vec4 iM0;
layout(location = 5) in vec4 iM1;
layout(location = 6) in vec4 iM2;
layout(location = 7) in vec4 iM3;
layout(location = 10) in vec4 iEmissive;  // w: segment color 0xRRGGBB
uniform mat4 uViewProj;
uniform vec3 uCameraPos;
uniform vec3 uForward;
out float vDepth;
flat out vec3 vSegment;
void main() {
  vec4 w = mat4(iM0, iM1, iM2, iM3) * vec4(aPos, 1.0);
  vDepth = dot(w.xyz - uCameraPos, uForward);
  int s = int(iEmissive.w);  // an exact integer (< 2^24); adding 0.5 would round to even up there
  vSegment = vec3((s >> 16) & 255, (s >> 8) & 255, s & 255) / 255.0;
  gl_Position = uViewProj * w;
}
)";

const char* const kPointDataVertex = R"(#version 330 core
layout(location = 0) in vec3 aPos;
uniform mat4 uViewProj;
uniform vec3 uCameraPos;
uniform vec3 uForward;
uniform float uPointSize;
uniform vec3 uSegment;
out float vDepth;
flat out vec3 vSegment;
void main() {
  vDepth = dot(aPos - uCameraPos, uForward);
  vSegment = uSegment;
  gl_Position = uViewProj * vec4(aPos, 1.0);
  gl_PointSize = uPointSize;
}
)";

const char* const kDataFragment = R"(#version 330 core
in float vDepth;
flat in vec3 vSegment;
layout(location = 0) out vec4 outSegment;
layout(location = 1) out float outDepth;
void main() {
  outSegment = vec4(vSegment, 1.0);
  outDepth = vDepth;
}
)";

const char* const kPostVertex = R"(#version 330 core
out vec2 vNdc;
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0;
  vNdc = p;
  gl_Position = vec4(p, 0.0, 1.0);
}
)";

const char* const kPostFragment = R"(#version 330 core
in vec2 vNdc;
uniform sampler2D uScene;      // linear HDR, premultiplied by coverage
uniform mat4 uInvViewProj;
uniform vec3 uCameraPos;
uniform bool uOrtho;
uniform int uMode;             // 0 plain color, 1 hdr, 2 sky
uniform bool uTransparent;
uniform vec3 uBackground;      // display color of plain_color
uniform sampler2D uHdr;
uniform vec3 uSunDir;
uniform float uCloud;
uniform bool uNight;
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

vec3 sky(vec3 d) {
  vec3 sun = normalize(uSunDir);
  float sunHeight = clamp(sun.z, -0.2, 1.0);
  float day = smoothstep(-0.15, 0.2, sunHeight);
  vec3 zenith = mix(vec3(0.005, 0.008, 0.02), vec3(0.10, 0.28, 0.72), day);
  vec3 horizon = mix(vec3(0.02, 0.025, 0.04), mix(vec3(0.85, 0.55, 0.35), vec3(0.60, 0.75, 0.95), smoothstep(0.0, 0.35, sunHeight)), day);
  float up = max(d.z, 0.0);
  vec3 c = mix(horizon, zenith, pow(up, 0.45));
  float mu = max(dot(d, sun), 0.0);
  c += vec3(1.0, 0.85, 0.6) * pow(mu, 8.0) * 0.25 * day;              // glow around the sun
  c += vec3(40.0, 36.0, 30.0) * smoothstep(0.99985, 0.99995, mu) * day;  // the disk
  vec3 cloud = vec3(0.62, 0.64, 0.68) * mix(0.05, 1.0, day);
  c = mix(c, cloud, clamp(uCloud, 0.0, 1.0) * 0.85);
  if (d.z < 0.0) {  // below the horizon: a dim ground haze
    vec3 ground = vec3(0.18, 0.17, 0.16) * mix(0.05, 1.0, day);
    c = mix(horizon * 0.8, ground, smoothstep(0.0, 0.25, -d.z));
  }
  if (uNight) c = c * 0.05 + vec3(0.002, 0.003, 0.008);
  return c;
}

vec3 background(vec3 d) {
  if (uMode == 0) return uBackground;
  vec3 c;
  if (uMode == 1) {
    vec2 uv = vec2(atan(d.y, d.x) / (2.0 * PI) + 0.5, acos(clamp(d.z, -1.0, 1.0)) / PI);
    c = texture(uHdr, uv).rgb;
  } else {
    c = sky(d);
  }
  if (uFogDensity > 0.0) c = mix(c, pow(uFogColor, vec3(2.2)), clamp(uFogDensity * 20.0, 0.0, 0.9));
  return toneMap(c);
}

void main() {
  vec4 s = texelFetch(uScene, ivec2(gl_FragCoord.xy), 0);
  vec3 surface = s.a > 0.0 ? toneMap(s.rgb / s.a) : vec3(0.0);
  // Fully covered (most pixels): no background to blend, no sky to compute.
  if (uTransparent || s.a >= 1.0) {
    fragColor = vec4(surface, uTransparent ? s.a : 1.0);
    return;
  }
  vec4 far = uInvViewProj * vec4(vNdc, 1.0, 1.0);
  vec4 near = uInvViewProj * vec4(vNdc, -1.0, 1.0);
  vec3 dir = normalize(far.xyz / far.w - near.xyz / near.w);
  vec3 bg = background(dir);
  fragColor = vec4(surface * s.a + bg * (1.0 - s.a), 1.0);
}
)";

}  // namespace rscene::render::shaders
