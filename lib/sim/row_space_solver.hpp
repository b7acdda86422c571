// Bullet's multibody constraint solver with its iterations done in the
// space of its constraint rows (issue 26).
//
// Bullet solves a robot's contacts, joint limits and motors by projected
// Gauss-Seidel: for each row it takes the row's Jacobian (J, ndof + 6
// numbers) dotted with the robot's accumulated velocity change, computes
// the impulse change, clamps it, and adds the row's unit response
// (u = M^-1 J^T, ndof + 6 numbers) times that change back into the
// velocity change, twice (its own copy and the multibody's).  Three
// vectors of the robot's size per row, at 80 iterations by default: most
// of a standing robot's step.
//
// The velocity change is only ever read through rows' Jacobians, so the
// same iteration can run on the rows' velocities w = G lambda, where
// G_ij = J_i . u_j (the Delassus matrix of the rows, built once per solve
// from Bullet's own J and u).  A row then costs one column of G (the rows
// sharing a robot with it) instead of three robot-sized vectors.  Every
// other part is Bullet's, unchanged: the rows and their right-hand sides
// (setup), the order of rows (non-contact rows alternating direction by
// iteration parity, then normals, then the friction pairs), the impulse
// update and clamps, the implicit friction cone (Bullet's angle form is
// the radial projection written here without trigonometry), the residual
// and the stopping rule (iterations, tolerance), and the write-back
// (finish).  The solution is Bullet's up to rounding: the same physics,
// the same number of iterations.
//
// The row-space path is taken only where it is exactly that: rows whose
// other side is a multibody or a body that cannot move (a dynamic rigid
// body moves through Bullet's solver bodies, coupled to rigid contacts),
// no torsional or spinning friction rows, Bullet's two-direction cone
// friction, and no group of coupled rows above kMaxGroupRows (G is dense
// per group: bounded memory).  Anything else runs Bullet's own iteration.
// Bullet-facing: included only by lib/sim sources.
#pragma once
#include <btBulletDynamicsCommon.h>

#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>

#include <cstddef>
#include <vector>

#include "sim/joint_space_inertia.hpp"

namespace rscene::sim {

class RowSpaceSolver : public btMultiBodyConstraintSolver {
 public:
  // Rows coupled through robots beyond this (a pile of robots in contact)
  // leave the solve to Bullet: G would take rows^2 numbers.
  static constexpr std::size_t kMaxGroupRows = 512;

  // Off: every solve runs Bullet's own iteration (tests compare the two).
  void setEnabled(bool on) { enabled_ = on; }

  // Solves done, and how many of them in row space (for the tests).
  long solves() const { return solves_; }
  long rowSpaceSolves() const { return rowSpaceSolves_; }

 protected:
  btScalar solveGroupCacheFriendlySetup(btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds,
                                        int numManifolds, btTypedConstraint** constraints, int numConstraints,
                                        const btContactSolverInfo& info, btIDebugDraw* debugDrawer) override;
  btScalar solveSingleIteration(int iteration, btCollisionObject** bodies, int numBodies,
                                btPersistentManifold** manifolds, int numManifolds, btTypedConstraint** constraints,
                                int numConstraints, const btContactSolverInfo& info, btIDebugDraw* debugDrawer) override;
  btScalar solveGroupCacheFriendlyFinish(btCollisionObject** bodies, int numBodies,
                                         const btContactSolverInfo& info) override;
  // Contact rows of robots against robots or fixed bodies are set up here
  // (row_space_setup.cpp), each row's unit response from the robot's
  // factored joint-space inertia; every other row by Bullet.
  void convertContacts(btPersistentManifold** manifolds, int numManifolds, const btContactSolverInfo& info) override;

 private:
  // One multibody row: where its velocity and its column of G live, and
  // a copy of Bullet's numbers for it (the iterations read nothing else;
  // the finish writes impulse and limits back).
  struct Row {
    btMultiBodySolverConstraint* c = nullptr;
    std::size_t group = 0, local = 0;
    btScalar start = 0;  // its impulse when the iterations began (the finish applies the change)
    btScalar rhs = 0, cfm = 0, invDiag = 0, lower = 0, upper = 0, friction = 0, impulse = 0;
    btScalar* w = nullptr;            // its group's row velocities
    btScalar* self = nullptr;         // its own entry there
    const btScalar* column = nullptr;  // its column of G
    std::size_t n = 0;                // rows in its group
    std::size_t normal = 0;           // a friction row's normal row (index into rows_)
  };
  // Rows coupled through shared multibodies: G (column-major, rows x rows)
  // and the rows' velocities w = G lambda.
  struct Group {
    std::vector<std::size_t> rows;  // indices into rows_
    std::size_t offset = 0;         // of its G in gram_
    std::vector<btScalar> w;
  };

