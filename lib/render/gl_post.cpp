// PostEffects (gl_post.hpp): the post-processing passes of a color view.
#include "render/gl_post.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/codes.hpp"
#include "render/camera.hpp"
#include "render/gl_renderer.hpp"
#include "render/shaders.hpp"
#include "render/gl_uniforms.hpp"

namespace rscene::render::detail {
namespace {

// Ambient occlusion: what counts as near (metres), how strong, and how far
// on screen a sample may go (a fraction of the image height): the cost is
// the same at any radius, but far samples miss the texture cache.
constexpr float kAoRadius = 0.5f, kAoIntensity = 1.0f, kAoMaxScreen = 0.1f;
// Bloom: the brightest (exposed) value a pixel gives the chain, so that
// the sun's disk (40), a specular spike or an overexposed wall does not
// flood the image with a blurred copy of itself: the glow next to a large
// bright area is at most about bloomIntensity x (16 - bloomThreshold).
constexpr float kBloomSourceClamp = 16.0f;

void bindTexture(GLuint p, const char* name, int unit, GLuint texture) {
  glActiveTexture(GLenum(GL_TEXTURE0 + unit));
  glBindTexture(GL_TEXTURE_2D, texture);
  glUniform1i(loc(p, name), unit);
}
void setTargetTexel(GLuint p, const PostTarget& t) {
  glUniform2f(loc(p, "uTargetTexel"), 1.0f / float(t.width), 1.0f / float(t.height));
}

}  // namespace

PostEffects::~PostEffects() {
  // The programs stay with the context (linkProgram()).
  auto free = [](PostTarget& t) {
    if (t.texture) glDeleteTextures(1, &t.texture);
    if (t.fbo) glDeleteFramebuffers(1, &t.fbo);
  };
  for (PostTarget* t : {&depth_, &hdr_, &ldr_, &aoRaw_, &ao_, &luminance_, &dof_}) free(*t);
  for (PostTarget& t : bloom_) free(t);
}

// The programs are built by the first view that asks for an effect, so
// that a scene that asks for none does not pay for compiling them.
bool PostEffects::buildPrograms() {
  if (built_) return true;
  built_ = true;
  std::string log;
  const char* v = shaders::kPostVertex;
  depthResolveProg_ = linkProgram(v, shaders::kDepthResolveFragment, log);
  ssaoProg_ = linkProgram(v, shaders::ssaoFragment(false).c_str(), log);
  ssaoMsProg_ = linkProgram(v, shaders::ssaoFragment(true).c_str(), log);
  ssaoBlurProg_ = linkProgram(v, shaders::kSsaoBlurFragment, log);
  prefilterProg_ = linkProgram(v, shaders::kBloomPrefilterFragment, log);
  downProg_ = linkProgram(v, shaders::kBloomDownFragment, log);
  upProg_ = linkProgram(v, shaders::kBloomUpFragment, log);
  luminanceProg_ = linkProgram(v, shaders::kLuminanceFragment, log);
  dofProg_ = linkProgram(v, shaders::dofFragment().c_str(), log);
  finalProg_ = linkProgram(v, shaders::finalFragment().c_str(), log);
  fxaaProg_ = linkProgram(v, shaders::kFxaaFragment, log);
  if (depthResolveProg_ && ssaoProg_ && ssaoMsProg_ && ssaoBlurProg_ && prefilterProg_ && downProg_ && upProg_ && luminanceProg_ && dofProg_ &&
      finalProg_ && fxaaProg_) {
    ready_ = true;
    return true;
  }
  r_.diag(Severity::Error, rs::RS9010, 0, "shader build failed: " + log);
  return false;
}

// Targets are made on first use and remade when the image size changes,
// so a scene that asks for no effect pays for none.
bool PostEffects::ensure(PostTarget& t, int w, int h, GLenum internalFormat, GLenum format, GLenum type,
                         GLenum filter) {
  w = std::max(w, 1), h = std::max(h, 1);
  if (t.texture && t.width == w && t.height == h) return true;
  if (!t.texture) {
    glGenTextures(1, &t.texture);
    glGenFramebuffers(1, &t.fbo);
  }
  t.width = w, t.height = h;
  glBindTexture(GL_TEXTURE_2D, t.texture);
  glTexImage2D(GL_TEXTURE_2D, 0, GLint(internalFormat), w, h, 0, format, type, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GLint(filter));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GLint(filter));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.texture, 0);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE) return true;
  r_.diag(Severity::Error, rs::RS9011, 0,
          "cannot create a " + std::to_string(w) + "x" + std::to_string(h) + " post-processing framebuffer");
  t.width = t.height = 0;
  return false;
}

