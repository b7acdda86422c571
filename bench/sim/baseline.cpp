// rscene-sim-baseline: the hand-written program rscene-sim is measured
// against (issue 5, "Speed").  Plain Bullet (Debian's double-precision
// build), no rscene library: it builds by hand the Bullet world that
// lib/sim/world.cpp builds for the same scene - same shapes, masses,
// poses, solver settings, contact handling, 64-bit group/mask filter and
// time step - steps it, and writes the final poses of the dynamic bodies
// to a file, one line each: `path x y z qw qx qy qz`.
//
//   rscene-sim-baseline pile [--count N] [--seed S] --steps K -o FILE
//       scene (a), built from bench/sim/scenes.hpp like rscene-sim-bench-gen
//   rscene-sim-baseline table FILE --steps K -o FILE
//       a whitespace table (bench/sim/run.sh extracts it from scene (b)):
//         time_step DT
//         gravity GX GY GZ
//         solver ITERATIONS TOLERANCE ERP ERP2 RESTITUTION_THRESHOLD
//         ground PATH Z
//         box PATH X Y Z QW QX QY QZ SX SY SZ MASS static|dynamic GROUP MASK
//       bodies are created in table order, as rscene-sim creates them in
//       record order.
//
// Only what these two scenes use is mapped (boxes and ground planes, no
// contact materials, wires, meshes, CCD or kinematic bodies); the solver
// keys the scenes leave out have Engine 2's defaults, as in lib/sim.
//
// Exit status: 0, or 2 on a usage, input or output error.
#include <algorithm>
#include <btBulletDynamicsCommon.h>

#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "scenes.hpp"

static_assert(sizeof(btScalar) == sizeof(double), "the baseline needs Bullet's double-precision build");

namespace {

struct Settings {
  double dt = 0.0025;
  double gravity[3] = {0, 0, -9.81};
  int iterations = 80;
  double tolerance = 1e-7, erp = 0.2, erp2 = 0, restitutionThreshold = 0.001;
  // Engine 2 defaults that neither scene changes.
  double friction = 0.8, restitution = 0, rolling = 0, spinning = 0;
  double sleepLinear = 0.002, sleepAngular = 0.01;
  int quietSteps = 5;
};

struct Body {
  std::string path;
  bool ground = false;
  double groundZ = 0;
  rscene::bench::Box box;
  std::uint64_t group = 1, mask = ~std::uint64_t{0};
};

// The 64-bit group/mask of every collision object, by its user index.
struct Filter64 : btOverlapFilterCallback {
  std::vector<std::pair<std::uint64_t, std::uint64_t>> groupMask;
  bool needBroadphaseCollision(btBroadphaseProxy* a, btBroadphaseProxy* b) const override {
    auto* oa = static_cast<btCollisionObject*>(a->m_clientObject);
    auto* ob = static_cast<btCollisionObject*>(b->m_clientObject);
    // Static pairs never meet, as in Bullet's own filter (and lib/sim's).
    if (oa->isStaticOrKinematicObject() && ob->isStaticOrKinematicObject()) return false;
    const auto& x = groupMask[static_cast<std::size_t>(oa->getUserIndex())];
    const auto& y = groupMask[static_cast<std::size_t>(ob->getUserIndex())];
    return (x.first & y.second) != 0 && (y.first & x.second) != 0;
  }
};

// Contact properties are the solver defaults, not Bullet's products of
// the two bodies' values.
Settings gSettings;
btScalar friction(const btCollisionObject*, const btCollisionObject*) { return gSettings.friction; }
btScalar restitution(const btCollisionObject*, const btCollisionObject*) { return gSettings.restitution; }
btScalar rolling(const btCollisionObject*, const btCollisionObject*) { return gSettings.rolling; }
btScalar spinning(const btCollisionObject*, const btCollisionObject*) { return gSettings.spinning; }

bool readTable(const char* file, Settings& s, std::vector<Body>& bodies, std::string& error) {
  std::ifstream in(file);
  if (!in) return error = std::string("cannot read '") + file + "'", false;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    std::istringstream ls(line);
    std::string tag;
    if (!(ls >> tag) || tag[0] == '#') continue;
    bool ok = true;
    if (tag == "time_step") ok = static_cast<bool>(ls >> s.dt);
    else if (tag == "gravity") ok = static_cast<bool>(ls >> s.gravity[0] >> s.gravity[1] >> s.gravity[2]);
    else if (tag == "solver")
      ok = static_cast<bool>(ls >> s.iterations >> s.tolerance >> s.erp >> s.erp2 >> s.restitutionThreshold);
    else if (tag == "ground") {
      Body b;
      b.ground = true;
      ok = static_cast<bool>(ls >> b.path >> b.groundZ);
      bodies.push_back(b);
    } else if (tag == "box") {
      Body b;
      rscene::bench::Box& x = b.box;
      std::string mode, group, mask;
      ok = static_cast<bool>(ls >> b.path >> x.position[0] >> x.position[1] >> x.position[2] >> x.orientation[0] >>
                             x.orientation[1] >> x.orientation[2] >> x.orientation[3] >> x.size[0] >> x.size[1] >>
                             x.size[2] >> x.mass >> mode >> group >> mask);
      x.path = b.path;
      x.dynamic = mode == "dynamic";
      ok = ok && (x.dynamic || mode == "static");
      b.group = std::strtoull(group.c_str(), nullptr, 10);
      b.mask = std::strtoull(mask.c_str(), nullptr, 10);
      bodies.push_back(b);
    } else {
      ok = false;
    }
    if (!ok) return error = std::string(file) + ":" + std::to_string(n) + ":1: bad table line", false;
  }
  return true;
}

