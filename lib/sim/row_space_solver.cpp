#include "sim/row_space_solver.hpp"

#include <BulletDynamics/Featherstone/btMultiBody.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace rscene::sim {

namespace {

// The multibody sides of a row: (multibody, Jacobian index, velocity slot).
struct Side {
  btMultiBody* mb;
  int jac, slot;
};

int sidesOf(const btMultiBodySolverConstraint& c, Side out[2]) {
  int n = 0;
  if (c.m_multiBodyA) out[n++] = {c.m_multiBodyA, c.m_jacAindex, c.m_deltaVelAindex};
  if (c.m_multiBodyB) out[n++] = {c.m_multiBodyB, c.m_jacBindex, c.m_deltaVelBindex};
  return n;
}

int ndofOf(const btMultiBody* mb) { return mb->getNumDofs() + 6; }

std::size_t root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

btScalar RowSpaceSolver::solveGroupCacheFriendlySetup(btCollisionObject** bodies, int numBodies,
                                                      btPersistentManifold** manifolds, int numManifolds,
                                                      btTypedConstraint** constraints, int numConstraints,
                                                      const btContactSolverInfo& info, btIDebugDraw* debugDrawer) {
  btScalar r = btMultiBodyConstraintSolver::solveGroupCacheFriendlySetup(bodies, numBodies, manifolds, numManifolds,
                                                                         constraints, numConstraints, info, debugDrawer);
  ++solves_;
  active_ = enabled_ && eligible(info) && build();
  if (active_) ++rowSpaceSolves_;
  return r;
}

// A side without a multibody adds nothing to a row's velocity when its
// solver body cannot move (the ground, a static or kinematic body, none).
bool RowSpaceSolver::sideIsFixed(btMultiBody* mb, int solverBody) const {
  if (mb || solverBody < 0) return true;
  const btSolverBody& b = m_tmpSolverBodyPool[solverBody];
  return !b.m_originalBody || b.m_originalBody->getInvMass() == btScalar(0);
}

bool RowSpaceSolver::eligible(const btContactSolverInfo& info) const {
  bool cone = (info.m_solverMode & SOLVER_USE_2_FRICTION_DIRECTIONS) &&
              !(info.m_solverMode & SOLVER_DISABLE_IMPLICIT_CONE_FRICTION);
  if (!cone || m_multiBodyTorsionalFrictionContactConstraints.size() > 0 ||
      m_multiBodySpinningFrictionContactConstraints.size() > 0)
    return false;
  if (m_multiBodyFrictionContactConstraints.size() != 2 * m_multiBodyNormalContactConstraints.size()) return false;
  for (const btMultiBodyConstraintArray* rows :
       {&m_multiBodyNonContactConstraints, &m_multiBodyNormalContactConstraints, &m_multiBodyFrictionContactConstraints})
    for (int i = 0; i < rows->size(); ++i) {
      const btMultiBodySolverConstraint& c = (*rows)[i];
      if (!sideIsFixed(c.m_multiBodyA, c.m_solverBodyIdA) || !sideIsFixed(c.m_multiBodyB, c.m_solverBodyIdB))
        return false;
      if (!c.m_multiBodyA && !c.m_multiBodyB) return false;
    }
  for (int i = 0; i + 1 < m_multiBodyFrictionContactConstraints.size(); i += 2)
    if (m_multiBodyFrictionContactConstraints[i].m_frictionIndex !=
        m_multiBodyFrictionContactConstraints[i + 1].m_frictionIndex)
      return false;
  return true;
}

bool RowSpaceSolver::build() {
  rows_.clear();
  groupCount_ = 0;
  nonContact_ = static_cast<std::size_t>(m_multiBodyNonContactConstraints.size());
  normal_ = static_cast<std::size_t>(m_multiBodyNormalContactConstraints.size());
  friction_ = static_cast<std::size_t>(m_multiBodyFrictionContactConstraints.size());
  for (btMultiBodyConstraintArray* rows :
       {&m_multiBodyNonContactConstraints, &m_multiBodyNormalContactConstraints, &m_multiBodyFrictionContactConstraints})
    for (int i = 0; i < rows->size(); ++i) rows_.push_back({&(*rows)[i], 0, 0, (*rows)[i].m_appliedImpulse});
  if (rows_.empty()) return true;

  // Groups: rows joined by a multibody they share (its velocity slot).
  std::size_t none = rows_.size();
  parent_.resize(rows_.size());
  std::iota(parent_.begin(), parent_.end(), std::size_t{0});
  owner_.assign(static_cast<std::size_t>(m_data.m_deltaVelocities.size()), none);
  Side sides[2];
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    int n = sidesOf(*rows_[r].c, sides);
    for (int s = 0; s < n; ++s) {
      auto slot = static_cast<std::size_t>(sides[s].slot);
      if (slot >= owner_.size()) return false;
      if (owner_[slot] == none)
        owner_[slot] = r;
      else
        parent_[root(parent_, r)] = root(parent_, owner_[slot]);
    }
  }
  groupOf_.assign(rows_.size(), none);
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    std::size_t top = root(parent_, r);
    if (groupOf_[top] == none) {
      groupOf_[top] = groupCount_;
      if (groupCount_ == groups_.size()) groups_.emplace_back();
      groups_[groupCount_++].rows.clear();
    }
    Group& g = groups_[groupOf_[top]];
    rows_[r].group = groupOf_[top];
    rows_[r].local = g.rows.size();
    g.rows.push_back(r);
    if (g.rows.size() > kMaxGroupRows) return false;
  }

  // G_ij = J_i . u_j over the multibodies the two rows share, column j
  // contiguous (a row's update walks its column).  J_i M^-1 J_j^T is
  // symmetric: each pair is computed once.
  std::size_t total = 0;
  for (std::size_t k = 0; k < groupCount_; ++k) {
    Group& g = groups_[k];
    g.offset = total;
    total += g.rows.size() * g.rows.size();
  }
  gram_.assign(total, btScalar(0));
  const btScalar* jac = &m_data.m_jacobians[0];
  const btScalar* unit = &m_data.m_deltaVelocitiesUnitImpulse[0];
  for (std::size_t k = 0; k < groupCount_; ++k) {
    Group& g = groups_[k];
    std::size_t n = g.rows.size();
    for (std::size_t b = 0; b < n; ++b) {
      Side sb[2];
      int nb = sidesOf(*rows_[g.rows[b]].c, sb);
      btScalar* column = &gram_[g.offset + b * n];
      for (std::size_t a = 0; a <= b; ++a) {
        Side sa[2];
        int na = sidesOf(*rows_[g.rows[a]].c, sa);
        btScalar v = 0;
        for (int i = 0; i < na; ++i)
          for (int j = 0; j < nb; ++j) {
            if (sa[i].slot != sb[j].slot) continue;
            const btScalar* x = jac + sa[i].jac;
            const btScalar* y = unit + sb[j].jac;
            for (int k = 0, nd = ndofOf(sa[i].mb); k < nd; ++k) v += x[k] * y[k];
          }
        column[a] = v;
        gram_[g.offset + a * n + b] = v;
      }
    }
    g.w.assign(n, btScalar(0));
    for (std::size_t b = 0; b < n; ++b) {
      btScalar impulse = rows_[g.rows[b]].start;
      if (impulse == 0) continue;
      const btScalar* column = &gram_[g.offset + b * n];
      for (std::size_t a = 0; a < n; ++a) g.w[a] += column[a] * impulse;
    }
  }
  return true;
}

