// ReflectionEffects (gl_effects.hpp): ambient light, the environment's
// image-based light and reflection probes on the surface program (GLSL:
// shader_reflections.cpp; CPU half: environment_light.cpp).
//
// The environment: the background (plain colour, HDR, procedural sky) is
// drawn into a 128-texel radiance cube, its irradiance projected on nine
// spherical harmonics (read back at 16 texels), and its radiance
// GGX-prefiltered into five levels (roughness 0, 1/4 .. 1).  A probe: the
// scene drawn from its position into the six faces (the renderer's own lit
// colour pass, one sample, without probes), the background behind what
// it does not cover, then the same prefiltering into its layer of a cube
// map array and the same harmonics.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/codes.hpp"
#include "render/environment_light.hpp"
#include "render/gl_effects.hpp"
#include "render/gl_renderer.hpp"
#include "render/reflection_shaders.hpp"
#include "render/shaders.hpp"
#include "render/gl_uniforms.hpp"

namespace rscene::render::detail {
namespace {

constexpr int kEnvSize = 128;    // the background's cube: ~0.7 degrees a texel
constexpr int kEnvLevels = 5;    // 128 .. 8 texels: roughness 0, 0.25 .. 1
constexpr int kEnvSamples = 32;  // GGX samples per texel (filtered importance sampling)
constexpr int kHdrWidth = 512;   // an equirectangular HDR is box-filtered to this first (~0.7 degrees a texel)
constexpr int kShSide = 16;      // the radiance level the harmonics are projected from
// Probe cubes: llvmpipe shades every texel of the six faces with the full
// lit program, so its captures stop at 128 unless the probe asks less.
constexpr int kSoftwareProbeSize = 128, kProbeSize = 256;
constexpr int kSoftwareProbeSamples = 64, kProbeSamples = 256;

int levelsFor(int size) {
  int n = 1;
  while ((size >> n) > 0) ++n;
  return n;
}

bool hasExtension(const char* name) {
  GLint n = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &n);
  for (GLint i = 0; i < n; ++i) {
    const char* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
    if (e && std::strcmp(e, name) == 0) return true;
  }
  return false;
}

// A half-float RGBA cube map (or cube map array of `layers` cubes) with
// `levels` mip levels, trilinear and seamless.
GLuint cubeTexture(int size, int levels, int layers = 0) {
  GLenum target = layers ? GL_TEXTURE_CUBE_MAP_ARRAY : GL_TEXTURE_CUBE_MAP;
  GLuint t = 0;
  glGenTextures(1, &t);
  glBindTexture(target, t);
  for (int level = 0; level < levels; ++level) {
    int side = std::max(1, size >> level);
    if (layers)
      glTexImage3D(target, level, GL_RGBA16F, side, side, 6 * layers, 0, GL_RGBA, GL_FLOAT, nullptr);
    else
      for (int f = 0; f < 6; ++f)
        glTexImage2D(GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f), level, GL_RGBA16F, side, side, 0, GL_RGBA,
                     GL_FLOAT, nullptr);
  }
  glTexParameteri(target, GL_TEXTURE_BASE_LEVEL, 0);
  glTexParameteri(target, GL_TEXTURE_MAX_LEVEL, levels - 1);
  glTexParameteri(target, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
  glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTexParameteri(target, wrap, GL_CLAMP_TO_EDGE);
  return t;
}

// The irradiance harmonics of a cube's level whose side is at most kShSide.
IrradianceSh cubeIrradiance(GLuint cube, int size) {
  int level = 0;
  while ((size >> level) > kShSide) ++level;
  int side = std::max(1, size >> level);
  std::vector<float> faces(std::size_t(6) * side * side * 4);
  glBindTexture(GL_TEXTURE_CUBE_MAP, cube);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  for (int f = 0; f < 6; ++f)
    glGetTexImage(GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f), level, GL_RGBA, GL_FLOAT,
                  &faces[std::size_t(f) * side * side * 4]);
  return irradianceFromCube(faces, side);
}

