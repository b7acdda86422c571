// PostEffects: the post-processing of a color view (internal to
// lib/render, a friend of GlRenderer like the modules of gl_effects.hpp),
// what the environment and rayrai_render records ask for (post_plan.hpp).
// After the lit pass is resolved, run() draws, in this order:
//   depth resolve      the nearest sample of each pixel (for depth of field)
//   ambient occlusion  half size, from the depth buffer, blurred
//   composite          surfaces x occlusion over the background, linear HDR
//   auto exposure      log luminance of a 1/16 downsample, read back
//   depth of field     a half-size gather, blended in by the blur radius
//   bloom              soft threshold, then a dual-filter chain of 5 levels
//   final              bloom added, exposure, tone map, gamma
//   FXAA               on the display colors
// into the renderer's RGBA8 target.  With nothing asked for it is the one
// pass it always was (background, tone map).  GLSL: shader_post.cpp and
// shader_post_effects.cpp.
#pragma once
#include <GL/glcorearb.h>

#include <Eigen/Core>
#include <vector>

#include "render/post_plan.hpp"
#include "render/view.hpp"

namespace rscene::render::detail {

class GlRenderer;

// A texture and the framebuffer that draws into it.
struct PostTarget {
  GLuint texture = 0, fbo = 0;
  int width = 0, height = 0;
};

class PostEffects {
 public:
  explicit PostEffects(GlRenderer& r) : r_(r) {}
  ~PostEffects();
  PostEffects(const PostEffects&) = delete;
  PostEffects& operator=(const PostEffects&) = delete;
  // color_.resolved (and the multisampled depth) into color_.final, which
  // is left bound for the read-back; false with an error diagnostic (a
  // program or a target that cannot be made).
  bool run(const View& view, const Eigen::Matrix4d& viewProj);
  float lastExposure() const { return exposure_; }  // environment x auto exposure of the last run

 private:
  bool buildPrograms();  // once; false (with the diagnostic) if any fails
  bool ensure(PostTarget& t, int w, int h, GLenum internalFormat, GLenum format, GLenum type, GLenum filter);
  void draw(const PostTarget* into);
  void composite(const View& view, const Eigen::Matrix4d& viewProj, bool linear, GLuint ao);
  void resolveDepth();
  void ambientOcclusion(const View& view, const Eigen::Matrix4d& proj);
  float autoExposure(float key);
  void depthOfField(const Eigen::Matrix4d& proj, const Eigen::Vector3f& dof);
  void bloom(float exposure);
  void finalPass(const Eigen::Matrix4d& proj, const Eigen::Vector3f& dof, const PostTarget* into);
  void fxaa();

  GlRenderer& r_;
  PostPlan plan_;
  GLuint depthResolveProg_ = 0, ssaoProg_ = 0, ssaoMsProg_ = 0, ssaoBlurProg_ = 0, prefilterProg_ = 0, downProg_ = 0, upProg_ = 0, luminanceProg_ = 0,
         dofProg_ = 0, finalProg_ = 0, fxaaProg_ = 0;
  // depth_: the nearest sample of each pixel of a multisampled pass (R32F,
  // depth of field only); depthSource_: what the passes read, depth_ or
  // the depth buffer itself.
  GLuint depthSource_ = 0;
  PostTarget depth_, hdr_, ldr_, aoRaw_, ao_, luminance_, dof_;
  std::vector<PostTarget> bloom_;
  int bloomLevels_ = 0;
  float exposure_ = 1;
  bool built_ = false, ready_ = false;
  std::vector<float> logLuminance_;
};

}  // namespace rscene::render::detail
