// VolumeEffects (gl_effects.hpp): projected decals, irradiance volumes and
// fog on the surface program, fog on the post pass's background (GLSL and
// the buffer layout: shader_volumes.cpp).
#include <algorithm>
#include <cmath>
#include <map>

#include "core/codes.hpp"
#include "core/assets.hpp"
#include "render/camera.hpp"
#include "render/gl_effects.hpp"
#include "render/gl_renderer.hpp"
#include "render/mipmap.hpp"

namespace rscene::render::detail {

// Most records of one kind (decals, irradiance volumes, fog spheres) a view
// draws: the nearest to the eye (RS9055 names how many were left out).
constexpr std::size_t kMaxInView = 1024;
namespace {

constexpr int kDecalTexels = 8, kIrradianceTexels = 5, kFogTexels = 3;
// Decal texture layers share one size: the largest image's (a power of
// two), at most this, halved until all layers fit the memory budget.
constexpr int kMaxDecalSide = 1024;
constexpr std::size_t kDecalTextureBytes = std::size_t{256} << 20;

float linear(float c) { return std::pow(std::max(c, 0.f), 2.2f); }
Eigen::Vector3f linear(const Eigen::Vector3f& c) { return {linear(c.x()), linear(c.y()), linear(c.z())}; }

void put(std::vector<float>& d, float a, float b, float c, float e) { d.insert(d.end(), {a, b, c, e}); }
void put(std::vector<float>& d, const Eigen::Vector3f& v, float w) { put(d, v.x(), v.y(), v.z(), w); }

// The three rows of world -> unit cube.
void putRows(std::vector<float>& d, const Eigen::Affine3d& world) {
  Eigen::Matrix4f m = world.inverse(Eigen::Affine).matrix().cast<float>();
  for (int r = 0; r < 3; ++r) put(d, m(r, 0), m(r, 1), m(r, 2), m(r, 3));
}

// `img` resampled (bilinear, wrapping: decals may tile) to side x side.
std::vector<std::uint8_t> resample(const Image& img, int side) {
  std::vector<std::uint8_t> out(std::size_t(side) * side * 4);
  if (img.width == side && img.height == side) {
    std::copy_n(img.rgba.begin(), out.size(), out.begin());
    return out;
  }
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      double u = (x + 0.5) * img.width / side - 0.5, v = (y + 0.5) * img.height / side - 0.5;
      int x0 = int(std::floor(u)), y0 = int(std::floor(v));
      double fx = u - x0, fy = v - y0;
      auto at = [&](int i, int j, int c) {
        i = (i % img.width + img.width) % img.width;
        j = (j % img.height + img.height) % img.height;
        return double(img.rgba[(std::size_t(j) * img.width + i) * 4 + c]);
      };
      for (int c = 0; c < 4; ++c) {
        double top = at(x0, y0, c) * (1 - fx) + at(x0 + 1, y0, c) * fx;
        double bottom = at(x0, y0 + 1, c) * (1 - fx) + at(x0 + 1, y0 + 1, c) * fx;
        out[(std::size_t(y) * side + x) * 4 + c] = std::uint8_t(std::lround(top * (1 - fy) + bottom * fy));
      }
    }
  return out;
}

}  // namespace

VolumeEffects::~VolumeEffects() {
  if (bufferTexture_) glDeleteTextures(1, &bufferTexture_);
  if (decalTextures_) glDeleteTextures(1, &decalTextures_);
  if (buffer_) glDeleteBuffers(1, &buffer_);
}

