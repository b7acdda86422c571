// MJCF loading (lib/robot/mjcf.cpp, mjcf_convert.cpp): the proof that the
// conversion is right is MuJoCo itself.  Each model is compiled again here
// with mj_loadXML and, for random coordinates, our forward kinematics of
// the converted model must put every body, geom and centre of mass where
// mj_kinematics puts them, with the coordinates used as MuJoCo's qpos
// unchanged.  The Gymnasium models come from ../shared (skipped when
// absent); the fixtures under tests/data/robots/mjcf/ run everywhere.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <array>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

#include "robot/kinematics.hpp"
#include "robot/load.hpp"
#include "robot/mjcf.hpp"

namespace rscene::robot {
namespace {

namespace fs = std::filesystem;

const std::string kFixtures = std::string(RSCENE_TEST_DATA) + "/robots/mjcf/";
const std::string kGymnasium = std::string(RSCENE_SHARED_DIR) + "/corpus/robots/gymnasium/";

struct MjDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using MjModelPtr = std::unique_ptr<mjModel, MjDeleter>;
using MjDataPtr = std::unique_ptr<mjData, MjDeleter>;

MjModelPtr compile(const std::string& path) {
  std::array<char, 1024> error{};
  MjModelPtr m(mj_loadXML(path.c_str(), nullptr, error.data(), static_cast<int>(error.size())));
  EXPECT_TRUE(m) << path << ": " << error.data();
  return m;
}

std::string name(const mjModel* m, int type, int id, const char* fallback) {
  const char* n = mj_id2name(m, type, id);
  return n && *n ? n : fallback + std::to_string(id);
}

int countCode(const Diagnostics& diags, const std::string& code) {
  int n = 0;
  for (const Diagnostic& d : diags) n += d.code == code;
  return n;
}

std::string dump(const Diagnostics& diags) {
  std::string s;
  for (const Diagnostic& d : diags) s += d.code + " " + d.file + ":" + std::to_string(d.line) + ": " + d.message + "\n";
  return s;
}

// A random qpos: hinge and slide values in [-1.5, 1.5], random unit
// quaternions for balls and the free base, a base position in a 2 m box.
Eigen::VectorXd randomQ(const mjModel* m, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  std::normal_distribution<double> n(0, 1);
  Eigen::VectorXd q(m->nq);
  for (int j = 0; j < m->njnt; ++j) {
    int a = m->jnt_qposadr[j];
    switch (m->jnt_type[j]) {
      case mjJNT_FREE:
        for (int i = 0; i < 3; ++i) q[a + i] = u(rng);
        a += 3;
        [[fallthrough]];
      case mjJNT_BALL: {
        Eigen::Vector4d r(n(rng), n(rng), n(rng), n(rng));
        q.segment<4>(a) = r.normalized();
        break;
      }
      default: q[a] = u(rng);
    }
  }
  return q;
}

double angle(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) { return a.angularDistance(b); }

// The `v x y z` lines of an OBJ file.
std::vector<Eigen::Vector3d> objVertices(const std::string& path) {
  std::vector<Eigen::Vector3d> out;
  std::ifstream f(path);
  std::string tag;
  for (std::string line; std::getline(f, line);) {
    std::istringstream s(line);
    Eigen::Vector3d v;
    if (s >> tag && tag == "v" && s >> v.x() >> v.y() >> v.z()) out.push_back(v);
  }
  return out;
}

// The mesh file's vertices placed by our visual (origin, meshScale) and
// MuJoCo's compiled vertices of geom g are the same points (float
// precision; MuJoCo 2.2.2 repeats an OBJ's vertices per face, so as sets).
void expectSameVertices(const mjModel* m, int g, const Eigen::Vector3d& gpos, const Eigen::Matrix3d& gmat,
                        const Pose& world, const Geometry& geometry, const std::string& name) {
  std::vector<Eigen::Vector3d> ours;
  for (const Eigen::Vector3d& v : objVertices(geometry.meshPath))
    ours.push_back(world.position + world.orientation * geometry.meshScale.cwiseProduct(v));
  ASSERT_FALSE(ours.empty()) << geometry.meshPath;
  const int mesh = m->geom_dataid[g];
  std::vector<Eigen::Vector3d> theirs;
  for (int i = 0; i < m->mesh_vertnum[mesh]; ++i) {
    const float* c = m->mesh_vert + 3 * (m->mesh_vertadr[mesh] + i);
    theirs.push_back(gpos + gmat * Eigen::Vector3d(c[0], c[1], c[2]));
  }
  auto nearest = [](const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& set) {
    double best = 1e300;
    for (const Eigen::Vector3d& q : set) best = std::min(best, (p - q).norm());
    return best;
  };
  for (const Eigen::Vector3d& t : theirs) EXPECT_LT(nearest(t, ours), 2e-6) << name;
  for (const Eigen::Vector3d& o : ours) EXPECT_LT(nearest(o, theirs), 2e-6) << name;
}

// Loads `path` with loadMjcf and checks it against MuJoCo's own compile:
// coordinate layout (MuJoCo's qpos order is RaiSim's depth-first order),
// mass, and body, geom and centre-of-mass poses for `samples` random q.
void expectMatchesMuJoCo(const std::string& path, int samples = 20) {
  SCOPED_TRACE(path);
  Model model;
  Diagnostics diags;
  ASSERT_TRUE(loadMjcf(path, LoadOptions{}, model, diags)) << dump(diags);
  EXPECT_FALSE(hasErrors(diags)) << dump(diags);
  MjModelPtr m = compile(path);
  ASSERT_TRUE(m);
  MjDataPtr d(mj_makeData(m.get()));

  Coordinates c;
  ASSERT_TRUE(makeCoordinates(model, {}, c).empty());
  EXPECT_EQ(c.coordinateDim, m->nq);
  EXPECT_EQ(c.velocityDim, m->nv);
  for (int j = 0; j < m->njnt; ++j) {
    if (m->jnt_type[j] == mjJNT_FREE) {
      EXPECT_TRUE(model.floatingBase);
      EXPECT_EQ(m->jnt_qposadr[j], 0);
      continue;
    }
    int ours = model.findJoint(name(m.get(), mjOBJ_JOINT, j, "joint"));
    ASSERT_GE(ours, 0) << name(m.get(), mjOBJ_JOINT, j, "joint");
    EXPECT_EQ(c.coordinateIndex[static_cast<std::size_t>(ours)], m->jnt_qposadr[j]) << model.joints[ours].name;
    EXPECT_EQ(c.velocityIndex[static_cast<std::size_t>(ours)], m->jnt_dofadr[j]) << model.joints[ours].name;
  }
  double mass = 0;
  for (int b = 0; b < m->nbody; ++b) mass += m->body_mass[b];
  EXPECT_NEAR(model.totalMass(), mass, 1e-12 * mass);

  std::mt19937 rng(7);
  for (int s = 0; s < samples; ++s) {
    Eigen::VectorXd q = randomQ(m.get(), rng);
    for (int i = 0; i < m->nq; ++i) d->qpos[i] = q[i];
    mj_kinematics(m.get(), d.get());
    std::vector<Pose> poses = linkPoses(model, c, Pose{}, q);
    for (int b = 1; b < m->nbody; ++b) {
      const std::string body = name(m.get(), mjOBJ_BODY, b, "body");
      int link = model.findLink(body);
      ASSERT_GE(link, 0) << body;
      const Pose& frame = poses[static_cast<std::size_t>(link)];
      // The link frame sits at the body's last joint's anchor (free: none).
      Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
      int last = m->body_jntadr[b] + m->body_jntnum[b] - 1;
      if (m->body_jntnum[b] > 0 && m->jnt_type[last] != mjJNT_FREE)
        anchor = Eigen::Vector3d(m->jnt_pos[3 * last], m->jnt_pos[3 * last + 1], m->jnt_pos[3 * last + 2]);
      Pose bodyFrame = frame * Pose{-anchor, Eigen::Quaterniond::Identity()};
      Eigen::Vector3d xpos(d->xpos[3 * b], d->xpos[3 * b + 1], d->xpos[3 * b + 2]);
      Eigen::Quaterniond xquat(d->xquat[4 * b], d->xquat[4 * b + 1], d->xquat[4 * b + 2], d->xquat[4 * b + 3]);
      EXPECT_LT((bodyFrame.position - xpos).norm(), 1e-9) << body << " sample " << s;
      EXPECT_LT(angle(bodyFrame.orientation, xquat), 1e-9) << body << " sample " << s;
      const Link& l = model.links[static_cast<std::size_t>(link)];
      Eigen::Vector3d com = (frame * l.inertial.origin).position;
      EXPECT_LT((com - Eigen::Vector3d(d->xipos[3 * b], d->xipos[3 * b + 1], d->xipos[3 * b + 2])).norm(), 1e-9)
          << body;
    }
    // Every converted geom where MuJoCo puts it; a mesh vertex by vertex.
    for (std::size_t li = 0; li < model.links.size(); ++li)
      for (const Visual& v : model.links[li].visuals) {
        int g = mj_name2id(m.get(), mjOBJ_GEOM, v.name.c_str());
        if (g < 0 && v.name.rfind("geom", 0) == 0) g = std::stoi(v.name.substr(4));
        ASSERT_GE(g, 0) << v.name;
        Pose world = poses[li] * v.origin;
        Eigen::Vector3d gpos(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]);
        Eigen::Matrix3d gmat = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d->geom_xmat + 9 * g);
        if (v.geometry.kind == GeometryKind::Mesh) {
          expectSameVertices(m.get(), g, gpos, gmat, world, v.geometry, v.name);
          continue;
        }
        EXPECT_LT((world.position - gpos).norm(), 1e-9) << v.name;
        EXPECT_LT(angle(world.orientation, Eigen::Quaterniond(gmat)), 1e-8) << v.name;
      }
  }
}

