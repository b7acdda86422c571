// Physics against closed-form answers.  Each tolerance is stated where it
// is asserted, with the reason it is not tighter.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/loader.hpp"
#include "scene/scene.hpp"
#include "core/writer.hpp"
#include "sim/world.hpp"

using namespace rscene;
using namespace rscene::sim;

namespace {

constexpr const char* kAll = "18446744073709551615";

struct Run {
  Document doc;
  Scene scene;
  Diagnostics diags;
  std::unique_ptr<World> world;
};

std::unique_ptr<Run> make(const std::string& body) {
  auto r = std::make_unique<Run>();
  LoadResult loaded = parse("raisim_engine_scene 1\n" + body);
  EXPECT_TRUE(loaded.ok()) << (loaded.diagnostics.empty() ? "" : loaded.diagnostics[0].message);
  r->doc = std::move(loaded.document);
  EXPECT_TRUE(buildScene(r->doc, {}, r->scene, r->diags));
  EXPECT_TRUE(checkPhysics(r->doc, r->scene, r->diags)) << (r->diags.empty() ? "" : r->diags[0].message);
  r->world = World::create(r->scene, r->diags);
  EXPECT_TRUE(r->world);
  return r;
}

// An object line of the 25-field layout.
std::string object(const std::string& path, const std::string& prim, double x, double y, double z,
                   const std::string& scale, double radius, double height, double mass, const std::string& mode,
                   const std::string& extra = "", const std::string& cm = "default", const std::string& group = "1",
                   const std::string& mask = kAll) {
  char buf[512];
  std::snprintf(buf, sizeof buf, "object %s %s %.17g %.17g %.17g 1 0 0 0 %s %.17g %.17g %.17g %s engine_default false true false - %s true %s %s %s\n",
                path.c_str(), prim.c_str(), x, y, z, scale.c_str(), radius, height, mass, cm.c_str(), mode.c_str(),
                group.c_str(), mask.c_str(), extra.c_str());
  return buf;
}

const std::string kGround = object("/World/Ground", "ground", 0, 0, 0, "10 10 1", 0.5, 1, 0, "static");

BodyState state(const World& w, const std::string& path) {
  for (const BodyState& s : w.states())
    if (s.path == path) return s;
  ADD_FAILURE() << "no body " << path;
  return {};
}

void steps(World& w, double seconds) {
  long n = std::lround(seconds / w.timeStep());
  for (long i = 0; i < n; ++i) w.step();
}

}  // namespace

TEST(Physics, FreeFallMatchesTheDiscreteIntegrator) {
  auto r = make("time_step 0.01\n" + object("/World/B", "sphere", 0, 0, 100, "1 1 1", 0.1, 1, 1, "dynamic"));
  // Semi-implicit Euler: v_n = -g n dt, z_n = z0 - g dt^2 n(n+1)/2.
  const double g = 9.81, dt = 0.01;
  for (int n = 1; n <= 200; ++n) {
    r->world->step();
    if (n % 50) continue;
    BodyState s = state(*r->world, "/World/B");
    EXPECT_NEAR(s.position.z(), 100 - g * dt * dt * n * (n + 1) / 2, 1e-9) << "step " << n;  // round-off only
    EXPECT_NEAR(s.linearVelocity.z(), -g * dt * n, 1e-9);
  }
}

TEST(Physics, BoxAtRestStaysAtItsRestingHeight) {
  auto r = make("solver 80 1e-07 0.2 accurate sleepingEnabled=false\n" + kGround +
                object("/World/B", "box", 0, 0, 0.25, "1 1 0.5", 0.5, 1, 5, "dynamic"));
  for (int i = 0; i < 4000; ++i) {  // 10 s
    r->world->step();
    BodyState s = state(*r->world, "/World/B");
    ASSERT_NEAR(s.position.z(), 0.25, 1e-3) << "t=" << r->world->time();  // issue 5: within 1 mm
  }
  BodyState s = state(*r->world, "/World/B");
  EXPECT_LT(std::hypot(s.position.x(), s.position.y()), 1e-3);  // no drift: under 1 mm over 10 s awake (measured 0.16 mm)
}


