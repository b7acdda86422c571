// LightEffects (gl_lights.hpp): the light buffer, the per-view light grid
// and the shadow atlas of the surface program (GLSL: shader_lights.cpp).
#include "render/gl_lights.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <string>

#include "core/codes.hpp"
#include "render/camera.hpp"
#include "render/gl_renderer.hpp"
#include "render/shaders.hpp"
#include "render/gl_uniforms.hpp"

namespace rscene::render::detail {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kPi = 3.14159265358979323846;
// Largest map side per kind (orthographic, perspective, one cube face):
// on a GPU, and on llvmpipe, which rasterises every shadow texel of every
// overlapping caster on the CPU (the budget: all shadow passes of
// the warehouse under 0.4 s; its directional map at 2048 took 1.2 s of a
// loaded machine, at 1024 a quarter of that).  A directional map fitted to
// the view at 1024 is sharper than the whole-scene 1024 map it replaces.
constexpr int kMaxMap[2][3] = {{4096, 2048, 1024}, {1024, 512, 256}};
constexpr int kMinMap = 64;
constexpr int kMaxAtlas[2] = {8192, 4096};
// A spot light wider than this casts its shadow through a cube map: one
// perspective map would spend most of its texels on the cone's rim.
constexpr double kWideSpotDegrees = 60;

// The shadow maps' program: positions only, no fragment work.
GLuint depthProgram(std::string& log) {
  return linkProgram(shaders::kShadowMapVertex, shaders::kDepthFragment, log);
}

// Most lights that cast shadows (the strongest; RS9050 says so).
constexpr std::size_t kMaxCasters = 64;

// What "strongest" means for environment shadowedLightBudget.
float strengthOf(const RenderLight& l) { return l.color.cwiseAbs().maxCoeff(); }


}  // namespace

LightEffects::~LightEffects() {
  GLuint textures[3] = {atlasTex_, lightTex_, gridTex_}, buffers[3] = {lightBuffer_, gridBuffer_, instanceVbo_};
  glDeleteTextures(3, textures);
  glDeleteBuffers(3, buffers);
  if (atlasFbo_) glDeleteFramebuffers(1, &atlasFbo_);
  for (GLuint vao : shadowVaos_)
    if (vao) glDeleteVertexArrays(1, &vao);
}

bool LightEffects::upload() {
  std::vector<RenderLight> all = r_.scene_.lights;
  if (all.empty()) {  // a scene without lights is lit by the sun of its sky
    RenderLight sun;
    sun.direction = -r_.scene_.environment.sunDirection;
    sun.color = Eigen::Vector3f(1.0f, 0.96f, 0.9f) * 3.0f;
    sun.shadows = true;
    all.push_back(sun);
  }
  // Directional lights first: they light every pixel; the grid lists the rest.
  for (int pass = 0; pass < 2; ++pass)
    for (const RenderLight& l : all)
      if ((l.type == LightType::Directional) == (pass == 0)) lights_.push_back(l);
  directionalCount_ = int(std::count_if(lights_.begin(), lights_.end(),
                                        [](const RenderLight& l) { return l.type == LightType::Directional; }));
  GLint maxTexels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  auto maxLights = std::size_t(std::max(maxTexels, 65536) / kLightTexels);
  if (lights_.size() > maxLights) {
    r_.diag(Severity::Warning, rs::RS9004, 0,
            std::to_string(lights_.size()) + " lights; the light buffer holds " + std::to_string(maxLights) +
                ", the rest are not drawn");
    lights_.resize(maxLights);
    directionalCount_ = std::min(directionalCount_, int(maxLights));
  }
  for (const RenderLight& l : lights_) {
    reach_.push_back(lightReach(l));
    bounds_.push_back(lightBounds(l, reach_.back()));
  }
  chooseCasters();
  std::string log;
  depthProg_ = depthProgram(log);
  if (!depthProg_) {
    r_.diag(Severity::Error, rs::RS9010, 0, "shader build failed: " + log);
    return false;
  }
  if (!makeAtlas()) return false;
  makeShadowArrays();
  // The lights the grid lists: those without a shadow map first.
  for (int shadowed = 0; shadowed < 2; ++shadowed) {
    if (shadowed) firstShadowed_ = localIndices_.size();
    for (std::size_t i = std::size_t(directionalCount_); i < lights_.size(); ++i)
      if (reach_[i] > 0 && (casterOf_[i] >= 0) == bool(shadowed)) {
        localBounds_.push_back(bounds_[i]);
        localIndices_.push_back(std::int32_t(i));
      }
  }
  GLuint buffers[2], textures[2];
  glGenBuffers(2, buffers);
  glGenTextures(2, textures);
  lightBuffer_ = buffers[0], gridBuffer_ = buffers[1];
  lightTex_ = textures[0], gridTex_ = textures[1];
  glBindBuffer(GL_TEXTURE_BUFFER, lightBuffer_);
  glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(lights_.size() * kLightTexels * 4 * sizeof(float)), nullptr,
               GL_DYNAMIC_DRAW);
  glBindTexture(GL_TEXTURE_BUFFER, lightTex_);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, lightBuffer_);
  glBindBuffer(GL_TEXTURE_BUFFER, gridBuffer_);
  glBufferData(GL_TEXTURE_BUFFER, 16, nullptr, GL_DYNAMIC_DRAW);
  glBindTexture(GL_TEXTURE_BUFFER, gridTex_);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_R32I, gridBuffer_);
  glBindTexture(GL_TEXTURE_BUFFER, 0);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  return true;
}

