// The granular solver (lib/sim/granular_*.cpp) against closed-form answers
// and the behaviours RaiSim's GranularSystem documents, on AnalyticSurfaces
// (a ground plane, spheres) so nothing but the solver is under test.  Each
// tolerance says why it is not tighter.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "sim/granular_body.hpp"
#include "sim/granular_contact.hpp"
#include "sim/granular_dem.hpp"
#include "sim/granular_material.hpp"

using namespace rscene;
using namespace rscene::sim;

namespace {

const Eigen::Vector3d kGravity(0, 0, -9.81);

// A record as RaiSim's GranularMedia.rst example writes its material
// (radius 0.02, normalStiffness 5e4 ...), linear law, explicit positions.
Granular record(std::vector<Eigen::Vector3d> positions, double radius = 0.02) {
  Granular g;
  g.path = "/World/Sand";
  g.positions = std::move(positions);
  g.radius = radius;
  g.spacing = 0.043;
  g.maxParticles = 20000;
  g.density = 1600;
  g.normalStiffness = 5e4;
  g.normalDamping = 25;
  g.tangentialStiffness = 2.5e4;
  g.tangentialDamping = 6;
  g.friction = 0.8;
  g.rollingFriction = 0.02;
  g.normalContactModel = "linear";
  g.substeps = 2;
  return g;
}

std::unique_ptr<GranularBody> make(const Granular& g, double dt, std::vector<GranularFinding>* out = nullptr) {
  std::vector<GranularFinding> findings;
  std::unique_ptr<GranularBody> body = GranularBody::create(g, dt, findings);
  for (const GranularFinding& f : findings)
    if (f.error || !out) ADD_FAILURE() << f.code << " " << f.field << ": " << f.message;
  if (out) *out = findings;
  return body;
}

// The findings of a record that must be refused.
std::vector<GranularFinding> refused(const Granular& g, double dt = 0.001) {
  std::vector<GranularFinding> findings;
  EXPECT_EQ(GranularBody::create(g, dt, findings), nullptr);
  return findings;
}

double sphereMass(double density, double r) { return density * 4.0 / 3.0 * M_PI * r * r * r; }

// A box fill of nx x ny x nz grains, spacing s, lowest centre at z0,
// centred on the z axis.  `jitter` moves each grain sideways by up to
// that much (a fixed sequence, like RaiSim's seeded emitBoxRandom): a
// perfect lattice stacks grain on grain and never collapses.
std::vector<Eigen::Vector3d> block(int nx, int ny, int nz, double s, double z0, double jitter = 0) {
  std::vector<Eigen::Vector3d> p;
  std::uint32_t seed = 12345;
  auto next = [&] {  // in [-1, 1)
    seed = seed * 1664525u + 1013904223u;
    return double(seed >> 8) / double(1u << 23) - 1;
  };
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        double dx = jitter * next(), dy = jitter * next();
        p.emplace_back((x - (nx - 1) / 2.0) * s + dx, (y - (ny - 1) / 2.0) * s + dy, z0 + z * s);
      }
  return p;
}

void run(GranularBody& body, AnalyticSurfaces& ground, double dt, double seconds) {
  long n = std::lround(seconds / dt);
  for (long k = 0; k < n; ++k) body.step(dt, kGravity, ground);
}

// The pile's angle: atan of its height over the horizontal distance from
// its axis within which 95 % of the grains lie (both from the grains'
// centres).  Lower than the slope a protractor would read on the flank
// (the 95 % radius reaches into the grains that rolled off the toe), but
// measured the same way for both runs, which is what the comparison needs.
double reposeAngleDegrees(const GranularBody& body) {
  const auto& p = body.positions();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& x : p) centre += x;
  centre /= double(p.size());
  std::vector<double> d;
  double top = 0;
  for (const auto& x : p) d.push_back(std::hypot(x.x() - centre.x(), x.y() - centre.y())), top = std::max(top, x.z());
  std::sort(d.begin(), d.end());
  double spread = d[static_cast<std::size_t>(0.95 * double(d.size() - 1))];
  return std::atan2(top, spread) * 180 / M_PI;
}

}  // namespace

TEST(Granular, MassIsDensityTimesSphereVolume) {
  auto body = make(record({{0, 0, 1}, {1, 0, 1}}, 0.02), 0.001);
  ASSERT_TRUE(body);
  EXPECT_DOUBLE_EQ(body->totalMass(), 2 * sphereMass(1600, 0.02));
}

TEST(Granular, RestingLinearOverlapIsWeightOverStiffness) {
  const double r = 0.02, dt = 0.001;
  Granular g = record({{0, 0, r}});
  g.normalDamping = 10;  // settles within the run
  auto body = make(g, dt);
  AnalyticSurfaces ground;
  ground.groundHeights = {0};
  run(*body, ground, dt, 3);
  const double expected = sphereMass(1600, r) * 9.81 / 5e4;  // kn d = m g
  // At rest the spring holds the weight exactly; 1e-6 relative is what
  // is left of the damped oscillation after 3 s (decay time 2m/c = 0.01 s).
  EXPECT_NEAR(r - body->positions()[0].z(), expected, 1e-6 * expected);
  EXPECT_LT(body->maxSpeed(), 1e-6);
}