TEST(Physics, ContactMaterialWithLowFrictionSlidesWhereTheDefaultSticks) {
  // A 20 degree incline (tan = 0.364): mu 0.8 sticks, mu 0.1 slides with
  // a = g (sin - mu cos).
  double a = 20 * M_PI / 180;
  char q[128];
  std::snprintf(q, sizeof q, "%.17g 0 %.17g 0", std::cos(a / 2), std::sin(a / 2));
  auto ramp = [&](const std::string& path, double y) {
    return "object " + path + " box 0 " + std::to_string(y) + " 0 " + q +
           " 20 1 1 0.5 1 0 default engine_default false true false - static true 1 " + kAll + "\n";
  };
  // Boxes sit on the top face of the ramp (rotated about y), 0.1 m high.
  Eigen::Quaterniond rot(std::cos(a / 2), 0, std::sin(a / 2), 0);
  Eigen::Vector3d up = rot * Eigen::Vector3d(0, 0, 0.5 + 0.1);
  auto box = [&](const std::string& path, double y, const std::string& cm) {
    return "object " + path + " box " + std::to_string(up.x()) + " " + std::to_string(y) + " " +
           std::to_string(up.z()) + " " + q + " 0.2 0.2 0.2 0.5 1 1 " + cm +
           " engine_default false true false - dynamic true 1 " + kAll + "\n";
  };
  auto r = make("time_step 0.001\ncontact_material ice default 0.1 0 0.001 0.1 0.001 0 0\n" + ramp("/World/R1", 0) +
                ramp("/World/R2", 3) + box("/World/Stick", 0, "default") + box("/World/Slide", 3, "ice"));
  steps(*r->world, 1.0);
  BodyState stick = state(*r->world, "/World/Stick"), slide = state(*r->world, "/World/Slide");
  Eigen::Vector3d along = rot * Eigen::Vector3d(1, 0, 0);
  double dStick = (stick.position - Eigen::Vector3d(up.x(), 0, up.z())).dot(along);
  double dSlide = (slide.position - Eigen::Vector3d(up.x(), 3, up.z())).dot(along);
  EXPECT_LT(std::abs(dStick), 0.005);  // sticks: under 5 mm in 1 s
  double accel = 9.81 * (std::sin(a) - 0.1 * std::cos(a));
  // Slides down (+x of the ramp tilts down): s = a t^2 / 2 within 5%.
  EXPECT_NEAR(dSlide, accel / 2, 0.05 * accel / 2);
}

TEST(Physics, RestitutionBounceReachesESquaredH) {
  const double e = 0.8, h = 1.0;
  auto r = make("time_step 0.001\ncontact_material ball floor " + std::to_string(e) + " 0.8 0.001 0.8 0.001 0 0\n" +
                object("/World/Ground", "ground", 0, 0, 0, "10 10 1", 0.5, 1, 0, "static", "", "floor") +
                object("/World/B", "sphere", 0, 0, h + 0.1, "1 1 1", 0.1, 1, 1, "dynamic", "", "ball"));
  double apex = 0;
  bool bounced = false;
  for (int i = 0; i < 1500; ++i) {
    r->world->step();
    BodyState s = state(*r->world, "/World/B");
    if (s.linearVelocity.z() > 0.5) bounced = true;
    if (bounced) apex = std::max(apex, s.position.z() - 0.1);
  }
  ASSERT_TRUE(bounced);
  EXPECT_NEAR(apex, e * e * h, 0.05 * e * e * h);  // 5%: impact is resolved over one 1 ms step
}

TEST(Physics, StiffWirePendulumPeriod) {
  const double L = 1.0, g = 9.81;
  // Bob hangs from a fixed anchor (a static sphere) on a stiff wire, started 5 degrees off.
  double th = 5 * M_PI / 180;
  auto r = make("time_step 0.001\n" +
                object("/World/Anchor", "sphere", 0, 0, 2, "1 1 1", 0.01, 1, 1, "static", "", "default", "2", "0") +
                object("/World/Bob", "sphere", L * std::sin(th), 0, 2 - L * std::cos(th), "1 1 1", 0.05, 1, 1,
                       "dynamic", "", "default", "2", "0") +
                "wire /World/W stiff /World/Anchor /World/Bob 1\n");
  // Period from successive upward zero crossings of x.
  std::vector<double> crossings;
  double prev = state(*r->world, "/World/Bob").position.x();
  for (int i = 0; i < 8000; ++i) {
    r->world->step();
    double x = state(*r->world, "/World/Bob").position.x();
    if (prev < 0 && x >= 0) crossings.push_back(r->world->time());
    prev = x;
  }
  ASSERT_GE(crossings.size(), 3u);
  double period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  EXPECT_NEAR(period, 2 * M_PI * std::sqrt(L / g), 0.02 * 2 * M_PI * std::sqrt(L / g));  // issue 5: 2%
}

