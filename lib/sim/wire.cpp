#include "sim/wire.hpp"

#include <algorithm>

#include "sim/bt_eigen.hpp"

namespace rscene::sim {

RopeConstraint::RopeConstraint(btRigidBody& a, btRigidBody* b, const btVector3& pivotA, const btVector3& pivotB,
                               double length)
    : btTypedConstraint(POINT2POINT_CONSTRAINT_TYPE, a, b ? *b : getFixedBody()),
      pivotA_(pivotA),
      pivotB_(pivotB),
      hasB_(b != nullptr),
      length_(length) {}

btVector3 RopeConstraint::worldA() const { return m_rbA.getCenterOfMassTransform() * pivotA_; }
btVector3 RopeConstraint::worldB() const { return hasB_ ? m_rbB.getCenterOfMassTransform() * pivotB_ : pivotB_; }

void RopeConstraint::getInfo1(btConstraintInfo1* info) {
  double d = (worldB() - worldA()).length();
  // Taut (or about to be): one row.  Slack: none, the bodies move freely.
  bool taut = d >= length_ - 1e-4 * std::max(length_, 1.0) && d > 1e-9;
  info->m_numConstraintRows = taut ? 1 : 0;
  info->nub = taut ? 5 : 6;
}

void RopeConstraint::getInfo2(btConstraintInfo2* info) {
  btVector3 pa = worldA(), pb = worldB();
  btVector3 delta = pb - pa;
  double d = delta.length();
  btVector3 n = delta / d;
  btVector3 ra = pa - m_rbA.getCenterOfMassPosition();
  btVector3 rb = pb - m_rbB.getCenterOfMassPosition();
  // C = d - length; dC/dt = n . (vB + wB x rB - vA - wA x rA).
  btVector3 j1a = -ra.cross(n), j2a = rb.cross(n);
  for (int k = 0; k < 3; ++k) {
    info->m_J1linearAxis[k] = -n[k];
    info->m_J1angularAxis[k] = j1a[k];
    if (info->m_J2linearAxis) info->m_J2linearAxis[k] = n[k];
    if (info->m_J2angularAxis) info->m_J2angularAxis[k] = j2a[k];
  }
  info->m_constraintError[0] = info->fps * info->erp * (length_ - d);
  info->m_lowerLimit[0] = -SIMD_INFINITY;  // the wire pulls, never pushes
  info->m_upperLimit[0] = 0;
}

btVector3 WireAnchor::world() const {
  if (rigid) return rigid->getCenterOfMassTransform() * local;
  if (robot) return bt(robot->bodyPose(body)) * local;
  return local;
}

btVector3 WireAnchor::velocity(const btVector3& at) const {
  if (rigid) return rigid->getVelocityInLocalPoint(at - rigid->getCenterOfMassPosition());
  if (robot) return bt(robot->pointVelocity(body, eig(at)));
  return btVector3(0, 0, 0);
}

void WireAnchor::apply(const btVector3& force, const btVector3& at) const {
  if (rigid) {
    rigid->activate();
    rigid->applyForce(force, at - rigid->getCenterOfMassPosition());
  } else if (robot) {
    robot->applyForce(body, eig(force), eig(at));
  }
}

void Spring::apply() const {
  btVector3 pa = a.world(), pb = b.world();
  btVector3 delta = pb - pa;
  double d = delta.length();
  if (d <= length || d < 1e-12) return;
  btVector3 n = delta / d;
  double rate = n.dot(b.velocity(pb) - a.velocity(pa));
  double f = std::max(0.0, stiffness * (d - length) + damping * rate);
  if (f == 0) return;
  a.apply(f * n, pa);
  b.apply(-f * n, pb);
}

namespace {
int bodyLink(const WireAnchor& e) { return e.robot ? e.body - 1 : -1; }  // Bullet's link index (-1: base)
btVector3 toCom(const WireAnchor& e) {
  if (!e.robot) return e.local;
  return bt(e.robot->layout().bodies[static_cast<std::size_t>(e.body)].com.inverse()) * e.local;
}
int islandOf(const btMultiBody* mb) {
  if (const btMultiBodyLinkCollider* c = mb->getBaseCollider()) return c->getIslandTag();
  for (int i = 0; i < mb->getNumLinks(); ++i)
    if (mb->getLink(i).m_collider) return mb->getLink(i).m_collider->getIslandTag();
  return -1;
}
}  // namespace

MultiBodyRope::MultiBodyRope(const WireAnchor& a, const WireAnchor& b, double length)
    : btMultiBodyConstraint(a.robot->multiBody(), b.robot ? b.robot->multiBody() : nullptr, bodyLink(a), bodyLink(b),
                            1, true, MULTIBODY_CONSTRAINT_POINT_TO_POINT),
      a_(a),
      b_(b),
      comA_(toCom(a)),
      comB_(toCom(b)),
      length_(length) {
  setMaxAppliedImpulse(SIMD_INFINITY);
}

void MultiBodyRope::finalizeMultiDof() {
  allocateJacobiansMultiDof();
  m_numDofsFinalized = m_jacSizeBoth;
}

int MultiBodyRope::getIslandIdA() const { return islandOf(m_bodyA); }
int MultiBodyRope::getIslandIdB() const {
  if (b_.rigid) return b_.rigid->getIslandTag();
  return m_bodyB ? islandOf(m_bodyB) : -1;
}

void MultiBodyRope::createConstraintRows(btMultiBodyConstraintArray& rows, btMultiBodyJacobianData& data,
                                         const btContactSolverInfo& info) {
  if (m_numDofsFinalized != m_jacSizeBoth) finalizeMultiDof();
  btVector3 pa = m_bodyA->localPosToWorld(m_linkA, comA_);
  btVector3 pb = b_.rigid ? b_.rigid->getCenterOfMassTransform() * comB_
                 : m_bodyB ? m_bodyB->localPosToWorld(m_linkB, comB_)
                           : comB_;
  btVector3 delta = pb - pa;
  double d = delta.length();
  // Slack: no row, the bodies move freely (as RopeConstraint).
  if (!(d >= length_ - 1e-4 * std::max(length_, 1.0)) || d <= 1e-9) return;
  btMultiBodySolverConstraint& row = rows.expandNonInitializing();
  row.m_orgConstraint = this;
  row.m_orgDofIndex = 0;
  row.m_relpos1CrossNormal.setValue(0, 0, 0);
  row.m_contactNormal1.setValue(0, 0, 0);
  row.m_relpos2CrossNormal.setValue(0, 0, 0);
  row.m_contactNormal2.setValue(0, 0, 0);
  row.m_angularComponentA.setValue(0, 0, 0);
  row.m_angularComponentB.setValue(0, 0, 0);
  row.m_solverBodyIdA = data.m_fixedBodyId;
  row.m_solverBodyIdB = b_.rigid ? b_.rigid->getCompanionId() : data.m_fixedBodyId;
  // C = length - d, dC/dt = n . (vA - vB) with n from A to B: the solver
  // drives C toward 0 with an impulse that only pulls (lower limit 0).
  btVector3 n = delta / d;
  fillMultiBodyConstraint(row, data, nullptr, nullptr, btVector3(0, 0, 0), n, pa, pb, length_ - d, info, 0,
                          SIMD_INFINITY);
}

}  // namespace rscene::sim