TEST(Granular, RestingHertzOverlapFollowsTheHertzLaw) {
  const double r = 0.02, dt = 0.001;
  Granular g = record({{0, 0, r}});
  g.normalContactModel = "hertz";
  g.normalDamping = 10;
  auto body = make(g, dt);
  AnalyticSurfaces ground;
  ground.groundHeights = {0};
  run(*body, ground, dt, 3);
  // kn d sqrt(d / R) = m g with R = r against a plane: d = (m g sqrt(R) / kn)^(2/3).
  const double weight = sphereMass(1600, r) * 9.81;
  const double expected = std::pow(weight * std::sqrt(r) / 5e4, 2.0 / 3.0);
  EXPECT_NEAR(r - body->positions()[0].z(), expected, 1e-6 * expected);
  // Softer than linear for small overlaps, as RaiSim says: deeper than m g / kn.
  EXPECT_GT(expected, weight / 5e4);
}

TEST(Granular, LinearBounceHasTheRestitutionItsDampingImplies) {
  // No gravity: the grain meets the ground at 1 m/s and leaves at e m/s.
  const double r = 0.02, dt = 1e-5, kn = 5e4, cn = 10;
  Granular g = record({{0, 0, r + 1e-4}});
  g.normalStiffness = kn;
  g.normalDamping = cn;
  g.velocity = {0, 0, -1};
  g.substeps = 1;
  auto body = make(g, dt);
  AnalyticSurfaces ground;
  ground.groundHeights = {0};
  for (int k = 0; k < 3000; ++k) body->step(dt, Eigen::Vector3d::Zero(), ground);
  const double m = sphereMass(1600, r), zeta = cn / (2 * std::sqrt(kn * m));
  const double e = std::exp(-M_PI * zeta / std::sqrt(1 - zeta * zeta));
  const double vOut = body->velocities()[0].z();
  std::printf("restitution: measured %.4f, spring-dashpot closed form %.4f (zeta %.3f)\n", vOut, e, zeta);
  // The closed form ends the contact when the overlap is back to 0; the
  // force reaches 0 (and is clamped there, never pulling) slightly
  // earlier, while the dashpot still pushes, so the grain leaves a little
  // faster than exp(-pi z / sqrt(1 - z^2)): within 3 % at zeta 0.14.
  EXPECT_GT(vOut, e);
  EXPECT_NEAR(vOut, e, 0.03 * e);
}

TEST(Granular, ASlidingGrainEndsRollingAtFiveSeventhsOfItsSpeed) {
  // Thrown flat without spin, Coulomb friction turns sliding into rolling:
  // v = 5/7 v0 for a solid sphere, whatever the friction coefficient.
  const double r = 0.02, v0 = 0.5, dt = 0.001;
  Granular g = record({{0, 0, r - sphereMass(1600, r) * 9.81 / 5e4}});
  g.rollingFriction = 0;
  g.velocity = {v0, 0, 0};
  auto body = make(g, dt);
  AnalyticSurfaces ground;
  ground.groundHeights = {0};
  ground.friction = 0.8;
  run(*body, ground, dt, 0.5);
  std::printf("sliding grain: rolls on at %.4f m/s, closed form %.4f m/s\n", body->velocities()[0].x(), v0 * 5 / 7);
  EXPECT_NEAR(body->velocities()[0].x(), v0 * 5 / 7, 0.01 * v0);  // the tangential spring's last wobble
}

TEST(Granular, RollingResistanceStopsARollingGrainWhereTheClosedFormSays) {
  // A grain rolling without slip on the ground at v0 under a resisting
  // torque mur r m g decelerates at mur g / (1 + 2/5) and stops after
  // v0^2 / (2 a).
  const double r = 0.02, v0 = 0.3, mur = 0.1, dt = 0.001;
  Granular g = record({{0, 0, r - sphereMass(1600, r) * 9.81 / 5e4}});
  g.rollingFriction = mur;
  g.velocity = {v0, 0, 0};
  g.angularVelocity = {0, v0 / r, 0};
  auto body = make(g, dt);
  AnalyticSurfaces ground;
  ground.groundHeights = {0};
  run(*body, ground, dt, 1);
  const double a = mur * 9.81 / 1.4, distance = v0 * v0 / (2 * a);
  std::printf("rolling grain: stopped after %.4f m, closed form %.4f m\n", body->positions()[0].x(), distance);
  // 5 %: the resting overlap shortens the lever arm, and the rolling
  // spring winds up elastically before it slips (granular_contact.hpp).
  EXPECT_NEAR(body->positions()[0].x(), distance, 0.05 * distance);
  EXPECT_LT(body->maxSpeed(), 1e-3);
}

TEST(Granular, ColumnCollapsesToAPileSteeperWithMoreFriction) {
  const double dt = 0.001;
  double angle[2];
  const double friction[2] = {0.2, 0.8};
  for (int k = 0; k < 2; ++k) {
    Granular g = record(block(8, 8, 8, 0.042, 0.021, 0.001));
    g.friction = friction[k];
    g.rollingFriction = 0.1;
    auto body = make(g, dt);
    AnalyticSurfaces ground;
    ground.groundHeights = {0};
    ground.friction = friction[k];
    run(*body, ground, dt, 2.5);
    angle[k] = reposeAngleDegrees(*body);
    std::printf("friction %.1f: angle of repose %.1f degrees (max speed %.3g m/s)\n", friction[k], angle[k],
                body->maxSpeed());
  }
  EXPECT_GT(angle[1], angle[0] + 3);  // ordered, by more than the measure's grain-sized noise
}

