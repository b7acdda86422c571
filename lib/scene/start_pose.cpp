#include "scene/start_pose.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <utility>

#include "core/codes.hpp"
#include "core/text.hpp"
#include "scene/reader.hpp"

namespace rscene {

bool groundRuleBody(const Object& o) {
  return o.bodyMode == BodyMode::Dynamic &&
         (o.primitive == "box" || o.primitive == "sphere" || o.primitive == "capsule" || o.primitive == "cylinder");
}

bool groundRulePlane(const Object& o) {
  return o.bodyMode != BodyMode::VisualOnly && (o.primitive == "ground" || o.primitive == "half_space");
}

double depthBelow(const Object& o, double z) {
  Eigen::Quaterniond q = o.world.orientation;
  q = q.norm() > 1e-12 ? q.normalized() : Eigen::Quaterniond::Identity();
  const Eigen::Matrix3d r = q.toRotationMatrix();
  const double c = o.world.position.z();
  double reach = 0;  // how far the shape reaches below its centre
  if (o.primitive == "box") {
    const Eigen::Vector3d h = o.scale / 2;
    reach = std::abs(r(2, 0)) * h.x() + std::abs(r(2, 1)) * h.y() + std::abs(r(2, 2)) * h.z();
  } else if (o.primitive == "sphere") {
    reach = o.physicsRadius();
  } else {  // cylinder, capsule: along the body's z
    const double axis = std::abs(r(2, 2)), half = o.physicsHeight() / 2, radius = o.physicsRadius();
    reach = axis * half + (o.primitive == "capsule" ? radius : radius * std::sqrt(std::max(0.0, 1 - axis * axis)));
  }
  return z - (c - reach);
}

std::vector<GroundStart> groundStarts(const Scene& scene) {
  std::vector<GroundStart> out;
  std::vector<int> planes;
  for (std::size_t i = 0; i < scene.objects.size(); ++i)
    if (groundRulePlane(scene.objects[i])) planes.push_back(static_cast<int>(i));
  if (planes.empty()) return out;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& o = scene.objects[i];
    if (!groundRuleBody(o)) continue;
    for (int p : planes) {
      const Object& g = scene.objects[static_cast<std::size_t>(p)];
      // rscene-sim's filter: the pair meets when each group is in the other's mask.
      if ((o.collisionGroup & g.collisionMask) == 0 || (g.collisionGroup & o.collisionMask) == 0) continue;
      const double depth = depthBelow(o, g.world.position.z());
      if (std::isfinite(depth) && depth > kStartOverlapDepth) out.push_back({static_cast<int>(i), p, depth});
    }
  }
  return out;
}

namespace {

// A pair-rule body in the world frame.
struct Solid {
  enum Kind { Box, Sphere, Capsule } kind = Sphere;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();    // centre
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();  // body axes (columns)
  Eigen::Vector3d h = Eigen::Vector3d::Zero();    // box half sides
  double radius = 0;                              // sphere, capsule
  Eigen::Vector3d p0 = Eigen::Vector3d::Zero(), p1 = Eigen::Vector3d::Zero();  // capsule segment (sphere: c, c)
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();  // bounding box
};

Solid solidOf(const Object& o) {
  Solid s;
  Eigen::Quaterniond q = o.world.orientation;
  q = q.norm() > 1e-12 ? q.normalized() : Eigen::Quaterniond::Identity();
  s.r = q.toRotationMatrix();
  s.c = o.world.position;
  if (o.primitive == "box") {
    s.kind = Solid::Box;
    s.h = o.scale / 2;
    const Eigen::Vector3d e = s.r.cwiseAbs() * s.h;
    s.lo = s.c - e;
    s.hi = s.c + e;
    return s;
  }
  s.kind = o.primitive == "sphere" ? Solid::Sphere : Solid::Capsule;
  s.radius = o.physicsRadius();
  const Eigen::Vector3d half = s.kind == Solid::Capsule ? Eigen::Vector3d(s.r.col(2) * (o.physicsHeight() / 2))
                                                        : Eigen::Vector3d::Zero();
  s.p0 = s.c - half;
  s.p1 = s.c + half;
  s.lo = s.p0.cwiseMin(s.p1).array() - s.radius;
  s.hi = s.p0.cwiseMax(s.p1).array() + s.radius;
  return s;
}

// Distance between segments [p1, q1] and [p2, q2] (Ericson, Real-Time
// Collision Detection 5.1.9).
double segmentSegment(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1, const Eigen::Vector3d& p2,
                      const Eigen::Vector3d& q2) {
  const Eigen::Vector3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr double eps = 1e-18;
  double s = 0, t = 0;
  if (a <= eps && e <= eps) return r.norm();
  if (a <= eps) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= eps) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > eps * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return (p1 + s * d1 - (p2 + t * d2)).norm();
}

