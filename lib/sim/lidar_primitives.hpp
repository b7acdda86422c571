// Exact ray-primitive intersections for the LiDAR's ray casts
// (lidar_geometry.cpp).  Each takes the ray in the primitive's own frame
// (origin o, unit direction d) and returns the distance t >= 0 at which the
// ray enters the primitive, or kNoHit.  A solid is not hit by a ray that
// starts inside it; a triangle is hit from either side.
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace rscene::sim::ray {

inline constexpr double kMiss = std::numeric_limits<double>::infinity();
inline constexpr double kInf = std::numeric_limits<double>::infinity();

// Where a ray is inside the slab |x_axis| <= h: [lo, hi] (empty: lo > hi).
inline void slab(double o, double d, double h, double& lo, double& hi) {
  if (d == 0) {
    if (std::abs(o) <= h)
      lo = -kInf, hi = kInf;
    else
      lo = kInf, hi = -kInf;
    return;
  }
  double inv = 1 / d, a = (-h - o) * inv, b = (h - o) * inv;
  lo = std::min(a, b), hi = std::max(a, b);
}

// The entry of [lo, hi] when the ray starts outside (lo >= 0) and meets it.
inline double entry(double lo, double hi) { return lo <= hi && lo >= 0 ? lo : kMiss; }

// Box of half extents h about the origin.
inline double box(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& h) {
  double lo = -kInf, hi = kInf;
  for (int k = 0; k < 3; ++k) {
    double a, b;
    slab(o[k], d[k], h[k], a, b);
    lo = std::max(lo, a), hi = std::min(hi, b);
  }
  return entry(lo, hi);
}

inline double sphere(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double r) {
  double b = o.dot(d), c = o.squaredNorm() - r * r;
  if (c < 0) return kMiss;  // inside
  double disc = b * b - c;
  if (disc < 0) return kMiss;
  double t = -b - std::sqrt(disc);
  return t >= 0 ? t : kMiss;
}

// Where a ray is inside the infinite cylinder x^2 + y^2 <= r^2.
inline void tube(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double r, double& lo, double& hi) {
  double a = d.x() * d.x() + d.y() * d.y(), c = o.x() * o.x() + o.y() * o.y() - r * r;
  if (a < 1e-300) {  // parallel to the axis
    if (c <= 0)
      lo = -kInf, hi = kInf;
    else
      lo = kInf, hi = -kInf;
    return;
  }
  double b = o.x() * d.x() + o.y() * d.y(), disc = b * b - a * c;
  if (disc < 0) {
    lo = kInf, hi = -kInf;
    return;
  }
  double s = std::sqrt(disc);
  lo = (-b - s) / a, hi = (-b + s) / a;
}

// Cylinder of radius r along z, from z = -h to h.
inline double cylinder(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double r, double h) {
  double lo, hi, a, b;
  tube(o, d, r, lo, hi);
  slab(o.z(), d.z(), h, a, b);
  return entry(std::max(lo, a), std::min(hi, b));
}

// Capsule: the points within r of the segment z in [-h, h] on the z axis.
inline double capsule(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double r, double h) {
  Eigen::Vector3d nearest(0, 0, std::clamp(o.z(), -h, h));
  if ((o - nearest).squaredNorm() < r * r) return kMiss;  // inside
  double best = kMiss, lo, hi;
  tube(o, d, r, lo, hi);
  if (lo <= hi && lo >= 0 && std::abs(o.z() + lo * d.z()) <= h) best = lo;
  for (double end : {-h, h}) best = std::min(best, sphere(o - Eigen::Vector3d(0, 0, end), d, r));
  return best;
}

// Convex polyhedron: the points with n . x <= w for every plane (n, w),
// n of unit length pointing out.
struct Plane {
  Eigen::Vector3d n;
  double w;
};
inline double convex(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Plane* planes, std::size_t count) {
  double lo = -kInf, hi = kInf;
  for (std::size_t i = 0; i < count; ++i) {
    double denom = planes[i].n.dot(d), dist = planes[i].w - planes[i].n.dot(o);
    if (denom == 0) {
      if (dist < 0) return kMiss;  // outside this plane and parallel to it
      continue;
    }
    double t = dist / denom;
    if (denom < 0)
      lo = std::max(lo, t);
    else
      hi = std::min(hi, t);
    if (lo > hi) return kMiss;
  }
  return entry(lo, hi);
}

// Half-space n . x <= w: entered from the side n points to.
inline double halfSpace(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& n, double w) {
  double dist = n.dot(o) - w, denom = n.dot(d);
  if (dist < 0 || denom >= 0) return kMiss;  // inside, or going away
  return -dist / denom;
}

// Triangle (a, a + e1, a + e2), either side (Moller-Trumbore).
inline double triangle(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& a,
                       const Eigen::Vector3d& e1, const Eigen::Vector3d& e2) {
  Eigen::Vector3d p = d.cross(e2);
  double det = e1.dot(p);
  if (std::abs(det) < 1e-300) return kMiss;
  double inv = 1 / det;
  Eigen::Vector3d s = o - a;
  double u = s.dot(p) * inv;
  if (u < 0 || u > 1) return kMiss;
  Eigen::Vector3d q = s.cross(e1);
  double v = d.dot(q) * inv;
  if (v < 0 || u + v > 1) return kMiss;
  double t = e2.dot(q) * inv;
  return t >= 0 ? t : kMiss;
}

}  // namespace rscene::sim::ray
