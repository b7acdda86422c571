// Bullet collision shapes -> exact ray targets in a flat BVH (see the
// header for why).
#include "sim/lidar_geometry.hpp"

#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btShapeHull.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <LinearMath/btConvexHullComputer.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <array>
#include <map>

#include "sim/bt_eigen.hpp"
#include "sim/lidar_primitives.hpp"
#include "sim/world.hpp"

namespace rscene::sim {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

struct Solid {
  // AlignedBox: a box whose frame is the world's (most static boxes of a
  // scene): tested in world coordinates, no rotation of the ray.
  enum Kind : std::uint8_t { Box, AlignedBox, Sphere, Cylinder, Capsule, Convex } kind = Box;
  Matrix3d toLocal = Matrix3d::Identity();  // world -> local rotation (R^T)
  Vector3d origin = Vector3d::Zero();       // the local frame's origin, world
  Vector3d size = Vector3d::Zero();         // box: half extents; sphere: r; cylinder, capsule: r, half height
  int firstPlane = 0, planeCount = 0;       // Convex: into RayGeometry::Impl::planes
  const btCollisionObject* owner = nullptr;
};

struct Triangle {
  Vector3d a, e1, e2;
  const btCollisionObject* owner = nullptr;
};

struct HalfSpace {
  Vector3d n;
  double w = 0;
  const btCollisionObject* owner = nullptr;
};

struct Aabb {
  Vector3d lo = Vector3d::Constant(ray::kInf), hi = Vector3d::Constant(-ray::kInf);
  void grow(const Vector3d& p) { lo = lo.cwiseMin(p), hi = hi.cwiseMax(p); }
  void grow(const Aabb& b) { lo = lo.cwiseMin(b.lo), hi = hi.cwiseMax(b.hi); }
};

// Entry distance of a ray into a box, or infinity (inv: 1/d, no zeros).
inline double enterBox(const Aabb& b, const Vector3d& o, const Vector3d& inv, double limit) {
  double lo = 0, hi = limit;
  for (int k = 0; k < 3; ++k) {
    double t1 = (b.lo[k] - o[k]) * inv[k], t2 = (b.hi[k] - o[k]) * inv[k];
    lo = std::max(lo, std::min(t1, t2));
    hi = std::min(hi, std::max(t1, t2));
  }
  return lo <= hi ? lo : ray::kInf;
}

// A flat BVH over references: >= 0 a solid, < 0 the triangle -ref - 1.
// Internal nodes have count 0 and their children at first and first + 1.
struct Bvh {
  static constexpr int kMaxDepth = 60;  // a traversal stack holds at most depth + 1 entries
  struct Node {
    Aabb box;
    int first = 0, count = 0;
  };
  std::vector<Node> nodes;
  std::vector<int> refs;

