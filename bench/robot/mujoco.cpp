// rscene-robot-bench-mujoco: MuJoCo 2.2.2's side of the robot benchmark
// (issue 11, "Speed"; bench/robot/run.sh drives it).  It links MuJoCo and
// tinyxml2 only, never an rscene library, so it measures MuJoCo alone.
//
//   rscene-robot-bench-mujoco scene URDF RESOURCE_DIR [world options]
//       writes the rscene scene of the same world to stdout, for rscene-sim
//   rscene-robot-bench-mujoco run URDF [world options] [--keep DIR]
//       compiles the world with MuJoCo, holds every robot by PD toward its
//       initial pose, steps it and prints one JSON line: compile time, steps,
//       step time, steps per second, and the lowest / highest final base
//       height and the largest base tilt (so a fallen robot shows)
//   rscene-robot-bench-mujoco run URDF [world options] --feet
//       the same run, untimed, measuring the feet (below) every 4 steps
//   rscene-robot-bench-mujoco feet URDF [world options] --trajectory CSV
//       the feet of rscene-sim's run of the same world, from its trajectory
//       (--trajectory-format csv), measured by MuJoCo's kinematics and
//       collision on each row's pose: both simulators by one yardstick
//
// The feet (ANYmal's sphere collision geometries): footPenetration, the
// deepest any foot went into the ground or terrain from the first second
// on (the start pose has them 2.7 mm in; both settle), and
// footPenetrationEnd, at the end (m, MuJoCo's contact distance: its hfield
// for the terrain, whose triangles may split the cells along the other
// diagonal from Bullet's, a fraction of a millimetre on this terrain);
// footSlip, the largest horizontal distance a foot's centre ended from
// where it started (m).
//
// World options (the same in both modes, so both sides get one world):
//   --robots N       robots on a square grid 1.5 m apart (default 1)
//   --terrain        a 41 x 41 height field of 12 x 12 m under them instead
//                    of a ground plane (heights: terrainHeight below)
//   --pose CSV       generalized coordinate of a robot at (0, 0), RaiSim's
//                    joint order, floating base (default ANYmal C standing)
//   --dt S --duration S --kp KP --kd KD   (0.0025, 10, 100, 2)
//
// How the URDF becomes a MuJoCo world: MuJoCo reads URDF itself.  Visual
// elements are discarded (MuJoCo 2.2.2 reads no COLLADA; ANYmal's
// collisions are primitives), inertias that break the triangle inequality
// are balanced (compiler balanceinertia, a camera link of ANYmal), static
// links are fused, and a `world` link with a floating joint gives the free
// base.  The compiled model is saved as MJCF (mj_saveLastXML), each robot
// is a renamed copy of its tree, and the ground or height field, time step
// and gravity are added.  PD: explicit joint torques kp (q* - q) - kd qdot
// written to qfrc_applied before each step.  MuJoCo keeps its defaults
// otherwise (Euler, Newton solver, pyramidal cones, its soft contacts).
//
// Exit status: 0, 2 on a usage, input or MuJoCo error.
#include <mujoco/mujoco.h>
#include <tinyxml2.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <cstdint>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;

struct World {
  std::string urdf, resourceDir;
  int robots = 1;
  bool terrain = false;
  double dt = 0.0025, duration = 10, kp = 100, kd = 2;
  std::vector<double> pose{0, 0, 0.54, 1, 0, 0, 0, 0.03, 0.4, -0.8, -0.03, 0.4, -0.8,
                           0.03, -0.4, 0.8, -0.03, -0.4, 0.8};
  std::string keep;  // directory for the generated files (default: a temporary one, removed)
  bool feet = false;       // run --feet
  std::string trajectory;  // feet --trajectory
};

constexpr double kSpacing = 1.5;
constexpr int kTerrainSamples = 41;
constexpr double kTerrainSize = 12;

// Symmetric in x, in y and under x <-> y, so the sample order of either
// program cannot change the surface.
double terrainHeight(double x, double y) {
  const double k = 2 * M_PI / 3;
  return 0.05 * (2 + std::cos(k * x) + std::cos(k * y));
}