void appendSh(std::vector<float>& out, const IrradianceSh& sh, float scale = 1) {
  for (const Eigen::Vector3f& c : sh.c)
    for (int k = 0; k < 3; ++k) out.push_back(c[k] * scale);
}

// The camera of a probe's cube face: 90 degrees, looking along the face's
// axis.  Which way is up does not matter (the copy into the cube projects
// each texel's direction through this camera's matrix), only that the
// square frustum is the face's.
Camera faceCamera(const Eigen::Vector3d& at, int face, int size, double farPlane) {
  static const Eigen::Vector3d axes[6] = {Eigen::Vector3d::UnitX(),  -Eigen::Vector3d::UnitX(),
                                          Eigen::Vector3d::UnitY(),  -Eigen::Vector3d::UnitY(),
                                          Eigen::Vector3d::UnitZ(),  -Eigen::Vector3d::UnitZ()};
  Eigen::Vector3d forward = axes[face];
  Eigen::Vector3d up = face < 4 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  Eigen::Matrix3d rot;
  rot.col(0) = forward;
  rot.col(1) = up.cross(forward);
  rot.col(2) = forward.cross(rot.col(1));
  Camera c;
  c.world.position = at;
  c.world.orientation = Eigen::Quaterniond(rot);
  c.verticalFov = 90;
  c.horizontalFov = 0;
  c.nearPlane = 0.02;
  c.farPlane = farPlane;
  c.width = c.height = size;
  c.projection = "perspective";
  c.enabled = true;
  return c;
}

}  // namespace

ReflectionEffects::~ReflectionEffects() {
  // The programs stay with the context (linkProgram()).
  GLuint textures[4] = {hdr_, envSpecular_, brdfLut_, probeCubes_};
  glDeleteTextures(4, textures);
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
}

bool ReflectionEffects::buildPrograms() {
  std::string log;
  backgroundProg_ = linkProgram(shaders::kPostVertex, shaders::backgroundFaceFragment().c_str(), log);
  prefilterProg_ = linkProgram(shaders::kPostVertex, shaders::prefilterFragment().c_str(), log);
  if (backgroundProg_ && prefilterProg_) return true;
  r_.diag(Severity::Error, rs::RS9010, 0, "shader build failed: " + log);
  return false;
}