// One full-screen triangle of the current program into `into` (the
// renderer's RGBA8 target when null).
void PostEffects::draw(const PostTarget* into) {
  const ColorTargets& c = r_.color_;
  glBindFramebuffer(GL_FRAMEBUFFER, into ? into->fbo : c.fbo[2]);
  glViewport(0, 0, into ? into->width : c.width, into ? into->height : c.height);
  glBindVertexArray(r_.emptyVao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
}

// The lit pass over its background: display colors (linear false: the
// whole post-processing when nothing else is asked for) or linear HDR
// with coverage in alpha into hdr_.
void PostEffects::composite(const View& view, const Eigen::Matrix4d& viewProj, bool linear, GLuint ao) {
  const Look& env = r_.scene_.environment;
  GLuint post = r_.postProg_;
  glUseProgram(post);
  bindTexture(post, "uScene", 0, r_.color_.resolved);
  bindTexture(post, "uHdr", 1, r_.hdrTexture_);
  bindTexture(post, "uAo", 2, ao);
  glUniform1i(loc(post, "uHasAo"), ao != 0);
  glUniform1i(loc(post, "uLinearOut"), linear);
  setMat(post, "uInvViewProj", viewProj.inverse());
  int mode = env.mode == Background::PlainColor ? 0 : (env.mode == Background::Hdr && r_.hdrTexture_) ? 1 : 2;
  glUniform1i(loc(post, "uMode"), mode);
  glUniform1i(loc(post, "uTransparent"), r_.opt_.transparent);
  setVec3(post, "uBackground", env.background);
  float exposure = std::max(env.exposure, 1e-6f);
  Eigen::Vector3f plain = env.background.cwiseMax(0.0f).array().pow(env.gamma).matrix() / exposure;
  setVec3(post, "uPlainLinear", plain);
  setVec3(post, "uSunDir", env.sunDirection.cast<float>());
  glUniform1f(loc(post, "uCloud"), env.cloudCoverage);
  glUniform1i(loc(post, "uNight"), env.night);
  glUniform1f(loc(post, "uFogDensity"), env.fogDensity);
  setVec3(post, "uFogColor", env.fogColor);
  glUniform1f(loc(post, "uExposure"), env.exposure);
  glUniform1f(loc(post, "uGamma"), env.gamma);
  glUniform1i(loc(post, "uToneMap"), int(env.toneMap));
  r_.volumes_->bindBackground(post, view);  // height fog and fog spheres over the background
  draw(linear ? &hdr_ : nullptr);
}

void PostEffects::resolveDepth() {
  glUseProgram(depthResolveProg_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, r_.color_.msaaDepth);
  glUniform1i(loc(depthResolveProg_, "uDepthMs"), 0);
  glUniform1i(loc(depthResolveProg_, "uSamples"), r_.color_.samples);
  draw(&depth_);
  glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, 0);
}

void PostEffects::ambientOcclusion(const View& view, const Eigen::Matrix4d& proj) {
  const ColorTargets& c = r_.color_;
  // Straight from the multisampled depth unless it was resolved (depth of field).
  bool multisampled = c.samples > 1 && depthSource_ == c.msaaDepth;
  GLuint prog = multisampled ? ssaoMsProg_ : ssaoProg_;
  glUseProgram(prog);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(multisampled ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D, depthSource_);
  glUniform1i(loc(prog, "uDepth"), 0);
  glUniform2i(loc(prog, "uDepthSize"), c.width, c.height);
  setMat(prog, "uInvProj", proj.inverse());
  glUniform1f(loc(prog, "uPixelsPerMetre"), float(proj(1, 1)) * float(c.height) / 2);
  glUniform1i(loc(prog, "uOrtho"), view.camera.projection == "orthographic");
  glUniform1f(loc(prog, "uRadius"), kAoRadius);
  glUniform1f(loc(prog, "uIntensity"), kAoIntensity);
  glUniform1f(loc(prog, "uMaxPixels"), kAoMaxScreen * float(c.height));
  draw(&aoRaw_);
  if (multisampled) glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, 0);
  glUseProgram(ssaoBlurProg_);
  bindTexture(ssaoBlurProg_, "uAoRaw", 0, aoRaw_.texture);
  draw(&ao_);
}