TEST(Granular, FreshlyPouredBedNeverLetsAGrainThroughTheGround) {
  const double r = 0.02, dt = 0.001;
  Granular g = record(block(10, 10, 8, 0.045, 0.15));
  auto body = make(g, dt);
  AnalyticSurfaces ground;
  ground.groundHeights = {0};
  double lowest = INFINITY;
  for (int k = 0; k < 1500; ++k) {
    body->step(dt, kGravity, ground);
    for (const auto& x : body->positions()) lowest = std::min(lowest, x.z());
  }
  std::printf("800 grains dropped 0.15 m: deepest overlap with the ground %.3g r\n", (r - lowest) / r);
  EXPECT_GT(lowest, 0.8 * r);  // a centre never sinks a fifth of a radius into the ground
  EXPECT_LT(body->maxSpeed(), 0.05);
}

TEST(Granular, RunsAreByteIdentical) {
  auto once = [] {
    Granular g = record(block(6, 6, 6, 0.043, 0.05));
    g.normalContactModel = "hertz";
    g.cohesionStiffness = 50;
    g.cohesionMaxDistance = 0.002;
    auto body = make(g, 0.001);
    AnalyticSurfaces world;
    world.groundHeights = {0};
    world.spheres.push_back({Eigen::Vector3d(0.05, 0, 0.5), 0.06, Eigen::Vector3d(0, 0, -0.5), true});
    run(*body, world, 0.001, 0.6);
    return body->positions();
  };
  auto a = once(), b = once();
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])), 0);
}

TEST(Granular, FixedGrainsNeverMoveAndStillPush) {
  Granular g = record(block(3, 3, 1, 0.042, 0.5));
  g.fixed = true;
  g.velocity = {1, 2, 3};  // ignored for fixed grains, as RaiSim's setters are
  auto body = make(g, 0.001);
  const auto start = body->positions();
  AnalyticSurfaces world;
  // A dynamic sphere resting into the grains from above.
  world.spheres.push_back({Eigen::Vector3d(0, 0, 0.5 + 0.02 + 0.05 - 0.001), 0.05, Eigen::Vector3d::Zero(), true});
  body->step(0.001, kGravity, world);
  EXPECT_EQ(body->positions(), start);
  EXPECT_EQ(body->maxSpeed(), 0);
  EXPECT_GT(world.spheres[0].force.z(), 0);  // pushed up
  EXPECT_NEAR(world.spheres[0].force.x(), 0, 1e-9);  // symmetric grains: no sideways push
}

TEST(Granular, CohesionPullsGrainsTogetherAndHoldsThem) {
  // Zero gravity, a gap of 1 mm: cohesion (range 2 mm) closes it and the
  // grains stay in touch; without cohesion they stay where they are.
  const double r = 0.02, gap = 0.001;
  for (bool cohesive : {true, false}) {
    Granular g = record({{0, 0, 0}, {2 * r + gap, 0, 0}});
    g.cohesionStiffness = cohesive ? 200 : 0;
    g.cohesionMaxDistance = 0.002;
    auto body = make(g, 0.001);
    AnalyticSurfaces none;
    double widest = 0;
    for (int k = 0; k < 2000; ++k) {
      body->step(0.001, Eigen::Vector3d::Zero(), none);
      widest = std::max(widest, (body->positions()[1] - body->positions()[0]).norm() - 2 * r);
    }
    double last = (body->positions()[1] - body->positions()[0]).norm() - 2 * r;
    if (cohesive) {
      EXPECT_LT(last, 1e-4) << "cohesion brought them into touch";
      EXPECT_LE(widest, gap + 1e-12) << "and never let them drift apart";
    } else {
      EXPECT_NEAR(last, gap, 1e-12);
    }
  }
}

TEST(Granular, SphereSinksLessIntoABedOfDenserGrains) {
  // Bearing capacity grows with the unit weight of the bed (Terzaghi's
  // 0.5 gamma B N_gamma): the same sphere on a bed of heavier grains stops
  // higher.  The sphere is an AnalyticSurfaces body this test integrates
  // under gravity and the grains' summed reaction (semi-implicit Euler,
  // the solver's own integrator, one world step at a time).
  const double dt = 0.001, R = 0.06, mass = 1;
  double sink[2];
  const double density[2] = {800, 3200};
  for (int k = 0; k < 2; ++k) {
    Granular g = record(block(16, 16, 6, 0.042, 0.021, 0.001));
    g.density = density[k];
    g.rollingFriction = 0.1;
    std::vector<GranularFinding> warnings;  // the light grains need a third substep (RS7086)
    auto body = make(g, dt, &warnings);
    AnalyticSurfaces world;
    world.groundHeights = {0};
    run(*body, world, dt, 0.6);  // settle
    double top = 0;
    for (const auto& x : body->positions())
      if (std::hypot(x.x(), x.y()) < R) top = std::max(top, x.z() + 0.02);
    world.spheres.push_back({Eigen::Vector3d(0, 0, top + R), R, Eigen::Vector3d::Zero(), true});
    AnalyticSurfaces::Sphere& s = world.spheres[0];
    for (int n = 0; n < 1500; ++n) {
      s.force.setZero();
      body->step(dt, kGravity, world);
      s.velocity += dt * (s.force / mass + kGravity);
      s.centre += dt * s.velocity;
    }
    sink[k] = top - (s.centre.z() - R);
    std::printf("grain density %.0f: the sphere sank %.4f m into the bed %.3f m deep\n", density[k], sink[k], top);
  }
  EXPECT_GT(sink[0], sink[1]);
}

