// The force one contact of a grain exerts (granular_material.hpp has the
// laws): the same code for grain-grain and grain-surface contacts, so the
// two cannot drift apart.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "sim/granular_material.hpp"

namespace rscene::sim {

// What a contact remembers from one substep to the next: its tangential
// spring (Cundall-Strack) and its rolling spring.
struct GranularHistory {
  Eigen::Vector3d slide = Eigen::Vector3d::Zero();  // m
  Eigen::Vector3d roll = Eigen::Vector3d::Zero();   // rad
};

struct GranularContact {
  Eigen::Vector3d n;     // unit, from the other body toward grain a
  double depth = 0;      // overlap (> 0) or gap (< 0)
  double ra = 0, rb = 0; // lever arms from the centres to the contact (rb 0 for a surface)
  double reff = 0;       // effective radius
  double friction = 0;   // Coulomb coefficient of the pair
  Eigen::Vector3d va, vb; // velocities of the two bodies' material points at the contact
  Eigen::Vector3d wa, wb; // angular velocities
};

struct GranularContactForce {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();    // on a (b gets the opposite)
  Eigen::Vector3d torqueA = Eigen::Vector3d::Zero();  // about a's centre
  Eigen::Vector3d torqueB = Eigen::Vector3d::Zero();  // about b's centre
  double normal = 0;                                  // fn >= 0 (repulsive part)
  bool cohesive = false;
};

// A spring that lives in the contact's tangent plane: turned with it
// (keeping its length) before it is stretched again.
inline void intoTangentPlane(Eigen::Vector3d& spring, const Eigen::Vector3d& n) {
  const double len = spring.norm();
  spring -= spring.dot(n) * n;
  const double projected = spring.norm();
  if (projected > 0) spring *= len / projected;
}

// One substep h of the contact; `history` is updated in place and
// cleared when the grains do not touch.
inline GranularContactForce granularContactForce(const GranularMaterial& m, const GranularContact& c, double h,
                                                 GranularHistory& history) {
  GranularContactForce out;
  if (c.depth <= 0) {
    history = {};
    double gap = -c.depth;
    // kc g (1 - g / gmax): slope kc at contact, zero again at the cut-off,
    // so no force jumps as a pair crosses gmax (scene/granular.hpp).
    if (m.cohesionStiffness > 0 && gap < m.cohesionMaxDistance) {
      out.force = -m.cohesionStiffness * gap * (1 - gap / m.cohesionMaxDistance) * c.n;
      out.cohesive = true;
    }
    return out;
  }
  // Velocity of a's contact point relative to b's (contact at a - ra n, b + rb n).
  const Eigen::Vector3d vr = (c.va + c.wa.cross(-c.ra * c.n)) - (c.vb + c.wb.cross(c.rb * c.n));
  const double vn = vr.dot(c.n);  // < 0 approaching
  const Eigen::Vector3d vt = vr - vn * c.n;

  const double elastic = m.hertz ? m.kn * c.depth * std::sqrt(c.depth / c.reff) : m.kn * c.depth;
  const double fn = std::max(0.0, elastic - m.cn * vn);  // damping never attracts
  out.normal = fn;

  // Cundall-Strack: the spring stretches with the sliding and slips at
  // the Coulomb cap, keeping the length that holds the capped force.
  Eigen::Vector3d& xi = history.slide;
  intoTangentPlane(xi, c.n);
  xi += vt * h;
  Eigen::Vector3d ft = -m.kt * xi - m.ct * vt;
  const double cap = c.friction * fn, ftNorm = ft.norm();
  if (ftNorm > cap) {
    ft *= ftNorm > 0 ? cap / ftNorm : 0;
    xi = m.kt > 0 ? Eigen::Vector3d(-(ft + m.ct * vt) / m.kt) : Eigen::Vector3d::Zero();
  }
  out.force = fn * c.n + ft;
  out.torqueA = (-c.ra * c.n).cross(ft);
  out.torqueB = (c.rb * c.n).cross(-ft);

  // Rolling resistance, the elastic-plastic spring of Iwashita and Oda /
  // Ai et al.: a spring of kr = kt Reff^2 on the relative rolling angle,
  // slipping at mur Reff fn.  A spring (not a torque of fixed size against
  // the spin) holds a pile still instead of letting it creep or chatter.
  if (m.rollingFriction > 0) {
    Eigen::Vector3d spin = c.wa - c.wb;
    spin -= spin.dot(c.n) * c.n;
    Eigen::Vector3d& theta = history.roll;
    intoTangentPlane(theta, c.n);
    theta += spin * h;
    const double kr = m.kt * c.reff * c.reff, limit = m.rollingFriction * c.reff * fn;
    Eigen::Vector3d torque = -kr * theta;
    const double tNorm = torque.norm();
    if (tNorm > limit) {
      torque *= tNorm > 0 ? limit / tNorm : 0;
      theta = kr > 0 ? Eigen::Vector3d(-torque / kr) : Eigen::Vector3d::Zero();
    }
    out.torqueA += torque;
    out.torqueB -= torque;
  }
  return out;
}

}  // namespace rscene::sim