double samplePosition(int i) { return -kTerrainSize / 2 + i * kTerrainSize / (kTerrainSamples - 1); }

// The (x, y) of robot i on the grid, centred on the origin.
std::array<double, 2> robotXY(int i, int n) {
  int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  double off = (side - 1) * kSpacing / 2;
  return {(i % side) * kSpacing - off, (i / side) * kSpacing - off};
}

// Base height of robot i: the pose's height above the highest ground
// under its footprint (1 x 0.8 m), so that no foot starts inside the
// terrain (a penalty-free start for both contact models; they settle).
double baseZ(const World& w, int i) {
  if (!w.terrain) return w.pose[2];
  auto xy = robotXY(i, w.robots);
  double top = -1e300;
  for (double dx = -0.5; dx <= 0.5; dx += 0.05)
    for (double dy = -0.4; dy <= 0.4; dy += 0.05) top = std::max(top, terrainHeight(xy[0] + dx, xy[1] + dy));
  return w.pose[2] + top;
}

int usage(const char* why) {
  std::fprintf(stderr,
               "rscene-robot-bench-mujoco: error: %s\n"
               "usage: rscene-robot-bench-mujoco scene URDF RESOURCE_DIR [options]\n"
               "       rscene-robot-bench-mujoco run URDF [options] [--keep DIR] [--feet]\n"
               "       rscene-robot-bench-mujoco feet URDF [options] --trajectory CSV\n"
               "options: --robots N --terrain --pose CSV --dt S --duration S --kp KP --kd KD\n",
               why);
  return 2;
}

bool number(const char* s, double& out) {
  char* end = nullptr;
  out = std::strtod(s, &end);
  return end != s && *end == 0 && std::isfinite(out);
}

