// The lit pass's draw calls (gl_renderer.hpp, main_pass.hpp): the layers
// of one view into the bound framebuffer, and the jittered single-sample
// passes a software rasteriser draws instead of MSAA on deep scenes.
#include "core/codes.hpp"
#include "render/gl_renderer.hpp"
#include "render/gl_uniforms.hpp"
#include "render/main_pass.hpp"

namespace rscene::render::detail {

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
    setMat(prepassProg_, "uViewProj", viewProj);
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
  setMat(surface, "uViewProj", viewProj);
  drawBatches(surface, false, false);
  if (prepass) glDisable(GL_STENCIL_TEST);  // else the caller's stencil test holds for every layer
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  if (pointVao_ && !view.sensor) {  // point clouds are visuals: no sensor sees them
    glUseProgram(pointProg_);
    glEnable(GL_PROGRAM_POINT_SIZE);
    setMat(pointProg_, "uViewProj", viewProj);
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
  // A texture (colorTargets: the post-processing reads it), single-sample here.
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, color_.msaaDepth, 0);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE) return true;
  diag(Severity::Error, rs::RS9011, 0,
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

bool GlRenderer::markEdges(const View& view, const Eigen::Matrix4d& viewProj, int samples) {
  JitterTargets& t = jitter_;
  int w = t.width, h = t.height;
  if (!t.idFbo) {
    glGenFramebuffers(1, &t.idFbo);
    glGenTextures(1, &t.ids);
    glGenRenderbuffers(1, &t.idDepth);
    t.idSamples = 0;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, t.idFbo);
  GLint have[2] = {0, 0};
  glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, t.ids);
  glGetTexLevelParameteriv(GL_TEXTURE_2D_MULTISAMPLE, 0, GL_TEXTURE_WIDTH, &have[0]);
  glGetTexLevelParameteriv(GL_TEXTURE_2D_MULTISAMPLE, 0, GL_TEXTURE_HEIGHT, &have[1]);
  if (have[0] != w || have[1] != h || t.idSamples != samples) {
    glTexImage2DMultisample(GL_TEXTURE_2D_MULTISAMPLE, samples, GL_RG32UI, w, h, GL_TRUE);
    glBindRenderbuffer(GL_RENDERBUFFER, t.idDepth);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, w, h);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D_MULTISAMPLE, t.ids, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t.idDepth);
    t.idSamples = samples;
  }
  glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, 0);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    t.idSamples = 0;
    return false;
  }
  // Ids of every sample: opaque layers by the depth test, blended ones
  // xor-ed over them (so an edge seen through glass is still an edge).
  glViewport(0, 0, w, h);
  const GLuint none[4] = {0, 0, 0, 0};
  glClearBufferuiv(GL_COLOR, 0, none);
  glDepthMask(GL_TRUE);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_BLEND);
  glCullFace(GL_BACK);
  glUseProgram(idProg_);
  setMat(idProg_, "uViewProj", viewProj);
  GLuint first = 0;
  std::vector<std::pair<std::size_t, GLuint>> firstIds;  // opaque batch, its first instance's id - 1
  for (int blended = 0; blended < 2; ++blended) {
    glUseProgram(idProg_);
    GLint base = glGetUniformLocation(idProg_, "uBase");
    if (blended) {
      glBindFramebuffer(GL_FRAMEBUFFER, t.idFbo);
      glViewport(0, 0, w, h);
      glEnable(GL_DEPTH_TEST);
      glDepthMask(GL_FALSE);
      glEnable(GL_COLOR_LOGIC_OP);
      glLogicOp(GL_XOR);
    }
    for (std::size_t i : drawOrder_) {
      const Batch& b = batches_[i];
      if (b.blend != bool(blended) || b.inView == 0) continue;
      if (b.doubleSided)
        glDisable(GL_CULL_FACE);
      else
        glEnable(GL_CULL_FACE);
      if (!blended) firstIds.emplace_back(i, first);
      glUniform1ui(base, first);
      first += GLuint(b.inView);
      glBindVertexArray(b.vao);
      glDrawElementsInstanced(GL_TRIANGLES, b.mesh->indexCount, GL_UNSIGNED_INT, nullptr, b.inView);
    }
    glBindVertexArray(0);
    if (!blended) keepVisible(samples, firstIds);
  }
  glBindVertexArray(0);
  glDisable(GL_COLOR_LOGIC_OP);
  glDepthMask(GL_TRUE);
  // Stencil 1 where the samples differ.
  glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_ALWAYS, 1, 0xff);
  glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
  glUseProgram(edgeProg_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, t.ids);
  glUniform1i(glGetUniformLocation(edgeProg_, "uIds"), 0);
  glUniform1i(glGetUniformLocation(edgeProg_, "uSamples"), samples);
  glBindVertexArray(emptyVao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, 0);
  glDisable(GL_STENCIL_TEST);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glEnable(GL_DEPTH_TEST);
  (void)view;
  return true;
}

