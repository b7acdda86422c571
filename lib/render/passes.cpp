// The drawing side of the Renderer (gl_renderer.hpp): per-view instance
// selection, the shadow map, the lit color pass (MSAA HDR, lights,
// shadows, background, tone mapping) and the flat data pass
// (segmentation colors and linear depth at one sample per pixel).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/codes.hpp"
#include "render/camera.hpp"
#include "render/gl_renderer.hpp"
#include "render/main_pass.hpp"
#include "render/occlusion.hpp"
#include "render/gl_uniforms.hpp"

namespace rscene::render::detail {
namespace {

using Clock = std::chrono::steady_clock;


// GL rows are bottom-up; images are top-down.
template <typename T>
void flipRows(const std::vector<T>& rows, int w, int h, int channels, T* out) {
  for (int y = 0; y < h; ++y)
    std::copy_n(&rows[std::size_t(h - 1 - y) * std::size_t(w) * channels], std::size_t(w) * channels,
                out + std::size_t(y) * std::size_t(w) * channels);
}

}  // namespace

bool GlRenderer::glOk() {
  GLenum e = glGetError();
  if (e == GL_NO_ERROR) return true;
  char b[16];
  std::snprintf(b, sizeof b, "%04x", e);
  diag(Severity::Error, rs::RS9012, 0, std::string("OpenGL error 0x") + b);
  return false;
}

void GlRenderer::selectInstances(const View& view, const Eigen::Matrix4d& viewProj) {
  // Front to back: opaque instances nearest first within a batch, batches
  // by their nearest instance, so that the depth test rejects what they
  // hide before it is shaded (GPUs; llvmpipe's single-sample passes), and
  // what opaque boxes hide entirely not drawn at all (occlusion.hpp; it
  // still casts shadows).  Blended batches keep their order (blending
  // depends on it) and the background batches (ground, terrains) stay last.
  const Camera& cam = view.camera;
  const Eigen::Vector3d eye = cam.world.position;
  const Eigen::Vector3d forward = cam.world.orientation.normalized() * Eigen::Vector3d::UnitX();
  const bool ortho = cam.projection == "orthographic";
  struct Candidate {
    double key;
    std::uint32_t batch, index;
  };
  std::vector<Candidate> candidates;  // in the frustum, of opaque batches
  std::vector<std::vector<std::uint32_t>> inFrustum(batches_.size());
  std::vector<std::vector<std::uint32_t>> outside(batches_.size());
  for (std::size_t bi = 0; bi < batches_.size(); ++bi) {
    const Batch& b = batches_[bi];
    for (std::uint32_t i = 0; i < b.instances.size(); ++i) {
      const Instance& in = b.instances[i];
      if (view.sensor && !in.worldObject) continue;  // RaiSim's sensors see world objects only
      if (!boxInFrustum(viewProj, in.bounds)) {
        outside[bi].push_back(i);
      } else if (b.blend) {
        inFrustum[bi].push_back(i);
      } else {
        candidates.push_back({nearness(in.bounds, eye, forward, ortho), std::uint32_t(bi), i});
      }
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& x, const Candidate& y) { return x.key < y.key; });
  OcclusionBuffer occlusion(viewProj, cam.width, cam.height);
  DepthComplexity complexity(viewProj);
  std::vector<std::pair<double, std::size_t>> batchNearest;
  std::vector<bool> nearestSet(batches_.size(), false);
  for (const Candidate& c : candidates) {
    const Batch& b = batches_[c.batch];
    const Instance& in = b.instances[c.index];
    if (!b.background && occlusion.hidden(in.bounds)) {
      outside[c.batch].push_back(c.index);
      ++timings_.occludedInstances;
      continue;
    }
    if (b.occluder) occlusion.addBox(Eigen::Map<const Eigen::Matrix4f>(in.data).cast<double>());
    inFrustum[c.batch].push_back(c.index);
    complexity.add(in.bounds, b.doubleSided && !b.background ? 2 : 1);
    if (!b.background && !nearestSet[c.batch]) {
      nearestSet[c.batch] = true;
      batchNearest.emplace_back(c.key, c.batch);
    }
  }
  depthComplexity_ = complexity.value();
  std::vector<std::uint32_t> order;
  std::vector<float> data;
  for (std::size_t bi = 0; bi < batches_.size(); ++bi) {
    Batch& b = batches_[bi];
    order = std::move(inFrustum[bi]);
    auto inView = GLsizei(order.size());
    order.insert(order.end(), outside[bi].begin(), outside[bi].end());
    setOrder(b, order, inView, data);
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  reselect_ = false;
  // Nearest opaque batches first, then the other non-background batches
  // (blended ones, those out of view) and the background ones, each group
  // in the order they were made.
  drawOrder_.clear();
  std::vector<bool> placed(batches_.size(), false);
  for (const auto& n : batchNearest) {  // already nearest first
    drawOrder_.push_back(n.second);
    placed[n.second] = true;
  }
  for (int background = 0; background < 2; ++background)
    for (std::size_t i = 0; i < batches_.size(); ++i)
      if (!placed[i] && batches_[i].background == bool(background)) drawOrder_.push_back(i);
}

void GlRenderer::setOrder(Batch& b, std::vector<std::uint32_t>& order, GLsizei inView, std::vector<float>& data) {
  if (!b.dirty && b.everUploaded && order == b.order && inView == b.inView) return;
  data.resize(order.size() * kInstanceFloats);
  for (std::size_t k = 0; k < order.size(); ++k)
    std::copy_n(b.instances[order[k]].data, kInstanceFloats, data.data() + k * kInstanceFloats);
  glBindBuffer(GL_ARRAY_BUFFER, b.instanceVbo);
  if (!data.empty()) glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(data.size() * sizeof(float)), data.data());
  b.order.swap(order);
  b.inView = inView;
  b.count = GLsizei(b.order.size());
  b.dirty = false;
  b.everUploaded = true;
}

void GlRenderer::drawBatches(GLuint prog, bool blendPass, bool shadowPass, bool flat) {
  for (std::size_t i : drawOrder_) {
    const Batch& b = batches_[i];
    if (shadowPass ? !b.castShadow : !flat && b.blend != blendPass) continue;
    if (!shadowPass) {
      if (!flat) {
        glUniform1i(loc(prog, "uHasAlbedo"), b.texture != 0);
        glUniform1i(loc(prog, "uDoubleSided"), b.doubleSided);
        glActiveTexture(GL_TEXTURE1);
        glBindTexture(GL_TEXTURE_2D, b.texture);
      }
      if (b.doubleSided)
        glDisable(GL_CULL_FACE);
      else
        glEnable(GL_CULL_FACE);
    }
    GLsizei n = shadowPass ? b.count : b.inView;
    if (n == 0) continue;
    glBindVertexArray(b.vao);
    glDrawElementsInstanced(GL_TRIANGLES, b.mesh->indexCount, GL_UNSIGNED_INT, nullptr, n);
  }
  glBindVertexArray(0);
}

bool GlRenderer::colorTargets(int w, int h, int samples) {
  ColorTargets& t = color_;
  if (t.fbo[0] && t.width == w && t.height == h && t.samples == samples) return true;
  if (!t.fbo[0]) {
    glGenFramebuffers(3, t.fbo);
    glGenRenderbuffers(1, &t.msaaColor);
    GLuint tex[2];
    glGenTextures(2, tex);
    t.resolved = tex[0], t.final = tex[1];
  }
  t.width = w, t.height = h, t.samples = samples;
  glBindRenderbuffer(GL_RENDERBUFFER, t.msaaColor);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples > 1 ? samples : 0, GL_RGBA16F, w, h);
  // The depth is a texture, so that the post-processing can read every
  // sample (gl_post.cpp); a texture's kind is fixed once bound, so a new
  // one for each sample count.
  if (t.msaaDepth) glDeleteTextures(1, &t.msaaDepth);
  glGenTextures(1, &t.msaaDepth);
  GLenum depthTarget = samples > 1 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
  glBindTexture(depthTarget, t.msaaDepth);
  if (samples > 1) {
    glTexImage2DMultisample(GL_TEXTURE_2D_MULTISAMPLE, samples, GL_DEPTH24_STENCIL8, w, h, GL_TRUE);
  } else {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH24_STENCIL8, w, h, 0, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, t.fbo[0]);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t.msaaColor);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, depthTarget, t.msaaDepth, 0);
  bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  for (int i = 0; i < 2; ++i) {
    GLuint tex = i == 0 ? t.resolved : t.final;
    glBindTexture(GL_TEXTURE_2D, tex);
    if (i == 0)
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, w, h, 0, GL_RGBA, GL_FLOAT, nullptr);
    else
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, t.fbo[1 + i]);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    complete = complete && glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  }
  if (complete) return true;
  diag(Severity::Error, rs::RS9011, 0,
       "cannot create a " + std::to_string(w) + "x" + std::to_string(h) + " framebuffer with " +
           std::to_string(samples) + " samples");
  t.width = t.height = 0;
  return false;
}

