#include "sim/separated_pairs.hpp"

#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>
#include <LinearMath/btAabbUtil2.h>

#include <algorithm>
#include <cmath>

namespace rscene::sim {

namespace {

// How far below a static plane's surface the deepest point of `box` is
// not; that is, the box's least signed distance to the plane.
btScalar planeGap(const btCollisionObject& planeObject, const btVector3& boxMin, const btVector3& boxMax) {
  const auto& plane = static_cast<const btStaticPlaneShape&>(*planeObject.getCollisionShape());
  const btTransform& t = planeObject.getWorldTransform();
  btVector3 normal = t.getBasis() * plane.getPlaneNormal();
  btScalar constant = plane.getPlaneConstant() + normal.dot(t.getOrigin());
  btVector3 centre = (boxMin + boxMax) * btScalar(0.5), half = (boxMax - boxMin) * btScalar(0.5);
  btVector3 reach(btFabs(normal.x()) * half.x(), btFabs(normal.y()) * half.y(), btFabs(normal.z()) * half.z());
  return normal.dot(centre) - (reach.x() + reach.y() + reach.z()) - constant;
}

// How far `box` is above a height field (z up): the box's bottom against
// the highest vertex of the cells under its footprint widened by `reach`
// (a cell's two triangles lie below its highest corner).  A footprint off
// the field has no triangle under it.  -inf (no verdict) for another up
// axis, mirrored scaling, or a footprint of more than kMaxCells cells,
// where reading them would cost more than Bullet's own walk.
btScalar terrainGap(const btCollisionObject& terrainObject, const btVector3& boxMin, const btVector3& boxMax,
                    btScalar reach) {
  constexpr double kMaxCells = 256;
  const auto& field = static_cast<const btHeightfieldTerrainShape&>(*terrainObject.getCollisionShape());
  const btVector3 scale = field.getLocalScaling();
  if (field.getUpAxis() != 2 || scale.x() <= 0 || scale.y() <= 0) return -BT_LARGE_FLOAT;
  btVector3 lo, hi;
  btTransformAabb(boxMin, boxMax, 0, terrainObject.getWorldTransform().inverse(), lo, hi);
  // getVertex(x, y) is ((x - width / 2) sx, (y - length / 2) sy, h): its
  // first vertex gives the grid's size.
  btVector3 first;
  field.getVertex(0, 0, first);
  const btScalar width = std::round(-2 * first.x() / scale.x()), length = std::round(-2 * first.y() / scale.y());
  const btScalar x0 = std::floor((lo.x() - reach) / scale.x() + width / 2), x1 = std::ceil((hi.x() + reach) / scale.x() + width / 2);
  const btScalar y0 = std::floor((lo.y() - reach) / scale.y() + length / 2), y1 = std::ceil((hi.y() + reach) / scale.y() + length / 2);
  if (x1 < 0 || y1 < 0 || x0 > width || y0 > length) return BT_LARGE_FLOAT;
  const int ix0 = static_cast<int>(std::max<btScalar>(x0, 0)), ix1 = static_cast<int>(std::min(x1, width));
  const int iy0 = static_cast<int>(std::max<btScalar>(y0, 0)), iy1 = static_cast<int>(std::min(y1, length));
  if (double(ix1 - ix0 + 1) * double(iy1 - iy0 + 1) > kMaxCells) return -BT_LARGE_FLOAT;
  btScalar top = -BT_LARGE_FLOAT;
  btVector3 v;
  for (int y = iy0; y <= iy1; ++y)
    for (int x = ix0; x <= ix1; ++x) {
      field.getVertex(x, y, v);
      top = std::max(top, v.z());
    }
  return lo.z() - top - field.getMargin();
}

// The largest gap between two boxes along an axis (negative: they overlap).
btScalar boxGap(const btVector3& aMin, const btVector3& aMax, const btVector3& bMin, const btVector3& bMax) {
  btScalar gap = -BT_LARGE_FLOAT;
  for (int i = 0; i < 3; ++i) gap = std::max({gap, bMin[i] - aMax[i], aMin[i] - bMax[i]});
  return gap;
}

// An object's box: the one Bullet gave the broadphase this step (its
// shape's, widened by gContactBreakingThreshold: larger, so never a wrong
// skip) for an active object; a sleeping one's box is taken anew.
void boxOf(const btCollisionObject& o, btVector3& lo, btVector3& hi) {
  const btBroadphaseProxy* proxy = o.getBroadphaseHandle();
  if (proxy && o.isActive()) {
    lo = proxy->m_aabbMin;
    hi = proxy->m_aabbMax;
  } else {
    o.getCollisionShape()->getAabb(o.getWorldTransform(), lo, hi);
  }
}

int shapeType(const btCollisionObject& o) { return o.getCollisionShape()->getShapeType(); }
bool isGround(const btCollisionObject& o) {
  return shapeType(o) == STATIC_PLANE_PROXYTYPE || shapeType(o) == TERRAIN_SHAPE_PROXYTYPE;
}

}  // namespace

bool fartherApartThan(const btCollisionObject& a, const btCollisionObject& b, btScalar reach) {
  if (isGround(a) && isGround(b)) return false;
  const btCollisionObject& ground = isGround(a) ? a : b;
  const btCollisionObject& other = isGround(a) ? b : a;
  btVector3 lo, hi;
  boxOf(other, lo, hi);
  switch (shapeType(ground)) {
    case STATIC_PLANE_PROXYTYPE:
      return planeGap(ground, lo, hi) > reach + ground.getCollisionShape()->getMargin();
    case TERRAIN_SHAPE_PROXYTYPE:
      return terrainGap(ground, lo, hi, reach) > reach;
    default: {
      btVector3 groundLo, groundHi;
      boxOf(ground, groundLo, groundHi);
      return boxGap(lo, hi, groundLo, groundHi) > reach;
    }
  }
}

namespace {

// How many manifolds a pair must hold to be skipped: any (kAny) for a
// pair without a compound shape; one per child for a compound over a
// plane; none can do (kNever) for any other compound pair.  Bullet's
// compound algorithm makes a child algorithm (with its manifold) for a
// child whose box meets the other shape's box and removes one whose box
// no longer does, every step; a removal reorders the dispatcher's
// manifolds, and with them the solver's rows.  Over a plane (an unbounded
// box) every child meets it, so once every child holds its algorithm
// nothing changes.  Against anything else, finding out would cost a box
// per child every step, more than a skip saves (measured on 16 ANYmals on
// a height field), and pairs of compounds keep a child-pair cache Bullet
// also prunes: those go to Bullet.
constexpr int kAny = -1, kNever = -2;
int manifoldsNeeded(const btCollisionObject& a, const btCollisionObject& b) {
  const btCollisionShape& sa = *a.getCollisionShape();
  const btCollisionShape& sb = *b.getCollisionShape();
  if (!sa.isCompound() && !sb.isCompound()) return kAny;
  if (sa.isCompound() && sb.isCompound()) return kNever;
  const btCollisionObject& other = sa.isCompound() ? b : a;
  if (shapeType(other) != STATIC_PLANE_PROXYTYPE) return kNever;
  return static_cast<const btCompoundShape&>(sa.isCompound() ? sa : sb).getNumChildShapes();
}

// How near two shapes must come for Bullet to add a point to this pair:
// its manifolds' contact-breaking threshold (a compound pair has one per
// child pair, all alike; the dispatcher's rule when it has none yet),
// plus the reach of the turned plane queries.  Negative when the pair
// must go to Bullet: a manifold holds a point (Bullet must refresh it) or
// the pair holds other than `needed` manifolds.
btScalar reachOf(btCollisionAlgorithm& algorithm, const btCollisionObject& a, const btCollisionObject& b,
                 int needed) {
  thread_local btManifoldArray manifolds;
  manifolds.resize(0);
  algorithm.getAllContactManifolds(manifolds);
  if (needed != kAny && manifolds.size() != needed) return -1;
  btScalar threshold = 0;
  for (int i = 0; i < manifolds.size(); ++i) {
    if (manifolds[i]->getNumContacts() > 0) return -1;
    threshold = std::max(threshold, manifolds[i]->getContactBreakingThreshold());
  }
  if (manifolds.size() == 0)
    threshold = std::min(a.getCollisionShape()->getContactBreakingThreshold(gContactBreakingThreshold),
                         b.getCollisionShape()->getContactBreakingThreshold(gContactBreakingThreshold));
  return threshold + gContactBreakingThreshold;
}

void nearCallback(btBroadphasePair& pair, btCollisionDispatcher& dispatcher, const btDispatcherInfo& info) {
  const auto* a = static_cast<const btCollisionObject*>(pair.m_pProxy0->m_clientObject);
  const auto* b = static_cast<const btCollisionObject*>(pair.m_pProxy1->m_clientObject);
  if (pair.m_algorithm && info.m_dispatchFunc == btDispatcherInfo::DISPATCH_DISCRETE) {
    int needed = manifoldsNeeded(*a, *b);
    if (needed != kNever) {
      btScalar reach = reachOf(*pair.m_algorithm, *a, *b, needed);
      if (reach >= 0 && fartherApartThan(*a, *b, reach)) return;
    }
  }
  btCollisionDispatcher::defaultNearCallback(pair, dispatcher, info);
}

}  // namespace

void skipSeparatedPairs(btCollisionDispatcher& dispatcher) { dispatcher.setNearCallback(nearCallback); }

}  // namespace rscene::sim