// The HDR background as the cube faces sample it: box-filtered to
// kHdrWidth (read through the asset cache: the renderer's own upload
// already decoded it).
void ReflectionEffects::uploadHdr() {
  const Look& env = r_.scene_.environment;
  if (env.mode != Background::Hdr || !r_.hdrTexture_) return;
  std::string err;
  std::shared_ptr<const FloatImage> hdr = r_.assets_.floatImage(env.hdrPath, &err);
  if (!hdr) return;
  FloatImage small = shrinkEquirect(*hdr, kHdrWidth);
  glGenTextures(1, &hdr_);
  glBindTexture(GL_TEXTURE_2D, hdr_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB16F, small.width, small.height, 0, GL_RGB, GL_FLOAT, small.rgb.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

void ReflectionEffects::drawBackgroundFace(GLuint cube, int face, int size, float scale, GLuint scene,
                                           const Eigen::Matrix4d& faceViewProj, const Eigen::Vector3d& probe) {
  const Look& env = r_.scene_.environment;
  GLuint p = backgroundProg_;
  glUseProgram(p);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face), cube, 0);
  glViewport(0, 0, size, size);
  glUniform1i(loc(p, "uFace"), face);
  glUniform1f(loc(p, "uSize"), float(size));
  int mode = env.mode == Background::PlainColor ? 0 : hdr_ ? 1 : 2;
  glUniform1i(loc(p, "uMode"), mode);
  Eigen::Vector3f linear = env.background.cwiseMax(0.0f).array().pow(2.2f).matrix();
  glUniform3f(loc(p, "uBackground"), linear.x(), linear.y(), linear.z());
  glUniform3f(loc(p, "uSunDir"), float(env.sunDirection.x()), float(env.sunDirection.y()),
              float(env.sunDirection.z()));
  glUniform1f(loc(p, "uCloud"), env.cloudCoverage);
  glUniform1i(loc(p, "uNight"), env.night);
  glUniform1f(loc(p, "uBackgroundScale"), scale);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, hdr_);
  glUniform1i(loc(p, "uHdr"), 1);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, scene);
  glUniform1i(loc(p, "uScene"), 0);
  glUniform1i(loc(p, "uCapture"), scene != 0);
  Eigen::Matrix4f m = faceViewProj.cast<float>();
  glUniformMatrix4fv(loc(p, "uFaceViewProj"), 1, GL_FALSE, m.data());
  glUniform3f(loc(p, "uProbePos"), float(probe.x()), float(probe.y()), float(probe.z()));
  glBindVertexArray(r_.emptyVao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void ReflectionEffects::prefilter(GLuint source, int sourceSize, GLuint target, bool array, int layer, int size,
                                  int levels, int samples) {
  GLuint p = prefilterProg_;
  glUseProgram(p);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_CUBE_MAP, source);
  glUniform1i(loc(p, "uSource"), 0);
  glUniform1f(loc(p, "uSourceSize"), float(sourceSize));
  glBindVertexArray(r_.emptyVao_);
  for (int level = 0; level < levels; ++level) {
    int side = std::max(1, size >> level);
    glViewport(0, 0, side, side);
    glUniform1f(loc(p, "uSize"), float(side));
    glUniform1f(loc(p, "uRough"), levels > 1 ? float(level) / float(levels - 1) : 0.0f);
    glUniform1f(loc(p, "uCopyLod"), std::max(0.0f, std::log2(float(sourceSize) / float(side))));
    glUniform1i(loc(p, "uSamples"), samples);
    for (int face = 0; face < 6; ++face) {
      if (array)
        glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, target, level, 6 * layer + face);
      else
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face),
                               target, level);
      glUniform1i(loc(p, "uFace"), face);
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }
}

// Box-filtered mip levels of a cube, each drawn from the one above it
// (sampled between four texels): glGenerateMipmap on llvmpipe took 0.2 s
// for a 128-texel cube, this a few milliseconds.
void ReflectionEffects::downsample(GLuint cube, int size) {
  GLuint p = prefilterProg_;
  glUseProgram(p);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_CUBE_MAP, cube);
  glUniform1i(loc(p, "uSource"), 0);
  glUniform1f(loc(p, "uRough"), 0.0f);
  glUniform1f(loc(p, "uCopyLod"), 0.0f);
  glBindVertexArray(r_.emptyVao_);
  int levels = levelsFor(size);
  for (int level = 1; level < levels; ++level) {
    // Only the level above is sampled: no feedback with the one drawn.
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_BASE_LEVEL, level - 1);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, level - 1);
    int side = std::max(1, size >> level);
    glViewport(0, 0, side, side);
    glUniform1f(loc(p, "uSize"), float(side));
    for (int face = 0; face < 6; ++face) {
      glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face), cube,
                             level);
      glUniform1i(loc(p, "uFace"), face);
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_BASE_LEVEL, 0);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, levels - 1);
}