bool GlRenderer::dataTargets(int w, int h) {
  DataTargets& t = data_;
  if (t.fbo && t.width == w && t.height == h) return true;
  if (!t.fbo) {
    glGenFramebuffers(1, &t.fbo);
    GLuint rb[3];
    glGenRenderbuffers(3, rb);
    t.segmentation = rb[0], t.depth = rb[1], t.z = rb[2];
  }
  t.width = w, t.height = h;
  glBindRenderbuffer(GL_RENDERBUFFER, t.segmentation);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
  glBindRenderbuffer(GL_RENDERBUFFER, t.depth);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_R32F, w, h);
  glBindRenderbuffer(GL_RENDERBUFFER, t.z);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, w, h);
  glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t.segmentation);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_RENDERBUFFER, t.depth);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t.z);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE) return true;
  diag(Severity::Error, rs::RS9011, 0,
       "cannot create a " + std::to_string(w) + "x" + std::to_string(h) + " depth and segmentation framebuffer");
  t.width = t.height = 0;
  return false;
}

bool GlRenderer::colorPass(const View& view, const Eigen::Matrix4d& viewProj, Image& out) {
  const Camera& camera = view.camera;
  int w = camera.width, h = camera.height;
  glVertexAttrib4f(3, 1, 1, 1, 1);  // vertex color of meshes that have none
  if (!reflections_->prepare(view)) return false;
  // A probe's faces use the shadow maps the capture fitted to the view
  // (ReflectionEffects::prepare): refitting them to each face cost more
  // than the capture's own drawing.
  const bool capture = reflections_->capturing();
  if (!capture && !lights_->prepare(view, viewProj)) return false;

  // Main pass: linear HDR, coverage in alpha, multisampled.
  GLint maxSamples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
  GLint maxDepthSamples = 1;  // the depth is a multisampled texture (colorTargets)
  glGetIntegerv(GL_MAX_DEPTH_TEXTURE_SAMPLES, &maxDepthSamples);
  maxSamples = std::min(maxSamples, maxDepthSamples);
  int samples = std::clamp(view.samples > 0 ? view.samples : opt_.samples, 1, std::max(1, int(maxSamples)));
  bool jitter = software_ && preferJitteredPasses(depthComplexity_, samples);
  if (!colorTargets(w, h, jitter ? 1 : samples)) return false;
  glBindFramebuffer(GL_FRAMEBUFFER, color_.fbo[0]);
  glViewport(0, 0, w, h);
  glClearColor(0, 0, 0, 0);
  glClearStencil(0);
  glDepthMask(GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glCullFace(GL_BACK);
  GLuint surface = surfaceProg_;
  glUseProgram(surface);
  setMat(surface, "uViewProj", viewProj);
  setVec3(surface, "uCameraPos", camera.world.position.cast<float>());
  glUniform1i(loc(surface, "uAlbedo"), units::kAlbedo);
  lights_->bind(surface, view, viewProj);
  volumes_->bind(surface, view);
  reflections_->bind(surface, view);
  // The layers: MSAA after a depth pre-pass on GPUs (the lit shader then
  // runs once per visible sample); on llvmpipe, which shades every
  // fragment of a multisampled target hidden or not, MSAA without one
  // (measured faster on shallow scenes) or, when the view is deep, one
  // jittered single-sample pass per sample (main_pass.hpp).
  if (jitter) {
    ++timings_.jitteredViews;
    if (!jitteredLayers(view, viewProj, samples)) return false;
  } else {
    drawLayers(view, viewProj, !software_);
  }
  glFinish();
  postStart_ = Clock::now();

  // Resolve, then background + tone map into RGBA8, with the
  // post-processing the scene asks for (gl_post.cpp).  The glFinish above:
  // the lit pass is done, so that what follows is post-processing time.
  glBindFramebuffer(GL_READ_FRAMEBUFFER, color_.fbo[0]);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, color_.fbo[1]);
  glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  if (capture) return glOk();  // the capture reads the resolved HDR image
  if (!post_->run(view, viewProj)) return false;

  out.width = w;
  out.height = h;
  out.rgba.assign(std::size_t(w) * h * 4, 0);
  std::vector<std::uint8_t> rows(out.rgba.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
  flipRows(rows, w, h, 4, out.rgba.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return glOk();
}

bool GlRenderer::dataPass(const View& view, const Eigen::Matrix4d& viewProj, ViewImages& out, bool wantDepth,
                          bool wantSegmentation) {
  const Camera& camera = view.camera;
  int w = camera.width, h = camera.height;
  if (!dataTargets(w, h)) return false;
  glBindFramebuffer(GL_FRAMEBUFFER, data_.fbo);
  const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glDrawBuffers(2, buffers);
  glViewport(0, 0, w, h);
  const GLfloat black[4] = {0, 0, 0, 1}, noHit[4] = {0, 0, 0, 0};  // depth 0: nothing hit (never in [near, far])
  glClearBufferfv(GL_COLOR, 0, black);
  glClearBufferfv(GL_COLOR, 1, noHit);
  glDepthMask(GL_TRUE);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glCullFace(GL_BACK);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  Eigen::Vector3f eye = camera.world.position.cast<float>();
  Eigen::Vector3f forward = (camera.world.orientation.normalized() * Eigen::Vector3d::UnitX()).cast<float>();
  glUseProgram(dataProg_);
  setMat(dataProg_, "uViewProj", viewProj);
  setVec3(dataProg_, "uCameraPos", eye);
  setVec3(dataProg_, "uForward", forward);
  drawBatches(dataProg_, false, false, true);  // every batch, blended ones as opaque
  if (pointVao_ && !view.sensor) {
    glUseProgram(pointDataProg_);
    glEnable(GL_PROGRAM_POINT_SIZE);
    setMat(pointDataProg_, "uViewProj", viewProj);
    setVec3(pointDataProg_, "uCameraPos", eye);
    setVec3(pointDataProg_, "uForward", forward);
    glBindVertexArray(pointVao_);
    for (std::size_t i = 0; i < pointRanges_.size(); ++i) {
      int s = pointSegments_[i];
      Eigen::Vector3f c = Eigen::Vector3f::Zero();
      if (s >= 0 && std::size_t(s) < scene_.segments.size())
        for (int k = 0; k < 3; ++k) c[k] = float(scene_.segments[std::size_t(s)].rgb[k]) / 255.0f;
      setVec3(pointDataProg_, "uSegment", c);
      glUniform1f(loc(pointDataProg_, "uPointSize"), pointSizes_[i]);
      glDrawArrays(GL_POINTS, pointRanges_[i].first, pointRanges_[i].second);
    }
    glBindVertexArray(0);
  }
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  if (wantSegmentation) {
    std::vector<std::uint8_t> rows(std::size_t(w) * h * 4);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    out.segmentation.width = w;
    out.segmentation.height = h;
    out.segmentation.rgba.assign(rows.size(), 0);
    flipRows(rows, w, h, 4, out.segmentation.rgba.data());
  }
  if (wantDepth) {
    std::vector<float> rows(std::size_t(w) * h);
    glReadBuffer(GL_COLOR_ATTACHMENT1);
    glReadPixels(0, 0, w, h, GL_RED, GL_FLOAT, rows.data());
    out.depth.assign(rows.size(), 0);
    flipRows(rows, w, h, 1, out.depth.data());
    // Clipping keeps what is drawn within [near, far] up to rounding; the
    // test here makes the rule exact and turns "nothing hit" (0) into NaN.
    const float n = float(camera.nearPlane), f = float(camera.farPlane);
    for (float& d : out.depth)
      if (!(d >= n && d <= f)) d = std::numeric_limits<float>::quiet_NaN();
  }
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glDrawBuffers(1, buffers);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return glOk();
}

bool GlRenderer::render(const View& view, ViewImages& out, Diagnostics& diagnostics) {
  auto t0 = Clock::now();
  diags_ = &diagnostics;
  out = ViewImages{};
  if (std::string problem = viewProblem(view); !problem.empty()) {
    diag(Severity::Error, rs::RS9040, 0, "view '" + view.name + "': " + problem);
    return false;
  }
  out.width = view.camera.width;
  out.height = view.camera.height;
  bool color = false, depth = false, segmentation = false;
  for (Pass p : view.passes) {
    color = color || p == Pass::Color;
    depth = depth || p == Pass::Depth;
    segmentation = segmentation || p == Pass::Segmentation;
  }
  Eigen::Matrix4d viewProj = viewProjection(view);
  selectInstances(view, viewProj);
  bool ok = true;
  // Drawing is what the shadow passes and the post-processing (from the
  // resolve to the read-back) leave of the view's time.
  double before = timings_.shadowSeconds + timings_.postSeconds;
  if (color) {
    postStart_ = Clock::now();
    ok = colorPass(view, viewProj, out.color);
    timings_.postSeconds += std::chrono::duration<double>(Clock::now() - postStart_).count();
  }
  // The jittered passes may have left out what no sample of the color
  // pass sees; the data pass samples pixel centres: select again.
  if (ok && (depth || segmentation) && reselect_) selectInstances(view, viewProj);
  if (ok && (depth || segmentation)) ok = dataPass(view, viewProj, out, depth, segmentation);
  if (ok && depth) addDepthNoise(out.depth, view.noiseMean, view.noiseStddev, view.noiseSeed);
  timings_.drawSeconds += std::chrono::duration<double>(Clock::now() - t0).count() -
                          (timings_.shadowSeconds + timings_.postSeconds - before);
  return ok;
}

}  // namespace rscene::render::detail