  void build(std::vector<int> all, const std::vector<Aabb>& boxes) {
    nodes.clear();
    refs = std::move(all);
    if (refs.empty()) return;
    std::vector<Vector3d> centre(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) centre[i] = (boxes[i].lo + boxes[i].hi) / 2;
    nodes.reserve(2 * refs.size());
    nodes.emplace_back();
    // Iterative top-down build with the surface area heuristic over 16
    // bins of the centres per axis: big walls and small boxes mixed (a
    // warehouse) make median splits visit 2-3x more nodes per ray.
    struct Job {
      int node, begin, end, depth;
    };
    std::vector<Job> jobs{{0, 0, static_cast<int>(refs.size()), 0}};
    auto slot = [&](int ref) { return static_cast<std::size_t>(ref); };
    auto area = [](const Aabb& b) {
      Vector3d e = b.hi - b.lo;
      return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
    };
    constexpr int kBins = 16;
    while (!jobs.empty()) {
      Job j = jobs.back();
      jobs.pop_back();
      Aabb box, spread;
      for (int i = j.begin; i < j.end; ++i) {
        box.grow(boxes[slot(refs[std::size_t(i)])]);
        spread.grow(centre[slot(refs[std::size_t(i)])]);
      }
      Node& node = nodes[std::size_t(j.node)];
      node.box = box;
      int n = j.end - j.begin;
      auto leaf = [&] {
        node.first = j.begin;
        node.count = n;
      };
      if (n <= 2 || j.depth >= kMaxDepth) {  // the depth cap bounds the traversal stack
        leaf();
        continue;
      }
      // Best (axis, bin boundary) by SAH cost: areas times counts.
      double bestCost = ray::kInf;
      int bestAxis = -1, bestSplit = 0;
      for (int axis = 0; axis < 3; ++axis) {
        double lo = spread.lo[axis], extent = spread.hi[axis] - lo;
        if (!(extent > 0)) continue;
        std::array<Aabb, kBins> bin;
        std::array<int, kBins> count{};
        auto binOf = [&](int ref) {
          return std::min(kBins - 1, static_cast<int>((centre[slot(ref)][axis] - lo) / extent * kBins));
        };
        for (int i = j.begin; i < j.end; ++i) {
          int b = binOf(refs[std::size_t(i)]);
          bin[std::size_t(b)].grow(boxes[slot(refs[std::size_t(i)])]);
          ++count[std::size_t(b)];
        }
        std::array<double, kBins> rightCost{};
        Aabb acc;
        int accCount = 0;
        for (int b = kBins - 1; b > 0; --b) {
          acc.grow(bin[std::size_t(b)]);
          accCount += count[std::size_t(b)];
          rightCost[std::size_t(b)] = accCount ? area(acc) * accCount : 0;
        }
        acc = Aabb();
        accCount = 0;
        for (int b = 0; b < kBins - 1; ++b) {
          acc.grow(bin[std::size_t(b)]);
          accCount += count[std::size_t(b)];
          if (accCount == 0 || accCount == n) continue;
          double cost = area(acc) * accCount + rightCost[std::size_t(b + 1)];
          if (cost < bestCost) bestCost = cost, bestAxis = axis, bestSplit = b;
        }
      }
      // A leaf when splitting does not pay (one traversal step ~ one test).
      if (bestAxis < 0 || (n <= 4 && bestCost / area(box) + 1 >= n)) {
        leaf();
        continue;
      }
      double lo = spread.lo[bestAxis], extent = spread.hi[bestAxis] - lo;
      auto mid = std::partition(refs.begin() + j.begin, refs.begin() + j.end, [&](int ref) {
        return std::min(kBins - 1, static_cast<int>((centre[slot(ref)][bestAxis] - lo) / extent * kBins)) <= bestSplit;
      });
      int m = static_cast<int>(mid - refs.begin());
      int left = static_cast<int>(nodes.size());
      nodes.emplace_back();
      nodes.emplace_back();
      nodes[std::size_t(j.node)].first = left;  // `node` may dangle after emplace_back
      nodes[std::size_t(j.node)].count = 0;
      jobs.push_back({left, j.begin, m, j.depth + 1});
      jobs.push_back({left + 1, m, j.end, j.depth + 1});
    }
  }
};

// Ref indices of triangles are stored negated in one int space.
inline int triangleRef(std::size_t i) { return -static_cast<int>(i) - 1; }

}  // namespace

// One set of targets: the static bodies, or the moving ones.
struct TargetSet {
  std::vector<Solid> solids;
  std::vector<Triangle> triangles;
  std::vector<HalfSpace> halfSpaces;
  Bvh bvh;

  void clear() {
    solids.clear();
    triangles.clear();
    halfSpaces.clear();
    bvh = {};
  }

  void index(const std::vector<Aabb>& convexBoxes) {
    std::vector<int> refs;
    std::vector<Aabb> boxes;  // indexed by ref for solids, then triangles after them
    refs.reserve(solids.size() + triangles.size());
    boxes.resize(solids.size() + triangles.size());
    for (std::size_t i = 0; i < solids.size(); ++i) {
      const Solid& s = solids[i];
      Vector3d lo = Vector3d::Zero(), hi = Vector3d::Zero();
      switch (s.kind) {
        case Solid::Box:
        case Solid::AlignedBox:
          hi = s.size;
          break;
        case Solid::Sphere:
          hi = Vector3d::Constant(s.size.x());
          break;
        case Solid::Cylinder:
          hi = Vector3d(s.size.x(), s.size.x(), s.size.y());
          break;
        case Solid::Capsule:
          hi = Vector3d(s.size.x(), s.size.x(), s.size.y() + s.size.x());
          break;
        case Solid::Convex: {
          const Aabb& b = convexBoxes[std::size_t(s.firstPlane)];
          lo = b.lo, hi = b.hi;
          break;
        }
      }
      if (s.kind != Solid::Convex) lo = -hi;
      Matrix3d r = s.toLocal.transpose();
      Vector3d c = r * ((lo + hi) / 2) + s.origin, e = r.cwiseAbs() * ((hi - lo) / 2);
      boxes[i].lo = c - e, boxes[i].hi = c + e;
      refs.push_back(static_cast<int>(i));
    }
    // Triangles share the box array after the solids; their refs are
    // mapped back to it below.
    for (std::size_t i = 0; i < triangles.size(); ++i) {
      const Triangle& t = triangles[i];
      Aabb& b = boxes[solids.size() + i];
      b.grow(t.a), b.grow(t.a + t.e1), b.grow(t.a + t.e2);
      refs.push_back(static_cast<int>(solids.size() + i));
    }
    bvh.build(std::move(refs), boxes);
    for (int& r : bvh.refs)
      if (std::size_t(r) >= solids.size()) r = triangleRef(std::size_t(r) - solids.size());
  }

