// VolumeEffects (gl_effects.hpp): projected decals, irradiance volumes and
// fog on the surface program (GLSL: shader_volumes.cpp).
#include "render/gl_effects.hpp"
#include "render/gl_renderer.hpp"

namespace rscene::render::detail {

VolumeEffects::~VolumeEffects() = default;

bool VolumeEffects::upload() { return true; }

void VolumeEffects::bind(GLuint program, const View&) {
  const Look& env = r_.scene_.environment;
  glUniform1f(glGetUniformLocation(program, "uFogDensity"), env.fogDensity);
  glUniform3f(glGetUniformLocation(program, "uFogColor"), env.fogColor.x(), env.fogColor.y(), env.fogColor.z());
}

}  // namespace rscene::render::detail
