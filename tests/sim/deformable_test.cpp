// The deformable solver (lib/sim/deformable_*) against closed forms, on
// models built by hand or from small OBJ meshes, with AnalyticSurfaces as
// the rigid world.  Each tolerance says why it is not tighter.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/deformable_test_util.hpp"

using namespace rscene;
using namespace rscene::sim;
using namespace rscene::sim::test;

TEST(Deformable, DihedralGradientMatchesFiniteDifferences) {
  Eigen::Vector3d p[4] = {{0.3, -1, 0.2}, {0.6, 1.1, -0.4}, {0, 0, 0}, {1, 0.1, 0.05}};
  Eigen::Vector3d g[4];
  ASSERT_TRUE(dihedralGradient(p[0], p[1], p[2], p[3], g));
  const double eps = 1e-6;
  for (int q = 0; q < 4; ++q)
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d a[4] = {p[0], p[1], p[2], p[3]}, b[4] = {p[0], p[1], p[2], p[3]};
      a[q][k] += eps;
      b[q][k] -= eps;
      double fd = (dihedralAngle(a[0], a[1], a[2], a[3]) - dihedralAngle(b[0], b[1], b[2], b[3])) / (2 * eps);
      EXPECT_NEAR(g[q][k], fd, 1e-7) << "particle " << q << " axis " << k;  // central difference error ~eps^2
    }
  // Flat: angle 0; folding `a` up and `b` down are opposite signs.
  EXPECT_NEAR(dihedralAngle({0.5, -1, 0}, {0.5, 1, 0}, {0, 0, 0}, {1, 0, 0}), 0, 1e-15);
  EXPECT_LT(dihedralAngle({0.5, -1, 0.3}, {0.5, 1, 0}, {0, 0, 0}, {1, 0, 0}) *
                dihedralAngle({0.5, -1, -0.3}, {0.5, 1, 0}, {0, 0, 0}, {1, 0, 0}),
            0);
}

namespace {

// A vertical chain of `segments` links of rest length `rest`, pinned at
// the top, one particle of `mass` at each joint.
DeformableModel chain(int segments, double rest, double mass, double alpha, int iterations) {
  DeformableModel m;
  for (int i = 0; i <= segments; ++i) {
    m.positions.emplace_back(0, 0, -rest * i);
    m.inverseMass.push_back(i == 0 ? 0 : 1 / mass);
  }
  for (int i = 0; i < segments; ++i)
    m.distances.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i + 1), rest, alpha});
  m.surfaceCount = m.positions.size();
  m.particleMass = mass;
  m.iterations = iterations;
  m.damping = 0.05;
  m.collidable = false;
  return m;
}

}  // namespace

TEST(Deformable, ChainStretchesByItsComplianceTimesTheWeightBelow) {
  // XPBD's static equilibrium: C_k + alpha * tension_k = 0, so link k
  // stretches by alpha x the weight of the particles below it.
  const int n = 5;
  const double rest = 0.1, mass = 0.2, alpha = 1e-3, g = 9.81;
  XpbdDeformable body(chain(n, rest, mass, alpha, 100));
  AnalyticSurfaces none;
  run(body, none, 10);
  const auto& x = body.positions();
  for (int k = 1; k <= n; ++k) {
    double stretch = (x[k - 1] - x[k]).norm() - rest;
    double expected = alpha * (n - k + 1) * mass * g;  // 1 to 5 mm
    // Gauss-Seidel with 100 iterations on 5 links is converged to round-off
    // at rest; the damped oscillation left after 10 s is below 1e-9 m.
    EXPECT_NEAR(stretch, expected, 1e-3 * expected) << "link " << k;
  }
  EXPECT_LT(body.maxSpeed(), 1e-6);
}

TEST(Deformable, ChainStretchIsTheSameWithSubsteps) {
  // XPBD scales the compliance by the substep (alpha / h^2): four substeps
  // of a quarter step reach the same equilibrium as one step.
  DeformableModel m = chain(5, 0.1, 0.2, 1e-3, 100);
  m.substeps = 4;
  XpbdDeformable body(std::move(m));
  AnalyticSurfaces none;
  run(body, none, 10);
  const auto& x = body.positions();
  for (int k = 1; k <= 5; ++k) {
    double expected = 1e-3 * (5 - k + 1) * 0.2 * 9.81;
    EXPECT_NEAR((x[k - 1] - x[k]).norm() - 0.1, expected, 1e-3 * expected) << "link " << k;  // as above
  }
}

