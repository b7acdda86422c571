#include "sim/separated_pairs.hpp"

#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>

#include <algorithm>

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

// The largest gap between two boxes along an axis (negative: they overlap).
btScalar boxGap(const btVector3& aMin, const btVector3& aMax, const btVector3& bMin, const btVector3& bMax) {
  btScalar gap = -BT_LARGE_FLOAT;
  for (int i = 0; i < 3; ++i) gap = std::max({gap, bMin[i] - aMax[i], aMin[i] - bMax[i]});
  return gap;
}

bool isPlane(const btCollisionObject& o) { return o.getCollisionShape()->getShapeType() == STATIC_PLANE_PROXYTYPE; }

// Whether the two shapes are farther apart than `reach`.
bool separated(const btCollisionObject& a, const btCollisionObject& b, btScalar reach) {
  if (isPlane(a) && isPlane(b)) return false;
  const btCollisionShape& sa = *a.getCollisionShape();
  const btCollisionShape& sb = *b.getCollisionShape();
  btVector3 aMin, aMax, bMin, bMax;
  if (isPlane(a)) {
    sb.getAabb(b.getWorldTransform(), bMin, bMax);
    return planeGap(a, bMin, bMax) > reach;
  }
  sa.getAabb(a.getWorldTransform(), aMin, aMax);
  if (isPlane(b)) return planeGap(b, aMin, aMax) > reach;
  sb.getAabb(b.getWorldTransform(), bMin, bMax);
  return boxGap(aMin, aMax, bMin, bMax) > reach;
}

// How near two shapes must come for Bullet to add a point to this pair:
// its manifolds' contact-breaking threshold (a compound pair has one per
// child pair, all alike; the dispatcher's rule when it has none yet),
// plus the reach of the turned plane queries.  Negative when a manifold
// holds a point: Bullet must refresh it.
btScalar reachOf(btCollisionAlgorithm& algorithm, const btCollisionObject& a, const btCollisionObject& b) {
  thread_local btManifoldArray manifolds;
  manifolds.resize(0);
  algorithm.getAllContactManifolds(manifolds);
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
    btScalar reach = reachOf(*pair.m_algorithm, *a, *b);
    if (reach >= 0 && separated(*a, *b, reach)) return;
  }
  btCollisionDispatcher::defaultNearCallback(pair, dispatcher, info);
}

}  // namespace

void skipSeparatedPairs(btCollisionDispatcher& dispatcher) { dispatcher.setNearCallback(nearCallback); }

}  // namespace rscene::sim
