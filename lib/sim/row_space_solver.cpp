#include "sim/row_space_solver.hpp"

#include <BulletDynamics/Featherstone/btMultiBody.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

namespace rscene::sim {

namespace {

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
  if (active_)
    ++rowSpaceSolves_;
  else
    completeUnitResponses();
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

  // Each row's multibody sides (the finish reads them too).
  const btScalar* jac = &m_data.m_jacobians[0];
  btScalar* unit = &m_data.m_deltaVelocitiesUnitImpulse[0];
  rowSides_.resize(2 * rows_.size());
  rowSideCount_.assign(rows_.size(), 0);
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    const btMultiBodySolverConstraint& c = *rows_[r].c;
    for (auto [mb, jacIndex, slot] : {std::tuple{c.m_multiBodyA, c.m_jacAindex, c.m_deltaVelAindex},
                                      std::tuple{c.m_multiBodyB, c.m_jacBindex, c.m_deltaVelBindex}}) {
      if (!mb) continue;
      int end = halfPathEnd(jacIndex);
      rowSides_[2 * r + static_cast<std::size_t>(rowSideCount_[r]++)] = {
          mb, slot, ndofOf(mb), end, jac + jacIndex, unit + jacIndex, end >= 0 ? &inertiaOfSlot(slot) : nullptr};
    }
  }
  auto sidesOf = [this](std::size_t r) {
    const RowSide* first = &rowSides_[2 * r];
    return std::pair{first, first + rowSideCount_[r]};
  };