void RowSpaceSolver::apply(std::size_t r, btScalar delta) {
  Group& g = groups_[rows_[r].group];
  std::size_t n = g.rows.size();
  const btScalar* column = &gram_[g.offset + rows_[r].local * n];
  btScalar* w = g.w.data();
  for (std::size_t a = 0; a < n; ++a) w[a] += column[a] * delta;
}

btScalar RowSpaceSolver::solveRow(std::size_t r) {
  btMultiBodySolverConstraint& c = *rows_[r].c;
  btScalar w = groups_[rows_[r].group].w[rows_[r].local];
  btScalar delta = c.m_rhs - c.m_appliedImpulse * c.m_cfm - w * c.m_jacDiagABInv;
  btScalar sum = c.m_appliedImpulse + delta;
  if (sum < c.m_lowerLimit) {
    delta = c.m_lowerLimit - c.m_appliedImpulse;
    c.m_appliedImpulse = c.m_lowerLimit;
  } else if (sum > c.m_upperLimit) {
    delta = c.m_upperLimit - c.m_appliedImpulse;
    c.m_appliedImpulse = c.m_upperLimit;
  } else {
    c.m_appliedImpulse = sum;
  }
  apply(r, delta);
  return delta / c.m_jacDiagABInv;
}

// Both rows' unclamped impulses first; when their vector leaves the cone
// of radius |lower| it is scaled back onto it (Bullet's clamp by the sine
// and cosine of its angle, which is the same point).
btScalar RowSpaceSolver::solveFrictionPair(std::size_t ra, std::size_t rb) {
  btMultiBodySolverConstraint& a = *rows_[ra].c;
  btMultiBodySolverConstraint& b = *rows_[rb].c;
  auto unclamped = [this](std::size_t r, const btMultiBodySolverConstraint& c) {
    btScalar w = groups_[rows_[r].group].w[rows_[r].local];
    return c.m_appliedImpulse + (c.m_rhs - c.m_appliedImpulse * c.m_cfm - w * c.m_jacDiagABInv);
  };
  btScalar sumB = unclamped(rb, b);
  btScalar sumA = unclamped(ra, a);
  btScalar newA = sumA, newB = sumB;
  btScalar radius2 = sumA * sumA + sumB * sumB;
  if (radius2 >= a.m_lowerLimit * b.m_lowerLimit) {
    btScalar radius = std::sqrt(radius2);
    btScalar limitA = std::fabs(a.m_lowerLimit), limitB = std::fabs(b.m_lowerLimit);
    if (radius == 0) {
      newA = newB = 0;
    } else {
      if (limitA < radius) newA = sumA * (limitA / radius);
      if (limitB < radius) newB = sumB * (limitB / radius);
    }
  }
  btScalar deltaA = newA - a.m_appliedImpulse, deltaB = newB - b.m_appliedImpulse;
  a.m_appliedImpulse = newA;
  b.m_appliedImpulse = newB;
  apply(ra, deltaA);
  apply(rb, deltaB);
  return deltaA / a.m_jacDiagABInv + deltaB / b.m_jacDiagABInv;
}