TEST(Granular, VelocityIsInTheRecordFrame) {
  Granular g = record({{0, 0, 0}});
  g.world.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  g.world.position = {1, 2, 3};
  g.velocity = {1, 0, 0};
  auto body = make(g, 0.001);
  AnalyticSurfaces none;
  body->step(0.001, Eigen::Vector3d::Zero(), none);
  EXPECT_NEAR(body->positions()[0].x(), 1, 1e-12);
  EXPECT_NEAR(body->positions()[0].y(), 2.001, 1e-12);
  EXPECT_NEAR(body->positions()[0].z(), 3, 1e-12);
}

TEST(Granular, StableSubstepIsAFractionOfTheDampedCriticalStep) {
  GranularMaterial m;
  m.kn = 5e4;
  m.cn = 25;
  m.kt = 2.5e4;
  m.ct = 6;
  m.hertz = false;
  const double mass = sphereMass(1600, 0.02), pair = mass / 2;
  auto critical = [](double k, double c, double mm) {
    double w = std::sqrt(k / mm), z = c / (2 * std::sqrt(k * mm));
    return 2 / w * (std::sqrt(1 + z * z) - z);
  };
  double expected = kStableFraction * std::min(critical(5e4, 25, pair), critical(3.5 * 2.5e4, 3.5 * 6, pair));
  EXPECT_DOUBLE_EQ(granularMaxSubstep(m, mass), expected);
  // RaiSim's example material runs at 1 ms in its 2 substeps.
  EXPECT_GT(granularMaxSubstep(m, mass), 0.0005);
}

TEST(Granular, SchemaDefaultsRaiseTheSubstepsWithAWarning) {
  Granular g = record(block(3, 3, 3, 0.025, 0.011), 0.01);
  g.normalStiffness = 1e6;
  g.normalDamping = 200;
  g.tangentialStiffness = 1e5;
  g.tangentialDamping = 20;
  g.normalContactModel = "hertz";
  g.friction = 0.6;
  g.rollingFriction = 0.05;
  std::vector<GranularFinding> findings;
  auto body = make(g, 0.0025, &findings);
  ASSERT_TRUE(body);
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_FALSE(findings[0].error);
  EXPECT_STREQ(findings[0].code, "RS7086");
  EXPECT_EQ(findings[0].field, "substeps");
  EXPECT_NE(findings[0].message.find("substeps raised from 2 to "), std::string::npos) << findings[0].message;
  // The raised substeps keep the stiff bed quiet: it settles, no grain flies.
  AnalyticSurfaces ground;
  ground.groundHeights = {0};
  run(*body, ground, 0.0025, 1);
  EXPECT_GT(body->stats().substepsPerStep, 2);
  EXPECT_TRUE(body->finite());
  EXPECT_LT(body->maxSpeed(), 0.05);
  for (const auto& x : body->positions()) EXPECT_GT(x.z(), 0.008);
}

TEST(Granular, HostileRecordsAreRefusedAtTheirKey) {
  auto one = [](auto edit) {
    Granular g = record({{0, 0, 1}});
    edit(g);
    auto f = refused(g);
    return f.empty() ? GranularFinding{} : f[0];
  };
  GranularFinding f = one([](Granular& g) { g.radii = {-0.01}; });
  EXPECT_STREQ(f.code, "RS7088");
  EXPECT_EQ(f.field, "radii");
  f = one([](Granular& g) { g.density = NAN; });
  EXPECT_STREQ(f.code, "RS7088");
  EXPECT_EQ(f.field, "density");
  f = one([](Granular& g) { g.density = -1600; });
  EXPECT_EQ(f.field, "density");
  f = one([](Granular& g) { g.normalDamping = -1; });
  EXPECT_EQ(f.field, "normalDamping");
  // An unknown normalContactModel is the reader's (the schema's
  // contact_model enumeration, RS2006): tests/scene/check_test.cpp.
  f = one([](Granular& g) { g.substeps = 0; });
  EXPECT_EQ(f.field, "substeps");
  f = one([](Granular& g) { g.velocity = {INFINITY, 0, 0}; });
  EXPECT_EQ(f.field, "velocity");
  f = one([](Granular& g) { g.positions = {{0, 0, NAN}}; });
  EXPECT_EQ(f.field, "positions");
  f = one([](Granular& g) { g.positions = {{0, 0, 1}, {1, 0, 1}}, g.radii = {0.001, 0.02}; });
  EXPECT_STREQ(f.code, "RS7088");  // a span the neighbour grid cannot serve
  EXPECT_EQ(f.field, "radii");
  f = one([](Granular& g) { g.positions = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}}; });  // one point
  EXPECT_STREQ(f.code, "RS7089");
  f = one([](Granular& g) { g.normalStiffness = 1e12; });  // would need millions of substeps
  EXPECT_STREQ(f.code, "RS7087");
  EXPECT_EQ(f.field, "normalStiffness");
}

