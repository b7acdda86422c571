// The CPU side of image-based light (gl_reflections.cpp): the directions
// of a cube map's texels, the diffuse irradiance of a cube map as nine
// spherical-harmonic coefficients, the split-sum BRDF table, and the
// shrinking of a large equirectangular HDR before it is resampled into a
// cube.  No GL: unit-tested on their own (tests/render/reflections_test.cpp).
#pragma once
#include <Eigen/Core>
#include <array>
#include <vector>

#include "render/image.hpp"

namespace rscene::render {

// The direction (not normalised) a texel of cube face `face` (GL order:
// +x, -x, +y, -y, +z, -z) looks along, for u, v in [-1, 1] the texel's
// position along the face's s and t axes (t = 0 is the first row GL
// stores and glGetTexImage returns).  The inverse of GL's face selection
// (OpenGL 4.6 table 8.19), so a cube map sampled along this direction
// returns that texel.  GLSL copy: cubeDirection() in shader_reflections.cpp.
Eigen::Vector3f cubeFaceDirection(int face, float u, float v);

// Light arriving at a surface of normal n from a cube map, divided by pi
// (the radiance a white Lambertian surface reflects): the order-2
// spherical-harmonic projection with the cosine lobe folded in
// (Ramamoorthi and Hanrahan 2001), error under 3% for smooth skies.
struct IrradianceSh {
  std::array<Eigen::Vector3f, 9> c{};  // basis order: 1, y, z, x, xy, yz, 3z^2-1, xz, x^2-y^2
  Eigen::Vector3f operator()(const Eigen::Vector3f& n) const;  // n unit
};

// `rgba`: six faces of size x size RGBA floats in GL order, rows as
// glGetTexImage returns them.  Each texel weighs by its solid angle.
IrradianceSh irradianceFromCube(const std::vector<float>& rgba, int size);

// The split-sum BRDF table of GGX with Smith-Schlick visibility (Karis
// 2013): for n.v = (i + 0.5) / size and perceptual roughness
// (j + 0.5) / size, at [2 * (j * size + i)], the scale A and bias B of
// the specular reflectance f0 * A + B.  `samples` importance samples per
// texel (Hammersley).
std::vector<float> splitSumLut(int size, int samples);
// The table the renderer uses (64 x 64, 256 samples): computed once per
// process, about 20 ms, and kept.
inline constexpr int kBrdfLutSize = 64;
const std::vector<float>& brdfLut();

// `image` box-filtered by the smallest power of two that brings its width
// to at most maxWidth (itself when it already is): a 4096-wide HDR
// resampled into a 128-texel cube face would otherwise alias, and
// glGenerateMipmap on llvmpipe is slow (mipmap.hpp).
FloatImage shrinkEquirect(const FloatImage& image, int maxWidth);

}  // namespace rscene::render
