#include "sim/surface_shapes.hpp"

#include <BulletCollision/CollisionShapes/btConcaveShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/CollisionShapes/btTriangleCallback.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#include <LinearMath/btConvexHullComputer.h>

#include <algorithm>
#include <cmath>

namespace rscene::sim {
namespace {

// Below this a direction is too short to normalise: the centre sits on
// the surface point (or on an axis), and a fixed direction is taken.
constexpr double kTiny = 1e-12;

btVector3 unitAxis(int axis) {
  btVector3 e(0, 0, 0);
  e[axis] = 1;
  return e;
}

// The closest point of a convex solid outside it: from the surface point q.
LocalContact fromOutside(const btVector3& q, const btVector3& c) {
  btVector3 d = c - q;
  double len = d.length();
  return {q, len > kTiny ? btVector3(d / len) : btVector3(0, 0, 1), len};
}

// Closest point of triangle abc to p (Ericson, Real-Time Collision
// Detection 5.1.5); `onFace` when it lies inside the triangle, not on an
// edge or a corner.
btVector3 closestOnTriangle(const btVector3& p, const btVector3& a, const btVector3& b, const btVector3& c,
                            bool& onFace) {
  onFace = false;
  btVector3 ab = b - a, ac = c - a, ap = p - a;
  double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  btVector3 bp = p - b;
  double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  btVector3 cp = p - c;
  double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  double denom = va + vb + vc;
  if (!(std::abs(denom) > 0)) return a;  // degenerate (zero-area) triangle
  onFace = true;
  double v = vb / denom, w = vc / denom;
  return a + ab * v + ac * w;
}

btVector3 faceNormal(const btVector3& a, const btVector3& b, const btVector3& c) {
  btVector3 n = (b - a).cross(c - a);
  double len = n.length();
  return len > 0 ? btVector3(n / len) : btVector3(0, 0, 1);
}

struct Collect : btTriangleCallback {
  btVector3 centre;
  double reach = 0;
  std::vector<TriangleHit>* hits = nullptr;
  void processTriangle(btVector3* t, int, int) override {
    TriangleHit h;
    h.a = t[0];
    h.b = t[1];
    h.c = t[2];
    btVector3 q = closestOnTriangle(centre, h.a, h.b, h.c, h.onFace);
    btVector3 d = centre - q;
    double len = d.length();
    h.contact.point = q;
    h.contact.distance = len;
    if (len > kTiny) {
      h.contact.normal = d / len;
    } else {  // on the surface: its face normal, toward the side the winding says
      h.contact.normal = faceNormal(h.a, h.b, h.c);
    }
    hits->push_back(h);
  }
};

// A centre below a height field's surface: the triangle whose footprint
// (along the up axis) holds the centre and lies above it.
bool underHeightField(int up, const btVector3& c, const std::vector<TriangleHit>& hits, LocalContact& out) {
  int u = (up + 1) % 3, v = (up + 2) % 3;
  for (const TriangleHit& h : hits) {
    // Barycentric coordinates of c's footprint in the triangle's footprint.
    double x0 = h.b[u] - h.a[u], y0 = h.b[v] - h.a[v], x1 = h.c[u] - h.a[u], y1 = h.c[v] - h.a[v];
    double px = c[u] - h.a[u], py = c[v] - h.a[v];
    double det = x0 * y1 - x1 * y0;
    if (!(std::abs(det) > 0)) continue;
    double s = (px * y1 - x1 * py) / det, t = (x0 * py - px * y0) / det;
    constexpr double kEdge = -1e-12;  // on a shared edge either triangle will do
    if (s < kEdge || t < kEdge || s + t > 1 - kEdge) continue;
    btVector3 n = faceNormal(h.a, h.b, h.c);
    if (n[up] < 0) n = -n;
    double distance = (c - h.a).dot(n);
    if (distance >= 0) return false;  // above the surface here: an ordinary surface contact
    out = {c - n * distance, n, distance};
    return true;
  }
  return false;
}

}  // namespace

LocalContact planeContact(const btVector3& n, double k, const btVector3& c) {
  double distance = n.dot(c) - k;
  return {c - n * distance, n, distance};
}

LocalContact boxContact(const btVector3& half, const btVector3& c) {
  btVector3 d = c.absolute() - half;
  if (d.x() > 0 || d.y() > 0 || d.z() > 0) {
    btVector3 q(std::clamp(c.x(), -half.x(), half.x()), std::clamp(c.y(), -half.y(), half.y()),
                std::clamp(c.z(), -half.z(), half.z()));
    return fromOutside(q, c);
  }
  int k = d.maxAxis();  // the nearest face: the least negative gap
  double side = c[k] < 0 ? -1 : 1;
  LocalContact out{c, unitAxis(k) * side, d[k]};
  out.point[k] = side * half[k];
  return out;
}

LocalContact sphereContact(double radius, const btVector3& c) {
  double len = c.length();
  btVector3 n = len > kTiny ? btVector3(c / len) : btVector3(0, 0, 1);
  return {n * radius, n, len - radius};
}

LocalContact cylinderContact(int axis, double radius, double halfLength, const btVector3& c) {
  btVector3 e = unitAxis(axis);
  double z = c[axis];
  btVector3 radial = c - e * z;
  double rho = radial.length();
  btVector3 out = rho > kTiny ? btVector3(radial / rho) : unitAxis((axis + 1) % 3);
  if (rho > radius || std::abs(z) > halfLength) {
    btVector3 q = out * std::min(rho, radius) + e * std::clamp(z, -halfLength, halfLength);
    return fromOutside(q, c);
  }
  double side = radius - rho, cap = halfLength - std::abs(z);
  if (side < cap) return {c + out * side, out, -side};
  double sign = z < 0 ? -1 : 1;
  btVector3 q = radial + e * (sign * halfLength);
  return {q, e * sign, -cap};
}

LocalContact capsuleContact(int axis, double radius, double halfLength, const btVector3& c) {
  btVector3 e = unitAxis(axis);
  btVector3 s = e * std::clamp(c[axis], -halfLength, halfLength);
  btVector3 d = c - s;
  double len = d.length();
  btVector3 n = len > kTiny ? btVector3(d / len) : unitAxis((axis + 1) % 3);
  return {s + n * radius, n, len - radius};
}

bool convexContact(const btConvexShape& shape, const btVector3& c, double probe, LocalContact& out) {
  btSphereShape sphere(probe);
  btVoronoiSimplexSolver simplex;
  btGjkEpaPenetrationDepthSolver epa;
  btGjkPairDetector gjk(&sphere, &shape, &simplex, &epa);
  btDiscreteCollisionDetectorInterface::ClosestPointInput in;
  in.m_transformA.setIdentity();
  in.m_transformA.setOrigin(c);
  in.m_transformB.setIdentity();
  btPointCollector result;
  gjk.getClosestPoints(in, result, nullptr);
  if (!result.m_hasResult || !std::isfinite(result.m_distance)) return false;
  // Bullet's normal points from B (the shape) toward A (the probe), and
  // its point lies on B; the distance is between the two surfaces.
  out = {result.m_pointInWorld, result.m_normalOnBInWorld.normalized(), result.m_distance + probe};
  return true;
}

HullPlanes hullPlanes(const btConvexHullShape& shape) {
  HullPlanes out;
  std::vector<btVector3> points;
  points.reserve(static_cast<std::size_t>(shape.getNumPoints()));
  for (int i = 0; i < shape.getNumPoints(); ++i) points.push_back(shape.getScaledPoint(i));
  if (points.size() < 4) return out;  // flat or empty: GJK for all of it
  btConvexHullComputer hull;
  hull.compute(&points[0].x(), sizeof(btVector3), static_cast<int>(points.size()), 0, 0);
  btVector3 centroid(0, 0, 0);
  for (int i = 0; i < hull.vertices.size(); ++i) centroid += hull.vertices[i];
  if (hull.vertices.size() > 0) centroid /= static_cast<double>(hull.vertices.size());
  for (int f = 0; f < hull.faces.size(); ++f) {
    const btConvexHullComputer::Edge* e = &hull.edges[hull.faces[f]];
    const btVector3& a = hull.vertices[e->getSourceVertex()];
    const btVector3& b = hull.vertices[e->getNextEdgeOfFace()->getSourceVertex()];
    const btVector3& c = hull.vertices[e->getNextEdgeOfFace()->getNextEdgeOfFace()->getSourceVertex()];
    btVector3 n = (b - a).cross(c - a);
    double len = n.length();
    if (!(len > 0)) continue;
    n /= len;
    if (n.dot(centroid - a) > 0) n = -n;  // outward
    out.normals.push_back(n);
    out.offsets.push_back(n.dot(a));
  }
  return out;
}

bool hullFaceContact(const HullPlanes& hull, double margin, const btVector3& c, LocalContact& out) {
  std::size_t n = hull.normals.size();
  if (n < 4) return false;
  std::size_t best = 0, positive = 0;
  double bestDistance = -BT_LARGE_FLOAT;
  for (std::size_t i = 0; i < n; ++i) {
    double d = hull.normals[i].dot(c) - hull.offsets[i];
    if (d > 0) ++positive;
    if (d > bestDistance) {
      bestDistance = d;
      best = i;
    }
  }
  if (positive > 1) return false;  // off an edge or a corner
  const btVector3& normal = hull.normals[best];
  btVector3 foot = c - normal * bestDistance;
  if (positive == 1) {  // over face `best`: its foot must lie on the face
    double tolerance = 1e-12 * (1 + foot.length());
    for (std::size_t i = 0; i < n; ++i)
      if (i != best && hull.normals[i].dot(foot) - hull.offsets[i] > tolerance) return false;
  }
  // Inside, the nearest face's plane is the nearest boundary (the hull is
  // convex); the margin grows every face outward by itself.
  out = {foot + normal * margin, normal, bestDistance - margin};
  return true;
}

void concaveContacts(const btConcaveShape& shape, bool heightField, const btVector3& c, double reach,
                     std::vector<TriangleHit>& scratch, std::vector<LocalContact>& out) {
  scratch.clear();
  btVector3 lo = c - btVector3(reach, reach, reach), hi = c + btVector3(reach, reach, reach);
  int up = 2;
  if (heightField) {
    // The whole column under and over the centre (Bullet skips triangles
    // outside the box's height range), to find the surface above a centre
    // that sank deeper than `reach` into it.
    up = static_cast<const btHeightfieldTerrainShape&>(shape).getUpAxis();
    btVector3 fieldLo, fieldHi;
    shape.getAabb(btTransform::getIdentity(), fieldLo, fieldHi);
    lo[up] = std::min(lo[up], fieldLo[up] - 1);
    hi[up] = std::max(hi[up], fieldHi[up] + 1);
  }
  Collect collect;
  collect.centre = c;
  collect.reach = reach;
  collect.hits = &scratch;
  shape.processAllTriangles(&collect, lo, hi);
  if (heightField) {
    LocalContact inside;
    if (underHeightField(up, c, scratch, inside)) {
      out.push_back(inside);
      return;
    }
  }
  // Nearest first (ties in the order Bullet visited them: deterministic).
  scratch.erase(std::remove_if(scratch.begin(), scratch.end(),
                               [&](const TriangleHit& h) { return !(h.contact.distance <= reach); }),
                scratch.end());
  // Insertion sort: a handful of triangles, stable, and no allocation
  // (std::stable_sort takes a buffer per call).
  for (std::size_t i = 1; i < scratch.size(); ++i)
    for (std::size_t j = i; j > 0 && scratch[j].contact.distance < scratch[j - 1].contact.distance; --j)
      std::swap(scratch[j], scratch[j - 1]);
  // A closest point on an edge or corner that also lies on a nearer
  // triangle is no local minimum of the distance over the surface (that
  // nearer triangle has a closer point): the same surface seen twice.
  for (std::size_t i = 0; i < scratch.size(); ++i) {
    const TriangleHit& h = scratch[i];
    bool seen = false;
    double eps = 1e-9 * (1 + h.contact.point.length());
    for (std::size_t j = 0; j < i && !seen; ++j) {
      bool face;
      btVector3 q = closestOnTriangle(h.contact.point, scratch[j].a, scratch[j].b, scratch[j].c, face);
      seen = (q - h.contact.point).length() <= eps;
    }
    if (!seen) out.push_back(h.contact);
  }
}

}  // namespace rscene::sim