TEST(Granular, AHugeBoxFillIsRefusedBeforeAllocating) {
  Granular g = record({});
  g.boxMin = {-1000, -1000, 0};
  g.boxMax = {1000, 1000, 1000};  // ~1e17 grains
  g.maxParticles = 0;             // no limit of its own: the hard limit holds
  auto f = refused(g);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_STREQ(f[0].code, "RS7082");
  EXPECT_EQ(f[0].field, "maxParticles");
  EXPECT_NE(f[0].message.find("more than the limit of 2000000"), std::string::npos) << f[0].message;
  g.boxMax = {1000, 1000, INFINITY};
  EXPECT_STREQ(refused(g)[0].code, "RS7082");
}

TEST(Granular, AnEmptyBedIsFine) {
  Granular g = record({});
  g.spacing = 0.05;  // box 0,0,0 - 0,0,0: no grain fits
  auto body = make(g, 0.001);
  ASSERT_TRUE(body);
  AnalyticSurfaces ground;
  body->step(0.001, kGravity, ground);
  EXPECT_TRUE(body->positions().empty());
  EXPECT_EQ(body->maxSpeed(), 0);
}

// Issue 24 (01): cohesionMaxDistance=100 listed every pair of a bed.  The
// range is at most the smallest radius: cohesion acts at contact distances.
TEST(Granular, ACohesionRangePastTheSmallestRadiusIsRefusedAtItsKey) {
  Granular g = record(block(3, 3, 1, 0.043, 0.5));
  g.cohesionStiffness = 1e-9;
  g.cohesionMaxDistance = 100;
  auto f = refused(g);
  ASSERT_FALSE(f.empty());
  EXPECT_STREQ(f[0].code, "RS7088");
  EXPECT_EQ(f[0].field, "cohesionMaxDistance");
  EXPECT_NE(f[0].message.find("cohesionMaxDistance 100 m is more than the smallest grain radius 0.02 m"),
            std::string::npos)
      << f[0].message;
  g.cohesionMaxDistance = 0.02;  // one radius: allowed
  EXPECT_NE(make(g, 0.001), nullptr);
  g.cohesionStiffness = 0;  // a range without a force is nothing
  g.cohesionMaxDistance = 100;
  EXPECT_NE(make(g, 0.001), nullptr);
}

// Issue 24 (06): the force jumped from kc gmax to 0 at the cut-off.
TEST(Granular, CohesionFallsContinuouslyToZeroAtItsCutOff) {
  GranularMaterial m;
  m.kn = 5e4;
  m.cohesionStiffness = 5e4;
  m.cohesionMaxDistance = 0.02;
  GranularContact c;
  c.n = Eigen::Vector3d::UnitX();
  c.ra = c.rb = 0.02;
  c.reff = 0.01;
  c.va = c.vb = c.wa = c.wb = Eigen::Vector3d::Zero();
  auto force = [&](double gap) {
    GranularHistory h;
    c.depth = -gap;
    return granularContactForce(m, c, 1e-4, h).force.x();
  };
  const double eps = 1e-9;
  EXPECT_NEAR(force(0.02 - eps), 0, 5e4 * eps * 1.01);  // nothing left to jump from
  EXPECT_EQ(force(0.02), 0);
  EXPECT_NEAR(force(1e-6), -5e4 * 1e-6, 1e-4 * 5e4 * 1e-6);  // slope kc at contact (1 - g/gmax = 1 - 5e-5)
  EXPECT_NEAR(force(0.01), -5e4 * 0.01 * 0.5, 1e-9);  // kc g (1 - g / gmax)
  EXPECT_EQ(force(0.03), 0);
}

// A pair at rest in contact under cohesion, no gravity: the cohesion is
// zero at contact, so nothing moves (closed form: rest stays rest).
TEST(Granular, GrainsAtRestUnderCohesionStayAtRest) {
  const double r = 0.02;
  // (A third grain at (0, 2r, 0) would be 0.83 r from the second: in
  // range, pulled in, as it should be.)
  Granular g = record({{0, 0, 0}, {2 * r, 0, 0}});
  g.cohesionStiffness = 9000;  // near the largest RS7092 lets pass at this range
  g.cohesionMaxDistance = r;
  auto body = make(g, 0.001);
  AnalyticSurfaces none;
  const auto start = body->positions();
  for (int k = 0; k < 1000; ++k) body->step(0.001, Eigen::Vector3d::Zero(), none);
  EXPECT_LT(body->maxSpeed(), 1e-9);  // round-off of 2 r as a distance, no more
  for (std::size_t i = 0; i < start.size(); ++i) EXPECT_LT((body->positions()[i] - start[i]).norm(), 1e-12);
  EXPECT_FALSE(body->failure());
}