  double hitSolid(const Solid& s, const Vector3d& o, const Vector3d& d, const Vector3d& inv,
                  const std::vector<ray::Plane>& planes) const {
    if (s.kind == Solid::AlignedBox) {
      double lo = -ray::kInf, hi = ray::kInf;
      for (int k = 0; k < 3; ++k) {
        double t1 = (s.origin[k] - s.size[k] - o[k]) * inv[k], t2 = (s.origin[k] + s.size[k] - o[k]) * inv[k];
        lo = std::max(lo, std::min(t1, t2)), hi = std::min(hi, std::max(t1, t2));
      }
      return ray::entry(lo, hi);
    }
    Vector3d lo = s.toLocal * (o - s.origin), ld = s.toLocal * d;
    switch (s.kind) {
      case Solid::Box:
      case Solid::AlignedBox:
        return ray::box(lo, ld, s.size);
      case Solid::Sphere:
        return ray::sphere(lo, ld, s.size.x());
      case Solid::Cylinder:
        return ray::cylinder(lo, ld, s.size.x(), s.size.y());
      case Solid::Capsule:
        return ray::capsule(lo, ld, s.size.x(), s.size.y());
      case Solid::Convex:
        return ray::convex(lo, ld, planes.data() + s.firstPlane, static_cast<std::size_t>(s.planeCount));
    }
    return ray::kMiss;
  }

  // The nearest hit closer than `best` (boxes farther than maxRange are
  // not visited), else `best`.
  double cast(const Vector3d& o, const Vector3d& d, const Vector3d& inv, double best, double maxRange,
              const btCollisionObject* exclude, const std::vector<ray::Plane>& planes) const {
    for (const HalfSpace& h : halfSpaces)
      if (h.owner != exclude) best = std::min(best, ray::halfSpace(o, d, h.n, h.w));
    if (bvh.nodes.empty()) return best;
    struct Entry {
      int node;
      double t;
    };
    std::array<Entry, 128> stack;
    int top = 0;
    double t0 = enterBox(bvh.nodes[0].box, o, inv, std::min(best, maxRange));
    if (t0 == ray::kInf) return best;
    stack[0] = {0, t0};
    top = 1;
    while (top > 0) {
      Entry e = stack[std::size_t(--top)];
      if (e.t > best) continue;
      const Bvh::Node& n = bvh.nodes[std::size_t(e.node)];
      if (n.count > 0) {
        for (int i = n.first; i < n.first + n.count; ++i) {
          int ref = bvh.refs[std::size_t(i)];
          double t;
          if (ref >= 0) {
            const Solid& s = solids[std::size_t(ref)];
            if (s.owner == exclude) continue;
            t = hitSolid(s, o, d, inv, planes);
          } else {
            const Triangle& tr = triangles[std::size_t(-ref - 1)];
            if (tr.owner == exclude) continue;
            t = ray::triangle(o, d, tr.a, tr.e1, tr.e2);
          }
          best = std::min(best, t);
        }
        continue;
      }
      double limit = std::min(best, maxRange);
      double ta = enterBox(bvh.nodes[std::size_t(n.first)].box, o, inv, limit);
      double tb = enterBox(bvh.nodes[std::size_t(n.first + 1)].box, o, inv, limit);
      // Nearer child on top.  Each level pops one and pushes at most two,
      // so the stack never holds more than kMaxDepth + 1 (< 128) entries.
      if (ta <= tb) {
        if (tb != ray::kInf) stack[std::size_t(top++)] = {n.first + 1, tb};
        if (ta != ray::kInf) stack[std::size_t(top++)] = {n.first, ta};
      } else {
        if (ta != ray::kInf) stack[std::size_t(top++)] = {n.first, ta};
        if (tb != ray::kInf) stack[std::size_t(top++)] = {n.first + 1, tb};
      }
    }
    return best;
  }
};

struct RayGeometry::Impl {
  TargetSet fixed, moving;
  // Convex hulls' planes (local frames), one range per hull shape, and the
  // local box of each range (indexed by its first plane).
  std::vector<ray::Plane> planes;
  std::vector<Aabb> convexBoxes;  // parallel to planes: the hull's local box at its first plane
  std::map<const btCollisionShape*, std::pair<int, int>> hullOf;  // shape -> first plane, count

