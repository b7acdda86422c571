// Convex shape against a static plane: Bullet's own
// btConvexPlaneCollisionAlgorithm (the system library's, made by its
// CreateFunc), behind a wrapper that leaves it uncalled when it could add
// nothing.  Bullet's algorithm, for a polyhedral shape (box, hull) whose
// manifold holds fewer than the minimum points, also queries the shape
// turned by a small angle `numPerturbationIterations` times, every step,
// however far above the plane the shape is: for a robot's boxes that is
// most of the time spent against the ground.
//
// The wrapper first finds the shape's deepest point toward the plane (its
// support along the plane's normal, public shape API) and, when that
// point is farther than the manifold's contact-breaking threshold (plus
// the result's closest-point distance and a margin, below) and the
// manifold holds no point, only sets the result's manifold as Bullet
// would and returns.  Bullet would have added nothing: its unturned query
// is that same point, past its threshold; each turned query takes another
// point of the same shape (its support in a turned direction) and
// measures it in the unturned pose, so never nearer than the deepest
// point; and with no point in the manifold Bullet refreshes nothing.  The
// margin, gContactBreakingThreshold, bounds how far a turned query's
// rotation could move a point (bounding radius times the turn angle,
// which Bullet sets to gContactBreakingThreshold / radius at most), far
// above rounding.  Otherwise Bullet's algorithm runs as is.
// Bullet-facing: included only by lib/sim sources.
#pragma once
#include <btBulletCollisionCommon.h>

#include <BulletCollision/CollisionDispatch/btConvexPlaneCollisionAlgorithm.h>

namespace rscene::sim {

class ConvexPlaneAlgorithm : public btCollisionAlgorithm {
 public:
  // Takes `bullet` (made by the dispatcher's allocator); swapped: the plane
  // is body0.
  ConvexPlaneAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, btCollisionAlgorithm* bullet, bool swapped);
  ~ConvexPlaneAlgorithm() override;

  void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                        const btDispatcherInfo& info, btManifoldResult* result) override;
  btScalar calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1, const btDispatcherInfo& info,
                                 btManifoldResult* result) override {
    return bullet_->calculateTimeOfImpact(body0, body1, info, result);
  }
  void getAllContactManifolds(btManifoldArray& manifolds) override { bullet_->getAllContactManifolds(manifolds); }

  struct CreateFunc : btCollisionAlgorithmCreateFunc {
    btConvexPlaneCollisionAlgorithm::CreateFunc bullet;  // makes the algorithm wrapped
    btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                   const btCollisionObjectWrapper* body0,
                                                   const btCollisionObjectWrapper* body1) override;
  };

 private:
  btCollisionAlgorithm* bullet_;
  btPersistentManifold* manifold_ = nullptr;  // bullet_'s own; none when the pair needs no collision
  bool swapped_;
};

// Puts ConvexPlaneAlgorithm in place of Bullet's for every convex shape
// type against a static plane, both ways round, wrapping Bullet's made
// with the settings of btCollisionConfiguration::setPlaneConvexMultipointIterations.
// The create functions must outlive the dispatcher's use of them.
void useConvexPlaneAlgorithm(btCollisionDispatcher& dispatcher, ConvexPlaneAlgorithm::CreateFunc& convexPlane,
                             ConvexPlaneAlgorithm::CreateFunc& planeConvex, int perturbations, int minimumPoints);

}  // namespace rscene::sim