TEST(Physics, StackOfTenBoxesStandsFiveSeconds) {
  std::string s = kGround;
  for (int i = 0; i < 10; ++i)
    s += object("/World/B" + std::to_string(i), "box", 0, 0, 0.1 + 0.2 * i, "0.4 0.4 0.2", 0.5, 1, 1, "dynamic");
  auto r = make(s);
  steps(*r->world, 5);
  BodyState top = state(*r->world, "/World/B9");
  EXPECT_NEAR(top.position.z(), 1.9, 0.01);  // 1 cm: ten contacts' worth of solver slop
  EXPECT_LT(std::hypot(top.position.x(), top.position.y()), 0.01);
}

TEST(Physics, MaskExcludesAPairWhichThenPassesThrough) {
  // Group 2 with mask 1: only group-1 bodies; the floor box is group 4.
  auto r = make(object("/World/Floor", "box", 0, 0, -0.5, "10 10 1", 0.5, 1, 0, "static", "", "default", "4", kAll) +
                object("/World/Ghost", "sphere", 0, 0, 1, "1 1 1", 0.1, 1, 1, "dynamic", "", "default", "2", "1") +
                object("/World/Solid", "sphere", 1, 0, 1, "1 1 1", 0.1, 1, 1, "dynamic"));
  steps(*r->world, 2);
  EXPECT_LT(state(*r->world, "/World/Ghost").position.z(), -5);
  EXPECT_NEAR(state(*r->world, "/World/Solid").position.z(), 0.1, 2e-3);
}

TEST(Physics, HighBitsOfTheMaskCount) {
  // Bit 40 is beyond Bullet's 32-bit filter: the pair must still collide.
  std::string bit40 = std::to_string(std::uint64_t{1} << 40);
  auto r = make(object("/World/Floor", "box", 0, 0, -0.5, "10 10 1", 0.5, 1, 0, "static", "", "default", bit40, bit40) +
                object("/World/B", "sphere", 0, 0, 1, "1 1 1", 0.1, 1, 1, "dynamic", "", "default", bit40, bit40));
  steps(*r->world, 2);
  EXPECT_NEAR(state(*r->world, "/World/B").position.z(), 0.1, 2e-3);
}

TEST(Physics, StaticAndKinematicBodiesDoNotFall) {
  auto r = make(object("/World/S", "box", 0, 0, 5, "1 1 1", 0.5, 1, 1, "static") +
                object("/World/K", "box", 3, 0, 5, "1 1 1", 0.5, 1, 1, "kinematic"));
  steps(*r->world, 1);
  EXPECT_EQ(state(*r->world, "/World/K").position.z(), 5);
  EXPECT_EQ(r->world->bodyCount(), 1);  // the static box is not a simulated body
}

TEST(Physics, BallRollsDownhillOnASlopedTerrain) {
  // A plane z = -0.2 x sampled 11 x 11 over 10 x 10 m.
  std::string heights;
  for (int y = 0; y < 11; ++y)
    for (int x = 0; x < 11; ++x) heights += (heights.empty() ? "" : ",") + std::to_string(-0.2 * (x - 5));
  auto r = make("terrain_region /World/T 11 11 10 10 0 0 0 heights=" + heights + "\n" +
                object("/World/B", "sphere", 0, 0, 0.3, "1 1 1", 0.1, 1, 1, "dynamic"));
  steps(*r->world, 2);
  BodyState s = state(*r->world, "/World/B");
  EXPECT_GT(s.position.x(), 0.5);  // rolled towards +x (downhill)
  // Rests on the surface: centre 0.1 above the plane along its normal.
  double surface = -0.2 * s.position.x();
  EXPECT_NEAR(s.position.z(), surface + 0.1 * std::sqrt(1 + 0.04), 5e-3);
}

TEST(Physics, TerrainRestingHeight) {
  auto r = make("terrain_region /World/T 3 3 4 4 0 0 1 heights=0,0,0,0,0,0,0,0,0\n" +
                object("/World/B", "box", 0, 0, 1.5, "0.4 0.4 0.2", 0.5, 1, 1, "dynamic"));
  steps(*r->world, 2);
  EXPECT_NEAR(state(*r->world, "/World/B").position.z(), 1.1, 2e-3);  // centre z 1 + half height
}

