// The physics of a scene in Bullet (double precision).  Built from the typed
// scene view; Bullet stays behind this interface (pimpl), so users of
// lib/sim need neither Bullet's headers nor BT_USE_DOUBLE_PRECISION.
//
// Mapping (the man page rscene-sim(1) has the full table):
//   time_step        fixed step, one Bullet step per World::step()
//   gravity          btDynamicsWorld::setGravity
//   solver           iterations, tolerance, erp, erp2, restitution threshold,
//                    default friction/restitution/rolling/spinning, sleeping
//                    thresholds and quiet steps, swept CCD, broadphase
//   object           ground/half_space = static plane at position.z; box,
//                    sphere, cylinder, capsule; mesh = convex hull (dynamic,
//                    kinematic) or triangle mesh (static), read through
//                    lib/asset's cache (one import and one shape per file)
//   group/mask       full 64-bit test in an overlap filter: a pair collides
//                    when (groupA & maskB) != 0 and (groupB & maskA) != 0;
//                    pairs of static or kinematic bodies never do (as in
//                    Bullet's own filter), whatever their groups
//   contact_material per-pair friction/restitution/rolling/spinning,
//                    combined by name when a contact point is created
//   compound         one btCompoundShape body about its centre of mass
//   terrain_region   static btHeightfieldTerrainShape, group bit 63
//   wire             stiff/custom: one-sided length limit (a rope);
//                    compliant: spring-damper beyond its length; an end on
//                    an articulated system is on its body localIndexA/B
//   articulated      one Featherstone btMultiBody per record
//                    (robot_sim.hpp, robot_layout.hpp), in the same world
//   deformable,      particle systems of our own beside Bullet, stepped
//   granular         first each step; their particles meet Bullet's bodies
//                    through BulletSurfaces (particle_systems.hpp)
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <map>
#include <utility>

#include "core/codes.hpp"
#include "asset/cache.hpp"
#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "robot/instance.hpp"
#include "robot/trajectory_format.hpp"
#include "scene/start_pose.hpp"
#include "scene/scene.hpp"
#include "sim/particle_systems.hpp"

class btCollisionObject;
class btCollisionWorld;
namespace rscene::sim { class BulletSurfaces; }