// Issue 24 (06): 32 grains resting on the ground, cohesion as stiff as the
// contacts over one radius (the reproducer): they flew to 53 m.  Such
// cohesion is now refused up front (RS7092: its well is deeper than the
// contacts hold); at the strongest cohesion the rule lets pass the bed
// stays a heap, or the run is stopped with RS7083 at the cohesion; never
// a grain above a metre with no error.
TEST(Granular, ACohesiveBedDoesNotGainEnergy) {
  const double r = 0.02;
  for (double kc : {5e4, 2e5}) {
    Granular g = record(block(4, 4, 2, 0.043, r + 0.003));
    g.substeps = 3;
    g.cohesionStiffness = kc;
    g.cohesionMaxDistance = r;
    std::vector<GranularFinding> f = refused(g);
    ASSERT_FALSE(f.empty());
    EXPECT_STREQ(f[0].code, "RS7092");
  }
  Granular g = record(block(4, 4, 2, 0.043, r + 0.003));
  g.substeps = 3;
  g.cohesionStiffness = 9000;
  g.cohesionMaxDistance = r;
  auto body = make(g, 0.001);
  AnalyticSurfaces ground;
  ground.groundHeights = {0};
  double top = 0;
  for (int k = 0; k < 1000 && !body->failure(); ++k) {
    body->step(0.001, kGravity, ground);
    for (const auto& p : body->positions()) top = std::max(top, p.z());
  }
  if (body->failure()) {
    EXPECT_STREQ(body->failure()->code, "RS7083");
    EXPECT_EQ(body->failure()->field, "cohesionStiffness");
  } else {
    EXPECT_LT(top, 0.2);  // the bed was 0.07 m tall
  }
}

// An unstable solver is stopped: a grain resting on the ground, no
// damping, a substep three times the critical one of its contact (built
// past the setup's stability rule, which would have raised the substeps).
// Each bounce gains energy from nothing: RS7083 at substeps (no cohesion),
// caught while the grain is still near (not at 1e300 m).
TEST(Granular, EnergyFromNothingStopsTheRun) {
  const double r = 0.02;
  Granular g = record({{0, 0, r - 1e-5}});
  g.normalDamping = 0, g.tangentialDamping = 0;
  std::vector<GranularFinding> findings;
  std::optional<GranularSetup> setup = granularSetup(g, 0.001, findings);
  ASSERT_TRUE(setup);
  const double critical = 2 / std::sqrt(5e4 / sphereMass(1600, r));
  setup->substeps = 1;
  setup->maxSubstep = 1;  // the step below is not raised
  auto body = makeGranularDem(std::move(*setup));
  AnalyticSurfaces ground;
  ground.groundHeights = {0};
  int k = 0;
  for (; k < 5000 && !body->failure(); ++k) body->step(3 * critical, kGravity, ground);
  ASSERT_TRUE(body->failure()) << "max speed " << body->maxSpeed();
  EXPECT_STREQ(body->failure()->code, "RS7083");
  EXPECT_EQ(body->failure()->field, "substeps");  // no cohesion: the time step
  EXPECT_LT(body->maxSpeed(), 100) << "stopped early, at step " << k;
  // The same grain at its stable step keeps its energy and runs on.
  setup = granularSetup(g, 0.001, findings);
  body = makeGranularDem(std::move(*setup));
  for (k = 0; k < 5000; ++k) body->step(0.001, kGravity, ground);
  EXPECT_FALSE(body->failure());
}

// Issue 24 (12): grains written past 1e9 m were refused on reload.
TEST(Granular, GrainsLeavingTheBoundsStopTheRun) {
  // 55 m inside the bound at the fastest start a record may give (1e4 m/s):
  // 10 m a step, past 1e9 m in the sixth.
  Granular g = record({{1e9 - 55, 0, 1}});
  g.velocity = {kMaxGranularSpeed, 0, 0};
  auto body = make(g, 0.001);
  AnalyticSurfaces none;
  for (int k = 0; k < 3000 && !body->failure(); ++k) body->step(0.001, Eigen::Vector3d::Zero(), none);
  ASSERT_TRUE(body->failure());
  EXPECT_STREQ(body->failure()->code, "RS7084");
  EXPECT_NE(body->failure()->message.find("grain 0 is past 1e9 m at step 6"), std::string::npos)
      << body->failure()->message;
  for (const auto& p : body->positions()) EXPECT_LE(std::abs(p.x()), 1.001e9);
}

// Hostile input round two, trial: velocity=1e9 was accepted and the run
// failed later (RS7084); a start past 1e4 m/s is refused at its key.
TEST(Granular, AStartFasterThanTheBoundIsRefusedAtItsKey) {
  Granular g = record({{0, 0, 1}});
  g.velocity = {1e9, 0, 0};
  auto f = refused(g);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_STREQ(f[0].code, "RS7088");
  EXPECT_EQ(f[0].field, "velocity");
  g.velocity = {0, 0, -1.01e4};
  EXPECT_EQ(refused(g).size(), 1u);
  g.velocity = {0, 0, 0};
  g.angularVelocity = {0, 6e5, 0};  // radius 0.02: 1.2e4 m/s at the surface
  f = refused(g);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].field, "angularVelocity");
  g.angularVelocity = {0, 4e5, 0};  // 8e3 m/s
  std::vector<GranularFinding> fine;
  EXPECT_TRUE(make(g, 0.001, &fine));
}