TEST(Physics, CompoundFallsAsOneRigidBody) {
  auto r = make(kGround +
                "compound /World/C 0 0 1 1 0 0 0 1 1 1 2 dynamic true true\n"
                "compound_child /World/C box -0.3 0 0 1 0 0 0 1 1 1 size=0.2,0.2,0.2\n"
                "compound_child /World/C box 0.3 0 0 1 0 0 0 1 1 1 size=0.2,0.2,0.2\n");
  ASSERT_EQ(r->world->bodyCount(), 1);
  steps(*r->world, 0.3);
  BodyState s = state(*r->world, "/World/C");
  EXPECT_NEAR(s.position.z(), 1 - 0.5 * 9.81 * 0.09, 0.01);  // free fall of the whole body
  steps(*r->world, 2);
  s = state(*r->world, "/World/C");
  EXPECT_NEAR(s.position.z(), 0.1, 2e-3);  // both children rest on the ground
  EXPECT_NEAR(s.orientation.w(), 1, 1e-3);
}

TEST(Physics, WriteBackIsDeterministic) {
  std::string text = kGround;
  for (int i = 0; i < 20; ++i)
    text += object("/World/B" + std::to_string(i), i % 2 ? "sphere" : "box", 0.05 * i, 0, 0.5 + 0.3 * i,
                   "0.2 0.2 0.2", 0.1, 1, 1, "dynamic");
  std::string out[2];
  for (std::string& o : out) {
    auto r = make(text);
    steps(*r->world, 1);
    r->world->writeBack(r->doc);
    o = canonicalText(r->doc);
  }
  EXPECT_EQ(out[0], out[1]);
  EXPECT_NE(out[0].find("/World/B3 sphere"), std::string::npos);
}

TEST(Physics, RefusesBadBodies) {
  LoadResult loaded = parse("raisim_engine_scene 1\n" + object("/World/A", "box", 0, 0, 1, "1 1 1", 0.5, 1, 0, "dynamic") +
                            object("/World/B", "box", 0, 0, 1, "1 0 1", 0.5, 1, 1, "dynamic") +
                            object("/World/C", "mesh", 0, 0, 1, "1 1 1", 0.5, 1, 1, "dynamic",
                                   "collisionMeshPath=/nonexistent/x.obj"));
  ASSERT_TRUE(loaded.ok());
  Scene scene;
  Diagnostics ds;
  ASSERT_TRUE(buildScene(loaded.document, {}, scene, ds));
  EXPECT_FALSE(checkPhysics(loaded.document, scene, ds));
  ASSERT_EQ(ds.size(), 3u);
  EXPECT_EQ(ds[0].code, "RS4008");  // rscene-validate's codes for the same problems
  EXPECT_EQ(ds[0].line, 2u);
  EXPECT_EQ(ds[1].code, "RS7003");
  EXPECT_EQ(ds[2].code, "RS5001");
  EXPECT_NE(ds[2].message.find("/nonexistent/x.obj"), std::string::npos);
}

TEST(Physics, MeshConvexHullRestsOnGround) {
  std::string dir = ::testing::TempDir();
  std::string path = dir + "/sim_cube.obj";
  std::ofstream f(path);
  f << "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
       "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n"
       "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
  f.close();
  auto r = make(kGround + object("/World/M", "mesh", 0, 0, 1, "0.4 0.4 0.4", 0.5, 1, 1, "dynamic",
                                 "collisionMeshPath=" + path));
  steps(*r->world, 2);
  EXPECT_NEAR(state(*r->world, "/World/M").position.z(), 0.2, 3e-3);  // hull margin 1 mm + contact slop
}

namespace {

// A flat box (0.5 x 0.5 x 0.2 m, low enough not to tip under friction)
// resting on the ground is launched along +x at v0; returns the distance
// it slides before it stops and the time that takes.
struct Slide {
  double distance = 0, time = 0;
  bool stopped = false;
};
Slide launchAlongTheGround(const std::string& extra, const std::string& material, double v0) {
  auto r = make(extra +
                object("/World/Ground", "ground", 0, 0, 0, "10 10 1", 0.5, 1, 0, "static", "", material) +
                object("/World/B", "box", 0, 0, 0.1, "0.5 0.5 0.2", 0.5, 1, 2, "dynamic", "", material));
  EXPECT_TRUE(r->world->setLinearVelocity("/World/B", Eigen::Vector3d(v0, 0, 0)));
  Slide out;
  for (int i = 0; i < 20000 && !out.stopped && !::testing::Test::HasFailure(); ++i) {
    r->world->step();
    BodyState s = state(*r->world, "/World/B");
    // Slides flat: within 1 mm of its resting height (measured 0.3 mm; 3.5 mm
    // before lib/sim asked Bullet for several box-plane contact points).
    EXPECT_NEAR(s.position.z(), 0.1, 1e-3) << "t=" << r->world->time();
    if (s.linearVelocity.x() <= 1e-3) {
      out.stopped = true;
      out.distance = s.position.x();
      out.time = r->world->time();
    }
  }
  return out;
}

}  // namespace

