#include "render/deformed_surface.hpp"

#include <algorithm>
#include <cmath>

namespace rscene::render {

DeformedSurface surfaceFromObj(const asset::ObjSurface& obj, const Eigen::Affine3d& world) {
  DeformedSurface s;
  s.positions.reserve(obj.vertices.size());
  for (const std::array<double, 3>& v : obj.vertices)
    s.positions.push_back((world * Eigen::Vector3d(v[0], v[1], v[2])).cast<float>());
  s.triangles = obj.triangles;
  return s;
}

void surfaceVertices(const DeformedSurface& surface, std::vector<float>& out) {
  const std::vector<Eigen::Vector3f>& p = surface.positions;
  std::vector<Eigen::Vector3f> normals(p.size(), Eigen::Vector3f::Zero());
  for (const std::array<std::uint32_t, 3>& t : surface.triangles) {
    if (t[0] >= p.size() || t[1] >= p.size() || t[2] >= p.size()) continue;  // loadObjSurface checked; stay safe
    Eigen::Vector3f n = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
    for (std::uint32_t i : t) normals[i] += n;
  }
  out.resize(p.size() * 8);
  for (std::size_t i = 0; i < p.size(); ++i) {
    float length = normals[i].norm();
    Eigen::Vector3f n = length > 0 && std::isfinite(length) ? Eigen::Vector3f(normals[i] / length) : Eigen::Vector3f::UnitZ();
    float* v = out.data() + i * 8;
    v[0] = p[i].x(), v[1] = p[i].y(), v[2] = p[i].z();
    v[3] = n.x(), v[4] = n.y(), v[5] = n.z();
    v[6] = v[7] = 0;
  }
}

MeshData surfaceMesh(const DeformedSurface& surface) {
  MeshData m;
  surfaceVertices(surface, m.vertices);
  m.indices.reserve(surface.triangles.size() * 3);
  for (const std::array<std::uint32_t, 3>& t : surface.triangles) m.indices.insert(m.indices.end(), t.begin(), t.end());
  return m;
}

namespace {

// The bounds of what a surface's drawable covers.
Eigen::AlignedBox3d boundsOf(const std::vector<Eigen::Vector3f>& points) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3f& p : points) box.extend(p.cast<double>());
  return box;
}

}  // namespace

bool poseParticles(RenderScene& scene, const robot::ParticlePositions& particles) {
  bool moved = false;
  for (std::size_t i = 0; i < particles.deformables.size() && i < scene.deformableSurfaces.size(); ++i) {
    const robot::ParticlePositions::Record& r = particles.deformables[i];
    int index = scene.deformableSurfaces[i];
    if (!r.given || index < 0) continue;
    DeformedSurface& s = scene.surfaces[std::size_t(index)];
    // The OBJ's vertices come first; fill particles (fem) after them are not drawn.
    if (r.version == s.framesVersion || r.points.size() < s.positions.size()) continue;
    for (std::size_t k = 0; k < s.positions.size(); ++k) s.positions[k] = r.points[k].cast<float>();
    s.framesVersion = r.version;
    ++s.version;
    Drawable& d = scene.drawables[s.drawable];
    d.localBounds = boundsOf(s.positions);
    d.bounds = d.localBounds;  // world is the identity
    moved = true;
  }
  for (std::size_t i = 0; i < particles.granulars.size() && i < scene.granularBatches.size(); ++i) {
    const robot::ParticlePositions::Record& r = particles.granulars[i];
    int index = scene.granularBatches[i];
    if (!r.given || index < 0) continue;
    Instanced& b = scene.instanced[std::size_t(index)];
    if (r.version == b.framesVersion || r.points.size() != b.worlds.size() || b.radii.size() != b.worlds.size())
      continue;
    const Eigen::AlignedBox3d unit = unitShapeBounds(Shape::Sphere);
    b.bounds.setEmpty();
    for (std::size_t k = 0; k < r.points.size(); ++k) {
      b.worlds[k] = Eigen::Translation3d(r.points[k]) * Eigen::Scaling(b.radii[k]);
      b.instanceBounds[k] = transformBox(b.worlds[k], unit);
      b.bounds.extend(b.instanceBounds[k]);
    }
    b.framesVersion = r.version;
    ++b.version;
    moved = true;
  }
  return moved;
}

robot::ParticleCounts particleCounts(const RenderScene& scene) {
  robot::ParticleCounts c;
  for (int s : scene.deformableSurfaces)
    c.deformables.push_back(s < 0 ? -1 : std::int64_t(scene.surfaces[std::size_t(s)].positions.size()));
  for (int b : scene.granularBatches)
    c.granulars.push_back(b < 0 ? -1 : std::int64_t(scene.instanced[std::size_t(b)].worlds.size()));
  return c;
}

robot::TrajectoryLimits trajectoryLimits(const RenderScene& scene) {
  robot::ParticleCounts c = particleCounts(scene);
  std::int64_t most = 0;
  for (const std::vector<std::int64_t>* list : {&c.deformables, &c.granulars})
    for (std::int64_t n : *list) {
      if (n < 0) return {};  // a record not drawn: its lines' length is unknown
      most = std::max(most, n);
    }
  for (const DeformedSurface& s : scene.surfaces)
    if (s.mayFill) return {};  // fill particles (fem) past the surface: how many is the solver's
  return robot::TrajectoryLimits::forPoints(std::size_t(most));
}

}  // namespace rscene::render