// Issue 24 (15): the messages point at the key that is wrong and print
// its number as written.
TEST(Granular, BoxFillMessagesNameTheirKeyAndNumber) {
  Granular g = record({});
  g.boxMin = {-0.1, -0.1, 0};
  g.boxMax = {0.1, 0.1, 0.1};
  g.radius = 0;
  auto f = refused(g);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_STREQ(f[0].code, "RS7082");
  EXPECT_EQ(f[0].field, "radius");
  EXPECT_NE(f[0].message.find("radius 0:"), std::string::npos) << f[0].message;
  EXPECT_EQ(f[0].message.find("0.000000"), std::string::npos) << f[0].message;
  g.radius = 0.02, g.spacing = -1;
  f = refused(g);
  EXPECT_EQ(f[0].field, "spacing");
  g.radius = 1e-9, g.spacing = 1e-8, g.maxParticles = 5000;
  f = refused(g);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].field, "maxParticles");  // the count against the record's own limit
  EXPECT_EQ(f[0].message.find("18446744073709551615"), std::string::npos) << f[0].message;
  EXPECT_NE(f[0].message.find("more than 1e18 particles"), std::string::npos) << f[0].message;
}

TEST(Granular, AFarGrainIsAPositionErrorNotAnOverlap) {
  Granular g = record({{0, 0, 1}, {1e300, 0, 1}, {2e300, 0, 1}});
  auto f = refused(g);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_STREQ(f[0].code, "RS7088");
  EXPECT_EQ(f[0].field, "positions");
}

TEST(Granular, APosePastTheBoundIsAPositionErrorAtThePose) {
  Granular g = record(block(3, 3, 1, 0.043, 0.5));
  g.world.position = {1e300, 0, 0};
  auto f = refused(g);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_STREQ(f[0].code, "RS7088");
  EXPECT_EQ(f[0].field, "position");
  EXPECT_EQ(f[0].message.find("overlap"), std::string::npos) << f[0].message;
}

// Hostile input round two (1): a grain starting inside the ground deeper
// than its spring can hold without throwing it is the scene model's
// finding (RS7091), with the count, the worst grain and its depth; a grain
// at its resting overlap (weight / kn, a hundredth of a millimetre) is not.
TEST(Granular, GrainsStartingInsideTheGroundAreCountedWithTheWorst) {
  const double r = 0.02, rest = sphereMass(1600, r) * 9.81 / 5e4;
  Granular g = record({{0, 0, r - rest}, {0.1, 0, r - 0.005}, {0.2, 0, r - 0.008}, {0.3, 0, 1}});
  std::vector<ParticleFinding> findings;
  std::optional<GranularSetup> s = granularSetup(g, 0.001, findings);
  ASSERT_TRUE(s);
  const double tol = granularStartDepthTolerance(s->material, r);
  // Linear: 1/2 kn d^2 = m g r.
  EXPECT_NEAR(tol, std::sqrt(2 * sphereMass(1600, r) * 9.81 * r / 5e4), 1e-12);
  EXPECT_GT(tol, 10 * rest);
  EXPECT_LT(tol, 0.005);
  GranularStartDepth deep = granularGroundDepth(*s, {0});
  EXPECT_EQ(deep.count, 2u);
  EXPECT_EQ(deep.worst, 2u);
  EXPECT_NEAR(deep.depth, 0.008, 1e-12);
  ParticleFinding f = granularStartDepthFinding(g, deep, "the ground");
  EXPECT_STREQ(f.code, "RS7091");
  EXPECT_EQ(f.field, "positions");
  EXPECT_NE(f.message.find("2 grains start inside the ground"), std::string::npos) << f.message;
  EXPECT_NE(f.message.find("grain 2 at (0.2, 0, 0.012), by 8 mm"), std::string::npos) << f.message;
  // A ground below them all: nothing.
  EXPECT_EQ(granularGroundDepth(*s, {-1}).count, 0u);
  // Never deeper than half the radius, however soft the spring.
  s->material.kn = 1e-3;
  EXPECT_DOUBLE_EQ(granularStartDepthTolerance(s->material, r), 0.5 * r);
}

// (1) The energy check does not count a start penetration as budget: a
// grain started 8 mm inside the ground (past the setup's rule, built
// directly) is thrown by its spring, and the run stops with RS7083 instead
// of accepting the energy as its own.
TEST(Granular, StartPenetrationEnergyIsNoBudget) {
  const double r = 0.02;
  Granular g = record({{0, 0, r - 0.008}});
  std::vector<GranularFinding> findings;
  std::optional<GranularSetup> setup = granularSetup(g, 0.001, findings);
  ASSERT_TRUE(setup);
  auto body = makeGranularDem(std::move(*setup));
  AnalyticSurfaces ground;
  ground.groundHeights = {0};
  for (int k = 0; k < 2000 && !body->failure(); ++k) body->step(0.001, kGravity, ground);
  ASSERT_TRUE(body->failure()) << "max speed " << body->maxSpeed();
  EXPECT_STREQ(body->failure()->code, "RS7083");
  // A grain just inside its tolerance settles with no error.
  setup = granularSetup(record({{0, 0, r - 0.9 * granularStartDepthTolerance(setup->material, r)}}), 0.001, findings);
  body = makeGranularDem(std::move(*setup));
  for (int k = 0; k < 2000; ++k) body->step(0.001, kGravity, ground);
  EXPECT_FALSE(body->failure());
  EXPECT_LT(body->maxSpeed(), 0.01);
}