bool haveGymnasium() { return fs::exists(kGymnasium + "ant.xml"); }

TEST(Mjcf, GymnasiumModelsMatchMuJoCosKinematics) {
  if (!haveGymnasium()) GTEST_SKIP() << kGymnasium << " is absent";
  for (const char* file : {"ant.xml", "half_cheetah.xml", "hopper.xml", "humanoid.xml", "inverted_pendulum.xml"})
    expectMatchesMuJoCo(kGymnasium + file);
}

TEST(Mjcf, GymnasiumDimensionsAndBase) {
  if (!haveGymnasium()) GTEST_SKIP() << kGymnasium << " is absent";
  struct Expect {
    const char* file;
    bool floating;
    int q, u;
  };
  for (const Expect& e : {Expect{"ant.xml", true, 15, 14}, Expect{"humanoid.xml", true, 24, 23},
                          Expect{"hopper.xml", false, 6, 6}, Expect{"half_cheetah.xml", false, 9, 9},
                          Expect{"inverted_pendulum.xml", false, 2, 2}}) {
    SCOPED_TRACE(e.file);
    Model model;
    Diagnostics diags;
    ASSERT_TRUE(loadMjcf(kGymnasium + e.file, LoadOptions{}, model, diags)) << dump(diags);
    Coordinates c;
    makeCoordinates(model, {}, c);
    EXPECT_EQ(model.floatingBase, e.floating);
    EXPECT_EQ(c.coordinateDim, e.q);
    EXPECT_EQ(c.velocityDim, e.u);
    if (!e.floating) {
      EXPECT_EQ(model.links[static_cast<std::size_t>(model.root)].name, "world");
    }
  }
}

