// SurfaceQuery over Bullet's collision objects.  prepare() flattens the
// objects that reach into a system's region into parts (one per primitive:
// compounds and robot link colliders are opened into their children) with
// their world transforms and boxes; contacts() walks those parts, closed-
// form for primitives (surface_shapes.hpp).  Forces are summed per body
// handle and handed to Bullet once per world step.
#include "sim/bullet_surfaces.hpp"

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include "sim/bt_eigen.hpp"
#include "sim/surface_shapes.hpp"

namespace rscene::sim {
namespace {

enum class Kind { Plane, Box, Sphere, Cylinder, Capsule, Convex, Concave, HeightField };

// One primitive of a prepared object, where it is now.
struct Part {
  Kind kind = Kind::Box;
  const btCollisionShape* shape = nullptr;
  btTransform toWorld, toLocal;
  btVector3 lo, hi;  // world box
  btVector3 dims;    // box half extents; x: radius, y: half length (cylinder, capsule); plane: world normal
  double planeConstant = 0;
  const HullPlanes* hull = nullptr;  // a convex hull's faces (Kind::Convex)
  int axis = 2;
  int body = -1;
  double friction = 0;
};

// A body that moves (dynamic, kinematic, or a robot link off a fixed base).
struct Handle {
  btCollisionObject* object = nullptr;
  btRigidBody* rigid = nullptr;
  btMultiBody* multi = nullptr;
  int link = -1;  // of `multi`: -1 is the base
  bool takesForce = false;  // dynamic: kinematic bodies carry a velocity but no force
  bool pending = false;
  btVector3 force{0, 0, 0}, torque{0, 0, 0};
  // A link's motion, cached by prepare() (stamp == the prepare it belongs to).
  std::uint64_t stamp = 0;
  btVector3 linear{0, 0, 0}, angular{0, 0, 0}, com{0, 0, 0};
};

bool finite(const btVector3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

// A robot link's (or base's) centre-of-mass velocity, angular velocity and
// centre, world frame: Bullet keeps link velocities in the links' frames.
void linkMotion(const btMultiBody& mb, int link, btVector3& linear, btVector3& angular, btVector3& com) {
  btAlignedObjectArray<btVector3> omega, vel;
  omega.resize(mb.getNumLinks() + 1);
  vel.resize(mb.getNumLinks() + 1);
  mb.compTreeLinkVelocities(&omega[0], &vel[0]);
  btMatrix3x3 basis = link < 0 ? mb.getBaseWorldTransform().getBasis()
                               : mb.localFrameToWorld(link, btMatrix3x3::getIdentity());
  linear = basis * vel[link + 1];
  angular = basis * omega[link + 1];
  com = link < 0 ? mb.getBasePos() : mb.localPosToWorld(link, btVector3(0, 0, 0));
}

btVector3 centreOfMass(const Handle& h, std::uint64_t stamp) {
  if (h.rigid) return h.rigid->getCenterOfMassPosition();
  if (h.stamp == stamp) return h.com;
  return h.link < 0 ? h.multi->getBasePos() : h.multi->localPosToWorld(h.link, btVector3(0, 0, 0));
}

struct Gather : btBroadphaseAabbCallback {
  std::vector<btCollisionObject*>* out = nullptr;
  bool process(const btBroadphaseProxy* proxy) override {
    out->push_back(static_cast<btCollisionObject*>(proxy->m_clientObject));
    return true;
  }
};

}  // namespace

struct BulletSurfaces::Impl {
  btCollisionWorld* world = nullptr;
  SurfaceFilter filter;
  std::vector<Handle> handles;
  std::unordered_map<const btCollisionObject*, int> handleOf;  // looked up, never iterated
  std::vector<Part> parts;
  std::vector<btCollisionObject*> candidates;
  std::uint64_t stamp = 0;
  std::map<const btCollisionShape*, HullPlanes> hulls;  // per shape, made on first sight; looked up, never iterated