namespace rscene::sim {

// Codes of the simulator's own findings (the scene view's are scene_code).
namespace sim_code {
inline constexpr const char* kLeftWorld = rs::RS7012;  // a dynamic body left the world (warning)
inline constexpr const char* kRobotTooLarge = robot::code::kTooLarge;  // more than robot::kMaxRobotBodies bodies
inline constexpr const char* kWireLocalIndex = rs::RS7046;  // a wire's localIndex is not a body of its articulated system (validate's code)
inline constexpr const char* kNotConvexified = rs::RS7051;  // convexifyCollisionMeshes=false: hulls all the same (warning)
}  // namespace sim_code

// The states a trajectory line carries (robot/trajectory_format.hpp).
using robot::BodyState;
using robot::RobotState;

// rscene-sim --pd-gains: every movable joint of every articulated system
// is driven toward its initial position with torque -kp e - kd e' (made
// implicit per joint: robot_sim.hpp), gains by joint name where given.
struct PdGains {
  bool enabled = false;
  double kp = 0, kd = 0;
  std::map<std::string, std::pair<double, double>> joints;  // name -> kp, kd
};

// Reads --pd-gains values: "KP,KD" for every joint, "JOINT=KP,KD" for one
// (the last of each wins); gains finite and >= 0.  False with `error`.
bool parsePdGains(const std::vector<std::string>& specs, PdGains& out, std::string& error);
// Joint names of `pd` that no robot has as a movable joint.
std::vector<std::string> unknownPdJoints(const PdGains& pd, const std::vector<robot::RobotInstance>& robots);

// The instance of every articulated record (Scene::articulated order),
// loaded through one robot::ModelCache: the one reading of each robot's
// state (robot::makeInstance).  A robot left out
// (robot::leaveOutMissingRobots) gets an instance with no model; with
// `allowMissingMeshes` (--allow-missing-assets) a URDF collision mesh that
// is missing is dropped with a warning.  Returns false after an error.
// `models`: a cache kept across scenes (a batch); null: one for this call.
bool makeRobots(const Document& doc, const Scene& scene, std::vector<robot::RobotInstance>& robots,
                Diagnostics& diagnostics, bool allowMissingMeshes = false, robot::ModelCache* models = nullptr);

// Checks what Bullet cannot simulate sensibly: checkScene() of
// scene/check.hpp (what rscene-validate reports too) with collision mesh
// files required and each deformable judged with its mesh, read through
// `files`.  Returns false when it added an error.
bool checkPhysics(const Document& doc, const Scene& scene, Diagnostics& diagnostics,
                  const FileSystem& files = diskFileSystem(), const MeshReader& readMesh = {});

// Records kept but not simulated, named in one warning (RS7010), or none.
std::optional<Diagnostic> unsupportedWarning(const Scene& scene);

// rscene-sim --allow-missing-assets: every object or compound whose
// collision mesh is missing (RS5001) or unreadable (RS7007) is left out of
// the simulation (made visual-only in `scene`, so its record is written
// back unchanged), with one warning per file naming it and the first
// record (and how many more), and a wire attached to such a body is
// skipped with a warning.  Meshes are read through `assets`, so
// World::create given the same cache reads nothing twice.
// Returns how many bodies were left out.
int skipBodiesWithMissingMeshes(const Document& doc, Scene& scene, asset::AssetCache& assets,
                                Diagnostics& diagnostics);

struct WorldOptions {
  asset::AssetCache* assets = nullptr;  // null: the world reads the disk through a cache of its own
  // A dynamic body more than this far below the lowest static geometry
  // has left the world (it fell off the edge or through the floor).
  double leaveMargin = kLeaveMargin;  // scene/start_pose.hpp (RS7015)
  // Cap on the overlapping body pairs the broadphase keeps (each costs a
  // contact manifold, about 8.5 KB): n dynamic bodies in one spot make n^2/2.
  // Past it no pair is added and pairOverflow() says so.  0: no cap.
  std::uint64_t maxPairs = 0;
  // The scene's document, when there is one: errors then point at the
  // record's field (line:col), as checkScene()'s do.
  const Document* document = nullptr;
  // The articulated systems to simulate (makeRobots); null or empty: none.
  // Instances must outlive the world.
  const std::vector<robot::RobotInstance>* robots = nullptr;
  PdGains pd;
  // --allow-missing-assets: a robot collision mesh that does not read is
  // left out of its link with a warning (RS7007), not an error.
  bool allowMissingAssets = false;
};

// A simulated body whose state is no longer finite (World::nonFinite()).
struct NonFinite {
  int recordIndex = -1;
  std::string path;
  std::uint64_t step = 0;
  double time = 0;
  std::string what;  // "position", "orientation", "linear velocity", "angular velocity",
                     // "generalized coordinate", "generalized velocity",
                     // "particle position or velocity"
  // A robot whose state is finite but diverged: a joint speed at Bullet's
  // cap (kMaxJointSpeed), or its base farther than kMaxLength.  Stiff
  // springs or gains for the time step; nothing it writes would be physics.
  bool diverged = false;
  // A deformable whose kinetic energy ran away (diverged, what "kinetic
  // energy"): the figures (ParticleSystems::deformableRunaway).
  std::string cause;
};

// Most a deformable's totalMass may exceed the mass of a dynamic body
// (object, compound or moving robot link) it may touch (RS7078): the particles' contact
// reactions reach Bullet as forces for the next step, stable up to about this.
inline constexpr double kMaxDeformableMassRatio = 20;

// The joint speed cap set on every robot (btMultiBody::setMaxCoordinateVelocity):
// a joint that reaches it has diverged.
inline constexpr double kMaxJointSpeed = 1e6;
// Most bodies (movable joints + 1) of one robot: robot/instance.hpp's rule.
inline constexpr std::size_t kMaxRobotBodies = robot::kMaxRobotBodies;

// A dynamic body that left the world: below the lowest static geometry
// by WorldOptions::leaveMargin, or outside the solver's broadphase bounds
// when broadphaseUseWorldBounds is set.  It is taken out of the world at
// that step (no longer stepped, no longer keeping atRest() false) and keeps
// the pose it had then.
struct Departure {
  int recordIndex = -1;
  std::string path;
  std::uint64_t step = 0;
  double time = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::string reason;  // "fell below z = -10 (10 m under the lowest static geometry)"
};

// The warning (RS7012) for a departure, at its record's line.
Diagnostic departureWarning(const Document& doc, const Departure& departure);

// A dynamic body that started inside another (or inside the ground) by
// more than kStartOverlap, as the first step's contacts found it.
struct StartOverlap {
  int recordIndex = -1;       // the dynamic body's record (a robot's: its articulated record)
  int otherRecordIndex = -1;  // what it is inside (-1: a robot's link)
  double depth = 0;           // m
  std::string link;           // a robot's link in the ground (RS7057); empty: a body (RS7013)
};
inline constexpr double kStartOverlap = kStartOverlapDepth;  // 1 cm: closer than this is contact, not a mistake
// Penetration the solver is still removing: no body in such a contact may
// sleep, and the world is not at rest, until it is below this.
inline constexpr double kRestPenetration = 0.005;  // m

// A primitive body below a ground or half_space is not among them: the
// scene model says that (scene/start_pose.hpp, checkScene()), for
// validate too.
// A dynamic body more than kRestPenetration inside another body (or a
// robot's link, otherRecordIndex -1) as the last step's contacts found it:
// the solver was still pushing it out when the run ended.
struct DeepContact {
  int recordIndex = -1;       // the dynamic body's record
  int otherRecordIndex = -1;  // what it is inside (-1: a robot's link)
  double depth = 0;           // m
};

// RS7002 for a run that ended with `contacts` (World::deepContacts(), not
// empty): at the deepest body's record, naming the first three;
// `untilRest`: the run asked to stop at rest and its duration ran out.
Diagnostic notAtRestWarning(const Document& doc, const std::vector<DeepContact>& contacts, double time,
                            bool untilRest);

// The warning for a start overlap: RS7013 at the body record's position;
// RS7057 for a robot's link in the ground, at the robot record's
// generalizedCoordinate (or position when it writes none).
Diagnostic startOverlapWarning(const Document& doc, const StartOverlap& overlap);
// RS7057, an error: robot `overlap.recordIndex` starts with link
// `overlap.link` in the ground (World::create refuses it before any step).
Diagnostic robotInGround(const Document& doc, const StartOverlap& overlap);

class World {
 public:
  // Builds the Bullet world; mesh files are read here (RS5001/RS7007 on
  // failure).  Returns nullptr after adding an error diagnostic.
  static std::unique_ptr<World> create(const Scene& scene, Diagnostics& diagnostics,
                                       const WorldOptions& options = {});
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  void step();                      // one fixed time step
  double time() const;              // simulated seconds since create()
  std::uint64_t steps() const;
  double timeStep() const;
  bool atRest() const;              // every dynamic body still in the world sleeps
  int bodyCount() const;            // simulated dynamic and kinematic bodies
  int contactCount() const;         // contact points after the last step
  std::vector<BodyState> states() const;  // in record order
  std::vector<RobotState> robotStates() const;  // in Scene::articulated order
  int robotCount() const;
  // Particles of every deformable and granular record now (valid until the next step).
  std::vector<ParticleState> particleStates() const;
  const ParticleSystems& particleSystems() const;  // counts and time spent (rscene-sim --report)
  const std::vector<Departure>& departures() const;  // in the order they happened
  const std::vector<StartOverlap>& startOverlaps() const;  // found by the first step
  // Each pair of bodies, one of them dynamic (not a robot's), in a contact
  // deeper than kRestPenetration after the last step, at its deepest,
  // deepest first (ties in record order); empty before the first step.
  // What keeps atRest() false while the solver pushes bodies apart.
  std::vector<DeepContact> deepContacts() const;
  // The first body in record order whose pose or velocity is not finite
  // (NaN or infinite), or nullopt.  O(bodies); cheap next to a step.
  std::optional<NonFinite> nonFinite() const;
  // Once the broadphase met more pairs than WorldOptions::maxPairs (the
  // world is then missing contacts and should not be trusted): the record
  // of a dynamic body in the first pair refused; nullopt before.
  std::optional<int> pairOverflow() const;
  // A particle system that stopped itself (ParticleSystems::failure()), and
  // one whose state now would not load again (unwritable()).
  std::optional<ParticleFailure> particleFailure() const;
  std::optional<ParticleFailure> particlesUnwritable() const;