TEST(Mjcf, HopperRootIsTwoSlidesAndAHingeFromAMasslessWorld) {
  if (!haveGymnasium()) GTEST_SKIP() << kGymnasium << " is absent";
  Model model;
  Diagnostics diags;
  ASSERT_TRUE(loadMjcf(kGymnasium + "hopper.xml", LoadOptions{}, model, diags)) << dump(diags);
  EXPECT_TRUE(diags.empty()) << dump(diags);  // the floor plane is the scene's ground: no warning
  const Link& world = model.links[static_cast<std::size_t>(model.root)];
  EXPECT_EQ(world.inertial.mass, 0);
  EXPECT_TRUE(world.visuals.empty());
  const Joint& rootx = model.joints[static_cast<std::size_t>(model.findJoint("rootx"))];
  const Joint& rootz = model.joints[static_cast<std::size_t>(model.findJoint("rootz"))];
  const Joint& rooty = model.joints[static_cast<std::size_t>(model.findJoint("rooty"))];
  EXPECT_EQ(rootx.type, JointType::Prismatic);
  EXPECT_FALSE(rootx.hasLimits);
  EXPECT_EQ(rootz.type, JointType::Prismatic);
  EXPECT_EQ(rooty.type, JointType::Continuous);
  // Intermediate links are massless and named after body and joint.
  EXPECT_EQ(model.links[static_cast<std::size_t>(rootx.childLink)].name, "torso::rootx");
  EXPECT_EQ(model.links[static_cast<std::size_t>(rootx.childLink)].inertial.mass, 0);
  EXPECT_EQ(model.links[static_cast<std::size_t>(rooty.childLink)].name, "torso");
  // rootz has ref 1.25: qpos rootz = 1.25 is the torso where the file puts it.
  Coordinates c;
  makeCoordinates(model, {}, c);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(c.coordinateDim);
  q[c.coordinateIndex[static_cast<std::size_t>(model.findJoint("rootz"))]] = 1.25;
  std::vector<Pose> poses = linkPoses(model, c, Pose{}, q);
  EXPECT_NEAR(poses[static_cast<std::size_t>(model.findLink("torso"))].position.z(), 1.25, 1e-12);
  // Joint parameters in SI after `angle="degree"`: thigh_joint range -150..0 degrees.
  const Joint& thigh = model.joints[static_cast<std::size_t>(model.findJoint("thigh_joint"))];
  EXPECT_EQ(thigh.type, JointType::Revolute);
  EXPECT_NEAR(thigh.lower, -150 * M_PI / 180, 1e-12);
  EXPECT_NEAR(thigh.upper, 0, 1e-12);
  EXPECT_EQ(thigh.damping, 1);
  EXPECT_EQ(thigh.rotorInertia, 1);  // armature
  // Capsules: MuJoCo's half-length doubled.
  const Link& leg = model.links[static_cast<std::size_t>(model.findLink("leg"))];
  ASSERT_EQ(leg.collisions.size(), 1u);
  EXPECT_EQ(leg.collisions[0].geometry.kind, GeometryKind::Capsule);
  EXPECT_NEAR(leg.collisions[0].geometry.length, 0.5, 1e-12);
  EXPECT_NEAR(leg.collisions[0].geometry.radius, 0.04, 1e-12);
  ASSERT_TRUE(leg.visuals[0].color.has_value());
  EXPECT_NEAR((*leg.visuals[0].color - Eigen::Vector4d(0.8, 0.6, 0.4, 1)).norm(), 0, 1e-6);
}