TEST(Deformable, DampingRemovesItsFractionPerWorldStepWhateverTheSubsteps) {
  for (int substeps : {1, 5}) {
    DeformableModel m;
    m.positions = {Eigen::Vector3d::Zero()};
    m.inverseMass = {1};
    m.particleMass = 1;
    m.surfaceCount = 1;
    m.substeps = substeps;
    m.damping = 0.1;
    m.collidable = false;
    XpbdDeformable body(std::move(m));
    AnalyticSurfaces none;
    body.step(0.01, {0, 0, -9.81}, none);  // some speed, then none added
    for (int i = 0; i < 3; ++i) {
      const double before = body.maxSpeed();
      body.step(0.01, Eigen::Vector3d::Zero(), none);
      EXPECT_NEAR(body.maxSpeed(), 0.9 * before, 1e-15) << substeps << " substeps";  // round-off of the root
    }
  }
}

TEST(Deformable, PbdIsStifferThanItsComplianceWithManyIterations) {
  // PBD restarts the multiplier every iteration: its stiffness grows with
  // the iterations, the legacy behaviour XPBD removes.
  DeformableModel m = chain(5, 0.1, 0.2, 1e-3, 100);
  m.xpbd = false;
  XpbdDeformable body(std::move(m));
  AnalyticSurfaces none;
  run(body, none, 10);
  double stretch = (body.positions()[0] - body.positions()[1]).norm() - 0.1;
  EXPECT_LT(stretch, 0.5 * 1e-3 * 5 * 0.2 * 9.81);
}

namespace {

// A 1 m cloth of n x n vertices at height z, pinned at the two corners of
// its y = -0.5 edge (vertices 0 and n - 1).
std::unique_ptr<XpbdDeformable> hangingCloth(int n, double compliance, int iterations = 40) {
  Deformable d = defaultRecord();
  d.world.position = {0, 0, 2};
  d.pinnedVertices = {0, n - 1};
  d.distanceCompliance = compliance;
  d.bendCompliance = 1;  // soft bending: the sag is the distance constraints'
  d.iterations = iterations;
  d.damping = 0.05;  // settles within 5 s
  return build(d, gridObj(n, 1));
}

}  // namespace

TEST(Deformable, ClothPinnedAtTwoCornersSagsByItsStiffnessAndStaysAtRest) {
  AnalyticSurfaces none;
  const int n = 9;
  const double dt = 0.01;
  auto rigid = hangingCloth(n, 0), stiff = hangingCloth(n, 1e-3), soft = hangingCloth(n, 1e-2);
  ASSERT_TRUE(rigid && stiff && soft);
  const Eigen::Vector3d pinA = rigid->positions()[0], pinB = rigid->positions()[n - 1];
  for (auto* b : {rigid.get(), stiff.get(), soft.get()}) run(*b, none, 5, dt);
  // Softer hangs lower (the far corner, vertex n*n - 1).  The rigid cloth
  // is 1 m long: nothing of it hangs more than 1 m (plus the stretch
  // below) under the pins at z = 2.
  EXPECT_LT(soft->positions().back().z(), stiff->positions().back().z() - 0.05);
  EXPECT_LT(stiff->positions().back().z(), rigid->positions().back().z() - 0.002);
  EXPECT_GT(lowest(rigid->positions()), 2 - 1.03);
  EXPECT_LT(lowest(rigid->positions()), 2 - 0.9);  // it does hang
  // Rigid edges stay within 2% of their rest length (40 Gauss-Seidel
  // iterations on a 9 x 9 cloth leave that much of the weight unresolved).
  const DeformableModel& m = rigid->model();
  double worst = 0;
  for (const DistanceConstraint& c : m.distances)
    worst = std::max(worst, std::abs((m.positions[c.a] - m.positions[c.b]).norm() / c.rest - 1));
  EXPECT_LT(worst, 0.02);
  // At rest: the centroid moves less than 0.1 mm over 10 s more.
  for (auto* b : {rigid.get(), stiff.get(), soft.get()}) {
    Eigen::Vector3d before = centroid(b->positions());
    run(*b, none, 10, dt);
    EXPECT_LT((centroid(b->positions()) - before).norm(), 1e-4);
    EXPECT_LT(b->maxSpeed(), 1e-3);
  }
  // Pinned vertices have not moved at all.
  EXPECT_EQ(rigid->positions()[0], pinA);
  EXPECT_EQ(rigid->positions()[n - 1], pinB);
}

