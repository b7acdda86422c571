// The lit pass's modules (internal to lib/render, beside gl_renderer.hpp):
// each uploads what it needs once, after the scene (GlRenderer::upload),
// and binds its uniforms and textures on the surface program before each
// lit pass (colorPass).  Their GLSL is in shader_volumes.cpp and
// shader_reflections.cpp.  They are friends of GlRenderer: they read its
// scene, options and diagnostics, and may draw its batches (a reflection
// probe's capture).
#pragma once
#include <GL/glcorearb.h>

#include <array>
#include <string>
#include <vector>

#include "render/render_scene.hpp"
#include "render/view.hpp"

namespace rscene::render::detail {

class GlRenderer;

// Texture units of the surface program (GL 3.3 guarantees 16).
namespace units {
inline constexpr int kShadow = 0;       // the main light's shadow map
inline constexpr int kAlbedo = 1;       // the batch's albedo texture
inline constexpr int kLights = 2;       // 2..7: more shadow maps
inline constexpr int kVolumes = 8;      // 8: volume records (buffer), 9: decal textures, 10..11 free
inline constexpr int kReflections = 12;  // 12..15: environment, probes, BRDF table
}  // namespace units

// Projected decals, irradiance volumes and fog (global, height, local).
// upload() reads the decals' textures into one texture array (unit
// kVolumes + 1); bind() gathers the records inside the view's frustum into
// one buffer texture (unit kVolumes) the surface shader loops over, so the
// cost per pixel grows with what the view holds and is nil without any.
class VolumeEffects {
 public:
  explicit VolumeEffects(GlRenderer& r) : r_(r) {}
  ~VolumeEffects();
  VolumeEffects(const VolumeEffects&) = delete;
  VolumeEffects& operator=(const VolumeEffects&) = delete;
  // Switches on, in a fragment program's source (the surface's or the
  // post pass's), the code of the record kinds `scene` has: the rest is
  // left out, as llvmpipe would pay for it at every fragment.
  static void configure(const RenderScene& scene, std::string& fragmentSource);
  bool upload();  // false with an error diagnostic (a missing decal texture)
  void bind(GLuint program, const View& view);
  // The post pass (`program`, in use): the sky behind height fog and fog
  // spheres, from the records the last bind() gathered.
  void bindBackground(GLuint program, const View& view);

 private:
  bool uploadDecalTextures();
  GlRenderer& r_;
  GLuint buffer_ = 0, bufferTexture_ = 0, decalTextures_ = 0;
  std::vector<std::array<float, 4>> decalLayers_;  // per RenderScene::decals: albedo, emission, normal, orm; -1 none
  std::vector<float> data_;                       // this view's texels (RGBA32F)
  int decals_ = 0, irradiance_ = 0, fogs_ = 0, irradianceBase_ = 0, fogBase_ = 0;
  bool warnedOverflow_ = false;
};

// Ambient light, the environment's image-based light and reflection
// probes (GLSL: shader_reflections.cpp; the CPU half: environment_light.hpp).
// upload() builds, once per renderer, the environment's prefiltered
// radiance cube, its irradiance (spherical harmonics) and binds the BRDF
// table; prepare() captures the reflection probes on the first colour
// pass (static captures, as rayrai's: poses that change later do not
// recapture them).  Units: units::kReflections + 0 the environment, + 1
// the BRDF table, + 2 the probes' cube map array.
class ReflectionEffects {
 public:
  explicit ReflectionEffects(GlRenderer& r) : r_(r) {}
  ~ReflectionEffects();
  ReflectionEffects(const ReflectionEffects&) = delete;
  ReflectionEffects& operator=(const ReflectionEffects&) = delete;
  bool upload();  // false with an error diagnostic
  // Before a view's lit pass, outside it (a probe's capture draws the
  // scene into its own targets): false with an error diagnostic.
  bool prepare(const View& view);
  void bind(GLuint program, const View& view);
  // Within a probe's capture: its faces draw the lit layers only (the
  // view's shadow maps, no post-processing, no read-back).
  bool capturing() const { return capturing_; }

  static constexpr int kMaxProbes = 8;  // the surface program's uniform arrays

 private:
  bool buildPrograms();
  void uploadHdr();
  // Draws the background (plain colour, HDR, sky) x scale into face
  // `face` of `cube` (level 0, `size` texels); with `scene`, the probe
  // camera's resolved image whose clip matrix is faceViewProj over it.
  void drawBackgroundFace(GLuint cube, int face, int size, float scale, GLuint scene = 0,
                          const Eigen::Matrix4d& faceViewProj = Eigen::Matrix4d::Identity(),
                          const Eigen::Vector3d& probe = Eigen::Vector3d::Zero());
  void downsample(GLuint cube, int size);  // fills levels 1.. of a cube from level 0
  // GGX-prefilters the mipmapped cube `source` into `levels` levels of
  // `target`: a cube map, or layers 6 x layer .. of a cube map array.
  void prefilter(GLuint source, int sourceSize, GLuint target, bool array, int layer, int size, int levels,
                 int samples);
  bool captureProbes();
  bool captureProbe(std::size_t index, int size);

  GlRenderer& r_;
  GLuint backgroundProg_ = 0, prefilterProg_ = 0, fbo_ = 0;
  GLuint hdr_ = 0;          // the HDR background, box-filtered to about a cube texel
  GLuint envSpecular_ = 0;  // prefiltered radiance of the background
  GLuint brdfLut_ = 0;
  GLuint probeCubes_ = 0;   // cube map array: one cube per probe, prefiltered
  int probeLevels_ = 1, probeSize_ = 0, probeSamples_ = 0;
  std::vector<float> sh_;   // 9 x 3 floats of the environment, then 27 per probe
  std::size_t probeCount_ = 0;  // captured (at most kMaxProbes)
  bool probeArrays_ = false, captured_ = false, capturing_ = false;
};

}  // namespace rscene::render::detail
