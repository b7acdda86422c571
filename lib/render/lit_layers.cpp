// The lit pass's draw calls (gl_renderer.hpp, main_pass.hpp): the layers
// of one view into the bound framebuffer, and the jittered single-sample
// passes a software rasteriser draws instead of MSAA on deep scenes.
#include "render/gl_renderer.hpp"
#include "render/main_pass.hpp"

namespace rscene::render::detail {
namespace {

void setMatrix(GLuint p, const char* name, const Eigen::Matrix4d& m) {
  Eigen::Matrix4f f = m.cast<float>();
  glUniformMatrix4fv(glGetUniformLocation(p, name), 1, GL_FALSE, f.data());
}

}  // namespace

void GlRenderer::drawLayers(const View& view, const Eigen::Matrix4d& viewProj, bool prepass) {
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glCullFace(GL_BACK);
  if (prepass) {
    // Depth only, culling as the lit pass will (a back face it would cull
    // must not hide what is behind it).
    glUseProgram(prepassProg_);
    setMatrix(prepassProg_, "uViewProj", viewProj);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    for (std::size_t i : drawOrder_) {
      const Batch& b = batches_[i];
      if (b.blend || b.inView == 0) continue;
      if (b.doubleSided)
        glDisable(GL_CULL_FACE);
      else
        glEnable(GL_CULL_FACE);
      glBindVertexArray(b.vao);
      glDrawElementsInstanced(GL_TRIANGLES, b.mesh->indexCount, GL_UNSIGNED_INT, nullptr, b.inView);
    }
    glBindVertexArray(0);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    // Each sample is lit once: coplanar surfaces (stacked boxes with level
    // tops, overlapping placeholders) all pass GL_LEQUAL, so the stencil
    // lets the first one drawn through and rejects the rest before they
    // are shaded (the one GL_LESS alone would have kept).
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, 0, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
  }
  GLuint surface = surfaceProg_;
  glUseProgram(surface);
  setMatrix(surface, "uViewProj", viewProj);
  drawBatches(surface, false, false);
  glDisable(GL_STENCIL_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  if (pointVao_ && !view.sensor) {  // point clouds are visuals: no sensor sees them
    glUseProgram(pointProg_);
    glEnable(GL_PROGRAM_POINT_SIZE);
    setMatrix(pointProg_, "uViewProj", viewProj);
    glBindVertexArray(pointVao_);
    for (std::size_t i = 0; i < pointRanges_.size(); ++i) {
      glUniform1f(glGetUniformLocation(pointProg_, "uPointSize"), pointSizes_[i]);
      glDrawArrays(GL_POINTS, pointRanges_[i].first, pointRanges_[i].second);
    }
    glBindVertexArray(0);
    glUseProgram(surface);
  }
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glDepthMask(GL_FALSE);
  drawBatches(surface, true, false);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
}

bool GlRenderer::jitterTargets(int w, int h) {
  JitterTargets& t = jitter_;
  if (!t.fbo) {
    glGenFramebuffers(1, &t.fbo);
    glGenTextures(1, &t.color);
  }
  if (t.width != w || t.height != h) {
    t.width = w, t.height = h;
    glBindTexture(GL_TEXTURE_2D, t.color);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, w, h, 0, GL_RGBA, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  // The depth and stencil of the (single-sample) color targets: the last
  // pass's depth stays there for what follows the lit pass.
  glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.color, 0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, color_.msaaDepth);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE) return true;
  diag(Severity::Error, "RS9011", 0,
       "cannot create a " + std::to_string(w) + "x" + std::to_string(h) + " framebuffer for the jittered passes");
  t.width = t.height = 0;
  return false;
}

// Where the driver's MSAA would sample, asked once per count from a 1x1
// multisampled framebuffer; the standard pattern if it cannot say.
const std::vector<Eigen::Vector2f>& GlRenderer::samplePositions(int samples) {
  auto it = samplePositions_.find(samples);
  if (it != samplePositions_.end()) return it->second;
  std::vector<Eigen::Vector2f> positions;
  GLuint rb = 0, fbo = 0;
  glGenRenderbuffers(1, &rb);
  glBindRenderbuffer(GL_RENDERBUFFER, rb);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, 1, 1);
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE) {
    GLint n = 0;
    glGetIntegerv(GL_SAMPLES, &n);
    for (GLint i = 0; i < n && n > 1; ++i) {
      GLfloat p[2] = {0.5f, 0.5f};
      glGetMultisamplefv(GL_SAMPLE_POSITION, GLuint(i), p);
      positions.emplace_back(p[0], p[1]);
    }
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &fbo);
  glDeleteRenderbuffers(1, &rb);
  while (glGetError() != GL_NO_ERROR) {
  }
  if (positions.size() < 2) positions = standardSamplePattern(samples);
  return samplePositions_.emplace(samples, std::move(positions)).first->second;
}

bool GlRenderer::jitteredLayers(const View& view, const Eigen::Matrix4d& viewProj, int samples) {
  int w = view.camera.width, h = view.camera.height;
  const std::vector<Eigen::Vector2f>& positions = samplePositions(samples);
  if (!jitterTargets(w, h)) return false;
  // The lit program's textures stay bound across the passes but unit 0,
  // which the average borrows.
  GLint unit0 = 0;
  glActiveTexture(GL_TEXTURE0);
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &unit0);
  auto weight = GLfloat(1.0 / double(positions.size()));
  for (const Eigen::Vector2f& offset : positions) {
    glBindFramebuffer(GL_FRAMEBUFFER, jitter_.fbo);
    glViewport(0, 0, w, h);
    glClearColor(0, 0, 0, 0);
    glClearStencil(0);
    glDepthMask(GL_TRUE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, GLuint(unit0));
    drawLayers(view, jittered(viewProj, offset, w, h), false);
    // Sum into the color target (cleared by colorPass), each pass weighted
    // 1/N: the MSAA resolve's average.
    glBindFramebuffer(GL_FRAMEBUFFER, color_.fbo[0]);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendColor(weight, weight, weight, weight);
    glBlendFunc(GL_CONSTANT_COLOR, GL_ONE);
    glUseProgram(averageProg_);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, jitter_.color);
    glUniform1i(glGetUniformLocation(averageProg_, "uPass"), 0);
    glBindVertexArray(emptyVao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    glBlendColor(0, 0, 0, 0);
    glEnable(GL_DEPTH_TEST);
  }
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, GLuint(unit0));
  glUseProgram(surfaceProg_);
  return true;
}

}  // namespace rscene::render::detail