btScalar RowSpaceSolver::solveSingleIteration(int iteration, btCollisionObject** bodies, int numBodies,
                                              btPersistentManifold** manifolds, int numManifolds,
                                              btTypedConstraint** constraints, int numConstraints,
                                              const btContactSolverInfo& info, btIDebugDraw* debugDrawer) {
  if (!active_)
    return btMultiBodyConstraintSolver::solveSingleIteration(iteration, bodies, numBodies, manifolds, numManifolds,
                                                             constraints, numConstraints, info, debugDrawer);
  // Rigid bodies' own rows (none of them shares a body with the rows here).
  btScalar residual = btSequentialImpulseConstraintSolver::solveSingleIteration(
      iteration, bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debugDrawer);
  btScalar nonContactResidual = 0;
  for (int inner = 0; inner < info.m_numNonContactInnerIterations; ++inner) {
    nonContactResidual = 0;
    for (std::size_t j = 0; j < nonContact_; ++j) {
      std::size_t r = (iteration & 1) ? j : nonContact_ - 1 - j;
      btScalar v = solveRow(r);
      nonContactResidual = std::max(nonContactResidual, v * v);
    }
  }
  residual = std::max(residual, nonContactResidual);
  if (iteration >= info.m_numIterations) return residual;
  for (std::size_t j = 0; j < normal_; ++j) {
    btScalar v = solveRow(nonContact_ + j);
    residual = std::max(residual, v * v);
  }
  std::size_t first = nonContact_ + normal_;
  for (std::size_t j = 0; j + 1 < friction_; j += 2) {
    btMultiBodySolverConstraint& a = *rows_[first + j].c;
    btMultiBodySolverConstraint& b = *rows_[first + j + 1].c;
    btScalar normalImpulse = m_multiBodyNormalContactConstraints[a.m_frictionIndex].m_appliedImpulse;
    a.m_lowerLimit = -(a.m_friction * normalImpulse);
    a.m_upperLimit = a.m_friction * normalImpulse;
    b.m_lowerLimit = -(b.m_friction * normalImpulse);
    b.m_upperLimit = b.m_friction * normalImpulse;
    btScalar v = solveFrictionPair(first + j, first + j + 1);
    residual = std::max(residual, v * v);
  }
  return residual;
}

// The iterations changed only impulses and row velocities: the multibodies
// get their velocity change now, each row's impulse change times its unit
// response, as Bullet would have added it row by row.
btScalar RowSpaceSolver::solveGroupCacheFriendlyFinish(btCollisionObject** bodies, int numBodies,
                                                       const btContactSolverInfo& info) {
  if (active_) {
    for (Row& row : rows_) {
      btMultiBodySolverConstraint& c = *row.c;
      btScalar change = c.m_appliedImpulse - row.start;
      Side sides[2];
      int n = sidesOf(c, sides);
      for (int s = 0; s < n; ++s) {
        if (change != 0) {
          btScalar* unit = &m_data.m_deltaVelocitiesUnitImpulse[sides[s].jac];
          sides[s].mb->applyDeltaVeeMultiDof2(unit, change);
          applyDeltaVee(unit, change, sides[s].slot, ndofOf(sides[s].mb));
        }
        sides[s].mb->setPosUpdated(false);
      }
    }
    active_ = false;
  }
  return btMultiBodyConstraintSolver::solveGroupCacheFriendlyFinish(bodies, numBodies, info);
}

}  // namespace rscene::sim