// Distance from a point (box frame) to the box of half sides h.
double pointBoxDistance(const Eigen::Vector3d& q, const Eigen::Vector3d& h) {
  return (q - q.cwiseMax(-h).cwiseMin(h)).norm();
}

// Penetration depth of a segment (box frame, q0-q1) swept by `radius` and
// the box of half sides h: separating axes (the box's faces, the
// segment's direction across each box edge) when the segment meets the
// box, else radius minus their distance.
double capsuleBox(const Eigen::Vector3d& q0, const Eigen::Vector3d& q1, double radius, const Eigen::Vector3d& h) {
  const Eigen::Vector3d d = q1 - q0;
  std::array<Eigen::Vector3d, 6> axes = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
  int n = 3;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d a = d.cross(Eigen::Vector3d::Unit(i));
    if (a.norm() > 1e-9 * std::max(1.0, d.norm())) axes[static_cast<std::size_t>(n++)] = a.normalized();
  }
  double least = std::numeric_limits<double>::infinity();
  bool meets = true;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d& l = axes[static_cast<std::size_t>(k)];
    const double rb = h.cwiseProduct(l).cwiseAbs().sum();
    const double a = l.dot(q0), b = l.dot(q1);
    const double lo = std::min(a, b), hi = std::max(a, b);
    const double push = std::min(hi + rb, rb - lo);  // along +l or -l until apart
    if (push < 0) {
      meets = false;
      break;
    }
    least = std::min(least, push);
  }
  if (meets) return radius + least;
  // Apart: the distance from the box is convex along the segment.
  double lo = 0, hi = 1;
  for (int i = 0; i < 100; ++i) {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (pointBoxDistance(q0 + m1 * d, h) <= pointBoxDistance(q0 + m2 * d, h))
      hi = m2;
    else
      lo = m1;
  }
  return radius - pointBoxDistance(q0 + (lo + hi) / 2 * d, h);
}

// Penetration depth of two boxes: the least overlap over the 15
// separating axes (negative: apart).
double boxBox(const Solid& a, const Solid& b) {
  const Eigen::Vector3d t = b.c - a.c;
  double least = std::numeric_limits<double>::infinity();
  auto axis = [&](const Eigen::Vector3d& l) {
    const double rb = (a.r.transpose() * l).cwiseAbs().dot(a.h) + (b.r.transpose() * l).cwiseAbs().dot(b.h);
    least = std::min(least, rb - std::abs(t.dot(l)));
  };
  for (int i = 0; i < 3; ++i) axis(a.r.col(i));
  for (int i = 0; i < 3; ++i) axis(b.r.col(i));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d l = a.r.col(i).cross(b.r.col(j));
      if (l.norm() > 1e-9) axis(l.normalized());
    }
  return least;
}

double solidDepth(const Solid& a, const Solid& b) {
  if (a.kind == Solid::Box && b.kind == Solid::Box) return boxBox(a, b);
  if (a.kind != Solid::Box && b.kind != Solid::Box)  // spheres are capsules of no length
    return a.radius + b.radius - segmentSegment(a.p0, a.p1, b.p0, b.p1);
  const Solid& box = a.kind == Solid::Box ? a : b;
  const Solid& round = a.kind == Solid::Box ? b : a;
  const Eigen::Matrix3d rt = box.r.transpose();
  return capsuleBox(rt * (round.p0 - box.c), rt * (round.p1 - box.c), round.radius, box.h);
}

}  // namespace

bool pairRuleBody(const Object& o) {
  return o.bodyMode == BodyMode::Dynamic && (o.primitive == "box" || o.primitive == "sphere" || o.primitive == "capsule");
}

double overlapDepth(const Object& a, const Object& b) {
  if (!pairRuleBody(a) || !pairRuleBody(b)) return std::numeric_limits<double>::quiet_NaN();
  return solidDepth(solidOf(a), solidOf(b));
}

