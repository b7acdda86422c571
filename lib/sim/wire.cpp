#include "sim/wire.hpp"

#include <algorithm>

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

void Spring::apply() const {
  btVector3 pa = a->getCenterOfMassTransform() * pivotA;
  btVector3 pb = b ? b->getCenterOfMassTransform() * pivotB : pivotB;
  btVector3 delta = pb - pa;
  double d = delta.length();
  if (d <= length || d < 1e-12) return;
  btVector3 n = delta / d;
  btVector3 ra = pa - a->getCenterOfMassPosition();
  btVector3 va = a->getVelocityInLocalPoint(ra);
  btVector3 vb(0, 0, 0), rb(0, 0, 0);
  if (b) {
    rb = pb - b->getCenterOfMassPosition();
    vb = b->getVelocityInLocalPoint(rb);
  }
  double rate = n.dot(vb - va);
  double f = std::max(0.0, stiffness * (d - length) + damping * rate);
  if (f == 0) return;
  a->activate();
  a->applyForce(f * n, ra);
  if (b) {
    b->activate();
    b->applyForce(-f * n, rb);
  }
}

}  // namespace rscene::sim
