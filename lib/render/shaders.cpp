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

// The surface fragment's prelude: inputs, the Surface every module takes,
// the material and checker helpers.  The modules' GLSL follows it
// (surfaceFragment()), then kSurfaceMain.
const char* const kSurfacePrelude = R"(#version 330 core
in vec3 vWorld;
in vec3 vNormal;
in vec2 vUv;
in vec4 vColor;
flat in vec4 vPbr;       // metallic, roughness, checker, flags (1 unlit, 2 receives no shadow)
flat in vec3 vEmissive;
uniform vec3 uCameraPos;
uniform sampler2D uAlbedo;
uniform bool uHasAlbedo;
uniform bool uDoubleSided;
out vec4 fragColor;
const float PI = 3.14159265;

vec3 toLinear(vec3 c) { return pow(max(c, vec3(0.0)), vec3(2.2)); }

// What the lighting modules take: a point of a surface, its material.
struct Surface {
  vec3 P;          // world position
  vec3 N;          // unit normal, towards the eye for two-sided surfaces
  vec3 V;          // unit direction to the eye
  vec4 base;       // linear base color, alpha
  float metallic;
  float rough;     // perceptual roughness
  vec3 emissive;   // linear emitted light
  bool receiveShadow;
};

float checker(vec2 p) {
  // Box-filtered 1 m checkerboard: fades to the mean far away instead of aliasing.
  vec2 w = max(fwidth(p), vec2(1e-4));
  vec2 i = 2.0 * (abs(fract((p - 0.5 * w) / 2.0) - 0.5) - abs(fract((p + 0.5 * w) / 2.0) - 0.5)) / w;
  return 0.5 - 0.5 * i.x * i.y;
}
)";

const char* const kSurfaceMain = R"(
void main() {
  Surface s;
  s.base = vec4(toLinear(vColor.rgb), vColor.a);
  if (uHasAlbedo) {
    vec4 t = texture(uAlbedo, vUv);
    s.base *= vec4(toLinear(t.rgb), t.a);
  }
  // The ground: 1 m squares of its material color and a light neutral gray.
  if (vPbr.z > 0.5) s.base.rgb = mix(vec3(0.52), s.base.rgb, checker(vWorld.xy));
  int flags = int(vPbr.w + 0.5);
  s.P = vWorld;
  s.N = normalize(vNormal);
  s.V = normalize(uCameraPos - vWorld);
  if (dot(s.N, s.V) < 0.0 && uDoubleSided) s.N = -s.N;
  s.metallic = clamp(vPbr.x, 0.0, 1.0);
  s.rough = clamp(vPbr.y, 0.03, 1.0);
  s.emissive = vEmissive;
  s.receiveShadow = (flags & 2) == 0;
  applyDecals(s);
  vec3 color;
  if ((flags & 1) != 0) {
    color = s.base.rgb;
  } else {
    color = directLight(s);  // first: it sets gSunVisibility, which indirectLight() reads
    color += indirectLight(s, volumeIrradiance(s));
  }
  color += s.emissive;
  color = applyFog(color, s.P, uCameraPos);
  fragColor = vec4(color, s.base.a);
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


}  // namespace rscene::render::shaders

namespace rscene::render::shaders {

std::string surfaceFragment(bool reflectionProbes) {
  std::string prelude = kSurfacePrelude;
  if (reflectionProbes) {
    // Probes sample a cube map array (GL 4.0, or this extension of 3.3):
    // enabled right after the #version line (no other token may come
    // first); shader_reflections.cpp compiles them out where it is
    // missing.  Only a scene with probes gets this code: llvmpipe pays for
    // the loop even when it runs no iteration.
    prelude.insert(prelude.find('\n') + 1,
                   "#extension GL_ARB_texture_cube_map_array : enable\n#define RSCENE_REFLECTION_PROBES 1\n");
  }
  return prelude + kLightsGlsl + kFogGlsl + kVolumesGlsl + kReflectionsGlsl + kSurfaceMain;
}

}  // namespace rscene::render::shaders