// Shortest text that reads back as the same double.
std::string num(double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string csv(const std::vector<double>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + num(v[i]);
  return s;
}

// --- the rscene scene -------------------------------------------------------

void writeScene(const World& w) {
  std::printf("raisim_engine_scene 2\n# rscene robot benchmark (bench/robot/mujoco.cpp): %d ANYmal(s) on %s\n",
              w.robots, w.terrain ? "a height field" : "a ground plane");
  std::printf("time_step %s\ngravity 0 0 -9.81\n", num(w.dt).c_str());
  std::printf("articulated_resource anymal_resource ANYmal %s resourceDirectory=%s\n", w.urdf.c_str(),
              w.resourceDir.c_str());
  if (w.terrain) {
    std::vector<double> h;
    for (int y = 0; y < kTerrainSamples; ++y)
      for (int x = 0; x < kTerrainSamples; ++x) h.push_back(terrainHeight(samplePosition(x), samplePosition(y)));
    std::printf("terrain_region /World/Terrain %d %d %g %g 0 0 0 id=terrain visible=true collidable=true "
                "sourceKind=samples heights=%s\n",
                kTerrainSamples, kTerrainSamples, kTerrainSize, kTerrainSize, csv(h).c_str());
  } else {
    std::printf("object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 0.5 1 1 default engine_default false true false - "
                "static true 1 18446744073709551615\n");
  }
  for (int i = 0; i < w.robots; ++i) {
    auto xy = robotXY(i, w.robots);
    std::vector<double> q = w.pose;
    q[0] += xy[0];
    q[1] += xy[1];
    q[2] = baseZ(w, i);
    std::printf("articulated /World/Robot%d anymal_resource %s %s %s 1 0 0 0 true true id=robot%d "
                "generalizedCoordinate=%s\n",
                i, num(q[0]).c_str(), num(q[1]).c_str(), num(q[2]).c_str(), i, csv(q).c_str());
  }
}

// --- the MuJoCo world -------------------------------------------------------

// Movable joints of the URDF in RaiSim's order: depth-first from the root,
// children in file order.
std::vector<std::string> raisimJointOrder(XMLElement* robot) {
  std::map<std::string, std::vector<XMLElement*>> children;
  std::map<std::string, bool> isChild;
  for (XMLElement* j = robot->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    XMLElement* p = j->FirstChildElement("parent");
    XMLElement* c = j->FirstChildElement("child");
    if (!p || !c || !p->Attribute("link") || !c->Attribute("link")) continue;
    children[p->Attribute("link")].push_back(j);
    isChild[c->Attribute("link")] = true;
  }
  std::vector<std::string> order;
  std::function<void(const std::string&)> visit = [&](const std::string& link) {
    for (XMLElement* j : children[link]) {
      std::string type = j->Attribute("type") ? j->Attribute("type") : "";
      if (type != "fixed" && type != "floating") order.push_back(j->Attribute("name"));
      visit(j->FirstChildElement("child")->Attribute("link"));
    }
  };
  for (XMLElement* l = robot->FirstChildElement("link"); l; l = l->NextSiblingElement("link"))
    if (l->Attribute("name") && !isChild[l->Attribute("name")]) visit(l->Attribute("name"));
  return order;
}

// Prefixes the name of `e` and of every element below it.
void prefixNames(XMLElement* e, const std::string& prefix) {
  if (const char* n = e->Attribute("name")) e->SetAttribute("name", (prefix + n).c_str());
  for (XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) prefixNames(c, prefix);
}

struct Compiled {
  mjModel* model = nullptr;
  double compileSeconds = 0;  // MuJoCo reading the URDF (the first compile)
  std::vector<std::string> jointOrder;
};

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

bool fail(const std::string& why) {
  std::fprintf(stderr, "rscene-robot-bench-mujoco: error: %s\n", why.c_str());
  return false;
}

int failed(const std::string& why) {
  fail(why);
  return 2;
}

bool compileWorld(const World& w, const fs::path& dir, Compiled& out) {
  XMLDocument urdf;
  if (urdf.LoadFile(w.urdf.c_str()) != tinyxml2::XML_SUCCESS) return fail("cannot read " + w.urdf);
  XMLElement* robot = urdf.FirstChildElement("robot");
  if (!robot) return fail(w.urdf + " has no <robot> root");
  out.jointOrder = raisimJointOrder(robot);
  std::string root;
  for (XMLElement* l = robot->FirstChildElement("link"); l && root.empty(); l = l->NextSiblingElement("link"))
    root = l->Attribute("name") ? l->Attribute("name") : "";
  XMLElement* mj = urdf.NewElement("mujoco");
  XMLElement* compiler = urdf.NewElement("compiler");
  compiler->SetAttribute("discardvisual", "true");
  compiler->SetAttribute("balanceinertia", "true");
  compiler->SetAttribute("fusestatic", "true");
  mj->InsertEndChild(compiler);
  robot->InsertFirstChild(mj);
  XMLElement* world = urdf.NewElement("link");
  world->SetAttribute("name", "world");
  robot->InsertEndChild(world);
  XMLElement* floating = urdf.NewElement("joint");
  floating->SetAttribute("name", "floating_base");
  floating->SetAttribute("type", "floating");
  floating->InsertNewChildElement("parent")->SetAttribute("link", "world");
  floating->InsertNewChildElement("child")->SetAttribute("link", root.c_str());
  robot->InsertEndChild(floating);
  const std::string urdfCopy = (dir / "robot.urdf").string(), saved = (dir / "robot.xml").string();
  if (urdf.SaveFile(urdfCopy.c_str()) != tinyxml2::XML_SUCCESS) return fail("cannot write " + urdfCopy);

  std::array<char, 1024> error{};
  double t0 = now();
  mjModel* single = mj_loadXML(urdfCopy.c_str(), nullptr, error.data(), static_cast<int>(error.size()));
  out.compileSeconds = now() - t0;
  if (!single) return fail("mujoco refuses " + urdfCopy + ": " + error.data());
  bool savedOk = mj_saveLastXML(saved.c_str(), single, error.data(), static_cast<int>(error.size()));
  mj_deleteModel(single);
  if (!savedOk) return fail("mj_saveLastXML: " + std::string(error.data()));

  XMLDocument mjcf;
  if (mjcf.LoadFile(saved.c_str()) != tinyxml2::XML_SUCCESS) return fail("cannot read back " + saved);
  XMLElement* top = mjcf.FirstChildElement("mujoco");
  XMLElement* worldbody = top ? top->FirstChildElement("worldbody") : nullptr;
  XMLElement* body = worldbody ? worldbody->FirstChildElement("body") : nullptr;
  if (!body || (!body->FirstChildElement("freejoint") && !body->FirstChildElement("joint")))
    return fail(saved + " has no free robot body under <worldbody>");
  // Contact and constraint buffers grow with the robots (MuJoCo 2.2.2
  // sizes them once, from <size>), rows up to 8000: its dense njmax x njmax
  // buffers could not be made for 64 robots at 500 rows each (a robot
  // standing uses about 25).
  XMLElement* size = top->FirstChildElement("size");
  if (!size) size = top->InsertNewChildElement("size");
  size->SetAttribute("njmax", std::min(500 * w.robots, 8000));
  size->SetAttribute("nconmax", 100 * w.robots);
  XMLElement* option = top->FirstChildElement("option");
  if (!option) option = top->InsertNewChildElement("option");
  option->SetAttribute("timestep", w.dt);
  option->SetAttribute("gravity", "0 0 -9.81");
  if (w.terrain) {
    XMLElement* asset = top->FirstChildElement("asset");
    if (!asset) asset = top->InsertNewChildElement("asset");
    XMLElement* hfield = asset->InsertNewChildElement("hfield");
    // MuJoCo 2.2.2 takes elevation from a file only; its binary format is
    // int32 nrow, int32 ncol, then float32 heights row by row.
    double lo = 1e300, hi = -1e300;
    std::vector<float> heights;
    for (int y = 0; y < kTerrainSamples; ++y)
      for (int x = 0; x < kTerrainSamples; ++x) {
        double h = terrainHeight(samplePosition(x), samplePosition(y));
        lo = std::min(lo, h);
        hi = std::max(hi, h);
        heights.push_back(static_cast<float>(h));
      }
    const std::string bin = (dir / "terrain.bin").string();
    {
      std::ofstream f(bin, std::ios::binary);
      const std::int32_t n[2] = {kTerrainSamples, kTerrainSamples};
      f.write(reinterpret_cast<const char*>(n), sizeof n);
      f.write(reinterpret_cast<const char*>(heights.data()), static_cast<std::streamsize>(heights.size() * sizeof(float)));
      if (!f) return fail("cannot write " + bin);
    }
    hfield->SetAttribute("name", "terrain");
    hfield->SetAttribute("file", bin.c_str());
    hfield->SetAttribute("size", (std::to_string(kTerrainSize / 2) + " " + std::to_string(kTerrainSize / 2) + " " +
                                  std::to_string(hi - lo) + " 0.1")
                                     .c_str());
    XMLElement* g = mjcf.NewElement("geom");
    g->SetAttribute("type", "hfield");
    g->SetAttribute("hfield", "terrain");
    g->SetAttribute("pos", ("0 0 " + std::to_string(lo)).c_str());
    worldbody->InsertFirstChild(g);
  } else {
    XMLElement* g = mjcf.NewElement("geom");
    g->SetAttribute("type", "plane");
    g->SetAttribute("size", "0 0 1");
    worldbody->InsertFirstChild(g);
  }
  // One renamed copy of the robot's tree per robot, placed by qpos later.
  tinyxml2::XMLNode* robotTree = body->DeepClone(&mjcf);
  worldbody->DeleteChild(body);
  for (int i = 0; i < w.robots; ++i) {
    XMLElement* copy = robotTree->DeepClone(&mjcf)->ToElement();
    prefixNames(copy, "r" + std::to_string(i) + "_");
    worldbody->InsertEndChild(copy);
  }
  mjcf.DeleteNode(robotTree);
  const std::string world16 = (dir / "world.xml").string();
  if (mjcf.SaveFile(world16.c_str()) != tinyxml2::XML_SUCCESS) return fail("cannot write " + world16);
  out.model = mj_loadXML(world16.c_str(), nullptr, error.data(), static_cast<int>(error.size()));
  if (!out.model) return fail("mujoco refuses " + world16 + ": " + error.data());
  return true;
}

double cpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// MuJoCo's own profiler (mjData::timer) reads this clock.
mjtNum timerClock() { return now(); }

// The feet of every robot (sphere geometries) and what they did: the
// deepest contact of any of them and each one's start position.
struct Feet {
  std::vector<int> geoms;
  std::vector<double> start;  // x y per foot
  double penetration = 0, last = 0;  // from the first second on; at the last sample
  bool started = false;

  explicit Feet(const mjModel* m) {
    for (int g = 0; g < m->ngeom; ++g)
      if (m->geom_type[g] == mjGEOM_SPHERE && m->geom_bodyid[g] > 0) geoms.push_back(g);
  }
  bool isFoot(int g) const { return std::find(geoms.begin(), geoms.end(), g) != geoms.end(); }
  // After mj_forward or mj_step (positions and contacts of the pose).
  void sample(const mjData* d, double time) {
    if (!started) {
      for (int g : geoms) start.insert(start.end(), {d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1]});
      started = true;
    }
    last = 0;
    for (int c = 0; c < d->ncon; ++c)
      if (isFoot(d->contact[c].geom1) || isFoot(d->contact[c].geom2))
        last = std::max(last, -static_cast<double>(d->contact[c].dist));
    if (time >= 1 - 1e-9) penetration = std::max(penetration, last);
  }
  double slip(const mjData* d) const {
    double most = 0;
    for (std::size_t k = 0; k < geoms.size(); ++k) {
      int g = geoms[k];
      most = std::max(most, std::hypot(d->geom_xpos[3 * g] - start[2 * k], d->geom_xpos[3 * g + 1] - start[2 * k + 1]));
    }
    return most;
  }
  void print(const mjData* d) const {
    std::printf("{\"feet\":%zu,\"footPenetration\":%.6f,\"footPenetrationEnd\":%.6f,\"footSlip\":%.6f}\n",
                geoms.size(), penetration, last, slip(d));
  }
};