  static bool movingObject(const btCollisionObject* o) {
    return btMultiBodyLinkCollider::upcast(o) != nullptr || o->isKinematicObject() || !o->isStaticObject();
  }

  void read(const World& world, bool staticOnes) {
    TargetSet& set = staticOnes ? fixed : moving;
    set.clear();
    for (const btCollisionObject* o : world.rayTargets())
      if (movingObject(o) != staticOnes) add(o->getCollisionShape(), o->getWorldTransform(), o, set);
    set.index(convexBoxes);
  }

  Solid solid(Solid::Kind kind, const btTransform& at, const Vector3d& size, const btCollisionObject* owner) {
    Solid s;
    s.kind = kind;
    s.toLocal = matrix(at.getBasis().transpose());
    s.origin = eig(at.getOrigin());
    s.size = size;
    s.owner = owner;
    return s;
  }

  static Matrix3d matrix(const btMatrix3x3& m) {
    Matrix3d r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r(i, j) = m[i][j];
    return r;
  }

  // A transform whose local z is the shape's up axis (Bullet's cylinders
  // and capsules run along x, y or z).
  static btTransform alongZ(const btTransform& at, int up) {
    if (up == 2) return at;
    btQuaternion q =
        up == 1 ? btQuaternion(btVector3(1, 0, 0), -SIMD_HALF_PI) : btQuaternion(btVector3(0, 1, 0), SIMD_HALF_PI);
    return at * btTransform(q);
  }

  // The outward planes of the convex hull of `points` (local frame).
  std::pair<int, int> hull(const btCollisionShape* shape, const std::vector<btVector3>& points) {
    if (auto it = hullOf.find(shape); it != hullOf.end()) return it->second;
    btConvexHullComputer hc;
    hc.compute(&points[0].x(), sizeof(btVector3), static_cast<int>(points.size()), 0, 0);
    int first = static_cast<int>(planes.size());
    Aabb box;
    Vector3d centre = Vector3d::Zero();
    for (int i = 0; i < hc.vertices.size(); ++i) {
      box.grow(sim::eig(hc.vertices[i]));
      centre += sim::eig(hc.vertices[i]);
    }
    if (hc.vertices.size() > 0) centre /= hc.vertices.size();
    for (int f = 0; f < hc.faces.size(); ++f) {
      // Newell's normal of the face polygon: robust to collinear corners.
      const btConvexHullComputer::Edge* start = &hc.edges[hc.faces[f]];
      const btConvexHullComputer::Edge* e = start;
      Vector3d n = Vector3d::Zero(), onFace = sim::eig(hc.vertices[start->getSourceVertex()]);
      do {
        Vector3d a = sim::eig(hc.vertices[e->getSourceVertex()]), b = sim::eig(hc.vertices[e->getTargetVertex()]);
        n += Vector3d((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()),
                      (a.x() - b.x()) * (a.y() + b.y()));
        e = e->getNextEdgeOfFace();
      } while (e != start);
      if (!(n.norm() > 0)) continue;
      n.normalize();
      double w = n.dot(onFace);
      if (n.dot(centre) > w) n = -n, w = -w;  // outward
      planes.push_back({n, w});
      convexBoxes.push_back(box);
    }
    return hullOf[shape] = {first, static_cast<int>(planes.size()) - first};
  }

  void addHull(const btCollisionShape* shape, const std::vector<btVector3>& points, const btTransform& at,
               const btCollisionObject* owner, TargetSet& set) {
    if (points.size() < 4) return;
    auto [first, count] = hull(shape, points);
    if (count < 4) return;  // flat: no volume to enter
    Solid s = solid(Solid::Convex, at, Vector3d::Zero(), owner);
    s.firstPlane = first, s.planeCount = count;
    set.solids.push_back(s);
  }

