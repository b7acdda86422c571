// Setting a program's uniforms by name (internal to lib/render): the few
// helpers every pass and module uses, in one place.
#pragma once
#include <GL/glcorearb.h>

#include <Eigen/Core>

namespace rscene::render::detail {

inline GLint loc(GLuint program, const char* name) { return glGetUniformLocation(program, name); }

inline void setMat(GLuint program, const char* name, const Eigen::Matrix4d& m) {
  Eigen::Matrix4f f = m.cast<float>();
  glUniformMatrix4fv(loc(program, name), 1, GL_FALSE, f.data());
}

inline void setVec3(GLuint program, const char* name, const Eigen::Vector3f& v) {
  glUniform3f(loc(program, name), v.x(), v.y(), v.z());
}

}  // namespace rscene::render::detail
