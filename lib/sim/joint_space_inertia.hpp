// A robot's joint-space inertia M, factored once per solve, so that each
// constraint row's unit response u = M^-1 J^T costs two sparse triangular
// solves instead of an articulated-body pass over every link (issue 26).
//
// Bullet computes a row's unit response with calcAccelerationDeltasMultiDof:
// a backward and a forward pass over all the robot's links, each a chain of
// spatial transforms, once per row (three per contact).  That was the
// largest item of a standing robot's step.  Here M is built by the
// composite-rigid-body algorithm in Bullet's own coordinates (base angular
// and linear velocity in world axes, then the joints' velocities), and
// factored as M = L^T L with L keeping the tree's sparsity (Featherstone,
// Rigid Body Dynamics Algorithms, section 6.5): L's row for a velocity
// holds only that velocity and its ancestors', so a row touching one leg
// costs a few dozen products.  The result is M^-1 J^T, the same vector as
// Bullet's pass, to rounding (tests compare the two on random trees).
//
// Built from what Bullet keeps for the step: base pose, each link's cached
// rotation and offset from its parent, mass, diagonal inertia and joint
// axes.  Robots it does not model (kinematic links) report false from
// factor(); the caller then uses Bullet's own pass.
// Bullet-facing: included only by lib/sim sources.
#pragma once
#include <btBulletDynamicsCommon.h>

#include <BulletDynamics/Featherstone/btMultiBody.h>

#include <vector>

namespace rscene::sim {

class JointSpaceInertia {
 public:
  // Builds and factors M for mb's current state.  False when mb has a
  // kinematic link, more than kMaxSize velocities, a tree so deep that
  // factoring costs more than a few of Bullet's passes (kMaxWorkPerBody),
  // or M is not positive definite; the caller then uses Bullet's pass.
  bool factor(const btMultiBody& mb);

  // out = M^-1 in, both of the robot's velocity size (getNumDofs() + 6,
  // Bullet's layout); a fixed or kinematic base gets zero in its six.
  void solve(const btScalar* in, btScalar* out) const;
  // The two halves of solve(): out = L^-T in, then x = L^-1 x in place.
  // For rows i and j, (L^-T J_i^T) . (L^-T J_j^T) = J_i M^-1 J_j^T, and
  // the first half touches only the velocities on a row's path.
  void solveFirstHalf(const btScalar* in, btScalar* out) const;
  void solveSecondHalf(btScalar* x) const;
  // solveFirstHalf for an `in` that is zero off the path ending at `end`
  // (a contact Jacobian, see pathEnd()): only the path is visited.
  void solvePathFirstHalf(int end, const btScalar* in, btScalar* out) const;

  // The Jacobian row of a contact at `point` (world) on `link` (-1 the
  // base) along `normal`, as Bullet's fillContactJacobianMultiDof writes it
  // (zero off the link's path to the root), from the twists of factor().
  void contactJacobian(int link, const btVector3& point, const btVector3& normal, btScalar* out) const;

  // The last velocity on `link`'s path to the root (-1 the base): a
  // contact row's Jacobian, and its first half, are zero off that velocity
  // and its ancestors.
  int pathEnd(int link) const { return lastOf_[static_cast<std::size_t>(link + 1)]; }
  // a . b over the path ending at `end` (exact when either is zero off it).
  btScalar pathDot(int end, const btScalar* a, const btScalar* b) const;

  int size() const { return n_; }
  // Whether mb has the tree this one last factored (its work space fits).
  bool sameTopology(const btMultiBody& mb) const;

  // Robots larger than this keep Bullet's pass (bounded memory).
  static constexpr int kMaxSize = 256;
  // Factoring costs about sum over velocities of (ancestors + 1)^2 products;
  // one of Bullet's passes about a few hundred per body.  A long chain
  // (sum ~ n^3 / 3) would cost more than the passes it saves: above this
  // many products per body, Bullet's pass it is.
  static constexpr long kMaxWorkPerBody = 256;

 private:
  // One link (or the base): its axes and centre of mass, then the inertia
  // of the subtree it heads, all about the base's centre of mass in world
  // axes (positions near the robot, not near the world's origin).
  struct Body {
    btQuaternion rotation;  // world vectors into its axes, as Bullet composes them
    btMatrix3x3 fromWorld;  // the same as a matrix
    btVector3 com;
    btScalar mass = 0;
    btVector3 moment;      // mass times centre of mass
    btScalar inertia[6];   // rotational inertia about the base's centre of mass: xx yy zz xy xz yz
  };
  // The tree of velocities, rebuilt only when the robot's shape changes:
  // velocity k's ancestors, nearest first, are ancestors_[start_[k]] to
  // ancestors_[start_[k + 1] - 1] (the base's six form a chain, angular
  // first; a velocity's parent is the previous one of its joint, else the
  // last of the nearest ancestor link that moves).  An ancestor's own list
  // is the rest of the list after it, which the factorization relies on.
  void buildTopology(const btMultiBody& mb);
  void eliminate(int k, btScalar* out) const;  // one step of the first half

  int n_ = 0;
  bool fixedBase_ = false;
  std::vector<int> topology_;  // (parent, dofs) of each link, to notice a different robot
  std::vector<int> start_, ancestors_, bodyOf_, lastOf_;  // lastOf_: each body's last velocity
  long work_ = 0;  // sum of (ancestors + 1)^2 over velocities
  // Per factor(): poses, twists (6 numbers each: angular, then linear at
  // the base's centre of mass), then M and, in place, L = its factor
  // (M = L^T L): diagonal_, and value_ beside ancestors_.
  std::vector<Body> bodies_;
  std::vector<btScalar> twists_, diagonal_, inverseDiagonal_, value_;
  btVector3 origin_;  // the base's centre of mass, world
};

}  // namespace rscene::sim
