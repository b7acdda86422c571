// Bit-for-bit comparison of two rigid bodies' states, for tests that step
// the same world two ways (Bullet's own algorithm against ours) and expect
// the very same numbers.
#pragma once
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <cstring>

namespace rscene::sim::test {

inline bool sameBits(const btVector3& a, const btVector3& b) {
  return std::memcmp(a.m_floats, b.m_floats, 3 * sizeof(btScalar)) == 0;
}

// Position, orientation and both velocities; says which part differs.
inline ::testing::AssertionResult sameState(const btRigidBody& a, const btRigidBody& b) {
  if (!sameBits(a.getWorldTransform().getOrigin(), b.getWorldTransform().getOrigin()))
    return ::testing::AssertionFailure() << "positions differ";
  for (int r = 0; r < 3; ++r)
    if (!sameBits(a.getWorldTransform().getBasis()[r], b.getWorldTransform().getBasis()[r]))
      return ::testing::AssertionFailure() << "orientations differ";
  if (!sameBits(a.getLinearVelocity(), b.getLinearVelocity())) return ::testing::AssertionFailure() << "velocities differ";
  if (!sameBits(a.getAngularVelocity(), b.getAngularVelocity()))
    return ::testing::AssertionFailure() << "angular velocities differ";
  return ::testing::AssertionSuccess();
}

}  // namespace rscene::sim::test