void GlRenderer::keepVisible(int samples, const std::vector<std::pair<std::size_t, GLuint>>& firstIds) {
  JitterTargets& t = jitter_;
  // In bands of rows: the spread texture and the read-back hold
  // kBandRows rows, not the image (memory: README, "Resource limits").
  constexpr int kBandRows = 64;
  int sw = t.width * samples, sh = std::min(t.height, kBandRows);
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  if (sw > maxSize || firstIds.empty()) return;
  if (!t.spreadFbo) {
    glGenFramebuffers(1, &t.spreadFbo);
    glGenTextures(1, &t.spread);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, t.spreadFbo);
  if (t.spreadWidth != sw || t.spreadHeight != sh) {
    glBindTexture(GL_TEXTURE_2D, t.spread);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32UI, sw, sh, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.spread, 0);
    t.spreadWidth = sw, t.spreadHeight = sh;
  }
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    t.spreadWidth = t.spreadHeight = 0;
    return;
  }
  glViewport(0, 0, sw, sh);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glUseProgram(spreadProg_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, t.ids);
  glUniform1i(glGetUniformLocation(spreadProg_, "uIds"), 0);
  glUniform1i(glGetUniformLocation(spreadProg_, "uSamples"), samples);
  GLint row = glGetUniformLocation(spreadProg_, "uRow");
  const Batch& last = batches_[firstIds.back().first];
  std::vector<char> seen(std::size_t(firstIds.back().second) + std::size_t(last.inView) + 1, 0);
  std::vector<GLuint> ids(std::size_t(sw) * std::size_t(sh));
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glBindVertexArray(emptyVao_);
  for (int y0 = 0; y0 < t.height; y0 += sh) {
    int rows = std::min(sh, t.height - y0);
    glUniform1i(row, y0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glReadPixels(0, 0, sw, rows, GL_RED_INTEGER, GL_UNSIGNED_INT, ids.data());
    for (std::size_t i = 0; i < std::size_t(sw) * std::size_t(rows); ++i)
      if (ids[i] < seen.size()) seen[ids[i]] = 1;
  }
  glBindVertexArray(0);
  glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, 0);
  std::vector<std::uint32_t> order, hidden;
  std::vector<float> data;
  for (const auto& [bi, first] : firstIds) {
    Batch& b = batches_[bi];
    order.clear();
    hidden.clear();
    for (GLsizei k = 0; k < b.inView; ++k)
      (seen[std::size_t(first) + std::size_t(k) + 1] ? order : hidden).push_back(b.order[std::size_t(k)]);
    if (hidden.empty()) continue;
    auto visible = GLsizei(order.size());
    timings_.occludedInstances += hidden.size();
    order.insert(order.end(), hidden.begin(), hidden.end());
    order.insert(order.end(), b.order.begin() + b.inView, b.order.end());
    setOrder(b, order, visible, data);
    reselect_ = true;
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

bool GlRenderer::jitteredLayers(const View& view, const Eigen::Matrix4d& viewProj, int samples) {
  int w = view.camera.width, h = view.camera.height;
  const std::vector<Eigen::Vector2f>& positions = samplePositions(samples);
  if (!jitterTargets(w, h)) return false;
  // The lit program's textures stay bound across the passes but unit 0,
  // which the edges and the average borrow.
  GLint unit0 = 0;
  glActiveTexture(GL_TEXTURE0);
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &unit0);
  // After the first pass, only the pixels whose samples see different
  // triangles are drawn again (the stencil); the others keep the first
  // pass's color, as MSAA shades such a pixel once.  Point clouds are not
  // in the ids: with them every pass draws every pixel.
  bool edgesOnly = !(pointVao_ && !view.sensor) && markEdges(view, viewProj, int(positions.size()));
  auto weight = GLfloat(1.0 / double(positions.size()));
  for (std::size_t k = 0; k < positions.size(); ++k) {
    glBindFramebuffer(GL_FRAMEBUFFER, jitter_.fbo);
    glViewport(0, 0, w, h);
    glClearColor(0, 0, 0, 0);
    glDepthMask(GL_TRUE);
    if (!edgesOnly) {
      glClearStencil(0);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    } else if (k == 0) {
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    } else {
      // Edge pixels start clear (a draw: glClear ignores the stencil);
      // the others keep the first pass's color.
      glClear(GL_DEPTH_BUFFER_BIT);
      glEnable(GL_STENCIL_TEST);
      glStencilFunc(GL_EQUAL, 1, 0xff);
      glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
      glDisable(GL_DEPTH_TEST);
      glDisable(GL_BLEND);
      glUseProgram(clearProg_);
      glBindVertexArray(emptyVao_);
      glDrawArrays(GL_TRIANGLES, 0, 3);
      glBindVertexArray(0);
    }
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, GLuint(unit0));
    drawLayers(view, jittered(viewProj, positions[k], w, h), false);
    glDisable(GL_STENCIL_TEST);
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