// Every light with shadows=true casts (environment shadows=true), the
// strongest shadowedLightBudget of them when that is > 0.
void LightEffects::chooseCasters() {
  const Look& env = r_.scene_.environment;
  casterOf_.assign(lights_.size(), -1);
  if (!env.shadows) return;
  std::vector<std::size_t> chosen;
  for (std::size_t i = 0; i < lights_.size(); ++i) {
    const RenderLight& l = lights_[i];
    float strength = env.customShadows ? env.shadowStrength : l.shadowStrength;
    if (l.shadows && strength > 0 && reach_[i] > 0 && strengthOf(l) > 0) chosen.push_back(i);
  }
  // At most kMaxCasters whatever the budget: each caster is a shadow pass
  // (six for a cube), and thousands made the upload quadratic in time.
  std::size_t budget = env.shadowedLightBudget > 0 ? std::size_t(env.shadowedLightBudget) : kMaxCasters;
  budget = std::min(budget, kMaxCasters);
  if (chosen.size() > budget) {
    if (budget == kMaxCasters && (env.shadowedLightBudget <= 0 || std::size_t(env.shadowedLightBudget) > kMaxCasters))
      r_.diag(Severity::Warning, rs::RS9050, 0,
              std::to_string(chosen.size()) + " lights cast shadows; the " + std::to_string(kMaxCasters) +
                  " strongest do, the others light without shadow");
    std::stable_sort(chosen.begin(), chosen.end(),
                     [&](std::size_t a, std::size_t b) { return strengthOf(lights_[a]) > strengthOf(lights_[b]); });
    chosen.resize(budget);
    std::sort(chosen.begin(), chosen.end());
  }
  const int sw = r_.software_ ? 1 : 0;
  for (std::size_t i : chosen) {
    const RenderLight& l = lights_[i];
    Caster c;
    c.light = i;
    c.kind = l.type == LightType::Directional                                   ? MapKind::Ortho
             : l.type == LightType::Spot && l.coneDegrees <= kWideSpotDegrees ? MapKind::Perspective
                                                                                : MapKind::Cube;
    c.strength = env.customShadows ? env.shadowStrength : l.shadowStrength;
    c.bias = std::max(env.customShadows ? env.shadowBias : l.shadowBias, 0.f);
    c.pcfRadius = std::clamp(env.customShadows ? env.shadowPcfRadius : l.shadowPcfRadius, 0.f, 3.f);
    int res = env.customShadows ? env.shadowResolution
                                : (l.shadowResolution > 0 ? l.shadowResolution : env.shadowResolution);
    if (env.shadowMapSize > 0) res = std::min(res, env.shadowMapSize);
    res = std::min(res, kMaxMap[sw][int(c.kind) - 1]);
    c.resolution = std::max(res, kMinMap);
    c.fitted = c.kind == MapKind::Ortho && !l.customShadowBox;
    c.reachBox = bounds_[i];
    casterOf_[i] = int(casters_.size());
    casters_.push_back(std::move(c));
  }
}

