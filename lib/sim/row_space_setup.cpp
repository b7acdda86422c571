// RowSpaceSolver's contact setup (issue 26): Bullet's own setup of a
// robot's contact rows (btMultiBodyConstraintSolver's
// convertMultiBodyContact, addMultiBodyFrictionConstraint and
// setupMultiBodyContactConstraint), step for step, except where each row's
// unit response u = M^-1 J^T comes from: JointSpaceInertia's factor of the
// robot, made once per solve, instead of an articulated-body pass over the
// whole robot per row.  The rows, their order, Jacobians, right-hand
// sides, limits and friction directions are Bullet's; u agrees with
// Bullet's to rounding.
//
// Taken for manifolds whose sides are robots or bodies that cannot move
// (the ground), without rolling, spinning or anisotropic friction, with
// Bullet's articulated warm starting off.  Anything else is Bullet's.
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include "sim/row_space_solver.hpp"

namespace rscene::sim {

namespace {

constexpr int kNotFactored = -1, kBulletsPass = -2;

btMultiBody* multiBodyOf(const btCollisionObject* o, int& link) {
  const btMultiBodyLinkCollider* collider = btMultiBodyLinkCollider::upcast(o);
  if (!collider) return nullptr;
  link = collider->m_link;
  return collider->m_multiBody;
}

bool hasAnyAnisotropicFriction(const btCollisionObject* o) {
  return o->hasAnisotropicFriction(btCollisionObject::CF_ANISOTROPIC_FRICTION) ||
         o->hasAnisotropicFriction(btCollisionObject::CF_ANISOTROPIC_ROLLING_FRICTION);
}

}  // namespace

void RowSpaceSolver::convertContacts(btPersistentManifold** manifolds, int numManifolds,
                                     const btContactSolverInfo& info) {
  if (!enabled_ || (info.m_solverMode & SOLVER_USE_ARTICULATED_WARMSTARTING)) {
    btMultiBodyConstraintSolver::convertContacts(manifolds, numManifolds, info);
    return;
  }
  inertiaCount_ = 0;
  inertiaOfSlot_.clear();
  halfRows_.clear();
  halfPathEnd_.clear();
  for (int i = 0; i < numManifolds; ++i) {
    btPersistentManifold* manifold = manifolds[i];
    const bool mbA = btMultiBodyLinkCollider::upcast(manifold->getBody0()) != nullptr;
    const bool mbB = btMultiBodyLinkCollider::upcast(manifold->getBody1()) != nullptr;
    if (!mbA && !mbB) {
      convertContact(manifold, info);
      continue;
    }
    // Solver bodies in Bullet's order (getOrInitSolverBody returns the same
    // body when Bullet's conversion asks again).
    int bodyA = mbA ? -1 : getOrInitSolverBody(*const_cast<btCollisionObject*>(manifold->getBody0()), info.m_timeStep);
    int bodyB = mbB ? -1 : getOrInitSolverBody(*const_cast<btCollisionObject*>(manifold->getBody1()), info.m_timeStep);
    if (setupEligible(*manifold, bodyA, bodyB))
      convertRobotContact(manifold, bodyA, bodyB, info);
    else
      convertMultiBodyContact(manifold, info);
  }
  // The multibody constraints' rows (joint limits, motors): Bullet's.
  btMultiBodyConstraintSolver::convertContacts(manifolds, 0, info);
}

bool RowSpaceSolver::setupEligible(const btPersistentManifold& manifold, int solverBodyA, int solverBodyB) const {
  for (int solverBody : {solverBodyA, solverBodyB})
    if (solverBody >= 0 && m_tmpSolverBodyPool[solverBody].m_originalBody) return false;
  if (hasAnyAnisotropicFriction(manifold.getBody0()) || hasAnyAnisotropicFriction(manifold.getBody1())) return false;
  for (int j = 0; j < manifold.getNumContacts(); ++j) {
    const btManifoldPoint& cp = manifold.getContactPoint(j);
    if (cp.m_combinedRollingFriction > 0 || cp.m_combinedSpinningFriction > 0) return false;
  }
  return true;
}

// convertMultiBodyContact without the rolling, spinning and anisotropic
// friction setupEligible() excludes.
void RowSpaceSolver::convertRobotContact(btPersistentManifold* manifold, int solverBodyA, int solverBodyB,
                                         const btContactSolverInfo& info) {
  for (int j = 0; j < manifold->getNumContacts(); ++j) {
    btManifoldPoint& cp = manifold->getContactPoint(j);
    if (cp.getDistance() > manifold->getContactProcessingThreshold()) {
      cp.m_appliedImpulse = 0;
      cp.m_prevRHS = 0;
      continue;
    }
    const int frictionIndex = m_multiBodyNormalContactConstraints.size();
    btMultiBodySolverConstraint& normal =
        addRow(m_multiBodyNormalContactConstraints, manifold, cp, solverBodyA, solverBodyB);
    setupContactRow(normal, cp.m_normalWorldOnB, cp, info, false);
    normal.m_frictionIndex = m_multiBodyFrictionContactConstraints.size();

    btPlaneSpace1(cp.m_normalWorldOnB, cp.m_lateralFrictionDir1, cp.m_lateralFrictionDir2);
    cp.m_lateralFrictionDir1.normalize();
    cp.m_lateralFrictionDir2.normalize();
    const bool twoDirections = info.m_solverMode & SOLVER_USE_2_FRICTION_DIRECTIONS;
    const bool cached = (info.m_solverMode & SOLVER_ENABLE_FRICTION_DIRECTION_CACHING) &&
                        (cp.m_contactPointFlags & BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED);
    for (int d = 0; d < (twoDirections ? 2 : 1); ++d) {
      btMultiBodySolverConstraint& friction =
          addRow(m_multiBodyFrictionContactConstraints, manifold, cp, solverBodyA, solverBodyB);
      friction.m_frictionIndex = frictionIndex;
      setupContactRow(friction, d == 0 ? cp.m_lateralFrictionDir1 : cp.m_lateralFrictionDir2, cp, info, true);
    }
    if (!cached && twoDirections && (info.m_solverMode & SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION))
      cp.m_contactPointFlags |= BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED;
    if (cached) {
      // Bullet's cached-direction branch also clears the normal row's impulses.
      btMultiBodySolverConstraint& n = m_multiBodyNormalContactConstraints[frictionIndex];
      n.m_appliedImpulse = 0;
      n.m_appliedPushImpulse = 0;
    }
  }
}

btMultiBodySolverConstraint& RowSpaceSolver::addRow(btMultiBodyConstraintArray& rows, btPersistentManifold* manifold,
                                                    btManifoldPoint& cp, int solverBodyA, int solverBodyB) {
  btMultiBodySolverConstraint& c = rows.expandNonInitializing();
  c.m_orgConstraint = nullptr;
  c.m_orgDofIndex = -1;
  c.m_solverBodyIdA = solverBodyA;
  c.m_solverBodyIdB = solverBodyB;
  c.m_multiBodyA = multiBodyOf(manifold->getBody0(), c.m_linkA);
  c.m_multiBodyB = multiBodyOf(manifold->getBody1(), c.m_linkB);
  c.m_originalContactPoint = &cp;
  return c;
}

// setupMultiBodyContactConstraint for sides that are robots or fixed
// bodies (no rigid body's velocity or inertia enters).
void RowSpaceSolver::setupContactRow(btMultiBodySolverConstraint& c, const btVector3& normal, btManifoldPoint& cp,
                                     const btContactSolverInfo& info, bool isFriction) {
  const btScalar relaxation = info.m_sor;
  const btScalar invTimeStep = btScalar(1) / info.m_timeStep;
  btScalar cfm = isFriction ? info.m_frictionCFM : info.m_globalCfm;
  btScalar erp = isFriction ? info.m_frictionERP : info.m_erp2;
  if (!isFriction) {
    if (cp.m_contactPointFlags & (BT_CONTACT_FLAG_HAS_CONTACT_CFM | BT_CONTACT_FLAG_HAS_CONTACT_ERP)) {
      if (cp.m_contactPointFlags & BT_CONTACT_FLAG_HAS_CONTACT_CFM) cfm = cp.m_contactCFM;
      if (cp.m_contactPointFlags & BT_CONTACT_FLAG_HAS_CONTACT_ERP) erp = cp.m_contactERP;
    } else if (cp.m_contactPointFlags & BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING) {
      btScalar denom = info.m_timeStep * cp.m_combinedContactStiffness1 + cp.m_combinedContactDamping1;
      if (denom < SIMD_EPSILON) denom = SIMD_EPSILON;
      cfm = btScalar(1) / denom;
      erp = (info.m_timeStep * cp.m_combinedContactStiffness1) / denom;
    }
  }
  cfm *= invTimeStep;

  // Each side: its lever arm's cross product with the normal (negated for
  // B, as Bullet writes it), and for a robot (B's along -normal) its Jacobian and unit response, J M^-1 J^T
  // (z . z when half-solved) and J v, summed as Bullet sums them.  A
  // half-solved side's J and z are zero off its path, so those run along it.
  const btVector3& pos1 = cp.getPositionWorldOnA();
  const btVector3& pos2 = cp.getPositionWorldOnB();
  auto dot = [this](const btMultiBody* mb, int slot, int jac, const btScalar* x, const btScalar* y, btScalar sum) {
    if (int end = halfPathEnd(jac); end >= 0) return sum + inertiaOfSlot(slot).pathDot(end, x, y);
    for (int k = 0, n = mb->getNumDofs() + 6; k < n; ++k) sum += x[k] * y[k];
    return sum;
  };
  btScalar denom[2] = {0, 0}, relVel = 0;
  auto side = [&](btMultiBody* mb, int link, int solverBody, const btVector3& pos, const btVector3& sideNormal,
                  int& slot, int& jac, btVector3& relPosCrossNormal, btVector3& angularComponent, btScalar& denominator) {
    if (!mb) {
      relPosCrossNormal = (pos - m_tmpSolverBodyPool[solverBody].getWorldTransform().getOrigin()).cross(normal);
      angularComponent.setZero();
      return;
    }
    btVector3 origin = link < 0 ? mb->getBasePos() : mb->getLink(link).m_cachedWorldTransform.getOrigin();
    setupSide(mb, link, pos, sideNormal, slot, jac);
    relPosCrossNormal = (pos - origin).cross(normal);
    const btScalar* unit = &m_data.m_deltaVelocitiesUnitImpulse[jac];
    const btScalar* jacobian = &m_data.m_jacobians[jac];
    denominator = dot(mb, slot, jac, unit, holdsHalf(jac) ? unit : jacobian, 0);
    relVel = dot(mb, slot, jac, mb->getVelocityVector(), jacobian, relVel);
  };
  side(c.m_multiBodyA, c.m_linkA, c.m_solverBodyIdA, pos1, normal, c.m_deltaVelAindex, c.m_jacAindex,
       c.m_relpos1CrossNormal, c.m_angularComponentA, denom[0]);
  side(c.m_multiBodyB, c.m_linkB, c.m_solverBodyIdB, pos2, -normal, c.m_deltaVelBindex, c.m_jacBindex,
       c.m_relpos2CrossNormal, c.m_angularComponentB, denom[1]);
  c.m_relpos2CrossNormal = -c.m_relpos2CrossNormal;
  c.m_contactNormal1 = normal;
  c.m_contactNormal2 = -normal;
  btScalar d = denom[0] + denom[1] + cfm;
  c.m_jacDiagABInv = d > SIMD_EPSILON ? relaxation / d : btScalar(0);

  btScalar distance = 0;
  if (!isFriction)
    distance = cp.getDistance() + info.m_linearSlop;
  else if (cp.m_contactPointFlags & BT_CONTACT_FLAG_FRICTION_ANCHOR)
    distance = (pos1 - pos2).dot(normal);
  c.m_friction = cp.m_combinedFriction;
  btScalar restitution = 0;
  if (!isFriction) {
    restitution = restitutionCurve(relVel, cp.m_combinedRestitution, info.m_restitutionVelocityThreshold);
    if (restitution <= btScalar(0)) restitution = 0;
  }

  btScalar positionalError = 0, velocityError = restitution - relVel;
  if (!isFriction && distance > 0)
    velocityError -= distance / info.m_timeStep;
  else
    positionalError = -distance * erp / info.m_timeStep;
  c.m_rhs = positionalError * c.m_jacDiagABInv + velocityError * c.m_jacDiagABInv;
  c.m_rhsPenetration = 0;
  c.m_lowerLimit = isFriction ? -c.m_friction : btScalar(0);
  c.m_upperLimit = isFriction ? c.m_friction : btScalar(1e10f);
  c.m_cfm = cfm * c.m_jacDiagABInv;
  c.m_appliedImpulse = 0;
  c.m_appliedPushImpulse = 0;
}

void RowSpaceSolver::setupSide(btMultiBody* mb, int link, const btVector3& point, const btVector3& normal, int& slot,
                               int& jac) {
  const int ndof = mb->getNumDofs() + 6;
  slot = mb->getCompanionId();
  if (slot < 0) {
    slot = m_data.m_deltaVelocities.size();
    mb->setCompanionId(slot);
    m_data.m_deltaVelocities.resize(m_data.m_deltaVelocities.size() + ndof);
  }
  jac = m_data.m_jacobians.size();
  m_data.m_jacobians.resize(m_data.m_jacobians.size() + ndof);
  m_data.m_deltaVelocitiesUnitImpulse.resize(m_data.m_deltaVelocitiesUnitImpulse.size() + ndof);
  btScalar* j = &m_data.m_jacobians[jac];
  btScalar* u = &m_data.m_deltaVelocitiesUnitImpulse[jac];
  if (const JointSpaceInertia* inertia = inertiaAt(mb, slot)) {
    const int end = inertia->pathEnd(link);
    inertia->contactJacobian(link, point, normal, j);
    inertia->solvePathFirstHalf(end, j, u);
    halfRows_.push_back({jac, slot});
    halfPathEnd_.resize(static_cast<std::size_t>(jac) + 1, -1);
    halfPathEnd_[static_cast<std::size_t>(jac)] = end;
    return;
  }
  mb->fillContactJacobianMultiDof(link, point, normal, j, m_data.scratch_r, m_data.scratch_v, m_data.scratch_m);
  mb->calcAccelerationDeltasMultiDof(j, u, m_data.scratch_r, m_data.scratch_v);
}

void RowSpaceSolver::completeUnitResponses() {
  for (const HalfRow& row : halfRows_)
    inertiaOfSlot(row.slot).solveSecondHalf(&m_data.m_deltaVelocitiesUnitImpulse[row.jac]);
  halfRows_.clear();
  halfPathEnd_.clear();
}

const JointSpaceInertia* RowSpaceSolver::inertiaAt(btMultiBody* mb, int slot) {
  auto s = static_cast<std::size_t>(slot);
  if (s >= inertiaOfSlot_.size()) inertiaOfSlot_.resize(s + 1, kNotFactored);
  int& index = inertiaOfSlot_[s];
  if (index == kNotFactored) {
    // A spare factor of the same tree keeps its work space (robots of
    // several kinds need not rebuild theirs every step).
    for (std::size_t spare = inertiaCount_; spare < inertias_.size(); ++spare)
      if (inertias_[spare].sameTopology(*mb)) {
        std::swap(inertias_[spare], inertias_[inertiaCount_]);
        break;
      }
    if (inertiaCount_ == inertias_.size()) inertias_.emplace_back();
    index = inertias_[inertiaCount_].factor(*mb) ? static_cast<int>(inertiaCount_++) : kBulletsPass;
  }
  return index >= 0 ? &inertias_[static_cast<std::size_t>(index)] : nullptr;
}

}  // namespace rscene::sim
