#include "render/environment_light.hpp"

#include <algorithm>
#include <cmath>

namespace rscene::render {
namespace {

constexpr float kPi = 3.14159265358979f;

// The nine real spherical harmonics of order <= 2 at unit direction n.
std::array<float, 9> shBasis(const Eigen::Vector3f& n) {
  float x = n.x(), y = n.y(), z = n.z();
  return {0.282095f,         0.488603f * y,     0.488603f * z,
          0.488603f * x,     1.092548f * x * y, 1.092548f * y * z,
          0.315392f * (3 * z * z - 1), 1.092548f * x * z, 0.546274f * (x * x - y * y)};
}

float radicalInverse(std::uint32_t bits) {
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return float(bits) * 2.3283064365386963e-10f;
}

}  // namespace

Eigen::Vector3f cubeFaceDirection(int face, float u, float v) {
  switch (face) {
    case 0: return {1, -v, -u};
    case 1: return {-1, -v, u};
    case 2: return {u, 1, v};
    case 3: return {u, -1, -v};
    case 4: return {u, -v, 1};
    default: return {-u, -v, -1};
  }
}

Eigen::Vector3f IrradianceSh::operator()(const Eigen::Vector3f& n) const {
  std::array<float, 9> y = shBasis(n);
  Eigen::Vector3f e = Eigen::Vector3f::Zero();
  for (int i = 0; i < 9; ++i) e += c[std::size_t(i)] * y[std::size_t(i)];
  return e.cwiseMax(0.0f);
}

IrradianceSh irradianceFromCube(const std::vector<float>& rgba, int size) {
  IrradianceSh sh;
  if (size <= 0 || rgba.size() < std::size_t(6) * size * size * 4) return sh;
  std::array<Eigen::Vector3d, 9> sum;
  sum.fill(Eigen::Vector3d::Zero());
  double weight = 0;
  const double texel = 2.0 / size;
  for (int f = 0; f < 6; ++f)
    for (int row = 0; row < size; ++row)
      for (int col = 0; col < size; ++col) {
        float u = float((col + 0.5) * texel - 1), v = float((row + 0.5) * texel - 1);
        Eigen::Vector3f d = cubeFaceDirection(f, u, v);
        double r2 = d.squaredNorm();
        double solidAngle = texel * texel / (r2 * std::sqrt(r2));
        const float* p = &rgba[((std::size_t(f) * size + row) * size + col) * 4];
        Eigen::Vector3d radiance(p[0], p[1], p[2]);
        if (!radiance.allFinite()) continue;
        std::array<float, 9> y = shBasis(d.normalized());
        for (int i = 0; i < 9; ++i) sum[std::size_t(i)] += radiance * (y[std::size_t(i)] * solidAngle);
        weight += solidAngle;
      }
  // The texels' solid angles add up to 4 pi up to the approximation above.
  double norm = weight > 0 ? 4 * kPi / weight : 0;
  const double band[9] = {1, 2.0 / 3, 2.0 / 3, 2.0 / 3, 0.25, 0.25, 0.25, 0.25, 0.25};  // A_l / pi
  for (int i = 0; i < 9; ++i) sh.c[std::size_t(i)] = (sum[std::size_t(i)] * (norm * band[i])).cast<float>();
  return sh;
}

std::vector<float> splitSumLut(int size, int samples) {
  size = std::max(size, 1);
  samples = std::max(samples, 1);
  std::vector<float> lut(std::size_t(size) * size * 2, 0.0f);
  // The sample directions depend on the roughness (a row) and not on n.v:
  // computed once a row.
  const auto n = static_cast<std::size_t>(samples);
  std::vector<float> cosPhi(n), xi(n);
  for (int s = 0; s < samples; ++s) {
    cosPhi[std::size_t(s)] = std::cos(2 * kPi * (s + 0.5f) / samples);
    xi[std::size_t(s)] = radicalInverse(std::uint32_t(s));
  }
  std::vector<float> hx(n), hz(n);
  for (int j = 0; j < size; ++j) {
    float rough = (j + 0.5f) / size;
    float a = rough * rough;
    float k = a / 2;  // Smith-Schlick for image-based light (Karis 2013)
    for (int s = 0; s < samples; ++s) {
      float x = xi[std::size_t(s)];
      float cosTheta = std::sqrt((1 - x) / (1 + (a * a - 1) * x));
      hz[std::size_t(s)] = cosTheta;
      hx[std::size_t(s)] = std::sqrt(std::max(0.0f, 1 - cosTheta * cosTheta)) * cosPhi[std::size_t(s)];
    }
    for (int i = 0; i < size; ++i) {
      float nv = (i + 0.5f) / size;
      float vx = std::sqrt(1 - nv * nv);  // v = (vx, 0, nv): only h's x and z matter
      float sumA = 0, sumB = 0;
      for (int s = 0; s < samples; ++s) {
        float h_x = hx[std::size_t(s)], nh = hz[std::size_t(s)];
        float vh = vx * h_x + nv * nh;
        float nl = 2 * vh * nh - nv;  // l = 2 (v.h) h - v
        if (nl <= 0 || vh <= 0) continue;
        float g = nv / (nv * (1 - k) + k) * nl / (nl * (1 - k) + k);
        float visibility = g * vh / (nh * nv);
        float m = 1 - vh, m2 = m * m;
        float fc = m2 * m2 * m;
        sumA += (1 - fc) * visibility;
        sumB += fc * visibility;
      }
      lut[2 * (std::size_t(j) * size + i)] = sumA / samples;
      lut[2 * (std::size_t(j) * size + i) + 1] = sumB / samples;
    }
  }
  return lut;
}

const std::vector<float>& brdfLut() {
  static const std::vector<float> lut = splitSumLut(kBrdfLutSize, 256);
  return lut;
}

FloatImage shrinkEquirect(const FloatImage& image, int maxWidth) {
  int factor = 1;
  while (image.width / factor > std::max(maxWidth, 1)) factor *= 2;
  if (factor == 1 || image.rgb.size() < std::size_t(image.width) * image.height * 3) return image;
  FloatImage out;
  out.width = std::max(1, image.width / factor);
  out.height = std::max(1, image.height / factor);
  out.rgb.assign(std::size_t(out.width) * out.height * 3, 0.0f);
  // Rows outer, a whole source row at a time: one pass over the source
  // in memory order.
  std::vector<double> acc(std::size_t(out.width) * 3);
  for (int oy = 0; oy < out.height; ++oy) {
    std::fill(acc.begin(), acc.end(), 0.0);
    int y0 = oy * factor, y1 = std::min(image.height, y0 + factor);
    for (int y = y0; y < y1; ++y) {
      const float* row = &image.rgb[std::size_t(y) * image.width * 3];
      for (int x = 0; x < out.width * factor; ++x)
        for (int c = 0; c < 3; ++c) {
          float value = row[std::size_t(x) * 3 + c];
          if (std::isfinite(value)) acc[std::size_t(x / factor) * 3 + c] += value;
        }
    }
    double n = double(y1 - y0) * factor;
    for (std::size_t i = 0; i < acc.size(); ++i)
      out.rgb[std::size_t(oy) * out.width * 3 + i] = float(acc[i] / n);
  }
  return out;
}

}  // namespace rscene::render