// One depth texture holds every map: one sampler for any number of
// shadowed lights.  Maps are halved until they fit (RS9050).
bool LightEffects::makeAtlas() {
  GLint maxTexture = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
  const int cap = std::min(int(maxTexture), kMaxAtlas[r_.software_ ? 1 : 0]);
  auto extent = [](const Caster& c) {
    return c.kind == MapKind::Cube ? Eigen::Vector2i(3 * c.resolution, 2 * c.resolution)
                                   : Eigen::Vector2i(c.resolution, c.resolution);
  };
  bool reduced = false;
  int side = 1;
  std::vector<Eigen::Vector2i> sizes, origins;
  while (!casters_.empty()) {
    sizes.clear();
    double area = 0;
    for (const Caster& c : casters_) {
      sizes.push_back(extent(c));
      area += double(sizes.back().x()) * sizes.back().y();
    }
    side = kMinMap;
    while (side < cap && double(side) * side < area) side *= 2;
    while (!packAtlas(sizes, side, origins) && side < cap) side *= 2;
    if (packAtlas(sizes, side, origins)) break;
    bool shrunk = false;
    for (Caster& c : casters_)
      if (c.resolution > kMinMap) c.resolution /= 2, shrunk = true;
    if (!shrunk) {  // thousands of shadowed lights: the rest draw unshadowed
      casters_.pop_back();
      casterOf_.assign(lights_.size(), -1);
      for (std::size_t k = 0; k < casters_.size(); ++k) casterOf_[casters_[k].light] = int(k);
    }
    reduced = true;
  }
  if (reduced)
    r_.diag(Severity::Warning, rs::RS9050, 0,
            std::to_string(casters_.size()) + " shadow maps reduced to fit a " + std::to_string(side) + "x" +
                std::to_string(side) + " shadow atlas");
  for (std::size_t k = 0; k < casters_.size(); ++k) casters_[k].origin = origins[k];
  atlasSide_ = casters_.empty() ? 1 : side;
  glGenTextures(1, &atlasTex_);
  glBindTexture(GL_TEXTURE_2D, atlasTex_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, atlasSide_, atlasSide_, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
               nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  glGenFramebuffers(1, &atlasFbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, atlasFbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, atlasTex_, 0);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);  // unshadowed until drawn
  bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (complete) return true;
  r_.diag(Severity::Error, rs::RS9011, 0,
          "cannot create a " + std::to_string(atlasSide_) + "x" + std::to_string(atlasSide_) + " shadow atlas");
  return false;
}