namespace {

// Calls visit(body, other, depth) once for each pair of pair-rule bodies
// (at least one dynamic; their groups meet; no stiff wire between them)
// whose bounding boxes come within `margin` of each other, with their
// penetration depth (negative: apart by that much), `body` a dynamic one
// (the later when both are).  A sweep over bounding boxes along the axis
// the bodies spread most on finds the candidates: pairs of two
// non-dynamic bodies are never visited, so a city of static boxes costs a
// sort.
template <class Visit>
void sweepPairs(const Scene& scene, double margin, Visit visit) {
  std::vector<int> index;  // Scene::objects index per solid
  std::vector<Solid> solids;
  std::vector<char> dynamic;
  bool anyDynamic = false;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& o = scene.objects[i];
    if (!pairRuleBody(o) || o.collisionGroup == 0 || o.collisionMask == 0) continue;
    Solid s = solidOf(o);
    // A shape of no size is RS7003's (an error); sim refuses it.
    if (!s.lo.allFinite() || !s.hi.allFinite() || (s.kind == Solid::Box ? !(s.h.minCoeff() > 0) : !(s.radius > 0)) ||
        (s.kind == Solid::Capsule && !((s.p1 - s.p0).norm() >= 0)))
      continue;
    index.push_back(static_cast<int>(i));
    solids.push_back(s);
    dynamic.push_back(o.bodyMode == BodyMode::Dynamic);
    anyDynamic = anyDynamic || dynamic.back();
  }
  if (!anyDynamic) return;
  // Records a stiff wire joins: Bullet does not collide them.
  std::set<std::pair<int, int>> wired;
  for (const Wire& w : scene.wires)
    if (w.simulated() && w.kind != "compliant" && w.endA == WireEnd::Body && w.endB == WireEnd::Body)
      wired.insert({std::min(w.recordA, w.recordB), std::max(w.recordA, w.recordB)});
  // The sweep axis: the one the centres spread most along.
  const std::size_t n = solids.size();
  int axis = 0;
  {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero(), var = Eigen::Vector3d::Zero();
    for (const Solid& s : solids) mean += (s.lo + s.hi) / 2;
    mean /= static_cast<double>(n);
    for (const Solid& s : solids) var += ((s.lo + s.hi) / 2 - mean).cwiseAbs2();
    var.maxCoeff(&axis);
  }
  // Solids sorted by (lower bound on the axis, index): a total order.
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
  auto before = [&](std::uint32_t x, std::uint32_t y) {
    const double a = solids[x].lo[axis], b = solids[y].lo[axis];
    return a < b || (a == b && x < y);
  };
  std::sort(order.begin(), order.end(), before);
  std::vector<std::uint32_t> dyn;  // the dynamic ones, in that order
  for (std::uint32_t i : order)
    if (dynamic[i]) dyn.push_back(i);
  std::vector<std::size_t> rank(n);
  for (std::size_t k = 0; k < n; ++k) rank[order[k]] = k;
  // The sweep's work is bounded: bodies piled in one place have pairs
  // quadratic in their number (rscene-sim's --max-pairs refuses such a
  // pile); past kMaxStartPairVisits the rule stops with what it found.
  std::uint64_t visits = 0;
  auto judge = [&](std::uint32_t x, std::uint32_t y) {
    const Solid& a = solids[x];
    const Solid& b = solids[y];
    for (int k = 0; k < 3; ++k)
      if (a.lo[k] > b.hi[k] + margin || b.lo[k] > a.hi[k] + margin) return;
    const Object& oa = scene.objects[static_cast<std::size_t>(index[x])];
    const Object& ob = scene.objects[static_cast<std::size_t>(index[y])];
    if ((oa.collisionGroup & ob.collisionMask) == 0 || (ob.collisionGroup & oa.collisionMask) == 0) return;
    if (wired.count({std::min(oa.recordIndex, ob.recordIndex), std::max(oa.recordIndex, ob.recordIndex)})) return;
    const double depth = solidDepth(a, b);
    if (!std::isfinite(depth) || !(depth >= -margin)) return;
    int body = index[x], other = index[y];
    if (!dynamic[x] || (dynamic[y] && other > body)) std::swap(body, other);
    visit(body, other, depth);
  };
  // Each pair with a dynamic member once: a dynamic solid with every solid
  // that starts within its interval after it; a non-dynamic solid with
  // every dynamic one that starts within its interval after it.
  for (std::uint32_t d : dyn)
    for (std::size_t k = rank[d] + 1;
         k < n && solids[order[k]].lo[axis] <= solids[d].hi[axis] + margin && ++visits <= kMaxStartPairVisits; ++k)
      judge(d, order[k]);
  // (Every solid is dynamic today: a static or kinematic partner is
  // rscene-sim's, see pairRuleBody().  The pass below keeps the rule whole
  // should one be added.)
  for (std::size_t k = 0; k < n && visits <= kMaxStartPairVisits; ++k) {
    const std::uint32_t s = order[k];
    if (dynamic[s]) continue;
    auto from = std::upper_bound(dyn.begin(), dyn.end(), s, before);
    for (auto it = from; it != dyn.end() && solids[*it].lo[axis] <= solids[s].hi[axis] + margin &&
                         ++visits <= kMaxStartPairVisits;
         ++it)
      judge(s, *it);
  }
}

}  // namespace