// Exposure factor of auto exposure from the composite's luminance: a
// read-back of a few thousand floats (a 1/16 downsample), averaged here.
float PostEffects::autoExposure(float key) {
  glUseProgram(luminanceProg_);
  bindTexture(luminanceProg_, "uSrc", 0, hdr_.texture);
  setTargetTexel(luminanceProg_, luminance_);
  draw(&luminance_);
  logLuminance_.resize(std::size_t(luminance_.width) * std::size_t(luminance_.height));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, luminance_.width, luminance_.height, GL_RED, GL_FLOAT, logLuminance_.data());
  return autoExposureFactor(logLuminance_.data(), logLuminance_.size(), key);
}

void PostEffects::depthOfField(const Eigen::Matrix4d& proj, const Eigen::Vector3f& dof) {
  glUseProgram(dofProg_);
  bindTexture(dofProg_, "uHdrImage", 0, hdr_.texture);
  bindTexture(dofProg_, "uDepth", 1, depthSource_);
  setMat(dofProg_, "uInvProj", proj.inverse());
  setVec3(dofProg_, "uDof", dof);
  draw(&dof_);
}

// The chain: bloom_[0] (half size) holds what passes the threshold, each
// level below halves it; going back up, each level is added onto the one
// above, so bloom_[0] ends as the sum of all levels (finalPass divides by
// their count).
void PostEffects::bloom(float exposure) {
  const Look& env = r_.scene_.environment;
  float spread = std::clamp(env.bloomRadius / 4.0f, 0.25f, 4.0f);
  glUseProgram(prefilterProg_);
  bindTexture(prefilterProg_, "uSrc", 0, hdr_.texture);
  setTargetTexel(prefilterProg_, bloom_[0]);
  glUniform1f(loc(prefilterProg_, "uExposure"), exposure);
  glUniform1f(loc(prefilterProg_, "uThreshold"), env.bloomThreshold);
  glUniform1f(loc(prefilterProg_, "uSourceClamp"), kBloomSourceClamp);
  draw(&bloom_[0]);
  glUseProgram(downProg_);
  glUniform1f(loc(downProg_, "uSpread"), spread);
  for (int i = 1; i < bloomLevels_; ++i) {
    bindTexture(downProg_, "uSrc", 0, bloom_[std::size_t(i - 1)].texture);
    setTargetTexel(downProg_, bloom_[std::size_t(i)]);
    draw(&bloom_[std::size_t(i)]);
  }
  glUseProgram(upProg_);
  glUniform1f(loc(upProg_, "uSpread"), spread);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  for (int i = bloomLevels_ - 2; i >= 0; --i) {
    bindTexture(upProg_, "uSrc", 0, bloom_[std::size_t(i + 1)].texture);
    setTargetTexel(upProg_, bloom_[std::size_t(i)]);
    draw(&bloom_[std::size_t(i)]);
  }
  glDisable(GL_BLEND);
}

void PostEffects::finalPass(const Eigen::Matrix4d& proj, const Eigen::Vector3f& dof, const PostTarget* into) {
  const Look& env = r_.scene_.environment;
  GLuint p = finalProg_;
  glUseProgram(p);
  bindTexture(p, "uHdrImage", 0, hdr_.texture);
  bindTexture(p, "uBloom", 1, plan_.bloom ? bloom_[0].texture : 0);
  bindTexture(p, "uDofImage", 2, plan_.depthOfField ? dof_.texture : 0);
  bindTexture(p, "uDepth", 3, plan_.depthOfField ? depthSource_ : 0);
  glUniform1i(loc(p, "uHasBloom"), plan_.bloom);
  glUniform1f(loc(p, "uBloomGain"), plan_.bloom ? bloomGain(env.bloomIntensity, bloomLevels_, exposure_) : 0.0f);
  glUniform1i(loc(p, "uHasDof"), plan_.depthOfField);
  setMat(p, "uInvProj", proj.inverse());
  setVec3(p, "uDof", dof);
  int mode = env.mode == Background::PlainColor ? 0 : 2;
  glUniform1i(loc(p, "uMode"), mode);
  glUniform1i(loc(p, "uTransparent"), r_.opt_.transparent);
  setVec3(p, "uBackground", env.background);
  float exposure = std::max(env.exposure, 1e-6f);
  setVec3(p, "uPlainLinear", env.background.cwiseMax(0.0f).array().pow(env.gamma).matrix() / exposure);
  glUniform1f(loc(p, "uExposure"), exposure_);
  glUniform1f(loc(p, "uGamma"), env.gamma);
  glUniform1i(loc(p, "uToneMap"), int(env.toneMap));
  draw(into);
}