// Each distinct texture file one layer, read once through the renderer's
// asset cache.  A missing file is RS5001 (an error unless
// --allow-missing-assets: then that slot is not drawn); one that does not
// decode is RS9002, a warning, as a material's texture.
bool VolumeEffects::uploadDecalTextures() {
  const auto& decals = r_.scene_.decals;
  decalLayers_.assign(decals.size(), {-1.f, -1.f, -1.f, -1.f});
  std::map<std::string, int> layerOf;
  std::vector<std::shared_ptr<const Image>> images;
  GLint maxLayers = 256;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  for (std::size_t i = 0; i < decals.size(); ++i) {
    const RenderDecal& d = decals[i];
    const std::string* paths[4] = {&d.albedoTexture, &d.emissionTexture, &d.normalTexture, &d.ormTexture};
    for (int slot = 0; slot < 4; ++slot) {
      const std::string& path = *paths[slot];
      if (path.empty()) continue;
      auto found = layerOf.find(path);
      if (found != layerOf.end()) {
        decalLayers_[i][std::size_t(slot)] = float(found->second);
        continue;
      }
      layerOf[path] = -1;
      std::uint32_t column = d.textureColumns[std::size_t(slot)];
      if (!r_.regularFile(path)) {
        if (!r_.assetProblem(d.line, column, {}, "decal texture file '" + path + "' " + whyNotAFile(path),
                             scene_code::kMissingFile))
          return false;
        continue;
      }
      std::string err;
      std::shared_ptr<const Image> image = r_.assets_.image(path, &err);
      if (!image || image->width <= 0 || image->height <= 0) {
        r_.diag(Severity::Warning, rs::RS9002, d.line, "decal texture " + path + " is not drawn: " + err, column);
        continue;
      }
      if (int(images.size()) >= maxLayers) {
        r_.diag(Severity::Warning, rs::RS9055, d.line,
                "decal texture " + path + " is not drawn: more than " + std::to_string(maxLayers) +
                    " distinct decal textures",
                column);
        continue;
      }
      layerOf[path] = int(images.size());
      decalLayers_[i][std::size_t(slot)] = float(images.size());
      images.push_back(std::move(image));
    }
  }
  if (images.empty()) return true;
  int side = 16;
  for (const auto& img : images)
    while (side < kMaxDecalSide && (side < img->width || side < img->height)) side *= 2;
  // Four thirds: the mipmaps.
  while (side > 16 && images.size() * std::size_t(side) * side * 4 * 4 / 3 > kDecalTextureBytes) side /= 2;
  int levels = 1;
  while ((side >> (levels - 1)) > 1) ++levels;
  glGenTextures(1, &decalTextures_);
  glActiveTexture(GL_TEXTURE0 + units::kVolumes + 1);
  glBindTexture(GL_TEXTURE_2D_ARRAY, decalTextures_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (int l = 0; l < levels; ++l)
    glTexImage3D(GL_TEXTURE_2D_ARRAY, l, GL_RGBA8, std::max(side >> l, 1), std::max(side >> l, 1),
                 GLsizei(images.size()), 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  // Mipmaps on the CPU: llvmpipe's glGenerateMipmap costs more (mipmap.hpp).
  std::vector<std::uint8_t> level, next;
  for (std::size_t layer = 0; layer < images.size(); ++layer) {
    level = resample(*images[layer], side);
    int s = side;
    for (int l = 0; l < levels; ++l) {
      glTexSubImage3D(GL_TEXTURE_2D_ARRAY, l, 0, 0, GLint(layer), s, s, 1, GL_RGBA, GL_UNSIGNED_BYTE, level.data());
      if (s == 1) break;
      halveImage(level.data(), s, s, next);
      level.swap(next);
      s = std::max(s / 2, 1);
    }
  }
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_REPEAT);
  glActiveTexture(GL_TEXTURE0);
  return true;
}

void VolumeEffects::configure(const RenderScene& scene, std::string& source) {
  std::string defines;
  if (!scene.decals.empty()) defines += "#define RSCENE_DECALS\n";
  // Each texture slot a decal uses: four textureGrad calls cost llvmpipe
  // at every fragment whether a decal holds it or not.
  bool slots[4] = {false, false, false, false};
  for (const RenderDecal& d : scene.decals) {
    slots[0] = slots[0] || !d.albedoTexture.empty();
    slots[1] = slots[1] || !d.emissionTexture.empty();
    slots[2] = slots[2] || !d.normalTexture.empty();
    slots[3] = slots[3] || !d.ormTexture.empty();
  }
  const char* names[4] = {"ALBEDO", "EMISSION", "NORMAL", "ORM"};
  for (int i = 0; i < 4; ++i)
    if (slots[i]) defines += std::string("#define RSCENE_DECAL_") + names[i] + "\n";
  if (!scene.irradianceVolumes.empty()) defines += "#define RSCENE_IRRADIANCE\n";
  if (!scene.fogs.empty()) defines += "#define RSCENE_FOG_SPHERES\n";
  for (const RenderFog& f : scene.fogs)
    if (f.noiseStrength > 0 && f.noiseScale > 0) {
      defines += "#define RSCENE_FOG_NOISE\n";
      break;
    }
  if (scene.environment.heightFog) defines += "#define RSCENE_HEIGHT_FOG\n";
  std::size_t afterVersion = source.find('\n');  // #version comes first
  source.insert(afterVersion == std::string::npos ? source.size() : afterVersion + 1, defines);
}

bool VolumeEffects::upload() {
  if (!uploadDecalTextures()) return false;
  glGenBuffers(1, &buffer_);
  glBindBuffer(GL_TEXTURE_BUFFER, buffer_);
  const float none[4] = {0, 0, 0, 0};
  glBufferData(GL_TEXTURE_BUFFER, sizeof none, none, GL_DYNAMIC_DRAW);
  glGenTextures(1, &bufferTexture_);
  glBindTexture(GL_TEXTURE_BUFFER, bufferTexture_);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, buffer_);
  glBindTexture(GL_TEXTURE_BUFFER, 0);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  // Samplers of different types may not share a unit, and the samplers'
  // default unit 0 is the shadow map's: set them now, before any draw (a
  // reflection probe's capture may draw before the first view's bind()).
  for (GLuint p : {r_.surfaceProg_, r_.postProg_}) {
    glUseProgram(p);
    glUniform1i(glGetUniformLocation(p, "uVolumeData"), units::kVolumes);
    glUniform1i(glGetUniformLocation(p, "uDecalTextures"), units::kVolumes + 1);
  }
  glUseProgram(0);
  return true;
}