// A record without coordinates starts where MuJoCo's model does: the
// neutral coordinate is qpos0 entry for entry (joint refs, a free body's
// pos and quat), and the links stand where mj_kinematics puts them there.
void expectNeutralIsQpos0(const std::string& path) {
  SCOPED_TRACE(path);
  MjModelPtr m = compile(path);
  ASSERT_TRUE(m);
  Model model;
  Diagnostics diags;
  ASSERT_TRUE(loadMjcf(path, LoadOptions{}, model, diags)) << dump(diags);
  Coordinates c;
  makeCoordinates(model, {}, c);
  ASSERT_EQ(c.coordinateDim, m->nq);
  Eigen::VectorXd q = neutralCoordinate(model, c, Pose{});
  for (int i = 0; i < m->nq; ++i) EXPECT_NEAR(q[i], m->qpos0[i], 1e-12) << "qpos entry " << i;
}

TEST(Mjcf, NeutralCoordinateIsQpos0) {
  expectNeutralIsQpos0(kFixtures + "joints.xml");
  if (!haveGymnasium()) GTEST_SKIP() << kGymnasium << " is absent";
  for (const char* file : {"ant.xml", "half_cheetah.xml", "hopper.xml", "humanoid.xml", "inverted_pendulum.xml"})
    expectNeutralIsQpos0(kGymnasium + file);
}

TEST(Mjcf, HopperStartsStandingAtRootzRef) {
  if (!haveGymnasium()) GTEST_SKIP() << kGymnasium << " is absent";
  Model model;
  Diagnostics diags;
  ASSERT_TRUE(loadMjcf(kGymnasium + "hopper.xml", LoadOptions{}, model, diags)) << dump(diags);
  Coordinates c;
  makeCoordinates(model, {}, c);
  const int rootz = model.findJoint("rootz");
  EXPECT_DOUBLE_EQ(model.joints[static_cast<std::size_t>(rootz)].initial, 1.25);
  Pose base;
  base.position = {2, 0, 0.5};  // the record's pose places MuJoCo's world
  Eigen::VectorXd q = neutralCoordinate(model, c, base);
  EXPECT_DOUBLE_EQ(q[c.coordinateIndex[static_cast<std::size_t>(rootz)]], 1.25);
  std::vector<Pose> poses = linkPoses(model, c, base, q);
  EXPECT_NEAR(poses[static_cast<std::size_t>(model.findLink("torso"))].position.z(), 1.75, 1e-12);
  // A scaled robot starts at its scaled height.
  Model big;
  ASSERT_TRUE(loadMjcf(kGymnasium + "hopper.xml", LoadOptions{}, big, diags)) << dump(diags);
  scaleModel(big, Eigen::Vector3d::Constant(2));
  Coordinates cb;
  makeCoordinates(big, {}, cb);
  std::vector<Pose> bigPoses = linkPoses(big, cb, Pose{}, neutralCoordinate(big, cb, Pose{}));
  EXPECT_NEAR(bigPoses[static_cast<std::size_t>(big.findLink("torso"))].position.z(), 2.5, 1e-12);
}

TEST(Mjcf, HumanoidWarnsAboutItsTendons) {
  if (!haveGymnasium()) GTEST_SKIP() << kGymnasium << " is absent";
  Model model;
  Diagnostics diags;
  ASSERT_TRUE(loadMjcf(kGymnasium + "humanoid.xml", LoadOptions{}, model, diags));
  EXPECT_EQ(countCode(diags, code::kSkipped), 1) << dump(diags);
  EXPECT_NE(dump(diags).find("tendon"), std::string::npos);
  EXPECT_EQ(diags[0].file, kGymnasium + "humanoid.xml");
}

TEST(Mjcf, FixtureMatchesMuJoCosKinematics) { expectMatchesMuJoCo(kFixtures + "joints.xml", 50); }