// One vertex array per casting batch: its mesh's positions and the model
// matrices of the instances one shadow view draws (instanceVbo_).
void LightEffects::makeShadowArrays() {
  shadowVaos_.assign(r_.batches_.size(), 0);
  if (casters_.empty()) return;
  if (!instanceVbo_) glGenBuffers(1, &instanceVbo_);
  for (std::size_t i = 0; i < r_.batches_.size(); ++i) {
    const Batch& b = r_.batches_[i];
    if (!b.castShadow) continue;
    glGenVertexArrays(1, &shadowVaos_[i]);
    glBindVertexArray(shadowVaos_[i]);
    glBindBuffer(GL_ARRAY_BUFFER, b.mesh->vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 8 * sizeof(float), nullptr);
    glBindBuffer(GL_ARRAY_BUFFER, instanceVbo_);
    for (int a = 0; a < 4; ++a) {
      glEnableVertexAttribArray(GLuint(4 + a));
      glVertexAttribPointer(GLuint(4 + a), 4, GL_FLOAT, GL_FALSE, 16 * sizeof(float),
                            reinterpret_cast<void*>(std::size_t(a) * 4 * sizeof(float)));
      glVertexAttribDivisor(GLuint(4 + a), 1);
    }
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, b.mesh->ebo);
    glBindVertexArray(0);
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

// The casters' box and the floor their shadows fall on.
void LightEffects::placeViews(const Eigen::Matrix4d& viewProj, bool fittedOnly) {
  const RenderScene& s = r_.scene_;
  const Eigen::AlignedBox3d& box = s.bounds;
  double floorZ = box.isEmpty() ? 0 : box.min().z();
  for (const Drawable& d : s.drawables)
    if (d.shape == Shape::Ground) floorZ = std::min(floorZ, d.bounds.max().z());
  for (Caster& c : casters_) {
    if (fittedOnly && !c.fitted) continue;
    const RenderLight& l = lights_[c.light];
    double margin = c.pcfRadius + 2;
    c.views.clear();
    if (c.kind == MapKind::Ortho) {
      c.views.push_back(c.fitted ? fitDirectionalShadow(l.direction, viewProj, box, floorZ, c.resolution, margin)
                                 : customDirectionalShadow(l.direction, l.shadowCenter, l.shadowOrthoHalfSize,
                                                           l.shadowNear, l.shadowFar, c.resolution));
      continue;
    }
    // Depth reaches the farthest caster, within the light's reach.
    double farthest = 0;
    if (!box.isEmpty())
      for (int k = 0; k < 8; ++k)
        farthest = std::max(farthest, (box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k)) - l.position).norm());
    double far = std::min(double(reach_[c.light]), farthest);
    double near = std::clamp(far * 0.002, 0.02, 0.5);
    bool nothing = box.isEmpty() || !(far > near * 2);
    if (c.kind == MapKind::Perspective) {
      // The cone, and a few texels more for the filter at its rim.
      double half = std::min(double(l.coneDegrees) + 2 + 45.0 * margin / c.resolution, 89.0);
      c.views.push_back(perspectiveShadow(l.position, l.direction, half, near, far, c.resolution));
    } else {
      double scale = cubeFaceScale(c.resolution, margin);
      // A face whose frustum (up to 54.7 degrees off its axis, at its
      // corners) lies wholly outside the light's cone (a half-space for an
      // area light) is never read: cleared, not drawn.
      double half = l.type == LightType::Area ? 90.0 : l.type == LightType::Spot ? double(l.coneDegrees) : 180.0;
      Eigen::Vector3d axis = l.direction.norm() > 1e-12 ? l.direction.normalized() : Eigen::Vector3d(0, 0, -1);
      for (int face = 0; face < 6; ++face) {
        c.views.push_back(cubeFaceShadow(l.position, face, near, far, scale, c.resolution));
        Eigen::Vector3d f(kCubeForward[face][0], kCubeForward[face][1], kCubeForward[face][2]);
        double off = std::acos(std::clamp(f.dot(axis), -1.0, 1.0)) * 180 / kPi;
        if (off > half + 54.8) c.views.back().empty = true;
      }
    }
    if (nothing)
      for (ShadowView& v : c.views) v.empty = true;
  }
}

void LightEffects::drawMap(const ShadowView& v, const Eigen::Vector2i& origin, int size, const Eigen::AlignedBox3d& reach,
                           bool sensor, bool ortho) {
  glViewport(origin.x(), origin.y(), size, size);
  glScissor(origin.x(), origin.y(), size, size);
  glClear(GL_DEPTH_BUFFER_BIT);
  ++r_.timings_.shadowMapsDrawn;
  if (v.empty) return;
  // Casters between the light and an orthographic box's near face are
  // flattened onto it instead of clipped away.
  if (ortho)
    glEnable(GL_DEPTH_CLAMP);
  else
    glDisable(GL_DEPTH_CLAMP);
  setMat(depthProg_, "uViewProj", v.viewProj);
  for (std::size_t bi = 0; bi < r_.batches_.size(); ++bi) {
    const Batch& b = r_.batches_[bi];
    if (!shadowVaos_[bi]) continue;
    matrices_.clear();
    for (const Instance& in : b.instances) {
      if (sensor && !in.worldObject) continue;
      if (!reach.intersects(in.bounds) || !boxInFrustum(v.viewProj, in.bounds)) continue;
      matrices_.insert(matrices_.end(), in.data, in.data + 16);
    }
    if (matrices_.empty()) continue;
    glBindBuffer(GL_ARRAY_BUFFER, instanceVbo_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(matrices_.size() * sizeof(float)), matrices_.data(), GL_STREAM_DRAW);
    glBindVertexArray(shadowVaos_[bi]);
    glDrawElementsInstanced(GL_TRIANGLES, b.mesh->indexCount, GL_UNSIGNED_INT, nullptr,
                            GLsizei(matrices_.size() / 16));
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

bool LightEffects::prepare(const View& view, const Eigen::Matrix4d& viewProj) {
  if (casters_.empty()) return true;
  const bool sensor = view.sensor && r_.visualCasters_;
  const bool stale = drawnVersion_ != r_.poseVersion_ || drawnForSensor_ != sensor;
  auto t0 = Clock::now();
  // Fitted directional maps follow the view; the others only the poses.
  std::vector<Eigen::Matrix4d> before;
  for (const Caster& c : casters_) before.push_back(c.views.empty() ? Eigen::Matrix4d::Zero() : c.views[0].viewProj);
  placeViews(viewProj, !stale);
  bool drew = false;
  for (std::size_t k = 0; k < casters_.size(); ++k) {
    Caster& c = casters_[k];
    if (!stale && (!c.fitted || c.views[0].viewProj == before[k])) continue;
    if (!drew) {
      glBindFramebuffer(GL_FRAMEBUFFER, atlasFbo_);
      glUseProgram(depthProg_);
      glEnable(GL_SCISSOR_TEST);
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_LESS);
      glDepthMask(GL_TRUE);
      glDisable(GL_CULL_FACE);
      glDisable(GL_BLEND);
      glDisable(GL_STENCIL_TEST);
      // Slope-scaled offset against acne on surfaces seen edge-on by the light.
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(1.5f, 1.0f);
      drew = true;
    }
    for (std::size_t f = 0; f < c.views.size(); ++f) {
      Eigen::Vector2i origin = c.origin;
      if (c.kind == MapKind::Cube) origin += Eigen::Vector2i(int(f % 3) * c.resolution, int(f / 3) * c.resolution);
      drawMap(c.views[f], origin, c.resolution, c.reachBox, sensor, c.kind == MapKind::Ortho);
    }
  }
  drawnVersion_ = r_.poseVersion_;
  drawnForSensor_ = sensor;
  if (drew) {
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_DEPTH_CLAMP);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glFinish();  // the time is the shadow passes', not the next pass's
    r_.timings_.shadowSeconds += std::chrono::duration<double>(Clock::now() - t0).count();
  }
  return true;
}