bool ReflectionEffects::upload() {
  glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
  if (!buildPrograms()) return false;
  glGenFramebuffers(1, &fbo_);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);

  // The split-sum table, shared by the environment and every probe.
  const std::vector<float>& lut = brdfLut();
  glGenTextures(1, &brdfLut_);
  glBindTexture(GL_TEXTURE_2D, brdfLut_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RG16F, kBrdfLutSize, kBrdfLutSize, 0, GL_RG, GL_FLOAT, lut.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

  // The environment: radiance, its harmonics, its prefiltered levels.
  uploadHdr();
  GLuint radiance = cubeTexture(kEnvSize, levelsFor(kEnvSize));
  for (int face = 0; face < 6; ++face) drawBackgroundFace(radiance, face, kEnvSize, 1.0f);
  downsample(radiance, kEnvSize);
  sh_.clear();
  appendSh(sh_, cubeIrradiance(radiance, kEnvSize));
  envSpecular_ = cubeTexture(kEnvSize, kEnvLevels);
  prefilter(radiance, kEnvSize, envSpecular_, false, 0, kEnvSize, kEnvLevels, kEnvSamples);
  glDeleteTextures(1, &radiance);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);

  const std::vector<RenderProbe>& probes = r_.scene_.probes;
  probeArrays_ = hasExtension("GL_ARB_texture_cube_map_array");
  if (!probes.empty() && !probeArrays_)
    r_.diag(Severity::Warning, rs::RS9060, probes.front().line,
            "reflection probes are not drawn: this OpenGL has no cube map arrays (4.0 or "
            "ARB_texture_cube_map_array); surfaces reflect the environment");
  if (probeArrays_ && probes.size() > std::size_t(kMaxProbes))
    r_.diag(Severity::Warning, rs::RS9061, probes[std::size_t(kMaxProbes)].line,
            std::to_string(probes.size()) + " reflection probes; only the first " + std::to_string(kMaxProbes) +
                " are drawn");
  return r_.glOk();
}

bool ReflectionEffects::prepare(const View& view) {
  if (capturing_ || captured_ || !probeArrays_ || r_.scene_.probes.empty()) return true;
  // The shadow maps fitted to the view, drawn once: the faces reuse them
  // (what lies outside the view's fit is lit in the probe; at 64-128
  // texels a face that matters little).
  if (!r_.lights_->prepare(view, viewProjection(view))) return false;
  captured_ = capturing_ = true;
  bool ok = captureProbes();
  capturing_ = false;
  // The capture chose its own instances per face: back to the view's.
  r_.selectInstances(view, viewProjection(view));
  return ok;
}

bool ReflectionEffects::captureProbes() {
  const std::vector<RenderProbe>& probes = r_.scene_.probes;
  probeCount_ = std::min(probes.size(), std::size_t(kMaxProbes));
  int cap = r_.software_ ? kSoftwareProbeSize : kProbeSize;
  int levels = 1;
  probeSize_ = 0;
  probeSamples_ = 1;
  for (std::size_t i = 0; i < probeCount_; ++i) {
    // Prefiltered at most at the captured size: more texels than the
    // capture has add no detail (the gallery's 64-texel capture was
    // prefiltered at 128: four times the GGX samples for an upsampling).
    probeSize_ = std::max(probeSize_, std::min({probes[i].prefilteredResolution, probes[i].cubemapSize, cap}));
    levels = std::max(levels, probes[i].prefilteredMipLevels);
    probeSamples_ = std::max(probeSamples_, probes[i].prefilteredSamples);
  }
  probeLevels_ = std::clamp(levels, 1, levelsFor(probeSize_));
  probeSamples_ = std::min(probeSamples_, r_.software_ ? kSoftwareProbeSamples : kProbeSamples);
  probeCubes_ = cubeTexture(probeSize_, probeLevels_, int(probeCount_));
  sh_.resize(27);
  for (std::size_t i = 0; i < probeCount_; ++i)
    if (!captureProbe(i, std::min(probes[i].cubemapSize, cap))) return false;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return r_.glOk();
}

