// ReflectionEffects (gl_effects.hpp): ambient and sky light, environment
// reflections and reflection probes on the surface program (GLSL:
// shader_reflections.cpp).
#include <algorithm>

#include "render/gl_effects.hpp"
#include "render/gl_renderer.hpp"

namespace rscene::render::detail {

ReflectionEffects::~ReflectionEffects() = default;

bool ReflectionEffects::upload() { return true; }

bool ReflectionEffects::prepare(const View&) { return true; }

void ReflectionEffects::bind(GLuint program, const View&) {
  const Look& env = r_.scene_.environment;
  glUniform3f(glGetUniformLocation(program, "uAmbient"), env.ambient.x(), env.ambient.y(), env.ambient.z());
  float day = env.night ? 0.02f : float(std::clamp((env.sunDirection.z() + 0.15) / 0.35, 0.0, 1.0));
  Eigen::Vector3f sky = env.mode == Background::PlainColor ? Eigen::Vector3f(Eigen::Vector3f::Zero())
                                                           : Eigen::Vector3f(Eigen::Vector3f(0.16f, 0.20f, 0.28f) * day);
  glUniform3f(glGetUniformLocation(program, "uSkyAmbient"), sky.x(), sky.y(), sky.z());
}

}  // namespace rscene::render::detail