// Per light (shader_lights.cpp reads the same):
//   0  position, type + 4 when it has a shadow map
//   1  unit direction of travel, cos(outer cone)
//   2  color x intensity, cos(inner cone)
//   3  attenuation constant, linear, quadratic, reach
//   4  shadow strength, bias (m), filter radius (texels), texel size (m; perspective: per m)
//   5  map origin in the atlas (uv), map side (uv; a cube: one face's), kind (1 ortho, 2 perspective, 3 cube)
//   6  near, far (m along the light), cube face scale
//   7..10  rows of the map's clip matrix
//   11, 12  an area light's half width and half height vectors
void LightEffects::writeLightBuffer() {
  texels_.assign(lights_.size() * kLightTexels * 4, 0.f);
  constexpr float kDeg = float(kPi / 180);
  for (std::size_t i = 0; i < lights_.size(); ++i) {
    const RenderLight& l = lights_[i];
    float* t = texels_.data() + i * kLightTexels * 4;
    Eigen::Vector3f d = l.direction.norm() > 1e-12 ? l.direction.normalized().cast<float>() : Eigen::Vector3f(0, 0, -1);
    const Caster* c = casterOf_[i] >= 0 ? &casters_[std::size_t(casterOf_[i])] : nullptr;
    if (c && (c->views.empty() || std::all_of(c->views.begin(), c->views.end(), [](const ShadowView& v) { return v.empty; })))
      c = nullptr;
    float v0[4] = {float(l.position.x()), float(l.position.y()), float(l.position.z()), float(int(l.type) + (c ? 4 : 0))};
    float v1[4] = {d.x(), d.y(), d.z(), std::cos(l.coneDegrees * kDeg)};
    float v2[4] = {l.color.x(), l.color.y(), l.color.z(),
                   std::cos(std::min(l.innerConeDegrees, l.coneDegrees - 0.01f) * kDeg)};
    float v3[4] = {l.attenuation.x(), l.attenuation.y(), l.attenuation.z(),
                   l.type == LightType::Directional ? 0.f : reach_[i]};
    std::copy_n(v0, 4, t);
    std::copy_n(v1, 4, t + 4);
    std::copy_n(v2, 4, t + 8);
    std::copy_n(v3, 4, t + 12);
    if (l.type == LightType::Area) {
      Eigen::Vector3d halfRight, halfUp;
      areaAxes(l, halfRight, halfUp);
      for (int k = 0; k < 3; ++k) {
        t[44 + k] = float(halfRight[k]);
        t[48 + k] = float(halfUp[k]);
      }
    }
    if (!c) continue;
    const ShadowView& v = c->views[0];
    const float side = float(atlasSide_);
    float range = float(v.farPlane - v.nearPlane);
    float v4[4] = {c->strength, std::min(c->bias * range, 0.1f), c->pcfRadius, float(v.texelWorld)};
    float v5[4] = {float(c->origin.x()) / side, float(c->origin.y()) / side, float(c->resolution) / side,
                   float(int(c->kind))};
    float scale = c->kind == MapKind::Cube ? float(cubeFaceScale(c->resolution, c->pcfRadius + 2)) : 0.f;
    float v6[4] = {float(v.nearPlane), float(v.farPlane), scale, 0};
    std::copy_n(v4, 4, t + 16);
    std::copy_n(v5, 4, t + 20);
    std::copy_n(v6, 4, t + 24);
    for (int row = 0; row < 4; ++row)
      for (int col = 0; col < 4; ++col) t[28 + row * 4 + col] = float(v.viewProj(row, col));
  }
}