TEST(Mjcf, FixtureJointsGeomsAndWarnings) {
  Model model;
  Diagnostics diags;
  ASSERT_TRUE(loadMjcf(kFixtures + "joints.xml", LoadOptions{}, model, diags)) << dump(diags);
  // The ellipsoid is the one approximation; the floor plane goes silently.
  ASSERT_EQ(diags.size(), 1u) << dump(diags);
  EXPECT_EQ(diags[0].code, code::kMjcfApproximated);
  EXPECT_EQ(diags[0].severity, Severity::Warning);
  EXPECT_EQ(diags[0].file, kFixtures + "joints.xml");
  EXPECT_FALSE(model.floatingBase);
  EXPECT_EQ(model.name, "joints");

  const Joint& swing = model.joints[static_cast<std::size_t>(model.findJoint("swing"))];
  EXPECT_EQ(swing.type, JointType::Continuous);
  EXPECT_DOUBLE_EQ(swing.damping, 0.5);
  EXPECT_DOUBLE_EQ(swing.rotorInertia, 0.02);
  EXPECT_DOUBLE_EQ(swing.friction, 0.1);
  const Joint& lift = model.joints[static_cast<std::size_t>(model.findJoint("lift"))];
  EXPECT_EQ(lift.type, JointType::Prismatic);
  EXPECT_TRUE(lift.hasLimits);
  EXPECT_DOUBLE_EQ(lift.lower, -0.2);
  EXPECT_DOUBLE_EQ(lift.upper, 0.4);
  const Joint& bend = model.joints[static_cast<std::size_t>(model.findJoint("bend"))];
  EXPECT_EQ(bend.type, JointType::Revolute);
  EXPECT_DOUBLE_EQ(bend.stiffness, 3);
  ASSERT_EQ(bend.springMount.size(), 1u);
  EXPECT_DOUBLE_EQ(bend.springMount[0], 0.25);
  EXPECT_NEAR(bend.axis.norm(), 1, 1e-12);
  const Joint& ball = model.joints[static_cast<std::size_t>(model.findJoint("wrist_ball"))];
  EXPECT_EQ(ball.type, JointType::Spherical);
  EXPECT_DOUBLE_EQ(ball.damping, 0.3);
  ASSERT_EQ(ball.springMount.size(), 4u);  // the rest quaternion
  EXPECT_DOUBLE_EQ(ball.springMount[0], 1);
  // The arm body has three joints: two massless links before it.
  EXPECT_EQ(model.links[static_cast<std::size_t>(lift.childLink)].name, "arm::lift");
  EXPECT_EQ(model.links[static_cast<std::size_t>(bend.childLink)].name, "arm::bend");
  const Link& arm = model.links[static_cast<std::size_t>(model.findLink("arm"))];
  EXPECT_EQ(model.joints[static_cast<std::size_t>(arm.parentJoint)].name, "twist");
  // The tool body has no joint: welded to the wrist by a fixed joint.
  const Link& tool = model.links[static_cast<std::size_t>(model.findLink("tool"))];
  EXPECT_EQ(model.joints[static_cast<std::size_t>(tool.parentJoint)].type, JointType::Fixed);
  EXPECT_DOUBLE_EQ(tool.inertial.mass, 0.05);
  // contype = conaffinity = 0: drawn, never collided.
  ASSERT_EQ(arm.visuals.size(), 2u);
  EXPECT_EQ(arm.collisions.size(), 1u);
  EXPECT_EQ(arm.visuals[1].geometry.kind, GeometryKind::Sphere);
  EXPECT_NEAR(arm.visuals[1].geometry.radius, std::cbrt(0.05 * 0.04 * 0.03), 1e-12);
  // Geom colors: the default class's, or the geom's own.
  const Link& wrist = model.links[static_cast<std::size_t>(model.findLink("wrist"))];
  ASSERT_EQ(wrist.visuals.size(), 1u);
  EXPECT_EQ(wrist.visuals[0].geometry.kind, GeometryKind::Cylinder);
  EXPECT_NEAR(wrist.visuals[0].geometry.length, 0.1, 1e-12);
  EXPECT_NEAR((*wrist.visuals[0].color - Eigen::Vector4d(1, 0, 0, 1)).norm(), 0, 1e-7);
  // A fixed base keeps its world geoms but the plane: the post.
  const Link& world = model.links[static_cast<std::size_t>(model.root)];
  ASSERT_EQ(world.visuals.size(), 1u);
  EXPECT_EQ(world.visuals[0].name, "post");
  EXPECT_EQ(world.visuals[0].geometry.kind, GeometryKind::Box);
  EXPECT_NEAR((world.visuals[0].geometry.size - Eigen::Vector3d(0.1, 0.1, 1)).norm(), 0, 1e-12);
}

TEST(Mjcf, ModulesDoNotApplyToMjcf) {
  Model model;
  Diagnostics diags;
  LoadOptions options;
  options.modules = {"actuator_pd"};
  ASSERT_TRUE(loadMjcf(kFixtures + "include.xml", options, model, diags)) << dump(diags);
  ASSERT_EQ(diags.size(), 1u) << dump(diags);
  EXPECT_EQ(diags[0].code, code::kSkipped);
  EXPECT_NE(diags[0].message.find("modules="), std::string::npos) << diags[0].message;
}