  // Initial conditions the format has no key for (tests, programs that
  // embed lib/sim): sets the velocity of the dynamic body named by path or
  // id, in the world frame, and wakes it.  Returns false (and changes
  // nothing) when no dynamic body has that name or a value is not finite.
  bool setLinearVelocity(const std::string& pathOrId, const Eigen::Vector3d& velocity);
  bool setAngularVelocity(const std::string& pathOrId, const Eigen::Vector3d& velocity);

  // Robot control for programs that embed lib/sim (the Python module's RL
  // loop), as RaiSim's ArticulatedSystem has it.  `robot` is an index into
  // the simulated robots (robotIndex()); q and u are in RaiSim's layout
  // (robot::Coordinates).  Each setter returns "" or why it changed nothing
  // (a size, a value that is not finite, a negative gain, a zero
  // quaternion); what it sets acts from the next step on and is kept until
  // changed.  setRobotPd: PD gains per entry of u (a floating base's six
  // are ignored), a position target in q's layout and a velocity target in
  // u's (empty: zero), through the joints' implicit drive (robot_sim.hpp),
  // in place of --pd-gains.  setRobotGeneralizedForce: a feedforward force
  // in u's layout (a floating base's: a world-frame force at the base
  // frame's origin, then a world-frame torque).  setRobotState: q
  // (quaternions normalised) and u now, as a record's state.
  int robotIndex(const std::string& pathOrId) const;  // -1: no simulated robot of that name
  const robot::RobotInstance& robotInstance(int robot) const;
  // q and u now (before the first step: the record's, as robotStates()).
  void robotState(int robot, Eigen::VectorXd& q, Eigen::VectorXd& u) const;
  std::string setRobotPd(int robot, const Eigen::VectorXd& qTarget, const Eigen::VectorXd& uTarget,
                         const Eigen::VectorXd& kp, const Eigen::VectorXd& kd);
  std::string setRobotGeneralizedForce(int robot, const Eigen::VectorXd& tau);
  std::string setRobotState(int robot, const Eigen::VectorXd& q, const Eigen::VectorXd& u);