  void add(const btCollisionShape* shape, const btTransform& at, const btCollisionObject* owner, TargetSet& set) {
    switch (shape->getShapeType()) {
      case EMPTY_SHAPE_PROXYTYPE:
        return;
      case BOX_SHAPE_PROXYTYPE: {
        Solid s =
            solid(Solid::Box, at, sim::eig(static_cast<const btBoxShape*>(shape)->getHalfExtentsWithMargin()), owner);
        if (s.toLocal == Matrix3d::Identity()) s.kind = Solid::AlignedBox;
        set.solids.push_back(s);
        return;
      }
      case SPHERE_SHAPE_PROXYTYPE:
        set.solids.push_back(
            solid(Solid::Sphere, at, Vector3d::Constant(static_cast<const btSphereShape*>(shape)->getRadius()), owner));
        return;
      case CYLINDER_SHAPE_PROXYTYPE: {
        auto* c = static_cast<const btCylinderShape*>(shape);
        int up = c->getUpAxis();
        btVector3 h = c->getHalfExtentsWithMargin();
        set.solids.push_back(solid(Solid::Cylinder, alongZ(at, up), Vector3d(h[up == 0 ? 1 : 0], h[up], 0), owner));
        return;
      }
      case CAPSULE_SHAPE_PROXYTYPE: {
        auto* c = static_cast<const btCapsuleShape*>(shape);
        set.solids.push_back(
            solid(Solid::Capsule, alongZ(at, c->getUpAxis()), Vector3d(c->getRadius(), c->getHalfHeight(), 0), owner));
        return;
      }
      case STATIC_PLANE_PROXYTYPE: {
        auto* p = static_cast<const btStaticPlaneShape*>(shape);
        // n . x <= c in the shape's frame is solid; in the world, n' . x <= c + n' . origin.
        Vector3d n = sim::eig(at.getBasis() * p->getPlaneNormal()).normalized();
        double w = p->getPlaneConstant() + n.dot(sim::eig(at.getOrigin()));
        set.halfSpaces.push_back({n, w, owner});
        return;
      }
      case COMPOUND_SHAPE_PROXYTYPE: {
        auto* c = static_cast<const btCompoundShape*>(shape);
        for (int i = 0; i < c->getNumChildShapes(); ++i)
          add(c->getChildShape(i), at * c->getChildTransform(i), owner, set);
        return;
      }
      case CONVEX_HULL_SHAPE_PROXYTYPE: {
        auto* h = static_cast<const btConvexHullShape*>(shape);
        std::vector<btVector3> points(static_cast<std::size_t>(h->getNumPoints()));
        for (int i = 0; i < h->getNumPoints(); ++i) points[std::size_t(i)] = h->getScaledPoint(i);
        addHull(shape, points, at, owner, set);
        return;
      }
      default:
        break;
    }
    if (shape->isConcave()) {  // triangle meshes, height fields
      struct Collect : btTriangleCallback {
        const btTransform* at;
        const btCollisionObject* owner;
        std::vector<Triangle>* out;
        void processTriangle(btVector3* t, int, int) override {
          Vector3d a = sim::eig((*at)(t[0])), b = sim::eig((*at)(t[1])), c = sim::eig((*at)(t[2]));
          out->push_back({a, b - a, c - a, owner});
        }
      } collect;
      collect.at = &at, collect.owner = owner, collect.out = &set.triangles;
      btVector3 lo, hi;
      shape->getAabb(btTransform::getIdentity(), lo, hi);
      btVector3 pad(1e-3, 1e-3, 1e-3);
      static_cast<const btConcaveShape*>(shape)->processAllTriangles(&collect, lo - pad, hi + pad);
      return;
    }
    if (shape->isConvex()) {  // any other convex shape: its hull from support points
      btShapeHull sh(static_cast<const btConvexShape*>(shape));
      sh.buildHull(0);
      std::vector<btVector3> points(sh.getVertexPointer(), sh.getVertexPointer() + sh.numVertices());
      addHull(shape, points, at, owner, set);
    }
  }
};

RayGeometry::RayGeometry(const World& world) : impl_(std::make_unique<Impl>()) {
  impl_->read(world, true);
  impl_->read(world, false);
}

RayGeometry::~RayGeometry() = default;

void RayGeometry::update(const World& world) { impl_->read(world, false); }

double RayGeometry::cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double maxRange,
                         const btCollisionObject* exclude) const {
  Vector3d inv;
  for (int k = 0; k < 3; ++k) inv[k] = 1 / (dir[k] != 0 ? dir[k] : 1e-300);
  double best = impl_->fixed.cast(origin, dir, inv, kNoHit, maxRange, exclude, impl_->planes);
  best = impl_->moving.cast(origin, dir, inv, best, maxRange, exclude, impl_->planes);
  return best <= maxRange ? best : kNoHit;
}

std::size_t RayGeometry::solidCount() const {
  return impl_->fixed.solids.size() + impl_->moving.solids.size() + impl_->fixed.halfSpaces.size() +
         impl_->moving.halfSpaces.size();
}

std::size_t RayGeometry::triangleCount() const {
  return impl_->fixed.triangles.size() + impl_->moving.triangles.size();
}

}  // namespace rscene::sim
