// A near callback for Bullet's dispatcher that leaves a broadphase pair's
// narrowphase uncalled when it could add nothing: the pair's contact
// manifolds hold no point and the two shapes' current bounding boxes
// (for a static plane, the other box's distance to the plane) are farther
// apart than any point Bullet would keep.
//
// Why: Bullet's broadphase keeps a pair while its fattened boxes overlap,
// and a static plane's box is unbounded, so every link of a robot pairs
// with the ground and many links pair with each other, every step.  Each
// of those runs the compound-shape algorithm (a tree walk, a box per
// child, a child algorithm each), which finds nothing for the links above
// the ground: about 45 pairs for 4 contacts on a standing ANYmal.
//
// Exactness: Bullet adds a point only closer than the manifold's
// contact-breaking threshold (the smaller of the two shapes' thresholds,
// CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD); a point lies on the shapes,
// inside their boxes (which include the collision margins); Bullet's
// turned queries against a plane move a point by at most
// gContactBreakingThreshold (convex_plane.hpp).  So when the boxes are
// farther apart than both together, Bullet's narrowphase adds nothing,
// and with no point in the pair's manifolds it has nothing to refresh or
// remove either.  Anything else runs Bullet's own callback.
// Bullet-facing: included only by lib/sim sources.
#pragma once
#include <btBulletCollisionCommon.h>

namespace rscene::sim {

void skipSeparatedPairs(btCollisionDispatcher& dispatcher);

// The callback's geometric test: whether the two objects' shapes are
// certainly farther apart than `reach` (their boxes, or a box's distance
// to a static plane or to the highest vertex of a height field under it).
// False when it cannot tell.  Exposed for its tests.
bool fartherApartThan(const btCollisionObject& a, const btCollisionObject& b, btScalar reach);

}  // namespace rscene::sim