  // One contact point after the last step (contacts()): the two bodies
  // (records; a robot's link by its name, else empty; record -1 for what
  // has none), the point on B and B's normal toward A (world frame, as
  // Bullet keeps them), the penetration depth (m, > 0 when overlapping)
  // and the normal impulse the solver applied in the step (N s).
  struct Contact {
    int recordA = -1, recordB = -1;
    std::string linkA, linkB;
    Eigen::Vector3d position = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero();
    double depth = 0, impulse = 0;
  };
  // Rigid contacts (Bullet's manifolds; particles are not among them).
  std::vector<Contact> contacts() const;

  // For sensors (sensor_recorder.hpp).  The world-frame velocity `v` of a
  // point `p` (world coordinates) fixed in a body and the body's angular
  // velocity `w`: an object or compound by path or id (a static one does
  // not move), or the link `link` (Model::links index) of the articulated
  // system named by path or id.  False when no body has that name.
  bool pointVelocity(const std::string& pathOrId, const Eigen::Vector3d& p, Eigen::Vector3d& v,
                     Eigen::Vector3d& w) const;
  bool robotPointVelocity(const std::string& pathOrId, int link, const Eigen::Vector3d& p, Eigen::Vector3d& v,
                          Eigen::Vector3d& w) const;
  // The world pose now of a dynamic or kinematic body's record frame
  // (nullopt for a static body or no such name: it is where the scene puts
  // it), and of a robot's link (nullopt: no such robot).
  std::optional<Pose> bodyPose(const std::string& pathOrId) const;
  std::optional<Pose> robotLinkPose(const std::string& pathOrId, int link) const;
  // For ray casts (lidar_geometry.hpp; Bullet's types, so lib/sim only):
  // the collision world, every collision object a ray can meet (those that
  // collide with something: not collidable=false, not a robot body without
  // shapes, not a body that left the world), and the collision object of a
  // body named as above (nullptr when none).
  const btCollisionWorld& collisionWorld() const;
  std::vector<const btCollisionObject*> rayTargets() const;
  const btCollisionObject* collisionObject(const std::string& pathOrId) const;
  const btCollisionObject* robotCollisionObject(const std::string& pathOrId, int link) const;
  // The rigid world as the particle systems see it (with the scene's
  // collision filter and contact materials); nullptr when the scene has no
  // deformable or granular record.  For tests of the queries.
  BulletSurfaces* particleSurfaces();

  // Writes the current poses of dynamic and kinematic bodies into `doc`
  // (positional position and orientation tokens, shortest round-trip),
  // relative to their parent frame when they inherit one; and each
  // articulated system's generalizedCoordinate and generalizedVelocity
  // (a floating base's pose also into its positional tokens).
  void writeBack(Document& doc) const;

  struct Impl;

 private:
  static void writeRobot(Document& doc, const RobotState& state);
  explicit World(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace rscene::sim