std::vector<BodyStart> bodyStarts(const Scene& scene) {
  std::vector<BodyStart> out;
  sweepPairs(scene, 0.0, [&](int body, int other, double depth) {
    if (depth > kStartOverlapDepth) out.push_back({body, other, depth});
  });
  // One per dynamic body: the deepest it starts inside (ties: the first).
  std::sort(out.begin(), out.end(), [](const BodyStart& a, const BodyStart& b) {
    return a.body != b.body ? a.body < b.body : a.depth != b.depth ? a.depth > b.depth : a.other < b.other;
  });
  out.erase(std::unique(out.begin(), out.end(), [](const BodyStart& a, const BodyStart& b) { return a.body == b.body; }),
            out.end());
  return out;
}

std::vector<MassRatioStart> massRatioStarts(const Scene& scene) {
  std::vector<MassRatioStart> out;
  sweepPairs(scene, kStartOverlapDepth, [&](int body, int other, double) {
    const Object& a = scene.objects[static_cast<std::size_t>(body)];
    const Object& b = scene.objects[static_cast<std::size_t>(other)];
    // Both dynamic (a static or kinematic partner holds any mass); a mass
    // that is not positive is RS4008's, past the bounds RS7020's.
    if (a.bodyMode != BodyMode::Dynamic || b.bodyMode != BodyMode::Dynamic) return;
    const double ma = a.effectiveMass(), mb = b.effectiveMass();
    if (!(ma > 0) || !(mb > 0) || !std::isfinite(ma) || !std::isfinite(mb)) return;
    const bool aHeavier = ma > mb || (ma == mb && body < other);
    const double ratio = aHeavier ? ma / mb : mb / ma;
    if (!(ratio > kMaxContactMassRatio)) return;
    out.push_back({aHeavier ? body : other, aHeavier ? other : body, ratio});
  });
  // One per heavier body: the largest ratio (ties: the first partner).
  std::sort(out.begin(), out.end(), [](const MassRatioStart& a, const MassRatioStart& b) {
    return a.heavy != b.heavy ? a.heavy < b.heavy : a.ratio != b.ratio ? a.ratio > b.ratio : a.light < b.light;
  });
  out.erase(std::unique(out.begin(), out.end(),
                        [](const MassRatioStart& a, const MassRatioStart& b) { return a.heavy == b.heavy; }),
            out.end());
  return out;
}

std::vector<BelowWorldStart> belowWorldStarts(const Scene& scene) {
  std::vector<BelowWorldStart> out;
  // rscene-sim's floor counts every plane it builds, whatever its filter.
  int lowest = -1;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& g = scene.objects[i];
    if (!groundRulePlane(g) || !std::isfinite(g.world.position.z())) continue;
    if (lowest < 0 || g.world.position.z() < scene.objects[static_cast<std::size_t>(lowest)].world.position.z())
      lowest = static_cast<int>(i);
  }
  if (lowest < 0) return out;
  const double bound = scene.objects[static_cast<std::size_t>(lowest)].world.position.z() - kLeaveMargin;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& o = scene.objects[i];
    if (o.bodyMode != BodyMode::Dynamic || groundRulePlane(o) || o.primitive == "ground" || o.primitive == "half_space")
      continue;
    if (o.world.position.z() < bound) out.push_back({o.recordIndex, lowest, o.world.position.z(), bound});
  }
  for (const Compound& c : scene.compounds)
    if (c.bodyMode == BodyMode::Dynamic && !c.children.empty() && c.world.position.z() < bound)
      out.push_back({c.recordIndex, lowest, c.world.position.z(), bound});
  std::sort(out.begin(), out.end(),
            [](const BelowWorldStart& a, const BelowWorldStart& b) { return a.record < b.record; });
  return out;
}

