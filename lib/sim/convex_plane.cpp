// ConvexPlaneAlgorithm: Bullet's convex-plane algorithm, left uncalled
// when it could add no contact (convex_plane.hpp says why that is exact).
#include "sim/convex_plane.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionShapes/btConvexShape.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>

#include <algorithm>

namespace rscene::sim {

// The dispatcher's pool hands out elements at least the size of Bullet's
// own algorithm (its largest is convex-convex).
static_assert(sizeof(ConvexPlaneAlgorithm) <= sizeof(btConvexPlaneCollisionAlgorithm));

ConvexPlaneAlgorithm::ConvexPlaneAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, btCollisionAlgorithm* bullet,
                                           bool swapped)
    : btCollisionAlgorithm(ci), bullet_(bullet), swapped_(swapped) {
  btManifoldArray manifolds;
  bullet_->getAllContactManifolds(manifolds);  // its own, made in its constructor, kept for its life
  if (manifolds.size() == 1) manifold_ = manifolds[0];
}

ConvexPlaneAlgorithm::~ConvexPlaneAlgorithm() {
  bullet_->~btCollisionAlgorithm();
  m_dispatcher->freeCollisionAlgorithm(bullet_);
}

void ConvexPlaneAlgorithm::processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                                            const btDispatcherInfo& info, btManifoldResult* result) {
  if (manifold_ && manifold_->getNumContacts() == 0) {
    const btCollisionObjectWrapper* convexWrap = swapped_ ? body1 : body0;
    const btCollisionObjectWrapper* planeWrap = swapped_ ? body0 : body1;
    const auto* convex = static_cast<const btConvexShape*>(convexWrap->getCollisionShape());
    const auto* plane = static_cast<const btStaticPlaneShape*>(planeWrap->getCollisionShape());
    const btTransform& convexPose = convexWrap->getWorldTransform();
    const btTransform& planePose = planeWrap->getWorldTransform();
    const btVector3 normal = planePose.getBasis() * plane->getPlaneNormal();  // world
    // The deepest point: the support along -normal, in the convex's frame.
    const btVector3 deepest = convexPose(convex->localGetSupportingVertex((-normal) * convexPose.getBasis()));
    const btScalar distance = normal.dot(deepest - planePose.getOrigin()) - plane->getPlaneConstant();
    const btScalar threshold = manifold_->getContactBreakingThreshold() +
                               std::max(btScalar(0), result->m_closestPointDistanceThreshold) + gContactBreakingThreshold;
    if (distance > threshold) {
      result->setPersistentManifold(manifold_);  // as Bullet's does, whatever it finds
      return;
    }
  }
  bullet_->processCollision(body0, body1, info, result);
}

btCollisionAlgorithm* ConvexPlaneAlgorithm::CreateFunc::CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                                               const btCollisionObjectWrapper* body0,
                                                                               const btCollisionObjectWrapper* body1) {
  btCollisionAlgorithm* wrapped = bullet.CreateCollisionAlgorithm(ci, body0, body1);
  void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(ConvexPlaneAlgorithm));
  return new (mem) ConvexPlaneAlgorithm(ci, wrapped, m_swapped);
}

void useConvexPlaneAlgorithm(btCollisionDispatcher& dispatcher, ConvexPlaneAlgorithm::CreateFunc& convexPlane,
                             ConvexPlaneAlgorithm::CreateFunc& planeConvex, int perturbations, int minimumPoints) {
  for (ConvexPlaneAlgorithm::CreateFunc* f : {&convexPlane, &planeConvex}) {
    f->bullet.m_numPerturbationIterations = perturbations;
    f->bullet.m_minimumPointsPerturbationThreshold = minimumPoints;
  }
  convexPlane.m_swapped = convexPlane.bullet.m_swapped = false;
  planeConvex.m_swapped = planeConvex.bullet.m_swapped = true;
  for (int type = 0; type < MAX_BROADPHASE_COLLISION_TYPES; ++type) {
    if (!btBroadphaseProxy::isConvex(type)) continue;
    dispatcher.registerCollisionCreateFunc(type, STATIC_PLANE_PROXYTYPE, &convexPlane);
    dispatcher.registerCollisionCreateFunc(STATIC_PLANE_PROXYTYPE, type, &planeConvex);
  }
}

}  // namespace rscene::sim