TEST(Physics, BoxLaunchedAlongTheGroundStopsAfterTheCoulombDistance) {
  // Issue 5: d = v0^2 / (2 mu g) within 5%, with the default friction
  // (mu = 0.8) and with a contact-material pair (mu = 0.3).  The stopping
  // time v0 / (mu g) is checked to the same 5%.  Measured: 1.0169 m for
  // 1.0194 and 1.5256 m for 1.5291 (0.3%); 0.510 s for 0.510, 1.0175 s for
  // 1.0194.
  const double g = 9.81;
  struct Case {
    std::string extra, material;
    double mu, v0;
  } cases[] = {{"", "default", 0.8, 4.0},
               {"contact_material rubber rubber 0.3 0 0.001 0.3 0.001 0 0\n", "rubber", 0.3, 3.0}};
  for (const Case& c : cases) {
    SCOPED_TRACE("mu=" + std::to_string(c.mu));
    Slide s = launchAlongTheGround(c.extra, c.material, c.v0);
    ASSERT_TRUE(s.stopped);
    double d = c.v0 * c.v0 / (2 * c.mu * g), t = c.v0 / (c.mu * g);
    EXPECT_NEAR(s.distance, d, 0.05 * d);
    EXPECT_NEAR(s.time, t, 0.05 * t);
  }
}

TEST(Physics, SetVelocityNamesOnlyDynamicBodies) {
  auto r = make(kGround + object("/World/K", "box", 3, 0, 5, "1 1 1", 0.5, 1, 1, "kinematic") +
                object("/World/B", "box", 0, 0, 5, "1 1 1", 0.5, 1, 1, "dynamic", "id=box_b"));
  EXPECT_FALSE(r->world->setLinearVelocity("/World/Ground", {1, 0, 0}));  // static
  EXPECT_FALSE(r->world->setLinearVelocity("/World/K", {1, 0, 0}));       // kinematic
  EXPECT_FALSE(r->world->setLinearVelocity("/World/Nope", {1, 0, 0}));
  EXPECT_FALSE(r->world->setLinearVelocity("/World/B", {NAN, 0, 0}));
  EXPECT_TRUE(r->world->setLinearVelocity("box_b", {0, 0, 20}));  // by id
  EXPECT_TRUE(r->world->setAngularVelocity("/World/B", {0, 0, 1}));
  r->world->step();
  BodyState b = state(*r->world, "/World/B");
  EXPECT_NEAR(b.linearVelocity.z(), 20 - 9.81 * r->world->timeStep(), 1e-12);  // one step of gravity
  EXPECT_NEAR(b.angularVelocity.z(), 1, 1e-12);
  EXPECT_EQ(state(*r->world, "/World/K").position.x(), 3);
}

TEST(Physics, StaticAndKinematicBodiesHoldABodyInTheAir) {
  // A static and a kinematic 1 m box at z = 5, each with a dynamic box on
  // top: after 3 s both dynamic boxes still rest at z = 5.6 (within 1 mm),
  // so the bodies under them neither fell nor let them through.
  auto r = make(object("/World/S", "box", 0, 0, 5, "1 1 1", 0.5, 1, 1, "static") +
                object("/World/K", "box", 3, 0, 5, "1 1 1", 0.5, 1, 1, "kinematic") +
                object("/World/OnS", "box", 0, 0, 5.6, "0.4 0.4 0.2", 0.5, 1, 1, "dynamic") +
                object("/World/OnK", "box", 3, 0, 5.6, "0.4 0.4 0.2", 0.5, 1, 1, "dynamic"));
  steps(*r->world, 3);
  EXPECT_NEAR(state(*r->world, "/World/OnS").position.z(), 5.6, 1e-3);
  EXPECT_NEAR(state(*r->world, "/World/OnK").position.z(), 5.6, 1e-3);
  BodyState k = state(*r->world, "/World/K");
  EXPECT_EQ(k.position, Eigen::Vector3d(3, 0, 5));  // bit for bit: nothing moves it
  EXPECT_EQ(k.linearVelocity, Eigen::Vector3d::Zero());
  EXPECT_FALSE(k.dynamic);
}