  // The object's handle, made on first sight; -1 for a static one.
  int handleFor(btCollisionObject* o) {
    if (auto it = handleOf.find(o); it != handleOf.end()) return it->second;
    Handle h;
    h.object = o;
    if (btRigidBody* r = btRigidBody::upcast(o)) {
      if (r->isStaticObject() && !r->isKinematicObject()) return -1;
      h.rigid = r;
      h.takesForce = !r->isStaticOrKinematicObject();
    } else if (auto* c = btMultiBodyLinkCollider::upcast(o)) {
      if (o->isStaticOrKinematicObject() || !c->m_multiBody) return -1;  // a fixed base
      h.multi = c->m_multiBody;
      h.link = c->m_link;
      h.takesForce = true;
    } else {
      return -1;
    }
    int index = static_cast<int>(handles.size());
    handles.push_back(h);
    handleOf.emplace(o, index);
    return index;
  }

  // Appends the parts of `shape` at `at` that reach into the region.
  void addParts(const btCollisionShape* shape, const btTransform& at, int body, double friction,
                const btVector3& regionLo, const btVector3& regionHi) {
    int type = shape->getShapeType();
    if (type == COMPOUND_SHAPE_PROXYTYPE) {
      const auto* compound = static_cast<const btCompoundShape*>(shape);
      for (int i = 0; i < compound->getNumChildShapes(); ++i)
        addParts(compound->getChildShape(i), at * compound->getChildTransform(i), body, friction, regionLo, regionHi);
      return;
    }
    if (type == EMPTY_SHAPE_PROXYTYPE) return;
    Part p;
    p.shape = shape;
    p.toWorld = at;
    p.toLocal = at.inverse();
    p.body = body;
    p.friction = friction;
    shape->getAabb(at, p.lo, p.hi);
    for (int k = 0; k < 3; ++k)
      if (p.lo[k] > regionHi[k] || p.hi[k] < regionLo[k]) return;
    switch (type) {
      case STATIC_PLANE_PROXYTYPE: {
        const auto* plane = static_cast<const btStaticPlaneShape*>(shape);
        p.kind = Kind::Plane;
        p.dims = at.getBasis() * plane->getPlaneNormal();
        p.planeConstant = plane->getPlaneConstant() + p.dims.dot(at.getOrigin());
        break;
      }
      case BOX_SHAPE_PROXYTYPE:
        p.kind = Kind::Box;
        p.dims = static_cast<const btBoxShape*>(shape)->getHalfExtentsWithMargin();
        break;
      case SPHERE_SHAPE_PROXYTYPE:
        p.kind = Kind::Sphere;
        p.dims.setX(static_cast<const btSphereShape*>(shape)->getRadius());
        break;
      case CYLINDER_SHAPE_PROXYTYPE: {
        const auto* cylinder = static_cast<const btCylinderShape*>(shape);
        p.kind = Kind::Cylinder;
        p.axis = cylinder->getUpAxis();
        p.dims.setValue(cylinder->getRadius(), cylinder->getHalfExtentsWithMargin()[p.axis], 0);
        break;
      }
      case CAPSULE_SHAPE_PROXYTYPE: {
        const auto* capsule = static_cast<const btCapsuleShape*>(shape);
        p.kind = Kind::Capsule;
        p.axis = capsule->getUpAxis();
        p.dims.setValue(capsule->getRadius(), capsule->getHalfHeight(), 0);
        break;
      }
      case TERRAIN_SHAPE_PROXYTYPE:
        p.kind = Kind::HeightField;
        break;
      case CONVEX_HULL_SHAPE_PROXYTYPE: {
        p.kind = Kind::Convex;
        auto it = hulls.find(shape);
        if (it == hulls.end())
          it = hulls.emplace(shape, hullPlanes(*static_cast<const btConvexHullShape*>(shape))).first;
        p.hull = &it->second;
        p.dims.setX(shape->getMargin());
        break;
      }
      default:
        if (shape->isConvex()) p.kind = Kind::Convex;
        else if (shape->isConcave()) p.kind = Kind::Concave;
        else return;  // nothing rscene-sim builds
    }
    parts.push_back(p);
  }
};

BulletSurfaces::BulletSurfaces(btCollisionWorld& world, SurfaceFilter filter) : impl_(std::make_unique<Impl>()) {
  impl_->world = &world;
  impl_->filter = std::move(filter);
  // Handles in the world's order, so they do not depend on which system
  // happens to touch a body first.
  const btCollisionObjectArray& all = world.getCollisionObjectArray();
  for (int i = 0; i < all.size(); ++i) impl_->handleFor(all[i]);
}

BulletSurfaces::~BulletSurfaces() = default;

void BulletSurfaces::prepare(const Eigen::AlignedBox3d& region, std::uint64_t group, std::uint64_t mask,
                             const std::string& contactMaterial) {
  Impl& s = *impl_;
  s.parts.clear();
  s.candidates.clear();
  ++s.stamp;
  if (region.isEmpty()) return;  // no particles
  bool bounded = region.min().allFinite() && region.max().allFinite();
  btVector3 lo = bounded ? bt(region.min()) : btVector3(-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT);
  btVector3 hi = bounded ? bt(region.max()) : btVector3(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
  // Bodies at rest (static or asleep) from the broadphase: their boxes
  // there are where they are.  Moving ones from their handles, each box
  // tested: the broadphase's lag a step behind them (Bullet updates them
  // before it integrates).
  auto moving = [](const Handle& h) { return !h.rigid || h.rigid->isActive(); };
  Gather gather;
  gather.out = &s.candidates;
  if (bounded) {
    s.world->getBroadphase()->aabbTest(lo, hi, gather);
  } else {
    const btCollisionObjectArray& all = s.world->getCollisionObjectArray();
    for (int i = 0; i < all.size(); ++i) s.candidates.push_back(all[i]);
  }
  s.candidates.erase(std::remove_if(s.candidates.begin(), s.candidates.end(),
                                    [&](btCollisionObject* o) {
                                      int h = s.handleFor(o);
                                      return h >= 0 && moving(s.handles[static_cast<std::size_t>(h)]);
                                    }),
                     s.candidates.end());
  for (const Handle& h : s.handles)
    if (h.object->getBroadphaseHandle() && moving(h)) s.candidates.push_back(h.object);  // still in the world
  std::sort(s.candidates.begin(), s.candidates.end(),
            [](const btCollisionObject* a, const btCollisionObject* b) { return a->getWorldArrayIndex() < b->getWorldArrayIndex(); });
  s.candidates.erase(std::unique(s.candidates.begin(), s.candidates.end()), s.candidates.end());

  for (btCollisionObject* o : s.candidates) {
    if (!o->getBroadphaseHandle() || o->getCollisionShape()->getShapeType() == EMPTY_SHAPE_PROXYTYPE) continue;
    if (!s.filter.collides(*o, group, mask)) continue;
    int body = s.handleFor(o);
    std::size_t before = s.parts.size();
    s.addParts(o->getCollisionShape(), o->getWorldTransform(), body, s.filter.friction(*o, contactMaterial), lo, hi);
    if (body < 0 || s.parts.size() == before) continue;
    Handle& h = s.handles[static_cast<std::size_t>(body)];
    if (h.multi && h.stamp != s.stamp) {
      linkMotion(*h.multi, h.link, h.linear, h.angular, h.com);
      h.stamp = s.stamp;
    }
  }
}

void BulletSurfaces::contacts(const Eigen::Vector3d& centre, double radius, double margin,
                              std::vector<SurfaceContact>& out) const {
  const Impl& s = *impl_;
  double reach = radius + margin;
  if (!(reach >= 0) || !centre.allFinite()) return;
  btVector3 c = bt(centre);
  thread_local std::vector<TriangleHit> scratch;
  thread_local std::vector<LocalContact> local;
  auto emit = [&](const Part& p, const LocalContact& l, bool inWorld) {
    SurfaceContact sc;
    sc.point = eig(inWorld ? l.point : p.toWorld * l.point);
    sc.normal = eig(inWorld ? l.normal : p.toWorld.getBasis() * l.normal);
    sc.depth = radius - l.distance;
    sc.body = p.body;
    sc.friction = p.friction;
    out.push_back(sc);
  };
  for (const Part& p : s.parts) {
    if (p.kind == Kind::Plane) {  // the ground: one dot product, no box test
      LocalContact l = planeContact(p.dims, p.planeConstant, c);
      if (l.distance <= reach) emit(p, l, true);
      continue;
    }
    if (c.x() < p.lo.x() - reach || c.y() < p.lo.y() - reach || c.z() < p.lo.z() - reach ||
        c.x() > p.hi.x() + reach || c.y() > p.hi.y() + reach || c.z() > p.hi.z() + reach)
      continue;
    btVector3 lc = p.toLocal * c;
    LocalContact l;
    switch (p.kind) {
      case Kind::Box: l = boxContact(p.dims, lc); break;
      case Kind::Sphere: l = sphereContact(p.dims.x(), lc); break;
      case Kind::Cylinder: l = cylinderContact(p.axis, p.dims.x(), p.dims.y(), lc); break;
      case Kind::Capsule: l = capsuleContact(p.axis, p.dims.x(), p.dims.y(), lc); break;
      case Kind::Convex:
        if (p.hull && hullFaceContact(*p.hull, p.dims.x(), lc, l)) break;
        if (!convexContact(*static_cast<const btConvexShape*>(p.shape), lc, std::max(radius, 1e-6), l)) continue;
        break;
      case Kind::Concave:
      case Kind::HeightField:
        local.clear();
        concaveContacts(*static_cast<const btConcaveShape*>(p.shape), p.kind == Kind::HeightField, lc, reach, scratch,
                        local);
        for (const LocalContact& x : local) emit(p, x, false);
        continue;
      case Kind::Plane: break;
    }
    if (l.distance <= reach) emit(p, l, false);
  }
}

Eigen::Vector3d BulletSurfaces::velocity(int body, const Eigen::Vector3d& point) const {
  const Impl& s = *impl_;
  if (body < 0 || static_cast<std::size_t>(body) >= s.handles.size()) return Eigen::Vector3d::Zero();
  const Handle& h = s.handles[static_cast<std::size_t>(body)];
  if (h.rigid) return eig(h.rigid->getVelocityInLocalPoint(bt(point) - h.rigid->getCenterOfMassPosition()));
  btVector3 linear = h.linear, angular = h.angular, com = h.com;
  if (h.stamp != s.stamp) linkMotion(*h.multi, h.link, linear, angular, com);
  return eig(linear + angular.cross(bt(point) - com));
}

void BulletSurfaces::addForce(int body, const Eigen::Vector3d& point, const Eigen::Vector3d& force) {
  Impl& s = *impl_;
  if (body < 0 || static_cast<std::size_t>(body) >= s.handles.size()) return;
  Handle& h = s.handles[static_cast<std::size_t>(body)];
  btVector3 f = bt(force), p = bt(point);
  if (!h.takesForce || !finite(f) || !finite(p)) return;  // a non-finite particle is nonFinite()'s business
  h.force += f;
  h.torque += (p - centreOfMass(h, s.stamp)).cross(f);
  h.pending = true;
}

void BulletSurfaces::applyForces(double dt) {
  for (Handle& h : impl_->handles) {
    if (!h.pending) continue;
    btVector3 f = h.force, t = h.torque;
    h.force.setZero();
    h.torque.setZero();
    h.pending = false;
    if (!h.object->getBroadphaseHandle()) continue;  // left the world
    if (h.rigid) {
      btRigidBody& r = *h.rigid;
      if (!r.isActive()) {
        // A sleeping body wakes only for a push that would move it faster,
        // within this step, than Bullet's own test lets a body sleep at: a
        // bed resting on a sleeping box does not keep it awake for ever.
        double dv = f.length() * r.getInvMass() * dt;
        double dw = (r.getInvInertiaTensorWorld() * t).length() * dt;
        if (!(dv > r.getLinearSleepingThreshold() || dw > r.getAngularSleepingThreshold())) continue;
        r.activate(true);
      }
      r.applyCentralForce(f);
      r.applyTorque(t);
      continue;
    }
    btMultiBody& mb = *h.multi;
    if (h.link < 0) {
      mb.addBaseForce(f);
      mb.addBaseTorque(t);
    } else {
      mb.addLinkForce(h.link, f);
      mb.addLinkTorque(h.link, t);
    }
    if (!mb.isAwake()) mb.wakeUp();
  }
}

}  // namespace rscene::sim