void VolumeEffects::bind(GLuint program, const View& view) {
  const RenderScene& scene = r_.scene_;
  const Look& env = scene.environment;
  Eigen::Matrix4d viewProj = viewProjection(view);
  Eigen::Vector3d eye = view.camera.world.position;
  data_.clear();
  decals_ = irradiance_ = fogs_ = 0;
  // Only what may touch a visible surface: the records inside the frustum,
  // at most kMaxInView of each kind, the nearest to the eye (every fragment
  // loops over the list: tens of thousands would cost minutes, and the
  // renderer's buffers have limits of their own).
  std::vector<std::pair<double, std::size_t>> chosen;
  auto choose = [&](const char* kind, std::size_t count, auto&& inView, auto&& distance) {
    chosen.clear();
    for (std::size_t i = 0; i < count; ++i)
      if (inView(i)) chosen.emplace_back(distance(i), i);
    if (chosen.size() > kMaxInView) {
      std::nth_element(chosen.begin(), chosen.begin() + kMaxInView, chosen.end());
      if (!warnedOverflow_)
        r_.diag(Severity::Warning, rs::RS9055, 0,
                std::to_string(chosen.size()) + " " + kind + " in view: the " + std::to_string(kMaxInView) +
                    " nearest the camera are drawn");
      warnedOverflow_ = true;
      chosen.resize(kMaxInView);
    }
    std::sort(chosen.begin(), chosen.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  };
  std::vector<float> decalAlpha(scene.decals.size(), 0.f);
  choose(
      "decals", scene.decals.size(),
      [&](std::size_t i) {
        const RenderDecal& d = scene.decals[i];
        float alpha = d.color.w();
        if (d.fadeLength > 0) {
          double distance = (d.world.translation() - eye).norm();
          alpha *= 1 - std::clamp(float(distance - d.fadeBegin) / d.fadeLength, 0.f, 1.f);
        }
        decalAlpha[i] = alpha;
        return alpha > 0 && boxInFrustum(viewProj, d.bounds);
      },
      [&](std::size_t i) { return scene.decals[i].bounds.exteriorDistance(eye); });
  for (auto [distance, i] : chosen) {
    const RenderDecal& d = scene.decals[i];
    putRows(data_, d.world);
    put(data_, linear(Eigen::Vector3f(d.color.head<3>())), decalAlpha[i]);
    const auto& layers = decalLayers_[i];
    put(data_, layers[0], layers[1], layers[2], layers[3]);
    put(data_, d.uvScale.x(), d.uvScale.y(), d.uvOffset.x(), d.uvOffset.y());
    put(data_, d.albedoMix, d.emissionEnergy, d.normalStrength, d.ormStrength);
    put(data_, d.edgeFade, d.normalFade, d.upperFade, d.lowerFade);
    ++decals_;
  }
  irradianceBase_ = int(data_.size() / 4);
  choose(
      "irradiance volumes", scene.irradianceVolumes.size(),
      [&](std::size_t i) { return boxInFrustum(viewProj, scene.irradianceVolumes[i].bounds); },
      [&](std::size_t i) { return scene.irradianceVolumes[i].bounds.exteriorDistance(eye); });
  for (auto [distance, i] : chosen) {
    const RenderIrradiance& v = scene.irradianceVolumes[i];
    putRows(data_, v.world);
    put(data_, v.color, v.edgeFade);
    Eigen::Vector3f half = v.world.linear().colwise().norm().transpose().cast<float>();
    put(data_, half, v.normalBias);
    ++irradiance_;
  }
  fogBase_ = int(data_.size() / 4);
  auto fogBox = [&](std::size_t i) {
    const RenderFog& f = scene.fogs[i];
    return Eigen::AlignedBox3d(f.center.array() - f.radius, f.center.array() + f.radius);
  };
  choose(
      "fog spheres", scene.fogs.size(), [&](std::size_t i) { return boxInFrustum(viewProj, fogBox(i)); },
      [&](std::size_t i) { return fogBox(i).exteriorDistance(eye); });
  for (auto [distance, i] : chosen) {
    const RenderFog& f = scene.fogs[i];
    Eigen::Vector3d fromCentre = eye - f.center;
    put(data_, fromCentre.cast<float>(), float(fromCentre.squaredNorm() - double(f.radius) * f.radius));
    put(data_, f.color, f.density);
    float inner = f.radius * (1 - f.edgeFade);
    put(data_, f.radius * f.radius - inner * inner, f.noiseScale, f.noiseStrength, 0);
    ++fogs_;
  }
  GLint maxTexels = 65536;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  if (data_.size() / 4 > std::size_t(maxTexels)) {
    // Not reached in practice (llvmpipe takes 2^27 texels, 8 a decal):
    // the view draws none of them rather than part of a list.
    if (!warnedOverflow_)
      r_.diag(Severity::Warning, rs::RS9055, 0,
              "decals, fog spheres and irradiance volumes in view need " + std::to_string(data_.size() / 4) +
                  " texels, more than this OpenGL's " + std::to_string(maxTexels) + ": none is drawn");
    warnedOverflow_ = true;
    data_.clear();
    decals_ = irradiance_ = fogs_ = 0;
  }
  if (data_.empty()) put(data_, 0, 0, 0, 0);
  glBindBuffer(GL_TEXTURE_BUFFER, buffer_);
  glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(data_.size() * sizeof(float)), data_.data(), GL_DYNAMIC_DRAW);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  glActiveTexture(GL_TEXTURE0 + units::kVolumes);
  glBindTexture(GL_TEXTURE_BUFFER, bufferTexture_);
  glActiveTexture(GL_TEXTURE0 + units::kVolumes + 1);
  glBindTexture(GL_TEXTURE_2D_ARRAY, decalTextures_);
  glActiveTexture(GL_TEXTURE0);

  auto loc = [&](const char* name) { return glGetUniformLocation(program, name); };
  glUniform1i(loc("uVolumeData"), units::kVolumes);
  glUniform1i(loc("uDecalTextures"), units::kVolumes + 1);
  glUniform1i(loc("uDecalCount"), decals_);
  glUniform1i(loc("uIrradianceCount"), irradiance_);
  glUniform1i(loc("uIrradianceBase"), irradianceBase_);
  glUniform1i(loc("uFogCount"), fogs_);
  glUniform1i(loc("uFogBase"), fogBase_);
  glUniform1f(loc("uFogDensity"), env.fogDensity);
  Eigen::Vector3f fogLinear = linear(env.fogColor);
  glUniform3f(loc("uFogColorLinear"), fogLinear.x(), fogLinear.y(), fogLinear.z());
  glUniform3f(loc("uFogEye"), float(eye.x()), float(eye.y()), float(eye.z()));
  glUniform4f(loc("uHeightFog"), env.heightFogDensity, env.heightFogBase, env.heightFogFalloff,
              env.heightFog ? 1.f : 0.f);
  glUniform3f(loc("uHeightFogColor"), fogLinear.x(), fogLinear.y(), fogLinear.z());
}

void VolumeEffects::bindBackground(GLuint program, const View& view) {
  const Look& env = r_.scene_.environment;
  auto loc = [&](const char* name) { return glGetUniformLocation(program, name); };
  // The buffer texture bind() filled is still on its unit.
  glUniform1i(loc("uVolumeData"), units::kVolumes);
  glUniform1i(loc("uFogCount"), fogs_);
  glUniform1i(loc("uFogBase"), fogBase_);
  glUniform4f(loc("uHeightFog"), env.heightFogDensity, env.heightFogBase, env.heightFogFalloff,
              env.heightFog ? 1.f : 0.f);
  Eigen::Vector3f fogLinear = linear(env.fogColor);
  glUniform3f(loc("uHeightFogColor"), fogLinear.x(), fogLinear.y(), fogLinear.z());
  Eigen::Vector3f eye = view.camera.world.position.cast<float>();
  glUniform3f(loc("uFogEye"), eye.x(), eye.y(), eye.z());
}

}  // namespace rscene::render::detail
