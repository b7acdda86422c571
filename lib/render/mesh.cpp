#include "render/mesh.hpp"

#include <cmath>

namespace rscene::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

void vertex(MeshData& m, double x, double y, double z, double nx, double ny, double nz, double u, double v) {
  m.vertices.insert(m.vertices.end(), {float(x), float(y), float(z), float(nx), float(ny), float(nz), float(u),
                                       float(v)});
}

void quad(MeshData& m, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
}

// A surface of revolution around z: rings of (radius, z, normal r, normal z).
struct Ring {
  double r, z, nr, nz, v;
};

void revolve(MeshData& m, const std::vector<Ring>& rings, int slices) {
  auto base = std::uint32_t(m.vertexCount());
  for (const Ring& ring : rings)
    for (int s = 0; s <= slices; ++s) {
      double a = 2 * kPi * s / slices, c = std::cos(a), sn = std::sin(a);
      vertex(m, ring.r * c, ring.r * sn, ring.z, ring.nr * c, ring.nr * sn, ring.nz, double(s) / slices, ring.v);
    }
  auto row = std::uint32_t(slices + 1);
  for (std::uint32_t k = 0; k + 1 < rings.size(); ++k)
    for (std::uint32_t s = 0; s < std::uint32_t(slices); ++s)
      quad(m, base + k * row + s, base + k * row + s + 1, base + (k + 1) * row + s + 1, base + (k + 1) * row + s);
}

void disk(MeshData& m, double z, double nz, int slices) {
  auto center = std::uint32_t(m.vertexCount());
  vertex(m, 0, 0, z, 0, 0, nz, 0.5, 0.5);
  for (int s = 0; s <= slices; ++s) {
    double a = 2 * kPi * s / slices;
    vertex(m, std::cos(a), std::sin(a), z, 0, 0, nz, 0.5 + 0.5 * std::cos(a), 0.5 + 0.5 * std::sin(a));
  }
  for (std::uint32_t s = 0; s < std::uint32_t(slices); ++s) {
    if (nz > 0) m.indices.insert(m.indices.end(), {center, center + 1 + s, center + 2 + s});
    else m.indices.insert(m.indices.end(), {center, center + 2 + s, center + 1 + s});
  }
}

}  // namespace

MeshData unitBox() {
  MeshData m;
  static const float n[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const auto& f : n) {
    Eigen::Vector3d normal(f[0], f[1], f[2]);
    Eigen::Vector3d u = std::abs(normal.z()) > 0.5 ? Eigen::Vector3d(1, 0, 0) : Eigen::Vector3d(0, 0, 1);
    Eigen::Vector3d t = u.cross(normal), b = normal.cross(t);
    auto base = std::uint32_t(m.vertexCount());
    const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const auto& c : corners) {
      Eigen::Vector3d p = 0.5 * (normal + c[0] * t + c[1] * b);
      vertex(m, p.x(), p.y(), p.z(), normal.x(), normal.y(), normal.z(), (c[0] + 1) / 2, (c[1] + 1) / 2);
    }
    quad(m, base, base + 1, base + 2, base + 3);
  }
  return m;
}

MeshData unitSphere(int slices, int stacks) {
  std::vector<Ring> rings;
  for (int k = 0; k <= stacks; ++k) {
    double phi = kPi * k / stacks - kPi / 2;
    rings.push_back({std::cos(phi), std::sin(phi), std::cos(phi), std::sin(phi), double(k) / stacks});
  }
  MeshData m;
  revolve(m, rings, slices);
  return m;
}

MeshData unitCylinder(int slices) {
  MeshData m;
  revolve(m, {{1, -0.5, 1, 0, 0}, {1, 0.5, 1, 0, 1}}, slices);
  disk(m, 0.5, 1, slices);
  disk(m, -0.5, -1, slices);
  return m;
}

MeshData capsule(double radius, double height, int slices) {
  std::vector<Ring> rings;
  int half = slices / 4;
  for (int k = 0; k <= half; ++k) {
    double phi = -kPi / 2 + (kPi / 2) * k / half;
    rings.push_back({radius * std::cos(phi), -height / 2 + radius * std::sin(phi), std::cos(phi), std::sin(phi), 0});
  }
  for (int k = 0; k <= half; ++k) {
    double phi = (kPi / 2) * k / half;
    rings.push_back({radius * std::cos(phi), height / 2 + radius * std::sin(phi), std::cos(phi), std::sin(phi), 1});
  }
  MeshData m;
  revolve(m, rings, slices);
  return m;
}

MeshData unitPlane() {
  MeshData m;
  vertex(m, -0.5, -0.5, 0, 0, 0, 1, 0, 0);
  vertex(m, 0.5, -0.5, 0, 0, 0, 1, 1, 0);
  vertex(m, 0.5, 0.5, 0, 0, 0, 1, 1, 1);
  vertex(m, -0.5, 0.5, 0, 0, 0, 1, 0, 1);
  quad(m, 0, 1, 2, 3);
  return m;
}

// Rows at heights t (width 1 - t), each a left and a right vertex, then
// the tip: 3 triangles, as few as still bend (80,000 blades are 240,000
// triangles; llvmpipe pays for each).  A lawn is lit like a surface, not
// like edge-on cards.
MeshData grassBlade() {
  MeshData m;
  const double rows[] = {0.0, 0.5};
  // Mostly up: seen from above, from either side, the normal faces the
  // viewer, so the double-sided flip (which would turn it to the ground
  // and the blade black) does not happen.
  auto normal = [](double t) { return Eigen::Vector3d(0, -0.3 * (1 - t), 1).normalized(); };
  for (double t : rows) {
    Eigen::Vector3d n = normal(t);
    double half = 0.5 * (1 - t);
    vertex(m, -half, t * t, t, n.x(), n.y(), n.z(), 0, t);
    vertex(m, half, t * t, t, n.x(), n.y(), n.z(), 1, t);
  }
  Eigen::Vector3d n = normal(1);
  vertex(m, 0, 1, 1, n.x(), n.y(), n.z(), 0.5, 1);
  quad(m, 0, 1, 3, 2);
  m.indices.insert(m.indices.end(), {2, 3, 4});
  return m;
}

std::vector<Eigen::Vector4f> grassBladeShading() {
  std::vector<Eigen::Vector4f> c;
  for (float t : {0.0f, 0.5f})
    for (int k = 0; k < 2; ++k) c.emplace_back(0.55f + 0.45f * t, 0.55f + 0.45f * t, 0.55f + 0.45f * t, 1.0f);
  c.emplace_back(1.0f, 1.0f, 1.0f, 1.0f);
  return c;
}

MeshData interleave(const asset::MeshPart& part) {
  MeshData m;
  m.vertices.reserve(part.vertexCount() * 8);
  for (std::size_t v = 0; v < part.vertexCount(); ++v) {
    const float* p = &part.positions[v * 3];
    const float* n = part.normals.empty() ? nullptr : &part.normals[v * 3];
    const float* uv = part.uvs.empty() ? nullptr : &part.uvs[v * 2];
    m.vertices.insert(m.vertices.end(), {p[0], p[1], p[2], n ? n[0] : 0.f, n ? n[1] : 0.f, n ? n[2] : 1.f,
                                         uv ? uv[0] : 0.f, uv ? uv[1] : 0.f});
  }
  m.indices = part.indices;
  return m;
}

}  // namespace rscene::render