class World {
 public:
  World(const Settings& s, const std::vector<Body>& list) : dt_(s.dt) {
    config_.setPlaneConvexMultipointIterations(3, 3);  // up to four box-plane contact points
    broadphase_ = std::make_unique<btDbvtBroadphase>();
    world_ = std::make_unique<btDiscreteDynamicsWorld>(&dispatcher_, broadphase_.get(), &solver_, &config_);
    world_->setGravity(btVector3(s.gravity[0], s.gravity[1], s.gravity[2]));
    world_->setForceUpdateAllAabbs(false);  // statics do not move (as lib/sim)
    btContactSolverInfo& si = world_->getSolverInfo();
    si.m_numIterations = s.iterations;
    si.m_erp = s.erp;
    if (s.erp2 > 0) si.m_erp2 = s.erp2;
    si.m_leastSquaresResidualThreshold = s.tolerance;
    si.m_restitutionVelocityThreshold = s.restitutionThreshold;
    si.m_solverMode &= ~SOLVER_RANDMIZE_ORDER;
    si.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS | SOLVER_ENABLE_FRICTION_DIRECTION_CACHING;
    si.m_restingContactRestitutionThreshold = 1 << 30;
    si.m_splitImpulse = true;
    si.m_splitImpulsePenetrationThreshold = 0;
    world_->getPairCache()->setOverlapFilterCallback(&filter_);
    gDeactivationTime = s.quietSteps * s.dt;
    gCalculateCombinedFrictionCallback = friction;
    gCalculateCombinedRestitutionCallback = restitution;
    gCalculateCombinedRollingFrictionCallback = rolling;
    gCalculateCombinedSpinningFrictionCallback = spinning;

    for (const Body& b : list) {
      btCollisionShape* shape;
      btTransform at = btTransform::getIdentity();
      if (b.ground) {
        shape = new btStaticPlaneShape(btVector3(0, 0, 1), b.groundZ);
      } else {
        const rscene::bench::Box& x = b.box;
        shape = new btBoxShape(btVector3(x.size[0] / 2, x.size[1] / 2, x.size[2] / 2));
        at = btTransform(btQuaternion(x.orientation[1], x.orientation[2], x.orientation[3], x.orientation[0]),
                         btVector3(x.position[0], x.position[1], x.position[2]));
      }
      shapes_.emplace_back(shape);
      bool dynamic = !b.ground && b.box.dynamic;
      double mass = dynamic ? b.box.mass : 0;
      btVector3 inertia(0, 0, 0);
      if (dynamic) shape->calculateLocalInertia(mass, inertia);
      auto* motion = new btDefaultMotionState(at);
      motion_.emplace_back(motion);
      btRigidBody::btRigidBodyConstructionInfo ci(mass, motion, shape, inertia);
      ci.m_friction = s.friction;
      ci.m_restitution = s.restitution;
      ci.m_rollingFriction = s.rolling;
      ci.m_spinningFriction = s.spinning;
      ci.m_linearSleepingThreshold = s.sleepLinear;
      ci.m_angularSleepingThreshold = s.sleepAngular;
      auto* body = new btRigidBody(ci);
      bodies_.emplace_back(body);
      body->setContactProcessingThreshold(0);  // touching contacts only, as lib/sim
      body->setUserIndex(static_cast<int>(filter_.groupMask.size()));
      body->setUserIndex2(-1);
      filter_.groupMask.emplace_back(b.group, b.mask);
      world_->addRigidBody(body);
      if (dynamic) dynamic_.push_back({b.path, body});
    }
  }
  ~World() {
    for (auto& b : bodies_) world_->removeRigidBody(b.get());
  }