  // Groups: rows joined by a multibody they share (its velocity slot).
  std::size_t none = rows_.size();
  parent_.resize(rows_.size());
  std::iota(parent_.begin(), parent_.end(), std::size_t{0});
  owner_.assign(static_cast<std::size_t>(m_data.m_deltaVelocities.size()), none);
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    auto [begin, end] = sidesOf(r);
    for (const RowSide* side = begin; side != end; ++side) {
      auto slot = static_cast<std::size_t>(side->slot);
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
  // One pair of sides on the same robot: z_a . z_b over a's path when both
  // are half-solved (exact: z_b is zero off b's path), else J . u with u
  // the full response.
  auto entry = [](const RowSide& a, const RowSide& b) {
    if (a.halfPathEnd >= 0 && b.halfPathEnd >= 0) return a.inertia->pathDot(a.halfPathEnd, a.response, b.response);
    const btScalar* x = (b.halfPathEnd >= 0 ? b : a).jacobian;
    const btScalar* u = (b.halfPathEnd >= 0 ? a : b).response;
    btScalar v = 0;
    for (int k = 0; k < a.ndof; ++k) v += x[k] * u[k];
    return v;
  };
  for (std::size_t k = 0; k < groupCount_; ++k) {
    Group& g = groups_[k];
    std::size_t n = g.rows.size();
    for (std::size_t b = 0; b < n; ++b) {
      const std::size_t rb = g.rows[b];
      btScalar* column = &gram_[g.offset + b * n];
      for (std::size_t a = 0; a <= b; ++a) {
        const std::size_t ra = g.rows[a];
        btScalar v = 0;
        auto [beginA, endA] = sidesOf(ra);
        auto [beginB, endB] = sidesOf(rb);
        for (const RowSide* sa = beginA; sa != endA; ++sa)
          for (const RowSide* sb = beginB; sb != endB; ++sb)
            if (sa->slot == sb->slot) v += entry(*sa, *sb);
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
  // Each row's numbers beside its place in G and w, for the iterations.
  for (Row& r : rows_) {
    const btMultiBodySolverConstraint& c = *r.c;
    Group& g = groups_[r.group];
    r.rhs = c.m_rhs;
    r.cfm = c.m_cfm;
    r.invDiag = c.m_jacDiagABInv;
    r.lower = c.m_lowerLimit;
    r.upper = c.m_upperLimit;
    r.friction = c.m_friction;
    r.impulse = c.m_appliedImpulse;
    r.n = g.rows.size();
    r.w = g.w.data();
    r.self = r.w + r.local;
    r.column = &gram_[g.offset + r.local * r.n];
  }
  for (std::size_t j = 0; j < friction_; ++j) {
    Row& r = rows_[nonContact_ + normal_ + j];
    r.normal = nonContact_ + static_cast<std::size_t>(r.c->m_frictionIndex);
  }
  return true;
}

// Bullet's generic row update (resolveSingleConstraintRowGeneric) on the
// row's copy of its numbers.
btScalar RowSpaceSolver::solveRow(Row& r) {
  btScalar delta = r.rhs - r.impulse * r.cfm - *r.self * r.invDiag;
  btScalar sum = r.impulse + delta;
  if (sum < r.lower) {
    delta = r.lower - r.impulse;
    r.impulse = r.lower;
  } else if (sum > r.upper) {
    delta = r.upper - r.impulse;
    r.impulse = r.upper;
  } else {
    r.impulse = sum;
  }
  // w and G never overlap (separate buffers): restrict lets the loop vectorise.
  btScalar* __restrict w = r.w;
  const btScalar* __restrict column = r.column;
  for (std::size_t k = 0, n = r.n; k < n; ++k) w[k] += column[k] * delta;
  return delta / r.invDiag;
}

// Both rows' unclamped impulses first; when their vector leaves the cone
// of radius |lower| it is scaled back onto it (Bullet's clamp by the sine
// and cosine of its angle, which is the same point).
btScalar RowSpaceSolver::solveFrictionPair(Row& a, Row& b) {
  btScalar sumB = b.impulse + (b.rhs - b.impulse * b.cfm - *b.self * b.invDiag);
  btScalar sumA = a.impulse + (a.rhs - a.impulse * a.cfm - *a.self * a.invDiag);
  btScalar newA = sumA, newB = sumB;
  btScalar radius2 = sumA * sumA + sumB * sumB;
  if (radius2 >= a.lower * b.lower) {
    btScalar radius = std::sqrt(radius2);
    btScalar limitA = std::fabs(a.lower), limitB = std::fabs(b.lower);
    if (radius == 0) {
      newA = newB = 0;
    } else {
      if (limitA < radius) newA = sumA * (limitA / radius);
      if (limitB < radius) newB = sumB * (limitB / radius);
    }
  }
  btScalar deltaA = newA - a.impulse, deltaB = newB - b.impulse;
  a.impulse = newA;
  b.impulse = newB;
  // Both columns in one pass (the two rows of a contact share its group).
  btScalar* __restrict w = a.w;
  const btScalar* __restrict columnA = a.column;
  const btScalar* __restrict columnB = b.column;
  for (std::size_t k = 0, n = a.n; k < n; ++k) w[k] += columnA[k] * deltaA + columnB[k] * deltaB;
  return deltaA / a.invDiag + deltaB / b.invDiag;
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
      btScalar v = solveRow(rows_[r]);
      nonContactResidual = std::max(nonContactResidual, v * v);
    }
  }
  residual = std::max(residual, nonContactResidual);
  if (iteration >= info.m_numIterations) return residual;
  for (std::size_t j = 0; j < normal_; ++j) {
    btScalar v = solveRow(rows_[nonContact_ + j]);
    residual = std::max(residual, v * v);
  }
  std::size_t first = nonContact_ + normal_;
  for (std::size_t j = 0; j + 1 < friction_; j += 2) {
    Row& a = rows_[first + j];
    Row& b = rows_[first + j + 1];
    btScalar normalImpulse = rows_[a.normal].impulse;
    a.lower = -(a.friction * normalImpulse);
    a.upper = a.friction * normalImpulse;
    b.lower = -(b.friction * normalImpulse);
    b.upper = b.friction * normalImpulse;
    btScalar v = solveFrictionPair(a, b);
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
    // Half-solved rows add z * change into their robot's sum; each sum
    // then takes its second half once (L^-1 sum z_i dlambda_i = sum u_i dlambda_i).
    finishSum_.assign(static_cast<std::size_t>(m_data.m_deltaVelocities.size()), btScalar(0));
    summed_.assign(inertiaCount_, nullptr);
    for (std::size_t r = 0; r < rows_.size(); ++r) {
      Row& row = rows_[r];
      btMultiBodySolverConstraint& c = *row.c;
      c.m_appliedImpulse = row.impulse;
      c.m_lowerLimit = row.lower;
      c.m_upperLimit = row.upper;
      btScalar change = c.m_appliedImpulse - row.start;
      for (std::size_t s = 0; s < static_cast<std::size_t>(rowSideCount_[r]); ++s) {
        const RowSide& side = rowSides_[2 * r + s];
        if (change != 0 && side.halfPathEnd >= 0) {
          btScalar* sum = &finishSum_[static_cast<std::size_t>(side.slot)];
          summed_[static_cast<std::size_t>(inertiaOfSlot_[static_cast<std::size_t>(side.slot)])] = &side;
          for (int k = 0; k < side.ndof; ++k) sum[k] += side.response[k] * change;
        } else if (change != 0) {
          side.mb->applyDeltaVeeMultiDof2(side.response, change);
          applyDeltaVee(side.response, change, side.slot, side.ndof);
        }
        side.mb->setPosUpdated(false);
      }
    }
    for (const RowSide* side : summed_) {
      if (!side) continue;
      btScalar* sum = &finishSum_[static_cast<std::size_t>(side->slot)];
      side->inertia->solveSecondHalf(sum);
      side->mb->applyDeltaVeeMultiDof2(sum, 1);
      applyDeltaVee(sum, 1, side->slot, side->ndof);
    }
    active_ = false;
  }
  return btMultiBodyConstraintSolver::solveGroupCacheFriendlyFinish(bodies, numBodies, info);
}

}  // namespace rscene::sim