TEST(Deformable, TotalMassIsTotalMassWhateverThePins) {
  Deformable d = defaultRecord();
  d.totalMass = 0.37;
  d.pinnedVertices = {0, 3, 5};
  auto b = build(d, gridObj(6, 1));
  ASSERT_TRUE(b);
  EXPECT_NEAR(b->totalMass(), 0.37, 1e-15);
  EXPECT_EQ(b->model().particleMass * 36, b->totalMass());
  EXPECT_EQ(b->model().inverseMass[3], 0);
  EXPECT_DOUBLE_EQ(b->model().inverseMass[4], 36 / 0.37);
}

TEST(Deformable, ConstraintCountsFollowTheMesh) {
  // A 4 x 4 grid: 3 x 4 x 2 axis edges + 9 diagonals = 33 edges, of which
  // 33 - 12 boundary = 21 interior (one bend each).
  auto cloth = build(defaultRecord(), gridObj(4, 1));
  ASSERT_TRUE(cloth);
  EXPECT_EQ(cloth->distanceConstraintCount(), 33u);
  EXPECT_EQ(cloth->bendingConstraintCount(), 21u);
  // mass_spring: the bends become flexion springs between opposite vertices.
  auto springs = build(defaultRecord("mass_spring"), gridObj(4, 1));
  ASSERT_TRUE(springs);
  EXPECT_EQ(springs->distanceConstraintCount(), 33u + 21u);
  EXPECT_EQ(springs->bendingConstraintCount(), 0u);
  // Negative bendCompliance and no bendStiffness: no bending at all (RaiSim).
  Deformable d = defaultRecord();
  d.bendCompliance = -1;
  d.bendStiffness = 0;
  EXPECT_EQ(build(d, gridObj(4, 1))->bendingConstraintCount(), 0u);
}

TEST(Deformable, ComplianceRulesFollowRaiSim) {
  Deformable d = defaultRecord();
  d.distanceCompliance = -1;  // negative: 1 / distanceStiffness
  d.distanceStiffness = 500;
  EXPECT_DOUBLE_EQ(build(d, gridObj(3, 1))->model().distances[0].compliance, 1.0 / 500);
  d.distanceCompliance = 2e-3;
  EXPECT_DOUBLE_EQ(build(d, gridObj(3, 1))->model().distances[0].compliance, 2e-3);
  // youngsModulus: alpha = L / (E A), A = thickness x (adjacent area / 3) / L.
  d.youngsModulus = 1e5;
  d.thickness = 0.01;
  auto b = build(d, gridObj(3, 1));  // cells 0.5 m: triangles of 0.125 m^2
  for (const DistanceConstraint& c : b->model().distances) {
    if (c.a == 0 && c.b == 1) {  // a boundary edge of one triangle, 0.5 m
      double area = 0.01 * (0.125 / 3) / 0.5;
      EXPECT_DOUBLE_EQ(c.compliance, 0.5 / (1e5 * area));
    }
  }
}

// Issue 24: the energy check.  A hanging chain's kinetic energy stays
// within what gravity gave it (runaway() empty); a chain whose links start
// at a tenth of their rest length is thrown apart by energy no gravity or
// body gave it, and runaway() says so with the figures (World stops the
// run with RS7024).
TEST(Deformable, RunawayIsKineticEnergyPastWhatGravityAndBodiesGave) {
  AnalyticSurfaces none;
  XpbdDeformable hanging(chain(5, 0.1, 0.2, 1e-3, 20));
  for (int i = 0; i < 400; ++i) {
    hanging.step(0.005, Eigen::Vector3d(0, 0, -9.81), none);
    ASSERT_EQ(hanging.runaway(), "") << "step " << i;
  }
  EXPECT_GE(hanging.gravityWork(), 0);
  EXPECT_LE(hanging.kineticEnergy(), hanging.gravityWork() + 1e-12);

  DeformableModel m = chain(5, 0.1, 0.2, 0, 20);
  for (std::size_t i = 0; i < m.positions.size(); ++i) m.positions[i] *= 0.1;  // compressed tenfold
  XpbdDeformable burst(std::move(m));
  burst.step(0.005, Eigen::Vector3d::Zero(), none);
  const std::string why = burst.runaway();
  EXPECT_NE(why.find("is past what gravity (0 J) and the bodies it touched (0 J) gave it"), std::string::npos) << why;
  EXPECT_GT(burst.kineticEnergy(), 0.5 * 1.0 * 1.0);  // past the 1 m/s margin for the 1 kg free
}