Diagnostic startOverlapDiagnostic(const Document& doc, int bodyRecord, int otherRecord, double depth) {
  auto pathOf = [&](int recordIndex) -> std::string {
    if (recordIndex < 0 || static_cast<std::size_t>(recordIndex) >= doc.records.size()) return "a robot's link";
    Diagnostics unused;
    RecordReader r(doc, static_cast<std::size_t>(recordIndex), unused);
    return "'" + r.text("path").value_or("") + "'";
  };
  char text[48];
  std::snprintf(text, sizeof text, "%.3g m", depth);
  Diagnostics one;
  reportAt(&doc, bodyRecord, "position", rs::RS7013,
           "dynamic body " + pathOf(bodyRecord) + " starts " + text + " inside " + pathOf(otherRecord) +
               "; the solver pushes it out over the first steps, which moves it and what it touches",
           one, Severity::Warning, "place it clear of what it starts inside");
  return one.front();  // reportAt() reports at the record, or bare
}

void checkGroundStarts(const Document& doc, const Scene& scene, Diagnostics& diagnostics) {
  auto pathOf = [&](int recordIndex) {
    Diagnostics unused;
    RecordReader r(doc, static_cast<std::size_t>(recordIndex), unused);
    return "'" + r.text("path").value_or("") + "'";
  };
  // RS7015: below the world's lower bound (an error; no RS7013 besides).
  std::set<int> below;
  for (const BelowWorldStart& b : belowWorldStarts(scene)) {
    below.insert(b.record);
    const int ground = scene.objects[static_cast<std::size_t>(b.ground)].recordIndex;
    reportAt(&doc, b.record, "position", rs::RS7015,
             "dynamic body " + pathOf(b.record) + " starts at z = " + roundedNumber(b.z, 6) +
                 ", below the world's lower bound z = " + roundedNumber(b.bound, 6) + " (" +
                 roundedNumber(kLeaveMargin, 6) + " m under the lowest ground, " + pathOf(ground) +
                 "): rscene-sim would take it out of the world at its first step",
             diagnostics, Severity::Error, "place it above the ground");
  }
  // One warning per body, naming the deepest it starts inside: the ground
  // or another body (a box sunk in the ground and into its neighbour is
  // one finding).
  struct Deepest {
    int other;
    double depth;
  };
  std::map<int, Deepest> deepest;  // body -> what it starts deepest inside
  auto take = [&](int body, int other, double depth) {
    if (below.count(scene.objects[static_cast<std::size_t>(body)].recordIndex)) return;
    auto [it, added] = deepest.emplace(body, Deepest{other, depth});
    if (!added && depth > it->second.depth) it->second = {other, depth};
  };
  for (const GroundStart& s : groundStarts(scene)) take(s.body, s.ground, s.depth);
  for (const BodyStart& s : bodyStarts(scene)) take(s.body, s.other, s.depth);
  for (const auto& [body, d] : deepest)
    diagnostics.push_back(startOverlapDiagnostic(doc, scene.objects[static_cast<std::size_t>(body)].recordIndex,
                                                 scene.objects[static_cast<std::size_t>(d.other)].recordIndex,
                                                 d.depth));
  // RS7014: a heavy body on a light one, at the heavier's mass.
  for (const MassRatioStart& m : massRatioStarts(scene)) {
    const Object& heavy = scene.objects[static_cast<std::size_t>(m.heavy)];
    const Object& light = scene.objects[static_cast<std::size_t>(m.light)];
    reportAt(&doc, heavy.recordIndex, "mass", rs::RS7014,
             "dynamic body " + pathOf(heavy.recordIndex) + " (" + roundedNumber(heavy.effectiveMass(), 6) +
                 " kg) starts touching " + pathOf(light.recordIndex) + " (" + roundedNumber(light.effectiveMass(), 6) +
                 " kg), " + roundedNumber(m.ratio, 3) + " times lighter (more than " +
                 roundedNumber(kMaxContactMassRatio, 6) +
                 "): the contact solver cannot hold such a pair, and the heavy body sinks through the light one",
             diagnostics, Severity::Warning,
             "keep the masses of touching dynamic bodies within a factor of " + roundedNumber(kMaxContactMassRatio, 6) +
                 ", or make the light one static or kinematic");
  }
}

}  // namespace rscene