// Splits one CSV line.
std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string f; std::getline(s, f, ',');) out.push_back(f);
  return out;
}

int run(const World& w) {
  fs::path dir = w.keep;
  std::error_code ec;
  if (dir.empty()) dir = fs::temp_directory_path() / ("rscene-robot-bench-" + std::to_string(::getpid()));
  fs::create_directories(dir, ec);
  Compiled c;
  bool ok = compileWorld(w, dir, c);
  if (w.keep.empty()) fs::remove_all(dir, ec);
  if (!ok) return 2;
  std::unique_ptr<mjModel, void (*)(mjModel*)> m(c.model, mj_deleteModel);
  std::unique_ptr<mjData, void (*)(mjData*)> d(mj_makeData(m.get()), mj_deleteData);
  const int joints = static_cast<int>(c.jointOrder.size());
  if (static_cast<int>(w.pose.size()) != 7 + joints)
    return usage(("--pose needs " + std::to_string(7 + joints) + " numbers for this robot").c_str());

  // Per robot: its base's qpos/qvel address and (qpos, dof, target) per joint.
  struct Pd {
    int q, v;
    double target;
  };
  std::vector<Pd> pd;
  std::vector<int> baseQ;
  for (int i = 0; i < w.robots; ++i) {
    const std::string p = "r" + std::to_string(i) + "_";
    int b = -1;
    for (int j = 0; j < m->njnt && b < 0; ++j)
      if (m->jnt_type[j] == mjJNT_FREE && std::string(mj_id2name(m.get(), mjOBJ_BODY, m->jnt_bodyid[j])).rfind(p, 0) == 0)
        b = j;
    if (b < 0) {
      fail("robot " + std::to_string(i) + " has no free joint");
      return 2;
    }
    int qa = m->jnt_qposadr[b];
    baseQ.push_back(qa);
    auto xy = robotXY(i, w.robots);
    d->qpos[qa] = w.pose[0] + xy[0];
    d->qpos[qa + 1] = w.pose[1] + xy[1];
    d->qpos[qa + 2] = baseZ(w, i);
    for (int k = 0; k < 4; ++k) d->qpos[qa + 3 + k] = w.pose[3 + k];
    for (int k = 0; k < joints; ++k) {
      int j = mj_name2id(m.get(), mjOBJ_JOINT, (p + c.jointOrder[static_cast<std::size_t>(k)]).c_str());
      if (j < 0) {
        fail("joint " + c.jointOrder[static_cast<std::size_t>(k)] + " is not in MuJoCo's model");
        return 2;
      }
      pd.push_back({m->jnt_qposadr[j], m->jnt_dofadr[j], w.pose[static_cast<std::size_t>(7 + k)]});
      d->qpos[m->jnt_qposadr[j]] = w.pose[static_cast<std::size_t>(7 + k)];
    }
  }
  mj_forward(m.get(), d.get());
  const long steps = std::lround(w.duration / w.dt);
  if (w.feet) {  // untimed: the feet every 4 steps
    Feet feet(m.get());
    feet.sample(d.get(), 0);
    for (long s = 0; s < steps; ++s) {
      for (const Pd& p : pd) d->qfrc_applied[p.v] = w.kp * (p.target - d->qpos[p.q]) - w.kd * d->qvel[p.v];
      mj_step(m.get(), d.get());
      if ((s + 1) % 4 == 0 || s + 1 == steps) feet.sample(d.get(), static_cast<double>(s + 1) * w.dt);
    }
    feet.print(d.get());
    return 0;
  }
  if (!w.trajectory.empty()) {  // mode feet: rscene-sim's poses, rows grouped by time
    std::ifstream in(w.trajectory);
    std::string line;
    if (!std::getline(in, line)) return failed("cannot read " + w.trajectory);
    std::vector<std::string> head = fields(line);
    std::vector<int> column;  // per RaiSim joint: its column
    for (const std::string& j : c.jointOrder) {
      auto it = std::find(head.begin(), head.end(), "q." + j);
      if (it == head.end()) return failed(w.trajectory + " has no column q." + j);
      column.push_back(static_cast<int>(it - head.begin()));
    }
    if (head.size() < 9 || head[2] != "px" || head[5] != "qw") return failed(w.trajectory + " is not a csv trajectory");
    Feet feet(m.get());
    std::string time;
    auto flush = [&] {
      mj_fwdPosition(m.get(), d.get());
      feet.sample(d.get(), std::stod(time));
    };
    while (std::getline(in, line)) {
      std::vector<std::string> f = fields(line);
      if (f.size() < head.size() - 1) return failed("short row in " + w.trajectory);
      if (!time.empty() && f[0] != time) flush();
      time = f[0];
      const std::string prefix = "/World/Robot";
      if (f[1].rfind(prefix, 0) != 0) continue;
      std::size_t i = std::stoul(f[1].substr(prefix.size()));
      if (i >= baseQ.size()) continue;
      for (int k = 0; k < 7; ++k) d->qpos[baseQ[i] + k] = std::stod(f[static_cast<std::size_t>(2 + k)]);
      for (int k = 0; k < joints; ++k)
        d->qpos[pd[i * static_cast<std::size_t>(joints) + static_cast<std::size_t>(k)].q] =
            std::stod(f[static_cast<std::size_t>(column[static_cast<std::size_t>(k)])]);
    }
    if (time.empty()) return failed(w.trajectory + " has no rows");
    flush();
    feet.print(d.get());
    return 0;
  }
  mjcb_time = timerClock;  // where MuJoCo's time goes: collision, constraint solver
  for (mjTimerStat& t : d->timer) t = mjTimerStat{};
  double wall0 = now(), cpu0 = cpuSeconds();
  for (long s = 0; s < steps; ++s) {
    for (const Pd& p : pd) d->qfrc_applied[p.v] = w.kp * (p.target - d->qpos[p.q]) - w.kd * d->qvel[p.v];
    mj_step(m.get(), d.get());
  }
  double wall = now() - wall0, cpu = cpuSeconds() - cpu0;
  double zmin = 1e300, zmax = -1e300, tilt = 0;
  for (std::size_t i = 0; i < baseQ.size(); ++i) {
    const double* q = d->qpos + baseQ[i];
    double z = q[2] - (baseZ(w, static_cast<int>(i)) - w.pose[2]);  // above the highest ground under its start footprint
    zmin = std::min(zmin, z);
    zmax = std::max(zmax, z);
    // Angle between the base's z axis and the world's: 1 - 2 (qx^2 + qy^2) is their cosine.
    double n = q[3] * q[3] + q[4] * q[4] + q[5] * q[5] + q[6] * q[6];
    double cosTilt = 1 - 2 * (q[4] * q[4] + q[5] * q[5]) / n;
    tilt = std::max(tilt, std::acos(std::clamp(cosTilt, -1.0, 1.0)) * 180 / M_PI);
  }
  const double total = std::max(d->timer[mjTIMER_STEP].duration, 1e-12);
  std::printf("{\"robots\":%d,\"terrain\":%s,\"compileTime\":%.6f,\"steps\":%ld,\"stepWall\":%.6f,\"stepCpu\":%.6f,"
              "\"stepsPerSecond\":%.1f,\"baseHeightMin\":%.4f,\"baseHeightMax\":%.4f,\"tiltMaxDeg\":%.3f,\"nv\":%d,"
              "\"contactsAtEnd\":%d,\"collisionShare\":%.3f,\"constraintShare\":%.3f}\n",
              w.robots, w.terrain ? "true" : "false", c.compileSeconds, steps, wall, cpu, steps / wall, zmin, zmax,
              tilt, m->nv, d->ncon, d->timer[mjTIMER_POS_COLLISION].duration / total,
              d->timer[mjTIMER_CONSTRAINT].duration / total);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) return usage("a mode (scene, run) and a URDF are needed");
  const std::string mode = argv[1];
  World w;
  w.urdf = argv[2];
  int i = 3;
  if (mode == "scene") {
    if (argc < 4) return usage("scene needs URDF and RESOURCE_DIR");
    w.resourceDir = argv[i++];
  } else if (mode != "run" && mode != "feet") {
    return usage(("unknown mode '" + mode + "'").c_str());
  }
  for (; i < argc; ++i) {
    const std::string a = argv[i];
    double v = 0;
    auto value = [&](double lo, double hi) { return i + 1 < argc && number(argv[++i], v) && v >= lo && v <= hi; };
    if (a == "--terrain") {
      w.terrain = true;
    } else if (a == "--robots") {
      if (!value(1, 1024)) return usage("--robots needs a count in [1, 1024]");
      w.robots = static_cast<int>(v);
    } else if (a == "--dt") {
      if (!value(1e-6, 1)) return usage("--dt needs seconds in [1e-6, 1]");
      w.dt = v;
    } else if (a == "--duration") {
      if (!value(0, 3600)) return usage("--duration needs seconds in [0, 3600]");
      w.duration = v;
    } else if (a == "--kp" || a == "--kd") {
      if (!value(0, 1e9)) return usage("--kp and --kd need a gain in [0, 1e9]");
      (a == "--kp" ? w.kp : w.kd) = v;
    } else if (a == "--pose" && i + 1 < argc) {
      w.pose.clear();
      std::stringstream s(argv[++i]);
      for (std::string item; std::getline(s, item, ',');) {
        if (!number(item.c_str(), v)) return usage("--pose needs comma-separated numbers");
        w.pose.push_back(v);
      }
      if (w.pose.size() < 7) return usage("--pose needs a floating base (7 numbers) and the joints");
    } else if (a == "--keep" && i + 1 < argc && mode == "run") {
      w.keep = argv[++i];
    } else if (a == "--feet" && mode == "run") {
      w.feet = true;
    } else if (a == "--trajectory" && i + 1 < argc && mode == "feet") {
      w.trajectory = argv[++i];
    } else {
      return usage(("unknown or incomplete option '" + a + "'").c_str());
    }
  }
  if (mode == "scene") {
    writeScene(w);
    return std::fflush(stdout) == 0 ? 0 : 2;
  }
  if (mode == "feet" && w.trajectory.empty()) return usage("feet needs --trajectory CSV");
  return run(w);
}