  // Setup (row_space_setup.cpp): Bullet's convertMultiBodyContact and
  // setupMultiBodyContactConstraint for the manifolds setupEligible()
  // accepts, with the unit responses from JointSpaceInertia.
  bool setupEligible(const btPersistentManifold& manifold, int solverBodyA, int solverBodyB) const;
  void convertRobotContact(btPersistentManifold* manifold, int solverBodyA, int solverBodyB,
                           const btContactSolverInfo& info);
  btMultiBodySolverConstraint& addRow(btMultiBodyConstraintArray& rows, btPersistentManifold* manifold,
                                      btManifoldPoint& cp, int solverBodyA, int solverBodyB);
  void setupContactRow(btMultiBodySolverConstraint& c, const btVector3& normal, btManifoldPoint& cp,
                       const btContactSolverInfo& info, bool isFriction);
  // A multibody side of a row: its velocity slot, Jacobian and unit
  // response, or only its first half z = L^-T J^T (see halfRows_).
  void setupSide(btMultiBody* mb, int link, const btVector3& point, const btVector3& normal, int& slot, int& jac);
  const JointSpaceInertia* inertiaAt(btMultiBody* mb, int slot);
  // The last velocity of a half-solved row side's path (see halfRows_), -1 for a full response.
  int halfPathEnd(int jac) const {
    return static_cast<std::size_t>(jac) < halfPathEnd_.size() ? halfPathEnd_[static_cast<std::size_t>(jac)] : -1;
  }
  bool holdsHalf(int jac) const { return halfPathEnd(jac) >= 0; }
  const JointSpaceInertia& inertiaOfSlot(int slot) const {
    return inertias_[static_cast<std::size_t>(inertiaOfSlot_[static_cast<std::size_t>(slot)])];
  }
  // Completes every half-solved response (u = L^-1 z) for Bullet's iteration.
  void completeUnitResponses();

  bool eligible(const btContactSolverInfo& info) const;
  bool sideIsFixed(btMultiBody* mb, int solverBody) const;
  bool build();
  // Bullet's generic row update; returns the row's velocity residual.
  static btScalar solveRow(Row& r);
  // Bullet's two friction rows of one contact, clamped to the cone.
  static btScalar solveFrictionPair(Row& a, Row& b);

  bool enabled_ = true, active_ = false;
  long solves_ = 0, rowSpaceSolves_ = 0;
  std::size_t nonContact_ = 0, normal_ = 0, friction_ = 0;  // row counts, in that order in rows_
  std::vector<Row> rows_;
  std::vector<Group> groups_;  // the first groupCount_ are this solve's (the rest keep their buffers)
  std::size_t groupCount_ = 0;
  std::vector<btScalar> gram_;
  std::vector<std::size_t> parent_, owner_, groupOf_;  // build()'s work space, kept between solves
  struct RowSide {  // a row's multibody side: where its numbers live
    btMultiBody* mb;
    int slot, ndof, halfPathEnd;        // halfPathEnd: see halfPathEnd()
    const btScalar* jacobian;
    btScalar* response;                 // u, or z for a half-solved side
    const JointSpaceInertia* inertia;  // for a half-solved side
  };
  std::vector<RowSide> rowSides_;      // two per row of rows_ (count in rowSideCount_)
  std::vector<int> rowSideCount_;
  // This solve's factored robots, found by velocity slot (-1: not yet,
  // -2: Bullet's pass); the vector keeps its buffers between solves.
  std::vector<JointSpaceInertia> inertias_;
  std::size_t inertiaCount_ = 0;
  std::vector<int> inertiaOfSlot_;
  // Rows set up here keep z = L^-T J^T where Bullet keeps u = M^-1 J^T:
  // G_ij = z_i . z_j, and the velocity change L^-1 (sum z_i dlambda_i) is
  // one second half per robot at the finish instead of one per row.  Where
  // Bullet's own iteration runs instead, completeUnitResponses() makes them u.
  struct HalfRow {
    int jac, slot;
  };
  std::vector<HalfRow> halfRows_;
  std::vector<int> halfPathEnd_;             // by Jacobian index, -1: not half-solved
  std::vector<btScalar> finishSum_;          // by velocity slot: sum of z dlambda
  std::vector<const RowSide*> summed_;       // by factor: a side of a robot with a sum, else null
};

}  // namespace rscene::sim
