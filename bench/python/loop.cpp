// rscene-python-bench-loop SCENE STEPS - the C++ side of bench/python/run.sh:
// the loops loop.py runs through the rscene Python module, here through
// lib/sim directly, on the same scene (one robot, held by PD toward its
// start pose with gains 400, 10 as bench/robot/run.sh).  Each loop starts
// from a freshly prepared simulation (preparation not timed):
//   step1  STEPS calls of one step, each through sim::runWorld as the
//          module's step(1) does (every state checked)
//   step1000  STEPS / 1000 calls of 1000 steps each
//   bare   STEPS World::step() calls alone (no checks: what a program
//          that trusts its state would do; for reference)
//   rl     STEPS iterations of read q and u, set PD targets, one step
// Prints "NAME CPU_SECONDS WALL_SECONDS STEPS" per loop.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <string>

#include "asset/cache.hpp"
#include "core/filesystem.hpp"
#include "core/loader.hpp"
#include "sim/prepare.hpp"
#include "sim/run.hpp"
#include "sim/world.hpp"

using namespace rscene;

namespace {

double cpuNow() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double wallNow() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Sim {
  Document doc;
  asset::AssetCache assets;
  sim::Prepared prepared;
  Eigen::VectorXd q0, kp, kd;
};

std::unique_ptr<Sim> prepare(const std::string& text, const std::string& dir) {
  auto s = std::make_unique<Sim>();
  LoadResult r = parse(text);
  if (!r.ok()) return nullptr;
  s->doc = std::move(r.document);
  sim::PrepareOptions po;
  po.scene.sceneDir = dir;
  po.steps = 0;
  Diagnostics ds;
  std::string usage;
  if (!sim::prepareSimulation(s->doc, po, s->assets, s->prepared, ds, usage) || s->prepared.world->robotCount() != 1)
    return nullptr;
  sim::World& w = *s->prepared.world;
  Eigen::VectorXd u;
  w.robotState(0, s->q0, u);
  s->kp = Eigen::VectorXd::Constant(u.size(), 400);
  s->kd = Eigen::VectorXd::Constant(u.size(), 10);
  if (!w.setRobotPd(0, s->q0, Eigen::VectorXd(), s->kp, s->kd).empty()) return nullptr;
  return s;
}

// One call of the module's step(n): runWorld from where the world is.
bool run(Sim& s, std::uint64_t n, bool first) {
  sim::RunOptions ro;
  ro.steps = s.prepared.world->steps() + n;
  ro.checkStart = first;
  return sim::runWorld(*s.prepared.world, s.doc, ro).ok();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: rscene-python-bench-loop SCENE STEPS\n");
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  long long steps = std::atoll(argv[2]);
  if (!in || steps < 1000) {
    std::fprintf(stderr, "rscene-python-bench-loop: cannot read %s, or STEPS < 1000\n", argv[1]);
    return 2;
  }
  const std::string dir = directoryOf(argv[1]);
  auto loop = [&](const char* name, const std::function<bool(Sim&)>& body) {
    std::unique_ptr<Sim> s = prepare(text.str(), dir);
    if (!s) {
      std::fprintf(stderr, "rscene-python-bench-loop: %s does not prepare as one robot\n", argv[1]);
      std::exit(1);
    }
    double c = cpuNow(), w = wallNow();
    if (!body(*s)) {
      std::fprintf(stderr, "rscene-python-bench-loop: %s: a step failed\n", name);
      std::exit(1);
    }
    std::printf("%s %.6f %.6f %llu\n", name, cpuNow() - c, wallNow() - w,
                static_cast<unsigned long long>(s->prepared.world->steps()));
  };
  loop("step1", [&](Sim& s) {
    for (long long i = 0; i < steps; ++i)
      if (!run(s, 1, i == 0)) return false;
    return true;
  });
  loop("step1000", [&](Sim& s) {
    for (long long i = 0; i < steps / 1000; ++i)
      if (!run(s, 1000, i == 0)) return false;
    return true;
  });
  loop("bare", [&](Sim& s) {
    for (long long i = 0; i < steps; ++i) s.prepared.world->step();
    return !s.prepared.world->nonFinite();
  });
  loop("rl", [&](Sim& s) {
    sim::World& w = *s.prepared.world;
    Eigen::VectorXd q, u, target = s.q0;
    double sum = 0;
    for (long long i = 0; i < steps; ++i) {
      w.robotState(0, q, u);
      sum += q[2];
      target[7] = s.q0[7] + 0.01 * static_cast<double>(i % 2);
      if (!w.setRobotPd(0, target, Eigen::VectorXd(), s.kp, s.kd).empty() || !run(s, 1, i == 0)) return false;
    }
    return sum > 0;
  });
  return 0;
}