// (3) Cohesion stronger than the contact repulsion: its well kc gmax^2 / 6
// past the normal spring's energy at a quarter of the smallest radius is
// refused at cohesionStiffness (RS7092), with the largest kc it allows.
TEST(Granular, CohesionStrongerThanTheContactsIsRefusedAtCohesionStiffness) {
  const double r = 0.02;
  Granular g = record(block(2, 2, 1, 0.043, 0.5));
  g.cohesionMaxDistance = r;
  // Linear: 1/2 5e4 (r / 4)^2 = 0.625 J; kc r^2 / 6 = 0.625 J at kc = 9375.
  g.cohesionStiffness = 9375 * 1.001;
  std::vector<GranularFinding> f = refused(g);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_STREQ(f[0].code, "RS7092");
  EXPECT_EQ(f[0].field, "cohesionStiffness");
  EXPECT_NE(f[0].message.find("cohesionStiffness may be at most 9.38e+03"), std::string::npos) << f[0].message;
  g.cohesionStiffness = 9375 * 0.999;
  EXPECT_TRUE(make(g, 0.001));
  // Hertz: 2/5 kn d^2 sqrt(d / Reff) at d = r / 4, Reff = r / 2.
  g.normalContactModel = "hertz";
  const double hertz = 0.4 * 5e4 * (r / 4) * (r / 4) * std::sqrt(0.5);
  g.cohesionStiffness = 6 * hertz / (r * r) * 1.001;
  EXPECT_EQ(refused(g).at(0).code, std::string("RS7092"));
  g.cohesionStiffness = 6 * hertz / (r * r) * 0.999;
  EXPECT_TRUE(make(g, 0.001));
}

// (3) When cohesion is the stiffest mode, RS7087 and RS7086 name
// cohesionStiffness, not normalStiffness.
TEST(Granular, StabilityFindingsNameCohesionWhenItIsTheStiffestMode) {
  Granular g = record(block(2, 2, 1, 0.041, 0.5));
  g.cohesionMaxDistance = 1e-4;
  g.cohesionStiffness = 3e8;  // well 0.5 J: within RS7092's rule
  std::vector<GranularFinding> f = refused(g, 0.02);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_STREQ(f[0].code, "RS7087");
  EXPECT_EQ(f[0].field, "cohesionStiffness");
  EXPECT_NE(f[0].message.find("lower cohesionStiffness"), std::string::npos) << f[0].message;
  std::vector<GranularFinding> warned;
  auto body = make(g, 0.001, &warned);
  ASSERT_TRUE(body);
  ASSERT_EQ(warned.size(), 1u);
  EXPECT_STREQ(warned[0].code, "RS7086");
  EXPECT_NE(warned[0].message.find("critical step of cohesionStiffness"), std::string::npos) << warned[0].message;
  EXPECT_NE(warned[0].message.find("or lower cohesionStiffness"), std::string::npos) << warned[0].message;
  // Without cohesion the same bed names the normal law.
  g.cohesionStiffness = 0;
  g.normalStiffness = 1e9;
  f = refused(g, 0.02);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].field, "normalStiffness");
}

// (4) The stable substep counts cohesion as one pair: a lattice of grains
// held by cohesion alone (no gravity, every neighbour in range, cohesion
// the stiffest mode by far) runs at the substeps the rule gives without
// gaining energy or flying apart.
TEST(Granular, ALatticeHeldByCohesionAloneIsStableAtTheRuleSubstep) {
  const double r = 0.02, gmax = 1e-4;
  Granular g = record(block(4, 4, 4, 2 * r + 0.5 * gmax, 0));
  g.cohesionMaxDistance = gmax;
  g.cohesionStiffness = 3e8;
  g.velocity = {0, 0, 0};
  std::vector<GranularFinding> warned;
  auto body = make(g, 0.001, &warned);
  ASSERT_TRUE(body);
  EXPECT_GT(body->stats().substepsPerStep, 50);  // cohesion's mode, not the contacts' 2
  AnalyticSurfaces none;
  const auto start = body->positions();
  for (int k = 0; k < 500 && !body->failure(); ++k) body->step(0.001, Eigen::Vector3d::Zero(), none);
  EXPECT_FALSE(body->failure()) << body->failure()->message;
  double moved = 0;
  for (std::size_t i = 0; i < start.size(); ++i) moved = std::max(moved, (body->positions()[i] - start[i]).norm());
  EXPECT_LT(moved, r) << "the lattice held together";
  EXPECT_LT(body->maxSpeed(), 1.0);
  // Cohesion is what sets that step: at a third of the rule's substeps
  // (built past the rule) the same lattice gains energy from nothing.
  std::vector<GranularFinding> findings;
  std::optional<GranularSetup> setup = granularSetup(g, 0.001, findings);
  ASSERT_TRUE(setup);
  const double h = 3 * setup->maxSubstep;
  setup->substeps = 1;
  setup->maxSubstep = 1;
  auto fast = makeGranularDem(std::move(*setup));
  for (int k = 0; k < 20000 && !fast->failure(); ++k) fast->step(h, Eigen::Vector3d::Zero(), none);
  ASSERT_TRUE(fast->failure());
  EXPECT_STREQ(fast->failure()->code, "RS7083");
  EXPECT_EQ(fast->failure()->field, "cohesionStiffness");
}

// (2) The pair list is built with the body, so the run's cost is known
// before its first step.
TEST(Granular, CandidatePairsAreKnownBeforeTheFirstStep) {
  auto body = make(record(block(3, 3, 1, 0.041, 0.5)), 0.001);
  ASSERT_TRUE(body);
  // 12 side-by-side pairs of a 3 x 3 grid (the diagonals are past the skin).
  EXPECT_EQ(body->candidatePairs(), 12u);
}