  // rscene-sim's rest rule, as written there (lib/sim/world.cpp): a dynamic
  // body in a contact deeper than 5 mm is kept awake, so that it is pushed
  // out instead of falling asleep inside another.  The same rule here keeps
  // the two programs' worlds, and so their final poses, the same.
  void step() {
    world_->stepSimulation(dt_, 0, dt_);
    for (int i = 0, m = dispatcher_.getNumManifolds(); i < m; ++i) {
      btPersistentManifold* manifold = dispatcher_.getManifoldByIndexInternal(i);
      double depth = 0;
      for (int k = 0; k < manifold->getNumContacts(); ++k)
        depth = std::max(depth, -double(manifold->getContactPoint(k).getDistance()));
      if (!(depth > 0.005)) continue;
      for (const btCollisionObject* o : {manifold->getBody0(), manifold->getBody1()})
        if (const btRigidBody* rb = btRigidBody::upcast(o); rb && !rb->isStaticOrKinematicObject())
          const_cast<btRigidBody*>(rb)->activate();
    }
  }

  // `path x y z qw qx qy qz` per dynamic body, %.17g (round trip).
  bool write(const char* file) const {
    std::string out;
    char buf[512];
    for (const auto& [path, body] : dynamic_) {
      const btTransform& t = body->getWorldTransform();
      btQuaternion q = t.getRotation().normalized();
      if (q.w() < 0) q = -q;
      const btVector3& p = t.getOrigin();
      std::snprintf(buf, sizeof buf, " %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", p.x(), p.y(), p.z(), q.w(), q.x(),
                    q.y(), q.z());
      out += path;
      out += buf;
    }
    std::string tmp = std::string(file) + ".tmp";
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) return false;
    bool ok = std::fwrite(out.data(), 1, out.size(), f) == out.size();
    ok = std::fclose(f) == 0 && ok;
    return ok && std::rename(tmp.c_str(), file) == 0;
  }

 private:
  double dt_;
  btDefaultCollisionConfiguration config_;
  btCollisionDispatcher dispatcher_{&config_};
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  Filter64 filter_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btMotionState>> motion_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  std::vector<std::pair<std::string, btRigidBody*>> dynamic_;
};

int usage(const std::string& why) {
  std::fprintf(stderr,
               "rscene-sim-baseline: error: %s\n"
               "usage: rscene-sim-baseline pile [--count N] [--seed S] --steps K -o FILE\n"
               "       rscene-sim-baseline table FILE --steps K -o FILE\n",
               why.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage("missing scene kind");
  std::string kind = argv[1];
  const char* table = nullptr;
  const char* output = nullptr;
  long long count = 1000, seed = 1, steps = -1;
  int i = 2;
  if (kind == "table") {
    if (argc < 3) return usage("missing table file");
    table = argv[i++];
  } else if (kind != "pile") {
    return usage("unknown scene kind '" + kind + "'");
  }
  for (; i < argc; ++i) {
    std::string a = argv[i];
    if (i + 1 >= argc) return usage("option '" + a + "' needs a value");
    char* end = nullptr;
    if (a == "-o") output = argv[++i];
    else if (a == "--steps") steps = std::strtoll(argv[++i], &end, 10);
    else if (a == "--count" && kind == "pile") count = std::strtoll(argv[++i], &end, 10);
    else if (a == "--seed" && kind == "pile") seed = std::strtoll(argv[++i], &end, 10);
    else return usage("unknown option '" + a + "'");
    if (end && *end) return usage("option '" + a + "' needs an integer");
  }
  if (steps < 0 || !output) return usage("--steps and -o are required");
  if (count < 0 || count > 1000000) return usage("--count must be in [0, 1000000]");

  Settings s;
  std::vector<Body> bodies;
  if (table) {
    std::string error;
    if (!readTable(table, s, bodies, error)) {
      std::fprintf(stderr, "rscene-sim-baseline: error: %s\n", error.c_str());
      return 2;
    }
  } else {
    Body ground;
    ground.path = "/World/Ground";
    ground.ground = true;
    bodies.push_back(ground);
    for (const rscene::bench::Box& x : rscene::bench::pile(static_cast<int>(count), static_cast<std::uint64_t>(seed))) {
      Body b;
      b.path = x.path;
      b.box = x;
      bodies.push_back(b);
    }
  }
  gSettings = s;
  World world(s, bodies);
  for (long long k = 0; k < steps; ++k) world.step();
  if (!world.write(output)) {
    std::fprintf(stderr, "rscene-sim-baseline: error: cannot write '%s'\n", output);
    return 2;
  }
  return 0;
}