TEST(Mjcf, IncludesAndDefaultClassesAreMuJoCos) {
  Model model;
  Diagnostics diags;
  ASSERT_TRUE(loadMjcf(kFixtures + "include.xml", LoadOptions{}, model, diags)) << dump(diags);
  EXPECT_TRUE(model.floatingBase);
  ASSERT_EQ(model.links.size(), 1u);
  EXPECT_EQ(model.links[0].name, "block");
  EXPECT_NEAR(model.links[0].inertial.mass, 5000 * 0.2 * 0.2 * 0.2, 1e-9);  // density of class "heavy"
  expectMatchesMuJoCo(kFixtures + "include.xml");
}

TEST(Mjcf, MeshGeomsKeepTheirFileScaleAndFrame) {
  Model model;
  Diagnostics diags;
  ASSERT_TRUE(loadMjcf(kFixtures + "meshes.xml", LoadOptions{}, model, diags)) << dump(diags);
  EXPECT_TRUE(diags.empty()) << dump(diags);
  const std::string box = fs::path(kFixtures + "meshes/box.obj").lexically_normal().string();
  const Link& base = model.links[static_cast<std::size_t>(model.findLink("base"))];
  ASSERT_EQ(base.visuals.size(), 1u);
  EXPECT_EQ(base.visuals[0].geometry.kind, GeometryKind::Mesh);
  EXPECT_EQ(base.visuals[0].geometry.meshPath, box);  // compiler meshdir, relative to the model
  EXPECT_LT((base.visuals[0].geometry.meshScale - Eigen::Vector3d(1, 2, 0.5)).norm(), 1e-6);
  ASSERT_EQ(base.collisions.size(), 1u);
  EXPECT_EQ(base.collisions[0].geometry.meshPath, box);
  const Link& arm = model.links[static_cast<std::size_t>(model.findLink("arm"))];
  ASSERT_EQ(arm.visuals.size(), 1u);  // the mesh named after its file
  EXPECT_LT((arm.visuals[0].geometry.meshScale - Eigen::Vector3d::Ones()).norm(), 1e-6);
  EXPECT_TRUE(arm.collisions.empty());
  expectMatchesMuJoCo(kFixtures + "meshes.xml");
}

TEST(Mjcf, MeshWithoutAFileIsSkippedWithAWarning) {
  Model model;
  Diagnostics diags;
  ASSERT_TRUE(loadMjcf(kFixtures + "inline_mesh.xml", LoadOptions{}, model, diags)) << dump(diags);
  EXPECT_EQ(countCode(diags, code::kSkipped), 2) << dump(diags);
  EXPECT_NE(dump(diags).find("mesh 'tetra' is skipped: it has no file"), std::string::npos) << dump(diags);
  ASSERT_EQ(model.links.size(), 1u);
  ASSERT_EQ(model.links[0].visuals.size(), 1u);  // the sphere stays
  EXPECT_EQ(model.links[0].visuals[0].name, "ball");
}

TEST(Mjcf, FreeJointBelowTheTopLevelIsRefused) {
  Model model;
  Diagnostics diags;
  EXPECT_FALSE(loadMjcf(kFixtures + "free_nested.xml", LoadOptions{}, model, diags));
  ASSERT_FALSE(diags.empty());
  // MuJoCo 2.2.2 may refuse it itself (RS7030); if it compiles, we do.
  const Diagnostic& d = diags.back();
  EXPECT_EQ(d.severity, Severity::Error);
  EXPECT_TRUE(d.code == std::string(code::kMjcfUnsupported) || d.code == std::string(code::kBadFile)) << dump(diags);
  EXPECT_NE(d.message.find("free"), std::string::npos) << d.message;
  EXPECT_EQ(d.file, kFixtures + "free_nested.xml");
}

TEST(Mjcf, SecondTopLevelBodyBesideAFloatingBaseIsRefused) {
  Model model;
  Diagnostics diags;
  EXPECT_FALSE(loadMjcf(kFixtures + "two_free.xml", LoadOptions{}, model, diags));
  ASSERT_EQ(countCode(diags, code::kMjcfUnsupported), 1) << dump(diags);
  EXPECT_NE(diags.back().message.find("'second'"), std::string::npos) << diags.back().message;
}

TEST(Mjcf, CompileErrorNamesFileAndLine) {
  Model model;
  Diagnostics diags;
  EXPECT_FALSE(loadMjcf(kFixtures + "unknown_attribute.xml", LoadOptions{}, model, diags));
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].code, code::kBadFile);
  EXPECT_EQ(diags[0].file, kFixtures + "unknown_attribute.xml");
  EXPECT_EQ(diags[0].line, 5u) << diags[0].message;
  EXPECT_NE(diags[0].message.find("colour"), std::string::npos) << diags[0].message;
  EXPECT_EQ(diags[0].message.find('\n'), std::string::npos);
}

