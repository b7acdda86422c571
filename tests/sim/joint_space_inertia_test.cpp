// JointSpaceInertia (lib/sim/joint_space_inertia.hpp) gives Bullet's unit
// responses: M^-1 b from its factored mass matrix equals Bullet's own
// articulated-body pass (calcAccelerationDeltasMultiDof) for random b and
// for contact Jacobians (its Jacobians are Bullet's, and the product of two
// rows' first halves is J M^-1 J'^T), on random trees of every joint type
// Bullet has, with a floating base far from the origin and with a fixed base.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "sim/joint_space_inertia.hpp"

namespace {

using rscene::sim::JointSpaceInertia;

enum class Joint { Revolute, Prismatic, Spherical, Planar, Fixed };

struct Tree {
  std::unique_ptr<btMultiBody> mb;
  btAlignedObjectArray<btScalar> r;
  btAlignedObjectArray<btVector3> v;
  btAlignedObjectArray<btMatrix3x3> m;
};

btVector3 randomVector(std::mt19937& rng, double lo, double hi) {
  std::uniform_real_distribution<double> d(lo, hi);
  return btVector3(d(rng), d(rng), d(rng));
}

btQuaternion randomRotation(std::mt19937& rng) {
  btVector3 axis = randomVector(rng, -1, 1);
  if (axis.length2() < 1e-6) axis = btVector3(0, 0, 1);
  return btQuaternion(axis.normalized(), std::uniform_real_distribution<double>(-3, 3)(rng));
}

// A tree of `joints.size()` links, each hung from a random earlier link (or
// the base), at a random pose, with random masses, inertias and velocities;
// Bullet's dynamics run once so its caches hold this state.
Tree randomTree(std::mt19937& rng, const std::vector<Joint>& joints, bool fixedBase) {
  Tree t;
  const int n = static_cast<int>(joints.size());
  t.mb = std::make_unique<btMultiBody>(n, 7.5, randomVector(rng, 0.05, 0.4), fixedBase, false);
  for (int i = 0; i < n; ++i) {
    int parent = i == 0 ? -1 : std::uniform_int_distribution<int>(-1, i - 1)(rng);
    double mass = std::uniform_real_distribution<double>(0.1, 3)(rng);
    btVector3 inertia = randomVector(rng, 0.001, 0.05);
    btQuaternion rot = randomRotation(rng);
    btVector3 toPivot = randomVector(rng, -0.3, 0.3), toCom = randomVector(rng, -0.2, 0.2);
    btVector3 axis = randomVector(rng, -1, 1).normalized();
    switch (joints[static_cast<std::size_t>(i)]) {
      case Joint::Revolute: t.mb->setupRevolute(i, mass, inertia, parent, rot, axis, toPivot, toCom); break;
      case Joint::Prismatic: t.mb->setupPrismatic(i, mass, inertia, parent, rot, axis, toPivot, toCom, false); break;
      case Joint::Spherical: t.mb->setupSpherical(i, mass, inertia, parent, rot, toPivot, toCom); break;
      case Joint::Planar: t.mb->setupPlanar(i, mass, inertia, parent, rot, axis, toPivot); break;
      case Joint::Fixed: t.mb->setupFixed(i, mass, inertia, parent, rot, toPivot, toCom); break;
    }
  }
  t.mb->finalizeMultiDof();
  t.mb->setBasePos(btVector3(40, -25, 3));
  t.mb->setWorldToBaseRot(randomRotation(rng));
  t.mb->setBaseOmega(randomVector(rng, -1, 1));
  t.mb->setBaseVel(randomVector(rng, -1, 1));
  for (int i = 0; i < n; ++i) {
    const btMultibodyLink& link = t.mb->getLink(i);
    if (link.m_jointType == btMultibodyLink::eSpherical) {
      btQuaternion q = randomRotation(rng);
      double p[4] = {q.x(), q.y(), q.z(), q.w()};
      t.mb->setJointPosMultiDof(i, p);
    } else {
      for (int d = 0; d < link.m_posVarCount; ++d) t.mb->getJointPosMultiDof(i)[d] = std::uniform_real_distribution<double>(-1, 1)(rng);
    }
    for (int d = 0; d < link.m_dofCount; ++d) t.mb->getJointVelMultiDof(i)[d] = std::uniform_real_distribution<double>(-1, 1)(rng);
    t.mb->getLink(i).updateCacheMultiDof();
  }
  t.mb->computeAccelerationsArticulatedBodyAlgorithmMultiDof(0.0025, t.r, t.v, t.m, false, false, false);
  return t;
}

// The largest difference between ours and Bullet's M^-1 b, relative to
// Bullet's largest entry.
double worstGap(Tree& t, const JointSpaceInertia& inertia, const std::vector<btScalar>& b) {
  const std::size_t n = b.size();
  std::vector<btScalar> ours(n), bullets(n);
  inertia.solve(b.data(), ours.data());
  t.mb->calcAccelerationDeltasMultiDof(b.data(), bullets.data(), t.r, t.v);
  double scale = 0, gap = 0;
  for (std::size_t k = 0; k < n; ++k) {
    scale = std::max(scale, std::abs(bullets[k]));
    gap = std::max(gap, std::abs(ours[k] - bullets[k]));
  }
  return scale > 0 ? gap / scale : gap;
}

// Random generalised forces, and contact Jacobians at points of every link.
double worstGapOverForces(std::mt19937& rng, Tree& t) {
  JointSpaceInertia inertia;
  EXPECT_TRUE(inertia.factor(*t.mb));
  const int n = t.mb->getNumDofs() + 6;
  EXPECT_EQ(inertia.size(), n);
  double worst = 0;
  std::vector<btScalar> b(static_cast<std::size_t>(n));
  for (int trial = 0; trial < 20; ++trial) {
    for (auto& x : b) x = std::uniform_real_distribution<double>(-2, 2)(rng);
    worst = std::max(worst, worstGap(t, inertia, b));
  }
  btAlignedObjectArray<btMatrix3x3> m;
  std::vector<btScalar> ours(b.size());
  for (int link = -1; link < t.mb->getNumLinks(); ++link) {
    btVector3 point = t.mb->getBasePos() + randomVector(rng, -0.5, 0.5);
    btVector3 normal = randomVector(rng, -1, 1).normalized();
    t.mb->fillContactJacobianMultiDof(link, point, normal, b.data(), t.r, t.v, m);
    inertia.contactJacobian(link, point, normal, ours.data());
    for (std::size_t k = 0; k < b.size(); ++k) {
      EXPECT_NEAR(ours[k], b[k], 1e-12) << "link " << link << " velocity " << k;
      if (b[k] == 0) {
        EXPECT_EQ(ours[k], 0.0) << "off the path: link " << link << " velocity " << k;
      }
    }
    worst = std::max(worst, worstGap(t, inertia, b));
    // The first half alone, along the path: the same as over every
    // velocity, and z . z' = J M^-1 J'^T with a second contact's J'.
    std::vector<btScalar> z(b.size()), zPath(b.size()), z2(b.size()), other(b.size()), u(b.size());
    inertia.solveFirstHalf(b.data(), z.data());
    inertia.solvePathFirstHalf(inertia.pathEnd(link), b.data(), zPath.data());
    for (std::size_t k = 0; k < b.size(); ++k) EXPECT_NEAR(zPath[k], z[k], 1e-12 * (1 + std::abs(z[k])));
    int otherLink = std::uniform_int_distribution<int>(-1, t.mb->getNumLinks() - 1)(rng);
    inertia.contactJacobian(otherLink, point + randomVector(rng, -0.1, 0.1), randomVector(rng, -1, 1).normalized(),
                            other.data());
    inertia.solvePathFirstHalf(inertia.pathEnd(otherLink), other.data(), z2.data());
    t.mb->calcAccelerationDeltasMultiDof(other.data(), u.data(), t.r, t.v);
    double bullets = 0, scale = 0;
    for (std::size_t k = 0; k < b.size(); ++k) bullets += b[k] * u[k], scale += std::abs(b[k] * u[k]);
    double ours = inertia.pathDot(inertia.pathEnd(link), zPath.data(), z2.data());
    worst = std::max(worst, std::abs(ours - bullets) / std::max(scale, 1e-300));
  }
  return worst;
}

TEST(JointSpaceInertia, FloatingQuadrupedsGiveBulletsUnitResponses) {
  std::mt19937 rng(7);
  for (int tree = 0; tree < 20; ++tree) {
    Tree t = randomTree(rng, std::vector<Joint>(12, Joint::Revolute), false);
    EXPECT_LT(worstGapOverForces(rng, t), 1e-11) << "tree " << tree;
  }
}

TEST(JointSpaceInertia, EveryJointTypeWithFloatingAndFixedBases) {
  std::mt19937 rng(11);
  const std::vector<Joint> joints = {Joint::Revolute, Joint::Spherical, Joint::Prismatic, Joint::Fixed,
                                     Joint::Revolute, Joint::Planar,    Joint::Spherical, Joint::Fixed,
                                     Joint::Prismatic, Joint::Revolute};
  for (int tree = 0; tree < 20; ++tree) {
    Tree t = randomTree(rng, joints, tree % 2 == 1);
    EXPECT_LT(worstGapOverForces(rng, t), 1e-11) << "tree " << tree << (tree % 2 ? " (fixed base)" : "");
  }
}

TEST(JointSpaceInertia, AFixedBaseGetsNoBaseResponse) {
  std::mt19937 rng(3);
  Tree t = randomTree(rng, std::vector<Joint>(4, Joint::Revolute), true);
  JointSpaceInertia inertia;
  ASSERT_TRUE(inertia.factor(*t.mb));
  std::vector<btScalar> b(static_cast<std::size_t>(inertia.size()), 1.0), x(b.size(), 7.0);
  inertia.solve(b.data(), x.data());
  for (int k = 0; k < 6; ++k) EXPECT_EQ(x[static_cast<std::size_t>(k)], 0.0);
  EXPECT_NE(x[6], 0.0);
}

TEST(JointSpaceInertia, AKinematicLinkIsLeftToBullet) {
  std::mt19937 rng(5);
  Tree t = randomTree(rng, std::vector<Joint>(3, Joint::Revolute), false);
  JointSpaceInertia inertia;
  btMultiBodyLinkCollider collider(t.mb.get(), 1);
  t.mb->getLink(1).m_collider = &collider;
  EXPECT_TRUE(inertia.factor(*t.mb));
  t.mb->setLinkDynamicType(1, btCollisionObject::CF_KINEMATIC_OBJECT);
  EXPECT_FALSE(inertia.factor(*t.mb));
  t.mb->getLink(1).m_collider = nullptr;
}

TEST(JointSpaceInertia, ALongChainIsLeftToBullet) {
  // A 40-link chain: factoring (~40^3 / 3 products) would cost more than
  // the passes it saves.  A 12-link chain still factors.
  std::mt19937 rng(9);
  JointSpaceInertia inertia;
  auto chain = [&](int links) {
    Tree t;
    t.mb = std::make_unique<btMultiBody>(links, 1.0, btVector3(0.1, 0.1, 0.1), false, false);
    for (int i = 0; i < links; ++i)
      t.mb->setupRevolute(i, 1.0, btVector3(0.01, 0.01, 0.01), i - 1, btQuaternion::getIdentity(),
                          btVector3(0, 1, 0), btVector3(0, 0, -0.1), btVector3(0, 0, -0.1));
    t.mb->finalizeMultiDof();
    t.mb->computeAccelerationsArticulatedBodyAlgorithmMultiDof(0.0025, t.r, t.v, t.m, false, false, false);
    return t;
  };
  Tree longChain = chain(40), shortChain = chain(12);
  EXPECT_FALSE(inertia.factor(*longChain.mb));
  EXPECT_TRUE(inertia.factor(*shortChain.mb));
  EXPECT_LT(worstGapOverForces(rng, shortChain), 1e-10);
}

}  // namespace