void LightEffects::bind(GLuint program, const View& view, const Eigen::Matrix4d& viewProj) {
  writeLightBuffer();
  glBindBuffer(GL_TEXTURE_BUFFER, lightBuffer_);
  glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(std::max<std::size_t>(texels_.size(), 4) * sizeof(float)),
               texels_.empty() ? nullptr : texels_.data(), GL_DYNAMIC_DRAW);
  // Larger tiles when the lists would pass 16 Mi entries (64 MiB): thousands
  // of lights over a large image stay bounded; one tile at the last.
  int tile = kLightTileSize;
  while (!buildLightGrid(localBounds_, localIndices_, viewProj, view.camera.width, view.camera.height, tile, grid_,
                         tile >= 16384 ? std::size_t(-1) : std::size_t{1} << 24, firstShadowed_))
    tile *= 2;
  glBindBuffer(GL_TEXTURE_BUFFER, gridBuffer_);
  glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(grid_.data.size() * sizeof(std::int32_t)), grid_.data.data(),
               GL_DYNAMIC_DRAW);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  auto loc = [&](const char* name) { return glGetUniformLocation(program, name); };
  int head = std::min(directionalCount_, kHeadLights);
  glUniform1i(loc("uHeadCount"), head);
  if (head > 0) glUniform4fv(loc("uLightHead"), head * kLightTexels, texels_.data());
  glUniform1i(loc("uDirectionalCount"), directionalCount_);
  glUniform1i(loc("uHasLocalLights"), !localIndices_.empty());
  glUniform1i(loc("uTileSize"), grid_.tileSize);
  glUniform1i(loc("uTilesX"), grid_.tilesX);
  glUniform1i(loc("uTilesY"), grid_.tilesY);
  glUniform1f(loc("uAtlasTexel"), 1.0f / float(atlasSide_));
  glUniform1i(loc("uShadowAtlas"), units::kShadow);
  glUniform1i(loc("uLights"), units::kLights);
  glUniform1i(loc("uLightGrid"), units::kLights + 1);
  glActiveTexture(GL_TEXTURE0 + units::kShadow);
  glBindTexture(GL_TEXTURE_2D, atlasTex_);
  glActiveTexture(GL_TEXTURE0 + units::kLights);
  glBindTexture(GL_TEXTURE_BUFFER, lightTex_);
  glActiveTexture(GL_TEXTURE0 + units::kLights + 1);
  glBindTexture(GL_TEXTURE_BUFFER, gridTex_);
  glActiveTexture(GL_TEXTURE0);
}

}  // namespace rscene::render::detail

namespace rscene::render::detail {

void LightEffects::configure(const RenderScene& scene, std::string& source) {
  int directional = 0;
  bool local = false;
  for (const RenderLight& l : scene.lights) {
    if (l.type == LightType::Directional)
      ++directional;
    else
      local = true;
  }
  std::string defines;
  if (local) defines += "#define RSCENE_LOCAL_LIGHTS\n";
  if (directional > kHeadLights) defines += "#define RSCENE_MANY_SUNS\n";
  std::size_t afterVersion = source.find('\n');  // #version comes first
  source.insert(afterVersion == std::string::npos ? source.size() : afterVersion + 1, defines);
}

}  // namespace rscene::render::detail
