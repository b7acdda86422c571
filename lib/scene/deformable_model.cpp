#include "scene/deformable_model.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "core/text.hpp"
#include "scene/deformable_check.hpp"
#include "scene/deformable_fill.hpp"

namespace rscene {
namespace {

// Strut reach in particle spacings: past the grid's diagonal (sqrt 3), so
// each fill particle is tied to its 26 neighbours, short of the next shell (2).
constexpr double kStrutReach = 1.75;
constexpr double kMaxCoordinate = 1e12;  // m, as for every other body

struct Fail {
  std::string& error;
  std::string& field;
  bool operator()(const std::string& f, std::string message) const {
    field = f;
    error = std::move(message);
    return false;
  }
};

std::string num(double x) { return roundedNumber(x, 6); }

// XPBD compliance from a compliance key, or 1/stiffness when it is
// negative; -1 when neither applies (bending off).
double compliance(double c, double stiffness) {
  if (c >= 0) return c;
  return stiffness > 0 ? 1 / stiffness : -1;
}

// One triangle edge: its vertices (sorted), the triangle and the vertex
// opposite; the edge in the triangle's own cyclic order (c -> d).
struct EdgeUse {
  std::uint32_t lo, hi, tri, opposite, c, d;
  bool operator<(const EdgeUse& o) const { return std::tie(lo, hi, tri) < std::tie(o.lo, o.hi, o.tri); }
};

double triangleArea(const DeformableModel& m, const std::array<std::uint32_t, 3>& t) {
  const auto& p = m.positions;
  return 0.5 * (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).norm();
}

}  // namespace

bool buildDeformableModel(const Deformable& r, const TriangleSurface& surface, DeformableModel& m,
                          std::string& error, std::string& field) {
  Fail fail{error, field};
  // The record's own values: the scene model's rule (checkScene() ran it
  // already; a caller that did not gets the same refusal).
  if (!checkDeformableRecord(r, error, field)) return false;
  const bool massSpring = r.kind == "mass_spring", fem = r.kind == "fem";
  if (!r.world.position.allFinite() || !r.world.orientation.coeffs().allFinite())
    return fail("position", "the record's pose is not finite");
  const bool filled = deformableFilled(r);
  const bool struts = fem || filled;  // fill particles are held by struts alone

  // Particles: the OBJ's vertices in file order, scaled, then the fill;
  // in the record's frame until the end.
  const std::size_t nv = surface.vertices.size();
  m.positions.clear();
  m.positions.reserve(nv);
  for (const auto& v : surface.vertices) {
    Eigen::Vector3d p = Eigen::Vector3d(v[0], v[1], v[2]).cwiseProduct(r.scale);
    if (!p.allFinite() || p.cwiseAbs().maxCoeff() > kMaxCoordinate)
      return fail("meshPath", "vertex " + std::to_string(m.positions.size()) + " is beyond 1e12 m once scaled");
    m.positions.push_back(p);
  }
  m.surfaceCount = nv;
  if (nv > kMaxDeformableParticles)
    return fail("meshPath", "the mesh has more than " + std::to_string(kMaxDeformableParticles) + " vertices");
  for (std::int64_t pin : r.pinnedVertices)
    if (pin < 0)  // the scene reader's mark for a value that is no whole number from 0
      return fail("pinnedVertices", "pinnedVertices holds a value that is not a vertex index (a whole number from 0 to " +
                                        std::to_string(nv - 1) + ")");
    else if (static_cast<std::uint64_t>(pin) >= nv)
      return fail("pinnedVertices", "pinnedVertices " + std::to_string(pin) + " is not a vertex of " + r.meshPath +
                                        " (it has " + std::to_string(nv) + ")");
  if (filled) {
    std::string why;
    if (!closedSurface(surface.triangles, why))
      return fail("meshPath", "a filled body needs a closed mesh: " + why);
    const std::vector<Eigen::Vector3d> shell = m.positions;  // the fill appends to m.positions
    if (!fillClosedSurface(shell, surface.triangles, r.particleSpacing, kMaxDeformableParticles, m.positions,
                           why))
      return fail("particleSpacing", why);
  }

  // Every unique triangle edge once, with the triangles using it.
  std::vector<EdgeUse> uses;
  uses.reserve(surface.triangles.size() * 3);
  for (std::uint32_t t = 0; t < surface.triangles.size(); ++t) {
    const auto& tr = surface.triangles[t];
    for (int k = 0; k < 3; ++k) {
      std::uint32_t c = tr[k], d = tr[(k + 1) % 3], o = tr[(k + 2) % 3];
      uses.push_back({std::min(c, d), std::max(c, d), t, o, c, d});
    }
  }
  std::sort(uses.begin(), uses.end());

  const double distanceAlpha = compliance(r.distanceCompliance, r.distanceStiffness);
  const double bendAlpha = compliance(r.bendCompliance, r.bendStiffness);
  auto edgeAlpha = [&](double length, double area) {
    if (!(r.youngsModulus > 0)) return distanceAlpha;
    // RaiSim: alpha = L / (E A).
    return area > 0 ? length / (r.youngsModulus * area) : 0.0;
  };
  m.distances.clear();
  m.bends.clear();
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    double adjacentArea = 0;
    while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi)
      adjacentArea += triangleArea(m, surface.triangles[uses[j++].tri]);
    const EdgeUse& e = uses[i];
    double length = (m.positions[e.lo] - m.positions[e.hi]).norm();
    // The edge's cross-section: thickness times the width that carries
    // it, a third of each adjacent triangle's area over the edge's length;
    // an edge of no area (degenerate triangles) takes a square of side thickness.
    double area = length > 0 ? r.thickness * adjacentArea / 3 / length : 0;
    if (!(area > 0)) area = r.thickness * r.thickness;
    m.distances.push_back({e.lo, e.hi, length, edgeAlpha(length, area)});
    if (j - i == 2 && bendAlpha >= 0) {
      const EdgeUse& f = uses[i + 1];
      if (massSpring) {  // a flexion spring between the two opposite vertices
        double l = (m.positions[e.opposite] - m.positions[f.opposite]).norm();
        m.distances.push_back({e.opposite, f.opposite, l, bendAlpha});
      } else if (e.opposite != f.opposite) {
        BendConstraint b{e.opposite, f.opposite, e.c, e.d, 0, bendAlpha};
        b.restAngle = dihedralAngle(m.positions[b.a], m.positions[b.b], m.positions[b.c], m.positions[b.d]);
        m.bends.push_back(b);
      }
    }
    if (m.distances.size() + m.bends.size() > kMaxDeformableConstraints)
      return fail("meshPath", "more than " + std::to_string(kMaxDeformableConstraints) + " constraints");
    i = j;
  }

  if (struts) {  // RaiSim's internal struts: pairs within kStrutReach spacings that no edge joins yet
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    std::string why;
    if (!pairsWithinRadius(m.positions, kStrutReach * r.particleSpacing, kMaxDeformableConstraints, pairs, why))
      return fail("particleSpacing", why);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const auto& d : m.distances) edges.emplace_back(std::min(d.a, d.b), std::max(d.a, d.b));
    std::sort(edges.begin(), edges.end());
    const double area = r.particleSpacing * r.particleSpacing;  // the grid cell's face
    for (const auto& [a, b] : pairs) {
      if (std::binary_search(edges.begin(), edges.end(), std::pair{a, b})) continue;
      double length = (m.positions[a] - m.positions[b]).norm();
      m.distances.push_back({a, b, length, edgeAlpha(length, area)});
      if (m.distances.size() + m.bends.size() > kMaxDeformableConstraints)
        return fail("particleSpacing", "more than " + std::to_string(kMaxDeformableConstraints) + " constraints");
    }
  }

  const double work = static_cast<double>(m.distances.size() + m.bends.size() + m.positions.size()) *
                      static_cast<double>(r.iterations) * static_cast<double>(r.substeps);
  if (work > kMaxDeformableWorkPerStep)
    return fail("iterations", "iterations x substeps x (constraints + particles) is " + num(work) +
                                  " a step (at most " + num(kMaxDeformableWorkPerStep) + ")");

  // A proxy sphere larger than the whole body is no contact model: every
  // particle starts deep inside the ground or its neighbours' surfaces and
  // is pushed out at once (collisionRadius=100 threw a 1 m cloth 9 km up).
  if (r.collidable && !m.positions.empty()) {  // in the record's frame: the size does not turn with the pose
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3d& p : m.positions) box.extend(p);
    const double size = box.diagonal().norm();
    if (r.collisionRadius > std::max(size, 1e-9))
      return fail("collisionRadius", "collisionRadius " + num(r.collisionRadius) +
                                         " m is larger than the body itself (" + num(size) +
                                         " m across): each particle's contact sphere should cover about the "
                                         "distance to its neighbours");
  }
  for (Eigen::Vector3d& p : m.positions) {
    p = r.world.position + r.world.orientation * p;
    if (!p.allFinite() || p.cwiseAbs().maxCoeff() > kMaxCoordinate)
      return fail("position", "a particle is beyond 1e12 m once placed");
  }
  const std::size_t n = m.positions.size();
  m.particleMass = r.totalMass / static_cast<double>(n);
  m.inverseMass.assign(n, 1 / m.particleMass);
  for (std::int64_t pin : r.pinnedVertices) m.inverseMass[static_cast<std::size_t>(pin)] = 0;
  m.iterations = static_cast<int>(r.iterations);
  m.substeps = static_cast<int>(r.substeps);
  m.xpbd = r.solverMode == "xpbd";
  m.damping = r.damping;
  m.collisionRadius = r.collisionRadius;
  m.collidable = r.collidable;
  m.collisionGroup = r.collisionGroup;
  m.collisionMask = r.collisionMask;
  m.contactMaterial = r.contactMaterial;
  return true;
}

}  // namespace rscene