TEST(Mjcf, MalformedXmlNamesTheLine) {
  fs::path dir = fs::temp_directory_path() / ("rscene_mjcf_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::string path = (dir / "broken.xml").string();
  {
    std::ofstream f(path);
    f << "<mujoco>\n  <worldbody>\n    <body name=\"a\">\n  </worldbody>\n</mujoco>\n";
  }
  Model model;
  Diagnostics diags;
  EXPECT_FALSE(loadMjcf(path, LoadOptions{}, model, diags));
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].code, code::kBadFile);
  EXPECT_GT(diags[0].line, 0u) << diags[0].message;
  fs::remove_all(dir);
}

TEST(Mjcf, CompositeIsRefusedBeforeMuJoCoExpandsIt) {
  Model model;
  Diagnostics diags;
  auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(loadMjcf(kFixtures + "composite.xml", LoadOptions{}, model, diags));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  ASSERT_EQ(diags.size(), 1u) << dump(diags);
  EXPECT_EQ(diags[0].code, code::kMjcfUnsupported);
  EXPECT_EQ(diags[0].file, kFixtures + "composite.xml");
  EXPECT_EQ(diags[0].line, 7u);
}

TEST(Mjcf, FifoNamedAsAMeshIsRefusedWhereItIsNamed) {
  fs::path dir = fs::temp_directory_path() / ("rscene_mjcf_fifo_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  ASSERT_EQ(::mkfifo((dir / "part.stl").c_str(), 0600), 0);
  const std::string path = (dir / "model.xml").string();
  {
    std::ofstream f(path);
    f << "<mujoco>\n  <asset>\n    <mesh file=\"part.stl\"/>\n  </asset>\n  <worldbody>\n"
         "    <geom type=\"mesh\" mesh=\"part\"/>\n  </worldbody>\n</mujoco>\n";
  }
  Model model;
  Diagnostics diags;
  EXPECT_FALSE(loadMjcf(path, LoadOptions{}, model, diags));  // and returns: MuJoCo never opens the FIFO
  ASSERT_EQ(diags.size(), 1u) << dump(diags);
  EXPECT_EQ(diags[0].code, code::kMissingFile);
  EXPECT_EQ(diags[0].file, path);
  EXPECT_EQ(diags[0].line, 3u);
  EXPECT_NE(diags[0].message.find("FIFO"), std::string::npos) << diags[0].message;
  fs::remove_all(dir);
}

TEST(Mjcf, OversizeIncludedFileIsRefusedWhereItIsIncluded) {
  fs::path dir = fs::temp_directory_path() / ("rscene_mjcf_big_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "model.xml").string();
  {
    std::ofstream f(path);
    f << "<mujoco>\n  <worldbody>\n    <include file=\"big.xml\"/>\n  </worldbody>\n</mujoco>\n";
    std::ofstream big(dir / "big.xml");
    big << "<mujoco><!--" << std::string(4000, 'x') << "--></mujoco>\n";
  }
  LoadOptions options;
  options.maxFileBytes = 1000;  // the model fits, its include does not
  Model model;
  Diagnostics diags;
  EXPECT_FALSE(loadMjcf(path, options, model, diags));
  ASSERT_EQ(diags.size(), 1u) << dump(diags);
  EXPECT_EQ(diags[0].code, code::kBadFile);
  EXPECT_EQ(diags[0].file, path);
  EXPECT_EQ(diags[0].line, 3u);
  EXPECT_NE(diags[0].message.find("over the cap of 1000"), std::string::npos) << diags[0].message;
  fs::remove_all(dir);
}

TEST(Mjcf, MissingDirectoryAndOversizeFilesAreRefusedBeforeMuJoCo) {
  Model model;
  Diagnostics diags;
  EXPECT_FALSE(loadMjcf(kFixtures + "no_such_model.xml", LoadOptions{}, model, diags));
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].code, code::kMissingFile);
  EXPECT_NE(diags[0].message.find("does not exist"), std::string::npos) << diags[0].message;

  diags.clear();
  EXPECT_FALSE(loadMjcf(kFixtures, LoadOptions{}, model, diags));
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].code, code::kMissingFile);

  diags.clear();
  LoadOptions small;
  small.maxFileBytes = 100;
  EXPECT_FALSE(loadMjcf(kFixtures + "joints.xml", small, model, diags));
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].code, code::kBadFile);
  EXPECT_NE(diags[0].message.find("over the cap"), std::string::npos) << diags[0].message;
}

