// The lit pass's modules (internal to lib/render, beside gl_renderer.hpp):
// each uploads what it needs once, after the scene (GlRenderer::upload),
// and binds its uniforms and textures on the surface program before each
// lit pass (colorPass).  Their GLSL is in shader_volumes.cpp and
// shader_reflections.cpp.  They are friends of GlRenderer: they read its
// scene, options and diagnostics, and may draw its batches (a reflection
// probe's capture).
#pragma once
#include <GL/glcorearb.h>

#include "render/view.hpp"

namespace rscene::render::detail {

class GlRenderer;

// Texture units of the surface program (GL 3.3 guarantees 16).
namespace units {
inline constexpr int kShadow = 0;       // the main light's shadow map
inline constexpr int kAlbedo = 1;       // the batch's albedo texture
inline constexpr int kLights = 2;       // 2..7: more shadow maps
inline constexpr int kVolumes = 8;      // 8..11: decal textures
inline constexpr int kReflections = 12;  // 12..15: environment, probes, BRDF table
}  // namespace units

// Projected decals, irradiance volumes and fog (global, height, local).
class VolumeEffects {
 public:
  explicit VolumeEffects(GlRenderer& r) : r_(r) {}
  ~VolumeEffects();
  VolumeEffects(const VolumeEffects&) = delete;
  VolumeEffects& operator=(const VolumeEffects&) = delete;
  bool upload();  // false with an error diagnostic
  void bind(GLuint program, const View& view);

 private:
  GlRenderer& r_;
};

// Ambient and sky light, environment reflections, reflection probes.
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

 private:
  GlRenderer& r_;
};

}  // namespace rscene::render::detail