bool ReflectionEffects::captureProbe(std::size_t index, int size) {
  const RenderProbe& probe = r_.scene_.probes[index];
  // Far enough to see the whole scene from the probe.
  double farPlane = 100;
  if (!r_.scene_.bounds.isEmpty())
    for (int i = 0; i < 8; ++i)
      farPlane = std::max(farPlane, 1.5 * (r_.scene_.bounds.corner(Eigen::AlignedBox3d::CornerType(i)) -
                                           probe.position).norm());
  GLuint radiance = cubeTexture(size, levelsFor(size));
  for (int face = 0; face < 6; ++face) {
    View v;
    v.name = "reflection probe";
    v.sensor = !probe.drawVisuals;  // world objects only, as a sensor sees
    v.camera = faceCamera(probe.position, face, size, farPlane);
    v.passes = {Pass::Color};
    v.samples = 1;
    Eigen::Matrix4d viewProj = viewProjection(v);
    r_.selectInstances(v, viewProj);
    Image scratch;
    if (!r_.colorPass(v, viewProj, scratch)) {
      glDeleteTextures(1, &radiance);
      return false;
    }
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    drawBackgroundFace(radiance, face, size, probe.captureBackground ? probe.exposure : 0.0f, r_.color_.resolved,
                       viewProj, probe.position);
  }
  downsample(radiance, size);
  appendSh(sh_, cubeIrradiance(radiance, size), probe.strength);
  prefilter(radiance, size, probeCubes_, true, int(index), probeSize_, probeLevels_, probeSamples_);
  glDeleteTextures(1, &radiance);
  return true;
}

void ReflectionEffects::bind(GLuint program, const View&) {
  const Look& env = r_.scene_.environment;
  glUniform3f(loc(program, "uAmbient"), env.ambient.x(), env.ambient.y(), env.ambient.z());
  glUniform1f(loc(program, "uEnvIntensity"), env.environmentIntensity);
  glUniform1f(loc(program, "uEnvLods"), float(kEnvLevels - 1));
  glUniform3fv(loc(program, "uEnvSh"), 9, sh_.data());
  if (sh_.size() > 27) glUniform3fv(loc(program, "uProbeSh"), GLsizei(sh_.size() / 3 - 9), sh_.data() + 27);
  int probes = capturing_ ? 0 : int(probeCount_);
  glUniform1i(loc(program, "uProbeCount"), probes);
  glUniform1f(loc(program, "uProbeLods"), float(probeLevels_ - 1));
  for (int i = 0; i < probes; ++i) {
    const RenderProbe& p = r_.scene_.probes[std::size_t(i)];
    std::string idx = "[" + std::to_string(i) + "]";
    glUniform4f(loc(program, ("uProbeSphere" + idx).c_str()), float(p.position.x()), float(p.position.y()),
                float(p.position.z()), p.radius);
    Eigen::Vector3f lo = p.box.min().cast<float>(), hi = p.box.max().cast<float>();
    bool box = p.boxProjection && !p.box.isEmpty();
    glUniform4f(loc(program, ("uProbeBoxMin" + idx).c_str()), lo.x(), lo.y(), lo.z(), box ? 1.0f : 0.0f);
    glUniform4f(loc(program, ("uProbeBoxMax" + idx).c_str()), hi.x(), hi.y(), hi.z(), p.strength);
  }
  // Every sampler gets its own unit, used or not: two sampler types on one
  // unit (the default 0) fail the draw.
  glActiveTexture(GL_TEXTURE0 + units::kReflections);
  glBindTexture(GL_TEXTURE_CUBE_MAP, envSpecular_);
  glUniform1i(loc(program, "uEnvSpecular"), units::kReflections);
  glActiveTexture(GL_TEXTURE0 + units::kReflections + 1);
  glBindTexture(GL_TEXTURE_2D, brdfLut_);
  glUniform1i(loc(program, "uBrdfLut"), units::kReflections + 1);
  if (probeArrays_) {
    glActiveTexture(GL_TEXTURE0 + units::kReflections + 2);
    glBindTexture(GL_TEXTURE_CUBE_MAP_ARRAY, capturing_ ? 0 : probeCubes_);
    glUniform1i(loc(program, "uProbeCubes"), units::kReflections + 2);
  }
  glActiveTexture(GL_TEXTURE0);
}

}  // namespace rscene::render::detail