TEST(Mjcf, MissingMeshesFollowTheUrdfRule) {
  // A mesh only drawn (contype = conaffinity = 0) that is not there: a
  // warning at its <mesh>, the geom left out, the robot loads.  A colliding
  // one: RS5001 there, a warning with --allow-missing-assets.
  fs::path dir = fs::temp_directory_path() / ("rscene_mjcf_missing_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "model.xml").string();
  auto write = [&](const char* contype) {
    std::ofstream f(path);
    f << "<mujoco>\n  <asset>\n    <mesh name=\"gone\" file=\"gone.stl\"/>\n  </asset>\n"
         "  <worldbody><body name=\"b\"><freejoint/><geom name=\"hull\" type=\"box\" size=\"0.1 0.1 0.1\"/>\n"
         "    <geom name=\"look\" type=\"mesh\" mesh=\"gone\" contype=\""
      << contype << "\" conaffinity=\"0\"/></body></worldbody>\n</mujoco>\n";
  };
  write("0");
  Model model;
  Diagnostics diags;
  ASSERT_TRUE(loadMjcf(path, LoadOptions{}, model, diags)) << dump(diags);
  ASSERT_FALSE(diags.empty());
  EXPECT_EQ(diags[0].code, std::string(code::kSkipped)) << dump(diags);
  EXPECT_EQ(diags[0].severity, Severity::Warning);
  EXPECT_EQ(diags[0].line, 3u);
  EXPECT_NE(diags[0].message.find("visual mesh"), std::string::npos) << diags[0].message;
  EXPECT_FALSE(hasErrors(diags)) << dump(diags);
  ASSERT_EQ(model.links.size(), 1u);
  ASSERT_EQ(model.links[0].visuals.size(), 1u);  // the box stays, the mesh is left out
  EXPECT_EQ(model.links[0].visuals[0].name, "hull");

  write("1");
  diags.clear();
  EXPECT_FALSE(loadMjcf(path, LoadOptions{}, model, diags));
  ASSERT_EQ(diags.size(), 1u) << dump(diags);
  EXPECT_EQ(diags[0].code, std::string(code::kMissingFile));
  EXPECT_EQ(diags[0].line, 3u);
  LoadOptions allow;
  allow.allowMissingMeshes = true;
  diags.clear();
  ASSERT_TRUE(loadMjcf(path, allow, model, diags)) << dump(diags);
  EXPECT_EQ(diags[0].code, std::string(code::kMissingFile));
  EXPECT_EQ(diags[0].severity, Severity::Warning);
  ASSERT_EQ(model.links[0].collisions.size(), 1u);  // only the box collides
  fs::remove_all(dir);
}

TEST(Mjcf, AllocationsPastTheCapsAreRefusedWhereTheyAreWrittenBeforeMuJoCo) {
  // 400 bytes asking MuJoCo for 9.4 GB (nuser_body), a dense njmax x njmax
  // matrix, a 20000 x 20000 height field, a 10000-wide skybox, and a PNG
  // whose header says 100000 x 100000: each refused at its line, quickly.
  fs::path dir = fs::temp_directory_path() / ("rscene_mjcf_caps_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "model.xml").string();
  {
    std::ofstream png(dir / "big.png", std::ios::binary);
    const unsigned char header[24] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                      0, 1, 0x86, 0xa0, 0, 1, 0x86, 0xa0};
    png.write(reinterpret_cast<const char*>(header), sizeof header);
    std::ofstream f(path);
    f << "<mujoco>\n"
         "  <size nuser_body=\"400000000\" nkey=\"5\" njmax=\"8000\"/>\n"
         "  <asset>\n"
         "    <hfield name=\"h\" nrow=\"20000\" ncol=\"20000\" size=\"1 1 1 1\"/>\n"
         "    <texture name=\"sky\" builtin=\"checker\" type=\"skybox\" width=\"10000\"/>\n"
         "    <texture name=\"t\" type=\"2d\" file=\"big.png\"/>\n"
         "    <texture name=\"small\" builtin=\"checker\" width=\"512\" height=\"512\"/>\n"
         "  </asset>\n"
         "  <worldbody><body><freejoint/><geom type=\"box\" size=\"0.1 0.1 0.1\"/></body></worldbody>\n"
         "</mujoco>\n";
  }
  Model model;
  Diagnostics diags;
  auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(loadMjcf(path, LoadOptions{}, model, diags));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  ASSERT_EQ(diags.size(), 5u) << dump(diags);
  const unsigned lines[5] = {2, 2, 4, 5, 6};
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(diags[i].code, std::string(code::kMjcfOverCap)) << dump(diags);
    EXPECT_EQ(diags[i].file, path);
    EXPECT_EQ(diags[i].line, lines[i]) << diags[i].message;
  }
  EXPECT_NE(diags[0].message.find("nuser_body=\"400000000\"> is over the cap of 1000"), std::string::npos)
      << diags[0].message;
  EXPECT_NE(diags[1].message.find("njmax"), std::string::npos) << diags[1].message;
  EXPECT_NE(diags[4].message.find("100000 x 100000"), std::string::npos) << diags[4].message;

  // At the caps, the same model compiles.
  {
    std::ofstream f(path);
    f << "<mujoco>\n  <size nuser_body=\"1000\" nkey=\"1000\" njmax=\"1000\"/>\n"
         "  <worldbody><body><freejoint/><geom type=\"box\" size=\"0.1 0.1 0.1\"/></body></worldbody>\n</mujoco>\n";
  }
  diags.clear();
  EXPECT_TRUE(loadMjcf(path, LoadOptions{}, model, diags)) << dump(diags);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rscene::robot