void PostEffects::fxaa() {
  glUseProgram(fxaaProg_);
  bindTexture(fxaaProg_, "uLdr", 0, ldr_.texture);
  draw(nullptr);
}

bool PostEffects::run(const View& view, const Eigen::Matrix4d& viewProj) {
  const ColorTargets& c = r_.color_;
  const Look& env = r_.scene_.environment;
  int w = c.width, h = c.height;
  plan_ = postPlan(env, r_.opt_.post);
  bool ortho = view.camera.projection == "orthographic";
  plan_.depthOfField = plan_.depthOfField && !ortho;  // no lens: nothing to defocus
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_BLEND);
  exposure_ = env.exposure;
  if (!plan_.any()) {
    composite(view, viewProj, false, 0);
    return true;
  }
  if (!buildPrograms() || !ready_) return false;
  Eigen::Matrix4d proj = viewProj * viewMatrix(view.camera).inverse();
  int hw = (w + 1) / 2, hh = (h + 1) / 2;
  bool ok = ensure(hdr_, w, h, GL_RGBA16F, GL_RGBA, GL_FLOAT, GL_LINEAR);
  depthSource_ = c.msaaDepth;
  if (plan_.depthOfField && c.samples > 1) {
    ok = ok && ensure(depth_, w, h, GL_R32F, GL_RED, GL_FLOAT, GL_NEAREST);
    depthSource_ = depth_.texture;
  }
  if (plan_.ssao)
    ok = ok && ensure(aoRaw_, hw, hh, GL_RG16F, GL_RG, GL_FLOAT, GL_NEAREST) &&
         ensure(ao_, hw, hh, GL_R8, GL_RED, GL_UNSIGNED_BYTE, GL_LINEAR);
  if (plan_.autoExposure)
    ok = ok && ensure(luminance_, (w + 15) / 16, (h + 15) / 16, GL_R32F, GL_RED, GL_FLOAT, GL_NEAREST);
  if (plan_.depthOfField) ok = ok && ensure(dof_, hw, hh, GL_RGBA16F, GL_RGBA, GL_FLOAT, GL_LINEAR);
  if (plan_.bloom) {
    bloomLevels_ = bloomLevels(w, h);
    plan_.bloom = bloomLevels_ > 0;
    bloom_.resize(std::max<std::size_t>(bloom_.size(), std::size_t(bloomLevels_)));
    for (int i = 0, bw = w / 2, bh = h / 2; i < bloomLevels_; ++i, bw /= 2, bh /= 2)
      ok = ok && ensure(bloom_[std::size_t(i)], bw, bh, GL_RGBA16F, GL_RGBA, GL_FLOAT, GL_LINEAR);
  }
  if (plan_.fxaa) ok = ok && ensure(ldr_, w, h, GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, GL_LINEAR);
  if (!ok) return false;

  if (plan_.depthOfField && c.samples > 1) resolveDepth();
  if (plan_.ssao) ambientOcclusion(view, proj);
  composite(view, viewProj, true, plan_.ssao ? ao_.texture : 0);
  if (plan_.autoExposure) exposure_ *= autoExposure(env.autoExposureKey);
  Eigen::Vector3f dof = Eigen::Vector3f::Zero();
  if (plan_.depthOfField) {
    float focalPixels = float(proj(1, 1)) * float(h) / 2;
    dof = {0.5f * env.aperture * focalPixels, 1.0f / env.focusDistance, maxCocPixels(h)};
    depthOfField(proj, dof);
  }
  if (plan_.bloom) bloom(exposure_);
  finalPass(proj, dof, plan_.fxaa ? &ldr_ : nullptr);
  if (plan_.fxaa) fxaa();
  glActiveTexture(GL_TEXTURE0);
  glBindFramebuffer(GL_FRAMEBUFFER, c.fbo[2]);
  return true;
}

}  // namespace rscene::render::detail
