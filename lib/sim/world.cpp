// Bullet world construction and stepping.  Compiled with
// BT_USE_DOUBLE_PRECISION (bullet-float64.pc) against Debian's *-float64
// libraries.
#include "sim/world.hpp"

#include "scene/limits.hpp"

#include <LinearMath/btConvexHullComputer.h>
#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <unordered_map>
#include <unordered_set>

#include "core/text.hpp"
#include "scene/mass_properties.hpp"
#include "scene/reader.hpp"
#include "scene/start_pose.hpp"
#include "sim/bt_eigen.hpp"
#include "sim/bullet_surfaces.hpp"
#include "sim/convex_plane.hpp"
#include "sim/multibody_world.hpp"
#include "sim/particle_systems.hpp"
#include "sim/robot_sim.hpp"
#include "sim/row_space_solver.hpp"
#include "sim/separated_pairs.hpp"
#include "sim/wire.hpp"

namespace rscene::sim {
namespace {

constexpr std::uint64_t kTerrainGroup = std::uint64_t{1} << 63;
constexpr std::uint64_t kAll = ~std::uint64_t{0};

// Per collision object: its 64-bit filter and its contact-material name.
struct BodyInfo {
  std::uint64_t group = 1, mask = kAll;
  int material = -1;  // index into World::Impl::materialNames, -1 = default
  int recordIndex = -1;  // its record, to point at in messages
  int robot = -1, body = -1;  // a robot's collider: index into World::Impl::robots, its body
};

// Which bodies of one robot may touch each other (robots' self-collision).
struct SelfPairs {
  int bodies = 0;
  std::vector<char> allowed;  // bodies x bodies
  bool operator()(int a, int b) const { return allowed[static_cast<std::size_t>(a * bodies + b)] != 0; }
};

// 64-bit group/mask test.  Bullet's own broadphase filter is 32-bit.
// Replacing it must keep what it does first: a pair of static or kinematic
// bodies never collides.  Letting those through makes n co-located static
// boxes n^2/2 pairs in the pair cache (12,000 of them: gigabytes).
struct Filter : btOverlapFilterCallback {
  const std::vector<BodyInfo>* info = nullptr;
  btOverlappingPairCache* cache = nullptr;
  const std::vector<SelfPairs>* self = nullptr;
  std::uint64_t maxPairs = 0;  // 0: no cap
  mutable int overflowRecord = -1;  // set once the cap refused a pair: a dynamic body of that pair
  mutable bool overflowed = false;
  bool needBroadphaseCollision(btBroadphaseProxy* a, btBroadphaseProxy* b) const override {
    auto* oa = static_cast<btCollisionObject*>(a->m_clientObject);
    auto* ob = static_cast<btCollisionObject*>(b->m_clientObject);
    if (oa->isStaticOrKinematicObject() && ob->isStaticOrKinematicObject()) return false;
    if (!groupsMeet(oa, ob)) return false;
    // At the cap a pair already kept stays; a new one is refused and noted.
    if (maxPairs && static_cast<std::uint64_t>(cache->getNumOverlappingPairs()) >= maxPairs &&
        !cache->findPair(a, b)) {
      if (!overflowed) overflowRecord = info0(oa->isStaticOrKinematicObject() ? ob : oa).recordIndex;
      overflowed = true;
      return false;
    }
    return true;
  }
  const BodyInfo& info0(const btCollisionObject* o) const { return (*info)[static_cast<std::size_t>(o->getUserIndex())]; }
  bool groupsMeet(const btCollisionObject* oa, const btCollisionObject* ob) const {
    const BodyInfo& x = (*info)[static_cast<std::size_t>(oa->getUserIndex())];
    const BodyInfo& y = (*info)[static_cast<std::size_t>(ob->getUserIndex())];
    if (x.robot >= 0 && x.robot == y.robot)  // a robot's own bodies: collidable, and as SelfPairs says
      return x.group != 0 && y.group != 0 && (*self)[static_cast<std::size_t>(x.robot)](x.body, y.body);
    return (x.group & y.mask) != 0 && (y.group & x.mask) != 0;
  }
};

// Per-pair contact properties, looked up when Bullet creates a contact
// point.  Bullet's combine hooks are global function pointers, so the
// table of the world being stepped is published per thread.
struct PairTable {
  double friction = 0.8, restitution = 0, rolling = 0, spinning = 0;
  std::map<std::pair<int, int>, ContactMaterial> pairs;
  const ContactMaterial* find(const btCollisionObject* a, const btCollisionObject* b) const {
    int x = a->getUserIndex2(), y = b->getUserIndex2();
    if (x < 0 || y < 0 || pairs.empty()) return nullptr;
    auto it = pairs.find({std::min(x, y), std::max(x, y)});
    return it == pairs.end() ? nullptr : &it->second;
  }
};
thread_local const PairTable* tPairs = nullptr;

btScalar combinedFriction(const btCollisionObject* a, const btCollisionObject* b) {
  const ContactMaterial* c = tPairs ? tPairs->find(a, b) : nullptr;
  return c ? c->friction : tPairs ? tPairs->friction : 0.8;
}
btScalar combinedRestitution(const btCollisionObject* a, const btCollisionObject* b) {
  const ContactMaterial* c = tPairs ? tPairs->find(a, b) : nullptr;
  return c ? c->restitution : tPairs ? tPairs->restitution : 0;
}
btScalar combinedRolling(const btCollisionObject* a, const btCollisionObject* b) {
  const ContactMaterial* c = tPairs ? tPairs->find(a, b) : nullptr;
  return c ? c->rollingFriction : tPairs ? tPairs->rolling : 0;
}
btScalar combinedSpinning(const btCollisionObject* a, const btCollisionObject* b) {
  const ContactMaterial* c = tPairs ? tPairs->find(a, b) : nullptr;
  return c ? c->spinningFriction : tPairs ? tPairs->spinning : 0;
}

// The volume of a mesh child's convex hull (what Bullet simulates for it):
// the hull's faces fanned into tetrahedra about its first vertex.
double hullVolume(const btCollisionShape* s) {
  const auto* hull = dynamic_cast<const btConvexHullShape*>(s);
  if (!hull || hull->getNumPoints() < 4) return 0;
  btConvexHullComputer computer;
  const btVector3* points = hull->getUnscaledPoints();
  std::vector<btVector3> scaled(points, points + hull->getNumPoints());
  for (btVector3& p : scaled) p *= hull->getLocalScaling();
  if (computer.compute(&scaled[0].x(), sizeof(btVector3), hull->getNumPoints(), 0, 0) < 0) return 0;
  if (computer.vertices.size() < 4) return 0;
  const btVector3 apex = computer.vertices[0];
  double volume = 0;
  for (int f = 0; f < computer.faces.size(); ++f) {
    const btConvexHullComputer::Edge* first = &computer.edges[computer.faces[f]];
    btVector3 a = computer.vertices[first->getSourceVertex()];
    const btConvexHullComputer::Edge* e = first->getNextEdgeOfFace();
    btVector3 b = computer.vertices[e->getSourceVertex()];
    for (e = e->getNextEdgeOfFace(); e != first; e = e->getNextEdgeOfFace()) {
      btVector3 c = computer.vertices[e->getSourceVertex()];
      volume += static_cast<double>((a - apex).dot((b - apex).cross(c - apex))) / 6.0;
      b = c;
    }
  }
  return std::fabs(volume);
}

bool hasMeshCollision(const robot::Model& model) {
  for (const robot::Link& l : model.links)
    for (const robot::Collision& c : l.collisions)
      if (c.geometry.kind == robot::GeometryKind::Mesh) return true;
  return false;
}

// RS7051: Bullet collides no triangle mesh on a moving body.
void warnNotConvexified(const Document* doc, const Articulated& a, Diagnostics& diagnostics) {
  std::string message = "articulated system '" + a.path +
                        "': convexifyCollisionMeshes=false, but its mesh collisions are simulated as convex hulls "
                        "(Bullet collides no triangle mesh on a moving body)";
  robot::FieldSource at = doc ? robot::writtenBy(*doc, a, "convexifyCollisionMeshes") : robot::FieldSource{};
  reportAt(doc, at.record, at.field ? at.field : "", sim_code::kNotConvexified, message, diagnostics,
           Severity::Warning);
}

// --allow-missing-assets: a robot collision mesh that does not read, left
// out of its link.
void warnMeshLeftOut(const Document* doc, const Articulated& a, const std::string& why, Diagnostics& diagnostics) {
  std::string message = "articulated system '" + a.path + "': " + why + "; that collision is left out";
  // Where the error is without --allow-missing-assets (World::create's fail).
  reportAt(doc, a.recordIndex, "resource", scene_code::kBadMesh, message, diagnostics, Severity::Warning);
}

}  // namespace

struct Simulated {
  int recordIndex = -1;
  std::string path;
  btRigidBody* body = nullptr;
  bool dynamic = true;
  Pose parentFrame;                             // world pose of the frame the record is written in
  btTransform toRecord = btTransform::getIdentity();  // body frame -> record frame (compound COM shift)
  int positionToken = 2;
  bool departed = false;
  // Steps in a row its speeds stayed below the solver's sleeping
  // thresholds (World::atRest(): a body Bullet keeps awake on a still
  // kinematic one).
  int quietSteps = 0;
};

// Bullet's contact-manifold and collision-algorithm pools are allocated
// and touched whole when the world is made: 4096 manifolds of 8.5 KB
// each by default, 35 MB of page faults, a tenth of the CPU time of a
// 10 s run of one robot.  Sized here to the scene (a manifold per pair of
// shapes that touch: four per body or compound child, as in a pile; one
// per robot collision shape, which a robot standing does not reach: ten
// of ANYmal's 45 touch something); past it Bullet takes further ones from
// the heap, which changes nothing but where they live.
static btDefaultCollisionConstructionInfo collisionPools(const Scene& scene, const WorldOptions& options) {
  std::size_t pairs = 4 * (scene.objects.size() + scene.terrains.size());
  for (const Compound& c : scene.compounds) pairs += 4 * c.children.size();
  if (options.robots)
    for (const robot::RobotInstance& r : *options.robots)
      if (r.model)
        for (const robot::Link& l : r.model->links) pairs += l.collisions.size();
  btDefaultCollisionConstructionInfo info;
  const std::size_t kMax = static_cast<std::size_t>(info.m_defaultMaxPersistentManifoldPoolSize);  // Bullet's default
  int pool = static_cast<int>(std::min(kMax, 64 + pairs));
  info.m_defaultMaxPersistentManifoldPoolSize = pool;
  info.m_defaultMaxCollisionAlgorithmPoolSize = pool;
  return info;
}

struct World::Impl {
  // A deformable far heavier than a dynamic body it may touch is refused
  // (RS7078): its contact reactions reach Bullet as forces for the next
  // step, an explicit coupling that holds up to about 20:1 (a 1 kg box
  // under a 40 kg cloth starts to jump; under 1e6 kg it was thrown 716 km).
  // The bodies: dynamic objects and compounds, and the moving links of
  // robots (each link's own mass: what a contact force on it accelerates
  // at the least, its joints free) that have a collision shape; each only
  // when the collision groups let it meet the deformable.
  bool deformableMassRatios(const Scene& scene, const Document* doc, Diagnostics& ds) const {
    struct Touchable {
      double mass;
      const btCollisionObject* object;
      std::string name;  // "dynamic body '/World/Box'", "link 'foot' of articulated system '/World/Robot'"
    };
    std::vector<Touchable> bodies;
    for (const Simulated& s : simulated)
      if (s.dynamic && s.body->getInvMass() > 0)
        bodies.push_back({1 / s.body->getInvMass(), s.body, "dynamic body '" + s.path + "'"});
    for (const std::unique_ptr<SimRobot>& r : robots) {
      btMultiBody* mb = r->multiBody();
      const robot::RobotInstance& instance = r->instance();
      const std::vector<RobotBody>& layout = r->layout().bodies;
      for (std::size_t b = 0; b < r->colliders().size(); ++b) {
        const btMultiBodyLinkCollider* c = r->colliders()[b];
        if (!c || !r->hasShapes(static_cast<int>(b))) continue;
        if (b == 0 && mb->hasFixedBase()) continue;  // fixed where it is
        const double mass = b == 0 ? mb->getBaseMass() : mb->getLinkMass(static_cast<int>(b) - 1);
        if (!(mass > 0)) continue;
        std::string link;
        if (instance.model && !layout[b].links.empty())
          link = instance.model->links[static_cast<std::size_t>(layout[b].links.front())].name;
        bodies.push_back({mass, c,
                          (link.empty() ? "body " + std::to_string(b) : "link '" + link + "'") +
                              " of articulated system '" + instance.record->path + "'"});
      }
    }
    bool ok = true;
    for (const Deformable& d : scene.deformables) {
      if (!d.collidable) continue;
      const Touchable* lightest = nullptr;
      for (const Touchable& t : bodies) {
        const int index = t.object->getUserIndex();
        if (index >= 0 && static_cast<std::size_t>(index) < info.size()) {
          const BodyInfo& b = info[static_cast<std::size_t>(index)];
          if ((b.group & d.collisionMask) == 0 || (d.collisionGroup & b.mask) == 0) continue;  // never meet
        }
        if (!lightest || t.mass < lightest->mass) lightest = &t;
      }
      if (!lightest || !(d.totalMass > kMaxDeformableMassRatio * lightest->mass)) continue;
      reportAt(doc, d.recordIndex, "totalMass", rs::RS7078,
               "deformable '" + d.path + "': totalMass " + roundedNumber(d.totalMass, 6) + " kg is more than " +
                   roundedNumber(kMaxDeformableMassRatio, 6) + " times the mass of " + lightest->name + " (" +
                   roundedNumber(lightest->mass, 6) +
                   " kg) it may touch: its contact reactions would throw the body (they reach it as forces for the "
                   "next step, stable up to about that ratio)",
               ds, Severity::Error, "make the deformable lighter or the body heavier, or keep them apart with collisionGroup/collisionMask");
      ok = false;
    }
    return ok;
  }

  // Names a body by id and path and, when it moves, remembers where its
  // pose is written back (objects and compounds alike).
  template <class Node>
  void registerBody(const Node& n, btRigidBody* body, const btTransform& toRecord = btTransform::getIdentity()) {
    name(byName, n.id, n.path, body);
    byRecord[n.recordIndex] = body;
    if (n.bodyMode != BodyMode::Dynamic && n.bodyMode != BodyMode::Kinematic) return;
    Simulated s;
    s.recordIndex = n.recordIndex;
    s.path = n.path;
    s.body = body;
    s.dynamic = n.bodyMode == BodyMode::Dynamic;
    s.parentFrame = n.world * n.local.inverse();
    s.toRecord = toRecord;
    s.positionToken = n.positionToken;
    simulated.push_back(s);
  }

  explicit Impl(const btDefaultCollisionConstructionInfo& pools) : config(pools) {}
  ConvexPlaneAlgorithm::CreateFunc convexPlane, planeConvex;  // the dispatcher's, for convex against plane
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  std::unique_ptr<btBroadphaseInterface> broadphase;
  RowSpaceSolver solver;  // Bullet's multibody solver, iterating on its rows' velocities (row_space_solver.hpp)
  std::unique_ptr<MultiBodyWorld> world;
  Filter filter;
  PairTable pairs;
  std::vector<BodyInfo> info;
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btStridingMeshInterface>> meshData;
  std::unique_ptr<asset::AssetCache> ownAssets;
  asset::AssetCache* assets = nullptr;
  std::vector<std::shared_ptr<const asset::Mesh>> meshes;  // triangle shapes point into them
  std::map<std::string, btCollisionShape*> meshShapes;     // one shape per file, scale and kind
  double floorZ = std::numeric_limits<double>::infinity();  // lowest static geometry
  double leaveMargin = kLeaveMargin;
  bool bounded = false;
  btVector3 boundsMin, boundsMax;
  std::vector<Departure> departures;
  std::vector<StartOverlap> startOverlaps;
  std::set<int> groundPlanes, groundRuleBodies;  // records: scene/start_pose.hpp's planes and bodies
  std::set<int> pairRuleBodies;                  // records: scene/start_pose.hpp's pair rule
  bool penetrating = false;  // a contact of a dynamic body deeper than kRestPenetration after the last step

  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::vector<std::unique_ptr<btMotionState>> motion;
  std::vector<std::unique_ptr<btTypedConstraint>> constraints;
  std::vector<std::vector<double>> heights;  // terrain data must outlive its shape
  std::vector<Simulated> simulated;
  std::vector<Spring> springs;
  std::vector<std::unique_ptr<SimRobot>> robots;
  std::vector<std::unique_ptr<MultiBodyRope>> robotWires;
  ParticleSystems particles;                 // deformables and granular media
  std::unique_ptr<BulletSurfaces> surfaces;  // what their particles touch (null when there are none)
  std::vector<SelfPairs> selfPairs;  // per robot
  double sleepLinear = 0, sleepAngular = 0;  // the solver's sleeping thresholds (robots' atRest)
  int sleepQuietSteps = 1;                   // and the steps below them before a body sleeps
  std::unordered_map<std::string, btRigidBody*> byName;  // id and path -> body
  // Names a node by the scene model's rule: an id wins over another node's
  // path, whichever was added first.
  std::unordered_set<std::string> ids;
  template <class T>
  void name(std::unordered_map<std::string, T>& by, const std::string& id, const std::string& path, T value) {
    if (!id.empty()) {
      by[id] = value;
      ids.insert(id);
    }
    if (!ids.count(path)) by[path] = value;
  }
  std::unordered_map<int, btRigidBody*> byRecord;       // record index -> body (wire ends: Wire::recordA/B)
  std::unordered_map<std::string, int> robotByName;      // id and path -> index into robots (sensor mounts)
  std::unordered_map<int, int> robotByRecord;           // articulated record index -> index into robots
  std::vector<char> robotStateSet;  // per robot: setRobotState was called (its state is Bullet's, even at step 0)
  std::map<std::string, int> materialIndex;
  double dt = 0.0025;
  std::uint64_t stepCount = 0;
  int contacts = 0;

  ~Impl() {
    if (world) {  // removing what is not (or no longer) in the world is a no-op
      for (auto& c : constraints) world->removeConstraint(c.get());
      for (auto& b : bodies) world->removeRigidBody(b.get());
      for (auto& c : robotWires) world->removeMultiBodyConstraint(c.get());
      for (auto& r : robots) {
        for (auto& c : r->constraints()) world->removeMultiBodyConstraint(c.get());
        r->removeLimits(*world);
        for (btMultiBodyLinkCollider* c : r->colliders())
          if (c) world->removeCollisionObject(c);
        world->removeMultiBody(r->multiBody());
      }
    }
  }

  int materialOf(const std::string& name) {
    auto it = materialIndex.find(name);
    if (it != materialIndex.end()) return it->second;
    int i = static_cast<int>(materialIndex.size());
    materialIndex.emplace(name, i);
    return i;
  }

  void lowerFloorTo(const btRigidBody* body) {
    btVector3 lo, hi;
    body->getAabb(lo, hi);
    floorZ = std::min(floorZ, double(lo.z()));
  }

  // Whether `s` has left the world, and why.
  std::string departure(const Simulated& s) const {
    btVector3 p = s.body->getCenterOfMassPosition();
    char why[160] = "";
    if (std::isfinite(floorZ) && p.z() < floorZ - leaveMargin)  // a world without statics has no floor
      std::snprintf(why, sizeof why, "fell below z = %g (%g m under the lowest static geometry)", floorZ - leaveMargin,
                    leaveMargin);
    else if (bounded && (p.x() < boundsMin.x() || p.y() < boundsMin.y() || p.z() < boundsMin.z() ||
                         p.x() > boundsMax.x() || p.y() > boundsMax.y() || p.z() > boundsMax.z()))
      std::snprintf(why, sizeof why, "left the broadphase bounds");
    else if (double far = std::max({std::abs(p.x()), std::abs(p.y()), std::abs(p.z())});
             std::isfinite(far) && far > kMaxLength)  // not finite: nonFinite()'s RS7024
      // Beyond what the scene may hold (scene/limits.hpp), and where double
      // precision no longer resolves a contact; also the only way out of a
      // world with no static geometry.
      std::snprintf(why, sizeof why, "went more than %g m from the origin", kMaxLength);
    return why;
  }

  // Whether every awake dynamic body is awake only because Bullet keeps a
  // body touching a kinematic one awake (a kinematic body never sleeps
  // here, DISABLE_DEACTIVATION, and wakes what it touches each step): it
  // can sleep (sleeping enabled), it has stayed below the sleeping
  // thresholds for sleepingQuietSteps steps, and the bodies it rests on,
  // through contacts between dynamic bodies, include a kinematic one and
  // no kinematic one that moves.  Such a body rests relative to a still
  // body, so --until-rest may stop.
  bool awakeOnlyOnStillKinematics() const {
    std::unordered_map<const btCollisionObject*, std::size_t> index;  // dynamic body -> simulated
    for (std::size_t i = 0; i < simulated.size(); ++i)
      if (simulated[i].dynamic && !simulated[i].departed) index[simulated[i].body] = i;
    std::vector<std::size_t> parent(simulated.size());
    for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = i;
    auto root = [&](std::size_t i) {
      while (parent[i] != i) i = parent[i] = parent[parent[i]];
      return i;
    };
    std::vector<char> held(simulated.size(), 0), moved(simulated.size(), 0);  // per body, then per root
    std::vector<std::pair<std::size_t, bool>> kinematicTouches;               // body, the kinematic one moves
    for (int i = 0, m = dispatcher.getNumManifolds(); i < m; ++i) {
      const btPersistentManifold* manifold = const_cast<btCollisionDispatcher&>(dispatcher).getManifoldByIndexInternal(i);
      if (manifold->getNumContacts() == 0) continue;
      const btCollisionObject* a = manifold->getBody0();
      const btCollisionObject* b = manifold->getBody1();
      auto ia = index.find(a), ib = index.find(b);
      if (ia != index.end() && ib != index.end()) {
        parent[root(ia->second)] = root(ib->second);
        continue;
      }
      for (auto [dyn, other] : {std::pair{ia, b}, std::pair{ib, a}}) {
        if (dyn == index.end() || !other->isKinematicObject()) continue;
        const btRigidBody* k = btRigidBody::upcast(other);
        const bool moves = !k || !k->getLinearVelocity().fuzzyZero() || !k->getAngularVelocity().fuzzyZero();
        kinematicTouches.push_back({dyn->second, moves});
      }
    }
    for (auto [body, moves] : kinematicTouches) {
      held[root(body)] = 1;
      if (moves) moved[root(body)] = 1;
    }
    for (std::size_t i = 0; i < simulated.size(); ++i) {
      const Simulated& s = simulated[i];
      if (!s.dynamic || s.departed || !s.body->isActive()) continue;
      if (s.body->getActivationState() == DISABLE_DEACTIVATION) return false;  // sleeping disabled: never rests
      if (s.quietSteps < sleepQuietSteps) return false;
      const std::size_t r = root(i);
      if (!held[r] || moved[r]) return false;
    }
    return true;
  }

  // RS7015 for each dynamic body that starts where departure() would take
  // it out at the first step (below the floor, outside the broadphase
  // bounds): refused before any step, not reported as having left.  Under
  // a ground or half_space the scene model said it already (checkScene(),
  // scene/start_pose.hpp); this is the rest: lower static geometry,
  // terrain, the bounds.
  bool startsInWorld(const Document* doc, Diagnostics& diagnostics) const {
    bool ok = true;
    for (const Simulated& s : simulated) {
      if (!s.dynamic) continue;
      const btVector3 p = s.body->getCenterOfMassPosition();
      char why[200] = "";
      if (std::isfinite(floorZ) && p.z() < floorZ - leaveMargin)
        std::snprintf(why, sizeof why,
                      "starts at z = %g, below the world's lower bound z = %g (%g m under the lowest static geometry)",
                      double(p.z()), floorZ - leaveMargin, leaveMargin);
      else if (bounded && (p.x() < boundsMin.x() || p.y() < boundsMin.y() || p.z() < boundsMin.z() ||
                           p.x() > boundsMax.x() || p.y() > boundsMax.y() || p.z() > boundsMax.z()))
        std::snprintf(why, sizeof why, "starts at (%g, %g, %g), outside the solver's broadphase bounds", double(p.x()),
                      double(p.y()), double(p.z()));
      if (!*why) continue;
      reportAt(doc, s.recordIndex, "position", rs::RS7015,
               "dynamic body '" + s.path + "' " + why + ": rscene-sim would take it out of the world at its first step",
               diagnostics, Severity::Error, "place it inside the world, above the ground");
      ok = false;
    }
    return ok;
  }

  // Takes `s` out of the world where it is now: no more steps, contacts,
  // wires or springs; its pose stays what it was.
  // One entry per dynamic body of a pair (a body inside another dynamic
  // one is named once, by the first of the pair).
  // A robot whose link starts inside the ground is refused (RS7057), before
  // any step: Bullet's multibody solver, unlike the rigid bodies' split
  // impulses, pushes such a link out with speed, and a hopper started
  // 0.5 m deep left at tens of m/s to 257 m.  contactPairTest asks the
  // narrow phase about one pair without touching the world's contact
  // cache, so the run that follows is the run it would have been.
  bool robotsAboveGround(const Document* doc, Diagnostics& diagnostics) {
    if (!doc || robots.empty() || groundPlanes.empty()) return true;
    std::vector<btCollisionObject*> grounds;
    btCollisionObjectArray& objects = world->getCollisionObjectArray();
    for (int i = 0; i < objects.size(); ++i) {
      const BodyInfo& bi = info[static_cast<std::size_t>(objects[i]->getUserIndex())];
      if (bi.robot < 0 && groundPlanes.count(bi.recordIndex)) grounds.push_back(objects[i]);
    }
    struct Deepest : btCollisionWorld::ContactResultCallback {
      double depth = 0;
      btScalar addSingleResult(btManifoldPoint& cp, const btCollisionObjectWrapper*, int, int, const btCollisionObjectWrapper*,
                               int, int) override {
        depth = std::max(depth, -double(cp.getDistance()));
        return 0;
      }
    };
    bool ok = true;
    for (std::size_t r = 0; r < robots.size(); ++r) {
      StartOverlap worst{-1, -1, 0, {}};
      for (btMultiBodyLinkCollider* c : robots[r]->colliders()) {
        if (c->getCollisionShape()->getShapeType() == EMPTY_SHAPE_PROXYTYPE) continue;
        const BodyInfo& bc = info[static_cast<std::size_t>(c->getUserIndex())];
        for (btCollisionObject* g : grounds) {
          if (!filter.groupsMeet(c, g)) continue;
          Deepest deepest;
          world->contactPairTest(c, g, deepest);
          if (!(deepest.depth > kStartOverlap) || deepest.depth <= worst.depth) continue;
          const RobotBody& body = robots[r]->layout().bodies[static_cast<std::size_t>(bc.body)];
          std::string link = body.links.empty()
                                 ? "?"
                                 : robots[r]->instance().model->links[static_cast<std::size_t>(body.links.front())].name;
          worst = {bc.recordIndex, info[static_cast<std::size_t>(g->getUserIndex())].recordIndex, deepest.depth, link};
        }
      }
      if (worst.recordIndex < 0) continue;
      diagnostics.push_back(robotInGround(*doc, worst));
      ok = false;
    }
    return ok;
  }

  void noteStartOverlap(const btPersistentManifold& m, double depth) {
    const btCollisionObject* a = m.getBody0();
    const btCollisionObject* b = m.getBody1();
    auto record = [&](const btCollisionObject* o) {
      const BodyInfo& bi = info[static_cast<std::size_t>(o->getUserIndex())];
      return bi.robot >= 0 ? -1 : bi.recordIndex;
    };
    // A robot's link in the ground was refused before the first step
    // (robotsAboveGround, RS7057); one that got there in the step is contact.
    for (auto [x, y] : {std::pair{a, b}, std::pair{b, a}}) {
      const BodyInfo& bx = info[static_cast<std::size_t>(x->getUserIndex())];
      const BodyInfo& by = info[static_cast<std::size_t>(y->getUserIndex())];
      if (bx.robot >= 0 && by.robot < 0 && groundPlanes.count(by.recordIndex)) return;
    }
    auto dynamic = [](const btCollisionObject* o) {
      const btRigidBody* rb = btRigidBody::upcast(o);
      return rb && !rb->isStaticOrKinematicObject();
    };
    if (!dynamic(a)) std::swap(a, b);
    if (!dynamic(a) || record(a) < 0) return;
    if (groundRuleBodies.count(record(a)) && groundPlanes.count(record(b))) return;  // the scene model's RS7013
    if (pairRuleBodies.count(record(a)) && pairRuleBodies.count(record(b))) return;  // its pair rule's RS7013
    for (StartOverlap& o : startOverlaps)
      if (o.recordIndex == record(a) && o.otherRecordIndex == record(b)) {
        o.depth = std::max(o.depth, depth);
        return;
      }
    startOverlaps.push_back({record(a), record(b), depth, {}});
  }

  void depart(Simulated& s, std::string reason) {
    btRigidBody* body = s.body;
    for (auto& c : constraints)
      if (&c->getRigidBodyA() == body || &c->getRigidBodyB() == body) world->removeConstraint(c.get());
    springs.erase(std::remove_if(springs.begin(), springs.end(),
                                 [&](const Spring& sp) { return sp.a.rigid == body || sp.b.rigid == body; }),
                  springs.end());
    for (auto& c : robotWires)
      if (c->rigid() == body) world->removeMultiBodyConstraint(c.get());
    world->removeRigidBody(body);
    body->setLinearVelocity(btVector3(0, 0, 0));
    body->setAngularVelocity(btVector3(0, 0, 0));
    body->forceActivationState(DISABLE_SIMULATION);
    s.departed = true;
    Departure d;
    d.recordIndex = s.recordIndex;
    d.path = s.path;
    d.step = stepCount;
    d.time = static_cast<double>(stepCount) * dt;
    d.position = eig(body->getWorldTransform() * s.toRecord * btVector3(0, 0, 0));
    d.reason = std::move(reason);
    departures.push_back(std::move(d));
  }

  btCollisionShape* keep(btCollisionShape* s) {
    shapes.emplace_back(s);
    return s;
  }

  // Shape of a primitive; nullptr (with `error`) when it cannot be made.
  btCollisionShape* primitive(const std::string& prim, const Eigen::Vector3d& box, double radius, double height,
                              const std::string& meshPath, double meshScale, bool convex, std::string& error) {
    if (prim == "box") return keep(new btBoxShape(bt(box / 2)));
    if (prim == "sphere") return keep(new btSphereShape(radius));
    if (prim == "cylinder") return keep(new btCylinderShapeZ(btVector3(radius, radius, height / 2)));
    if (prim == "capsule") return keep(new btCapsuleShapeZ(radius, height));
    if (prim == "mesh") return meshShape(meshPath, meshScale, convex, error);
    error = "unknown primitive '" + prim + "'";
    return nullptr;
  }

  // Ten bodies naming one mesh file at one scale share one shape (one
  // convex hull, one BVH): Bullet shapes may be shared between bodies.
  btCollisionShape* meshShape(const std::string& path, double scale, bool convex, std::string& error) {
    return meshShape(path, Eigen::Vector3d::Constant(scale), convex, error);
  }
  btCollisionShape* meshShape(const std::string& path, const Eigen::Vector3d& scale, bool convex, std::string& error) {
    char key[32];
    std::memcpy(key, scale.data(), 3 * sizeof(double));
    key[3 * sizeof(double)] = convex ? 'h' : 't';
    std::string name = std::string(key, 3 * sizeof(double) + 1) + path;
    if (auto it = meshShapes.find(name); it != meshShapes.end()) return it->second;
    std::string why;
    std::shared_ptr<const asset::Mesh> mesh = assets->mesh(path, asset::MeshContent::Geometry, &why);
    if (!mesh) {
      error = "cannot read mesh '" + path + "': " + why;
      return nullptr;
    }
    const asset::MeshPart& part = mesh->parts.front();  // Geometry: one part of all triangles
    btCollisionShape* shape = nullptr;
    if (convex) {
      std::vector<double> points(part.positions.begin(), part.positions.end());
      for (std::size_t i = 0; i < points.size(); ++i) points[i] *= scale[static_cast<Eigen::Index>(i % 3)];
      auto* hull = new btConvexHullShape(points.data(), static_cast<int>(part.vertexCount()), 3 * sizeof(double));
      hull->optimizeConvexHull();
      hull->setMargin(0.001);
      shape = keep(hull);
    } else {
      // Bullet reads the cached float vertices in place, scaled as it reads.
      btIndexedMesh im;
      im.m_numTriangles = static_cast<int>(part.indices.size() / 3);
      im.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(part.indices.data());
      im.m_triangleIndexStride = 3 * sizeof(std::uint32_t);
      im.m_numVertices = static_cast<int>(part.vertexCount());
      im.m_vertexBase = reinterpret_cast<const unsigned char*>(part.positions.data());
      im.m_vertexStride = 3 * sizeof(float);
      im.m_indexType = PHY_INTEGER;
      im.m_vertexType = PHY_FLOAT;
      auto* array = new btTriangleIndexVertexArray();
      array->addIndexedMesh(im, PHY_INTEGER);
      array->setScaling(bt(scale));
      meshData.emplace_back(array);
      shape = keep(new btBvhTriangleMeshShape(array, true));
    }
    meshes.push_back(std::move(mesh));
    return meshShapes[name] = shape;
  }

  // A robot link's collision shape: primitives sized as the model says
  // (capsule length between the sphere centres), meshes as convex hulls
  // (Bullet collides no triangle mesh on a moving body).
  btCollisionShape* robotShape(const robot::Geometry& g, std::string& error) {
    switch (g.kind) {
      case robot::GeometryKind::Box: return keep(new btBoxShape(bt(Eigen::Vector3d(g.size / 2))));
      case robot::GeometryKind::Sphere: return keep(new btSphereShape(g.radius));
      case robot::GeometryKind::Cylinder: return keep(new btCylinderShapeZ(btVector3(g.radius, g.radius, g.length / 2)));
      case robot::GeometryKind::Capsule: return keep(new btCapsuleShapeZ(g.radius, g.length));
      case robot::GeometryKind::Mesh: {
        btCollisionShape* shape = meshShape(g.meshPath, g.meshScale, true, error);
        if (!shape && allowMissingAssets) {
          // SimRobot::create leaves out a shape with no error.
          robotMeshesLeftOut.push_back(error);
          error.clear();
        }
        return shape;
      }
    }
    error = "unknown geometry";
    return nullptr;
  }

  std::string robotError;  // why addRobot failed
  bool allowMissingAssets = false;
  std::vector<std::string> robotMeshesLeftOut;  // by the robot being added, with allowMissingAssets

  // Builds one articulated system into the world: its multibody, colliders
  // (the record's group and mask; self-collision as selfPairsOf decides),
  // joint limits and friction motors.
  bool addRobot(const robot::RobotInstance& instance, const PdGains& pd, const Solver& sv) {
    if (!instance.model || !instance.record) return true;  // makeRobots reported it
    auto maker = [this](const robot::Geometry& g, std::string& e) { return robotShape(g, e); };
    // Robots never sleep: Bullet's multibody sleep test (a fixed 0.01 bound
    // on the sum of squared speeds for 2 s) stops slow swings mid-way.
    // atRest() asks their bodies' speeds against the solver's thresholds.
    std::unique_ptr<SimRobot> r = SimRobot::create(instance, maker, pd, false, robotError);
    if (!r) return false;
    r->addFriction(dt);
    const Articulated& a = *instance.record;
    int index = static_cast<int>(robots.size());
    btMultiBody* mb = r->multiBody();
    // Before any collider is in the broadphase, which asks the filter.
    selfPairs.push_back(selfPairsOf(*r, a.doNotCollideWithParent));
    for (std::size_t b = 0; b < r->colliders().size(); ++b) {
      btMultiBodyLinkCollider* c = r->colliders()[b];
      if (!c) continue;
      c->setFriction(sv.defaultFriction);
      c->setRestitution(sv.defaultRestitution);
      c->setRollingFriction(sv.defaultRollingFriction);
      c->setSpinningFriction(sv.defaultSpinningFriction);
      c->setContactProcessingThreshold(0);
      bool collides = a.collidable && r->hasShapes(static_cast<int>(b));  // group 0 meets nothing
      BodyInfo bi{collides ? a.collisionGroup : 0, collides ? a.collisionMask : 0, -1, a.recordIndex, index,
                  static_cast<int>(b)};
      c->setUserIndex(static_cast<int>(info.size()));
      c->setUserIndex2(-1);
      info.push_back(bi);
      world->addCollisionObject(c, btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter);
    }
    world->addMultiBody(mb);
    for (auto& c : r->constraints()) world->addMultiBodyConstraint(c.get());
    name(robotByName, a.id, a.path, index);
    robotByRecord[a.recordIndex] = index;
    robots.push_back(std::move(r));
    return true;
  }

  // RaiSim collides a robot's bodies with each other, except a body with
  // its parent under doNotCollideWithParent.  Pairs whose shapes already
  // touch in the initial pose are left out too: a coarse collision model
  // (hulls, cylinders around meshes) often overlaps at the joints of a
  // robot that is fine, and the solver would throw them apart.
  SelfPairs selfPairsOf(const SimRobot& r, bool noParent) {
    const std::vector<RobotBody>& bodies = r.layout().bodies;
    SelfPairs p;
    p.bodies = static_cast<int>(bodies.size());
    p.allowed.assign(bodies.size() * bodies.size(), 1);
    struct Touch : btCollisionWorld::ContactResultCallback {
      bool touching = false;
      btScalar addSingleResult(btManifoldPoint& cp, const btCollisionObjectWrapper*, int, int,
                               const btCollisionObjectWrapper*, int, int) override {
        if (cp.getDistance() <= 0) touching = true;
        return 0;
      }
    };
    for (int a = 0; a < p.bodies; ++a) {
      for (int b = 0; b < p.bodies; ++b) {
        bool adjacent = bodies[static_cast<std::size_t>(a)].parentBody == b || bodies[static_cast<std::size_t>(b)].parentBody == a;
        bool off = a == b || (noParent && adjacent);
        btMultiBodyLinkCollider* ca = r.colliders()[static_cast<std::size_t>(a)];
        btMultiBodyLinkCollider* cb = r.colliders()[static_cast<std::size_t>(b)];
        if (!off && a < b && r.hasShapes(a) && r.hasShapes(b)) {
          Touch t;
          world->contactPairTest(ca, cb, t);
          off = t.touching;
        }
        if (off) p.allowed[static_cast<std::size_t>(a * p.bodies + b)] = 0;
      }
    }
    for (int a = 0; a < p.bodies; ++a)  // symmetric
      for (int b = 0; b < a; ++b)
        p.allowed[static_cast<std::size_t>(a * p.bodies + b)] = p.allowed[static_cast<std::size_t>(b * p.bodies + a)];
    return p;
  }

  btRigidBody* addBody(btCollisionShape* shape, const btTransform& at, BodyMode mode, double mass,
                       const btVector3& inertiaIn, bool useInertia, const BodyInfo& filterInfo,
                       const std::string& contactMaterial, const Solver& sv) {
    bool dynamic = mode == BodyMode::Dynamic;
    btVector3 inertia(0, 0, 0);
    if (dynamic) {
      if (useInertia) inertia = inertiaIn;
      else shape->calculateLocalInertia(mass, inertia);
    }
    auto* ms = new btDefaultMotionState(at);
    motion.emplace_back(ms);
    btRigidBody::btRigidBodyConstructionInfo ci(dynamic ? mass : 0, ms, shape, inertia);
    ci.m_friction = sv.defaultFriction;
    ci.m_restitution = sv.defaultRestitution;
    ci.m_rollingFriction = sv.defaultRollingFriction;
    ci.m_spinningFriction = sv.defaultSpinningFriction;
    ci.m_linearSleepingThreshold = sv.sleepingLinearVelocityThreshold;
    ci.m_angularSleepingThreshold = sv.sleepingAngularVelocityThreshold;
    auto* body = new btRigidBody(ci);
    bodies.emplace_back(body);
    // Solve only touching contacts: Bullet's speculative (still separated)
    // contacts subtract gap/dt from the rebound and eat restitution.
    body->setContactProcessingThreshold(0);
    if (mode == BodyMode::Kinematic) {
      body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
      body->setActivationState(DISABLE_DEACTIVATION);
    }
    if (dynamic && !sv.sleepingEnabled) body->setActivationState(DISABLE_DEACTIVATION);
    if (dynamic && sv.sweptCcdEnabled) {
      btVector3 c;
      btScalar r;
      shape->getBoundingSphere(c, r);
      body->setCcdMotionThreshold(std::max(sv.sweptCcdMinSpeed * dt, r * 0.5));
      body->setCcdSweptSphereRadius(r * 0.5);
    }
    body->setUserIndex(static_cast<int>(info.size()));
    BodyInfo bi = filterInfo;
    bi.material = contactMaterial.empty() ? -1 : materialOf(contactMaterial);
    info.push_back(bi);
    body->setUserIndex2(bi.material);
    world->addRigidBody(body);
    return body;
  }

  // What create() refuses a body or a wire for (refuse() sets it): the
  // whole message, its code and where it points.
  struct BuildError {
    std::string message;
    const char* code = nullptr;
    int recordIndex = -1;
    const char* field = "";
  } buildError;
  bool refuse(const std::string& what, const std::string& message, const char* code, int recordIndex,
              const char* field) {
    buildError = {what + ": " + message, code, recordIndex, field};
    return false;
  }

  // The Bullet world with the scene's solver settings, broadphase, filter
  // and contact materials; no bodies yet.
  void configure(const Scene& scene, const WorldOptions& options) {
    assets = options.assets;
    if (!assets) {
      ownAssets = std::make_unique<asset::AssetCache>();
      assets = ownAssets.get();
    }
    leaveMargin = options.leaveMargin;
    allowMissingAssets = options.allowMissingAssets;
    sleepLinear = scene.solver.sleepingLinearVelocityThreshold;
    sleepAngular = scene.solver.sleepingAngularVelocityThreshold;
    sleepQuietSteps = std::max(1, scene.solver.sleepingQuietSteps);
    const Solver& sv = scene.solver;
    bounded = sv.broadphaseUseWorldBounds;
    boundsMin = bt(sv.broadphaseWorldMin);
    boundsMax = bt(sv.broadphaseWorldMax);
    // Up to four contact points between a convex body and a plane (Bullet
    // finds one by default): a box sliding faster than its contact-breaking
    // threshold per step otherwise keeps a single corner point, rocks and
    // sinks millimetres into the ground.
    config.setPlaneConvexMultipointIterations(3, 3);
    useConvexPlaneAlgorithm(dispatcher, convexPlane, planeConvex, 3, 3);  // the same contacts, less work (convex_plane.hpp)
    skipSeparatedPairs(dispatcher);  // the same contacts, fewer narrowphase calls (separated_pairs.hpp)
    dt = scene.timeStep;
    if (sv.broadphaseType == "sap3_axis" && sv.broadphaseUseWorldBounds)
      broadphase = std::make_unique<btAxisSweep3>(bt(sv.broadphaseWorldMin), bt(sv.broadphaseWorldMax));
    else
      broadphase = std::make_unique<btDbvtBroadphase>();
    world = std::make_unique<MultiBodyWorld>(&dispatcher, broadphase.get(), &solver, &config);  // multibody_world.hpp
    world->setGravity(bt(scene.gravity));
    // Static bodies do not move: Bullet's default re-sets every AABB each
    // step, which keeps statics in the broadphase's dynamic tree and
    // collides them with each other there, every step.
    world->setForceUpdateAllAabbs(false);
    btContactSolverInfo& si = world->getSolverInfo();
    si.m_numIterations = std::max(1, sv.iterations);
    si.m_erp = sv.erp;
    if (sv.erp2 > 0) si.m_erp2 = sv.erp2;
    si.m_leastSquaresResidualThreshold = sv.tolerance;
    si.m_restitutionVelocityThreshold = sv.defaultRestitutionThreshold;
    si.m_solverMode &= ~SOLVER_RANDMIZE_ORDER;  // deterministic order, always
    si.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS | SOLVER_ENABLE_FRICTION_DIRECTION_CACHING;
    // Bullet drops restitution on contacts older than this many steps, which
    // loses bounces whose contact point was found before impact; the
    // restitution velocity threshold alone decides, as in Engine 2.
    si.m_restingContactRestitutionThreshold = 1 << 30;
    // Penetration is always removed by split impulses, which move bodies
    // without adding velocity (Baumgarte would add energy to bounces).
    si.m_splitImpulse = true;
    si.m_splitImpulsePenetrationThreshold = 0;
    filter.info = &info;
    filter.self = &selfPairs;
    filter.cache = world->getPairCache();
    filter.maxPairs = options.maxPairs;
    world->getPairCache()->setOverlapFilterCallback(&filter);
    // Bullet sleeps a body after gDeactivationTime seconds below its thresholds.
    gDeactivationTime = std::max(1, sv.sleepingQuietSteps) * dt;

    pairs.friction = sv.defaultFriction;
    pairs.restitution = sv.defaultRestitution;
    pairs.rolling = sv.defaultRollingFriction;
    pairs.spinning = sv.defaultSpinningFriction;
    for (const ContactMaterial& c : scene.contactMaterials) {
      int a = materialOf(c.materialA), b = materialOf(c.materialB);
      pairs.pairs[{std::min(a, b), std::max(a, b)}] = c;
    }
  }

  // One add-function per body kind, as Bullet's examples build a world.
  bool addObject(const Object& o, const Solver& sv) {
    if (o.bodyMode == BodyMode::VisualOnly) return true;
    BodyInfo fi{o.collisionGroup, o.collisionMask, -1, o.recordIndex};
    btRigidBody* body = nullptr;
    if (groundRulePlane(o)) groundPlanes.insert(o.recordIndex);
    if (groundRuleBody(o)) groundRuleBodies.insert(o.recordIndex);
    if (pairRuleBody(o)) pairRuleBodies.insert(o.recordIndex);
    if (o.primitive == "ground" || o.primitive == "half_space") {
      btCollisionShape* plane = keep(new btStaticPlaneShape(btVector3(0, 0, 1), o.world.position.z()));
      body = addBody(plane, btTransform::getIdentity(), BodyMode::Static, 0, btVector3(0, 0, 0), false, fi, o.contactMaterial, sv);
      floorZ = std::min(floorZ, o.world.position.z());  // a plane's AABB is unbounded: its height is the floor
    } else {
      std::string error;
      bool convex = o.bodyMode != BodyMode::Static;
      Eigen::Vector3d box = o.scale;
      btCollisionShape* shape = primitive(o.primitive, box, o.physicsRadius(), o.physicsHeight(),
                                            o.collisionMeshPath, o.meshScale(), convex, error);
      if (!shape) return refuse("body '" + o.path + "'", error, scene_code::kBadMesh, o.recordIndex, "meshPath");
      // customInertia: the record's principal moments (checked by RS7090),
      // as RaiSim's <inertia> sets them; else the shape's.
      double mass = o.effectiveMass();
      body = addBody(shape, bt(o.world), o.bodyMode, mass, bt(o.inertiaDiagonal), o.hasInertia, fi,
                       o.contactMaterial, sv);
      if (o.bodyMode == BodyMode::Static) lowerFloorTo(body);
    }
    registerBody(o, body);
    return true;
  }

  // Child shapes about the centre of mass (scene/mass_properties.hpp).
  bool addCompound(const Compound& c, const Solver& sv) {
    if (c.bodyMode == BodyMode::VisualOnly || c.children.empty()) return true;
    // Child shapes about the centre of mass: given, or volume-weighted.
    std::vector<std::pair<btCollisionShape*, btTransform>> parts;
    std::vector<double> volumes;  // true volumes (scene/mass_properties.hpp); a mesh child's hull's
    for (const CompoundChild& ch : c.children) {
      Eigen::Vector3d s = ch.scale.cwiseProduct(c.scale);
      Eigen::Vector3d box = ch.size.isZero() ? s : ch.size.cwiseProduct(s);
      std::string error;
      btCollisionShape* shape = primitive(ch.primitive, box, ch.radius * s.x(), ch.height * s.z(), ch.meshPath,
                                            s.mean(), true, error);
      if (!shape) return refuse("body '" + c.path + "'", error, scene_code::kBadMesh, ch.recordIndex, "meshPath");
      Pose local = ch.local;
      local.position = local.position.cwiseProduct(c.scale);
      parts.emplace_back(shape, bt(local));
      volumes.push_back(ch.primitive == "mesh" ? hullVolume(shape) : primitiveVolume(c, ch));
    }
    Eigen::Vector3d com = compoundCenterOfMass(c, volumes);
    // Uniform density; children with no volume (a degenerate hull) get no mass.
    double total = 0;
    for (double v : volumes) total += v;
    auto* compound = new btCompoundShape();
    keep(compound);
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
    double mass = compoundMass(c);
    for (std::size_t i = 0; i < parts.size(); ++i) {
      btTransform t = parts[i].second;
      t.setOrigin(t.getOrigin() - bt(com));
      compound->addChildShape(t, parts[i].first);
      double m = total > 0 ? mass * volumes[i] / total : mass / static_cast<double>(parts.size());
      btVector3 li;
      parts[i].first->calculateLocalInertia(m, li);
      Eigen::Matrix3d r = eig(t.getRotation()).toRotationMatrix();
      Eigen::Vector3d d = eig(t.getOrigin());
      inertia += r * Eigen::Vector3d(li.x(), li.y(), li.z()).asDiagonal() * r.transpose() +
                 m * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
    }
    btVector3 diag = c.hasInertia ? bt(c.inertiaDiagonal) : btVector3(inertia(0, 0), inertia(1, 1), inertia(2, 2));
    btTransform comShift(btQuaternion::getIdentity(), bt(com));
    BodyInfo fi{c.collisionGroup, c.collisionMask, -1, c.recordIndex};
    btRigidBody* body = addBody(compound, bt(c.world) * comShift, c.bodyMode, mass, diag, true, fi,
                                  c.contactMaterial, sv);
    if (c.bodyMode == BodyMode::Static) lowerFloorTo(body);
    registerBody(c, body, comShift.inverse());
    return true;
  }

  void addTerrain(const Terrain& t, const Solver& sv) {
    if (!t.collidable) return;
    heights.push_back(t.heights);
    const std::vector<double>& h = heights.back();
    auto [lo, hi] = std::minmax_element(h.begin(), h.end());
    double minH = *lo, maxH = *hi;
    auto* shape = new btHeightfieldTerrainShape(t.xSamples, t.ySamples, h.data(), minH, maxH, 2, false);
    shape->setLocalScaling(btVector3(t.xSize / (t.xSamples - 1), t.ySize / (t.ySamples - 1), 1));
    keep(shape);
    // Bullet centres a height field on its bounding box.
    btTransform at(btQuaternion::getIdentity(), btVector3(t.center.x(), t.center.y(), t.center.z() + (minH + maxH) / 2));
    BodyInfo fi{kTerrainGroup, kAll, -1, t.recordIndex};
    btRigidBody* body = addBody(shape, at, BodyMode::Static, 0, btVector3(0, 0, 0), false, fi, t.contactMaterial, sv);
    lowerFloorTo(body);
    name(byName, t.id, t.path, body);
    byRecord[t.recordIndex] = body;
  }

  // A wire between its two ends as the scene model resolved them; false
  // with buildError set when an end is no body of its robot.
  bool addWire(const Wire& wire) {
    if (!wire.simulated()) return true;  // disabled, or to a node not modelled (RS7011)
    // Each end: the world (no name), a rigid body (attachment point in its
    // record frame; compounds simulate about their centre of mass), or a
    // robot's body localIndex (point in that body's frame).
    enum Kind { None, Point, Body };
    auto anchor = [&](const std::string& ref, int record, int localIndex, const Eigen::Vector3d& p,
                      const char* field, WireAnchor& out) -> Kind {
      out.local = bt(p);
      if (ref.empty()) return Point;
      if (auto it = robotByRecord.find(record); it != robotByRecord.end()) {
        SimRobot* r = robots[static_cast<std::size_t>(it->second)].get();
        int bodies = static_cast<int>(r->layout().bodies.size());
        if (localIndex < 0 || localIndex >= bodies) {
          // At the localIndex key, where validate's RS7046 points.
          const char* key = field == std::string("bodyA") ? "localIndexA" : "localIndexB";
          refuse("wire '" + wire.path + "'",
                 std::string(key) + " " + std::to_string(localIndex) + " is not a body of articulated system '" +
                     ref + "' (it has " + std::to_string(bodies) + ", 0 to " + std::to_string(bodies - 1) + ")",
                 sim_code::kWireLocalIndex, wire.recordIndex, key);
          return None;
        }
        out.robot = r;
        out.body = localIndex;
        return Body;
      }
      auto it = byRecord.find(record);
      if (it == byRecord.end()) return None;  // checkPhysics reported it
      out.rigid = it->second;
      for (const Simulated& s : simulated)
        if (s.body == out.rigid) out.local = s.toRecord.inverse() * bt(p);
      return Body;
    };
    WireAnchor a, b;
    Kind ka = anchor(wire.bodyA, wire.recordA, wire.localIndexA, wire.localPositionA, "bodyA", a);
    Kind kb = anchor(wire.bodyB, wire.recordB, wire.localIndexB, wire.localPositionB, "bodyB", b);
    if (buildError.code) return false;
    if (ka == None || kb == None || (ka == Point && kb == Point)) return true;
    if (wire.kind == "compliant") {
      springs.push_back({a, b, wire.length, wire.stiffness, wire.damping});
      return true;
    }
    if (!a.robot && b.robot) std::swap(a, b);  // a robot end first
    if (a.robot) {
      auto* c = new MultiBodyRope(a, b, wire.length);
      robotWires.emplace_back(c);
      world->addMultiBodyConstraint(c);
      return true;
    }
    if (!a.rigid) std::swap(a, b);  // the world is end B
    auto* c = new RopeConstraint(*a.rigid, b.rigid, a.local, b.local, wire.length);
    constraints.emplace_back(c);
    world->addConstraint(c, true);
    return true;
  }

  // Deformable and granular records collide with the bodies through
  // Bullet's world, filtered and rubbed as the bodies are.
  void attachParticleSurfaces() {
    SurfaceFilter filter;
    Impl* wp = this;
    filter.collides = [wp](const btCollisionObject& o, std::uint64_t group, std::uint64_t mask) {
      if (o.getUserIndex() < 0 || static_cast<std::size_t>(o.getUserIndex()) >= wp->info.size()) return false;
      const BodyInfo& b = wp->info[static_cast<std::size_t>(o.getUserIndex())];
      return (b.group & mask) != 0 && (group & b.mask) != 0;
    };
    filter.friction = [wp](const btCollisionObject& o, const std::string& material) {
      auto it = wp->materialIndex.find(material);
      int x = material.empty() || it == wp->materialIndex.end() ? -1 : it->second, y = o.getUserIndex2();
      if (x >= 0 && y >= 0)
        if (auto p = wp->pairs.pairs.find({std::min(x, y), std::max(x, y)}); p != wp->pairs.pairs.end())
          return p->second.friction;
      return wp->pairs.friction;
    };
    surfaces = std::make_unique<BulletSurfaces>(*world, std::move(filter));
  }
};

World::World(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
World::~World() = default;

std::unique_ptr<World> World::create(const Scene& scene, Diagnostics& diagnostics, const WorldOptions& options) {
  auto impl = std::make_unique<Impl>(collisionPools(scene, options));
  Impl& w = *impl;
  w.configure(scene, options);
  const Solver& sv = scene.solver;
  auto fail = [&] {
    const Impl::BuildError& e = w.buildError;
    reportAt(options.document, e.recordIndex, e.field, e.code, e.message, diagnostics);
    return nullptr;
  };
  for (const Object& o : scene.objects)
    if (!w.addObject(o, sv)) return fail();
  for (const Compound& c : scene.compounds)
    if (!w.addCompound(c, sv)) return fail();
  for (const Terrain& t : scene.terrains) w.addTerrain(t, sv);
  if (options.robots) {
    for (const robot::RobotInstance& instance : *options.robots) {
      w.robotMeshesLeftOut.clear();
      if (!w.addRobot(instance, options.pd, sv)) {
        const Articulated& a = *instance.record;
        w.refuse("body '" + a.path + "'", w.robotError, scene_code::kBadMesh, a.recordIndex, "resource");
        return fail();
      }
      for (const std::string& why : w.robotMeshesLeftOut)
        warnMeshLeftOut(options.document, *instance.record, why, diagnostics);
      if (instance.model && !instance.record->convexifyCollisionMeshes && hasMeshCollision(*instance.model))
        warnNotConvexified(options.document, *instance.record, diagnostics);
    }
  }
  for (const Wire& wire : scene.wires)
    if (!w.addWire(wire)) return fail();
  if (!w.particles.create(scene, options.document, *w.assets, diagnostics)) return nullptr;
  if (!w.particles.empty()) w.attachParticleSurfaces();
  // A deformable starting inside a body is refused, as grains starting in
  // overlap are (RS7089): its first substep would throw it (RS7077).
  if (w.surfaces && !w.particles.checkDeformableStarts(*w.surfaces, options.document, diagnostics)) return nullptr;
  // Grains likewise (RS7091; the ground is the scene model's, checkScene()).
  if (w.surfaces && !w.particles.checkGranularStarts(*w.surfaces, options.document, diagnostics)) return nullptr;
  if (!w.deformableMassRatios(scene, options.document, diagnostics)) return nullptr;
  if (!w.robotsAboveGround(options.document, diagnostics)) return nullptr;
  if (!w.startsInWorld(options.document, diagnostics)) return nullptr;
  return std::unique_ptr<World>(new World(std::move(impl)));
}

void World::step() {
  Impl& w = *impl_;
  if (w.surfaces) {  // particles first, against the bodies where they are; their reactions act in this step
    w.particles.step(w.dt, eig(w.world->getGravity()), *w.surfaces);
    w.surfaces->applyForces(w.dt);
  }
  for (const Spring& s : w.springs) s.apply();
  for (auto& r : w.robots) {
    r->applyJointForces(w.dt);
    r->updateLimits(*w.world);
  }
  gCalculateCombinedFrictionCallback = combinedFriction;
  gCalculateCombinedRestitutionCallback = combinedRestitution;
  gCalculateCombinedRollingFrictionCallback = combinedRolling;
  gCalculateCombinedSpinningFrictionCallback = combinedSpinning;
  tPairs = &w.pairs;
  w.world->stepSimulation(w.dt, 0, w.dt);
  tPairs = nullptr;
  ++w.stepCount;
  for (Simulated& s : w.simulated) {
    if (!s.dynamic || s.departed) continue;
    const bool quiet = s.body->getLinearVelocity().length() < w.sleepLinear &&
                       s.body->getAngularVelocity().length() < w.sleepAngular;
    s.quietSteps = quiet ? std::min(s.quietSteps + 1, 1 << 30) : 0;
    // Bullet silently stops simulating a dynamic body whose bounding box
    // (swept over the step) spans more than 10^6 m: it moved too fast or
    // grew too large.  Say so instead of writing a frozen pose as if it rested.
    if (s.body->getActivationState() == DISABLE_SIMULATION) {
      w.depart(s, "moved more than 1e+06 m in one step (Bullet drops such a body)");
      continue;
    }
    // Sleeping bodies do not move; only awake dynamic ones can leave.
    if (!s.body->isActive()) continue;
    std::string why = w.departure(s);
    if (!why.empty()) w.depart(s, std::move(why));
  }
  int n = 0;
  w.penetrating = false;
  for (int i = 0, m = w.dispatcher.getNumManifolds(); i < m; ++i) {
    const btPersistentManifold* manifold = w.dispatcher.getManifoldByIndexInternal(i);
    n += manifold->getNumContacts();
    double depth = 0;  // as the step's collision detection found it, before the solver moved anything
    for (int k = 0; k < manifold->getNumContacts(); ++k)
      depth = std::max(depth, -double(manifold->getContactPoint(k).getDistance()));
    if (!(depth > kRestPenetration)) continue;
    // Split impulses push such a body out a little each step without
    // giving it speed: it must not fall asleep (or count as at rest) half
    // inside another, where Bullet's sleep test alone would freeze it.
    bool dynamic = false;
    for (const btCollisionObject* o : {manifold->getBody0(), manifold->getBody1()})
      if (const btRigidBody* rb = btRigidBody::upcast(o); rb && !rb->isStaticOrKinematicObject()) {
        const_cast<btRigidBody*>(rb)->activate();
        dynamic = true;
      }
    w.penetrating = w.penetrating || dynamic;
    if (w.stepCount == 1 && depth > kStartOverlap) w.noteStartOverlap(*manifold, depth);
  }
  w.contacts = n;
}

double World::time() const { return decimalMultiple(impl_->stepCount, impl_->dt); }
std::uint64_t World::steps() const { return impl_->stepCount; }
double World::timeStep() const { return impl_->dt; }
int World::bodyCount() const { return static_cast<int>(impl_->simulated.size()); }
int World::contactCount() const { return impl_->contacts; }

bool World::atRest() const {
  bool awake = false;
  for (const Simulated& s : impl_->simulated)
    awake = awake || (s.dynamic && !s.departed && s.body->isActive());
  if (awake && !impl_->awakeOnlyOnStillKinematics()) return false;
  if (impl_->penetrating) return false;  // still being pushed out of another body
  if (!impl_->particles.atRest(impl_->sleepLinear)) return false;
  if (impl_->robots.empty()) return true;
  for (const RobotState& r : robotStates()) {
    for (const Eigen::Vector3d& v : r.bodyLinearVelocities)
      if (!(v.norm() < impl_->sleepLinear)) return false;
    for (const Eigen::Vector3d& w : r.bodyAngularVelocities)
      if (!(w.norm() < impl_->sleepAngular)) return false;
  }
  return true;
}

int World::robotCount() const { return static_cast<int>(impl_->robots.size()); }

std::vector<RobotState> World::robotStates() const {
  std::vector<RobotState> out;
  out.reserve(impl_->robots.size());
  for (const auto& r : impl_->robots) {
    const robot::RobotInstance& in = r->instance();
    RobotState s;
    s.recordIndex = in.record->recordIndex;
    s.path = in.record->path;
    s.instance = &in;
    robotState(static_cast<int>(out.size()), s.q, s.u);
    s.base = r->bodyPose(0);
    if (in.model->floatingBase) {
      s.baseLinearVelocity = s.u.head<3>();
      s.baseAngularVelocity = s.u.segment<3>(3);
    }
    const std::vector<RobotBody>& bodies = r->layout().bodies;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      Pose p = r->bodyPose(static_cast<int>(b));
      s.bodyPoses.push_back(p);
      Eigen::Vector3d w, com = (p * bodies[b].com).position;
      s.bodyLinearVelocities.push_back(r->pointVelocity(static_cast<int>(b), com, &w));
      s.bodyAngularVelocities.push_back(w);
    }
    out.push_back(std::move(s));
  }
  return out;
}

const std::vector<Departure>& World::departures() const { return impl_->departures; }

std::optional<int> World::pairOverflow() const {
  if (!impl_->filter.overflowed) return std::nullopt;
  return impl_->filter.overflowRecord;
}

std::optional<NonFinite> World::nonFinite() const {
  const Impl& w = *impl_;
  auto finite = [](const btVector3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); };
  for (const Simulated& s : w.simulated) {
    const btTransform& t = s.body->getWorldTransform();
    const btMatrix3x3& m = t.getBasis();
    const char* what = !finite(t.getOrigin())                                     ? "position"
                       : !(finite(m[0]) && finite(m[1]) && finite(m[2]))          ? "orientation"
                       : !finite(s.body->getLinearVelocity())                     ? "linear velocity"
                       : !finite(s.body->getAngularVelocity())                    ? "angular velocity"
                                                                                  : nullptr;
    if (!what) continue;
    NonFinite bad;
    bad.recordIndex = s.recordIndex;
    bad.path = s.path;
    bad.step = w.stepCount;
    bad.time = time();
    bad.what = what;
    return bad;
  }
  Eigen::VectorXd q, u;
  for (const auto& r : w.robots) {
    r->state(q, u);
    const char* what = !q.allFinite() ? "generalized coordinate" : !u.allFinite() ? "generalized velocity" : nullptr;
    // Finite but diverged: a joint at the speed cap, or the base far away.
    const robot::Coordinates& c = r->instance().coordinates;
    bool diverged = !what && ((u.size() > c.baseVelocities &&
                               u.tail(u.size() - c.baseVelocities).lpNorm<Eigen::Infinity>() >= 0.999 * kMaxJointSpeed) ||
                              (c.baseCoordinates && q.head<3>().lpNorm<Eigen::Infinity>() > kMaxLength));
    if (diverged) what = "generalized velocity";
    if (!what) continue;
    NonFinite bad;
    bad.diverged = diverged;
    bad.recordIndex = r->instance().record->recordIndex;
    bad.path = r->instance().record->path;
    bad.step = w.stepCount;
    bad.time = time();
    bad.what = what;
    return bad;
  }
  if (auto p = w.particles.nonFinite()) {
    NonFinite bad;
    bad.recordIndex = p->first;
    bad.path = p->second;
    bad.step = w.stepCount;
    bad.time = time();
    bad.what = "particle position or velocity";
    return bad;
  }
  if (auto r = w.particles.deformableRunaway()) {  // finite, but gaining energy from nowhere
    NonFinite bad;
    bad.diverged = true;
    bad.recordIndex = r->recordIndex;
    bad.path = r->path;
    bad.step = w.stepCount;
    bad.time = time();
    bad.what = "kinetic energy";
    bad.cause = r->why;
    return bad;
  }
  return std::nullopt;
}

const std::vector<StartOverlap>& World::startOverlaps() const { return impl_->startOverlaps; }

std::vector<DeepContact> World::deepContacts() const {
  const Impl& w = *impl_;
  std::map<std::pair<int, int>, DeepContact> deepest;  // by the pair's records
  if (w.stepCount == 0) return {};
  const btCollisionDispatcher& dispatcher = w.dispatcher;
  for (int i = 0, m = dispatcher.getNumManifolds(); i < m; ++i) {
    const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(i);
    double depth = 0;  // as World::step() measures it
    for (int k = 0; k < manifold->getNumContacts(); ++k)
      depth = std::max(depth, -double(manifold->getContactPoint(k).getDistance()));
    if (!(depth > kRestPenetration)) continue;
    const btCollisionObject* a = manifold->getBody0();
    const btCollisionObject* b = manifold->getBody1();
    auto record = [&](const btCollisionObject* o) {
      const BodyInfo& bi = w.info[static_cast<std::size_t>(o->getUserIndex())];
      return bi.robot >= 0 ? -1 : bi.recordIndex;
    };
    for (auto [x, y] : {std::pair{a, b}, std::pair{b, a}}) {  // the pair once, named by a dynamic body
      const btRigidBody* rb = btRigidBody::upcast(x);
      if (!rb || rb->isStaticOrKinematicObject() || record(x) < 0) continue;
      DeepContact& d = deepest[{std::min(record(x), record(y)), std::max(record(x), record(y))}];
      if (depth > d.depth) d = {record(x), record(y), depth};
      break;
    }
  }
  std::vector<DeepContact> out;
  for (const auto& [record, d] : deepest) out.push_back(d);
  std::stable_sort(out.begin(), out.end(), [](const DeepContact& x, const DeepContact& y) { return x.depth > y.depth; });
  return out;
}

Diagnostic notAtRestWarning(const Document& doc, const std::vector<DeepContact>& contacts, double time,
                            bool untilRest) {
  auto pathOf = [&](int recordIndex) -> std::string {
    if (recordIndex < 0 || static_cast<std::size_t>(recordIndex) >= doc.records.size()) return "a robot's link";
    Diagnostics unused;
    RecordReader r(doc, static_cast<std::size_t>(recordIndex), unused);
    return "'" + r.text("path").value_or("") + "'";
  };
  std::string which;
  const std::size_t named = std::min<std::size_t>(contacts.size(), 3);
  for (std::size_t i = 0; i < named; ++i) {
    char depth[48];
    std::snprintf(depth, sizeof depth, "%.3g m", contacts[i].depth);
    which += (i == 0 ? "" : i + 1 == named && contacts.size() == named ? " and " : ", ") +
             pathOf(contacts[i].recordIndex) + " " + depth + " inside " + pathOf(contacts[i].otherRecordIndex);
  }
  if (contacts.size() > named) which += " and " + std::to_string(contacts.size() - named) + " more";
  char at[64];
  std::snprintf(at, sizeof at, "t = %.6g s", time);
  const bool one = contacts.size() == 1;
  const std::string still = std::string(one ? "dynamic body " : "dynamic bodies ") + which +
                            " (more than 5 mm deep: a longer run may push " + (one ? "it" : "them") +
                            " out, unless " + (one ? "it is" : "they are") + " trapped)";
  const std::string message =
      untilRest ? std::string("--until-rest reached the end of the duration (") + at +
                      ") before the scene came to rest: " + still + "; the scene written is not at rest"
                : std::string("the run ended (") + at + ") with " + still + ": the scene written is not at rest";
  Diagnostics found;
  reportAt(&doc, contacts.empty() ? -1 : contacts.front().recordIndex, "position", rs::RS7002, message, found,
           Severity::Warning, "run longer (--duration), or place the bodies clear of what they start inside");
  return found.front();
}

Diagnostic startOverlapWarning(const Document& doc, const StartOverlap& o) {
  if (o.link.empty()) return startOverlapDiagnostic(doc, o.recordIndex, o.otherRecordIndex, o.depth);
  return robotInGround(doc, o);
}

Diagnostic robotInGround(const Document& doc, const StartOverlap& o) {
  auto pathOf = [&](int recordIndex) -> std::string {
    Diagnostics unused;
    RecordReader r(doc, static_cast<std::size_t>(recordIndex), unused);
    return r.text("path").value_or("");
  };
  const bool valid = o.recordIndex >= 0 && static_cast<std::size_t>(o.recordIndex) < doc.records.size();
  Diagnostics unused;
  const bool written =
      valid && RecordReader(doc, static_cast<std::size_t>(o.recordIndex), unused).has("generalizedCoordinate");
  char depth[48];
  std::snprintf(depth, sizeof depth, "%.3g m", o.depth);
  Diagnostics one;
  reportAt(&doc, o.recordIndex, written ? "generalizedCoordinate" : "position", rs::RS7057,
           "articulated system '" + (valid ? pathOf(o.recordIndex) : std::string("?")) + "' starts with link '" +
               o.link + "' " + depth + " inside '" +
               (o.otherRecordIndex >= 0 && static_cast<std::size_t>(o.otherRecordIndex) < doc.records.size()
                    ? pathOf(o.otherRecordIndex)
                    : std::string("the ground")) +
               "', more than 1 cm: Bullet's multibody solver would throw it out of the ground; nothing was "
               "simulated",
           one, Severity::Error, "raise the robot's base or change its start pose so that no link is in the ground");
  return one.front();
}

Diagnostic departureWarning(const Document& doc, const Departure& d) {
  Diagnostic w;
  w.severity = Severity::Warning;
  w.code = sim_code::kLeftWorld;
  if (d.recordIndex >= 0 && static_cast<std::size_t>(d.recordIndex) < doc.records.size()) {
    const Record& r = doc.records[static_cast<std::size_t>(d.recordIndex)];
    w.line = r.line;
    w.column = 1;  // the record: no one field made it leave
    w.tag = std::string(doc.tag(r));
  }
  char at[96];
  std::snprintf(at, sizeof at, "at step %llu (t = %.6g s)", static_cast<unsigned long long>(d.step), d.time);
  w.message = "dynamic body '" + d.path + "' left the world " + at + ": " + d.reason +
              "; no longer simulated, written at its last pose";
  return w;
}

std::vector<BodyState> World::states() const {
  std::vector<BodyState> out;
  out.reserve(impl_->simulated.size());
  for (const Simulated& s : impl_->simulated) {
    BodyState b;
    b.recordIndex = s.recordIndex;
    b.path = s.path;
    btTransform t = s.body->getWorldTransform() * s.toRecord;
    b.position = eig(t.getOrigin());
    b.orientation = eig(t.getRotation()).normalized();
    b.linearVelocity = eig(s.body->getLinearVelocity());
    b.angularVelocity = eig(s.body->getAngularVelocity());
    b.dynamic = s.dynamic;
    b.sleeping = !s.body->isActive();
    b.departed = s.departed;
    out.push_back(std::move(b));
  }
  return out;
}

namespace {
// The dynamic body named by path or id, or nullptr.
btRigidBody* dynamicBody(const World::Impl& w, const std::string& name) {
  auto it = w.byName.find(name);
  if (it == w.byName.end()) return nullptr;
  for (const Simulated& s : w.simulated)
    if (s.body == it->second) return s.dynamic ? s.body : nullptr;
  return nullptr;
}
}  // namespace

bool World::pointVelocity(const std::string& pathOrId, const Eigen::Vector3d& p, Eigen::Vector3d& v,
                          Eigen::Vector3d& w) const {
  auto it = impl_->byName.find(pathOrId);
  if (it == impl_->byName.end()) return false;
  const btRigidBody* body = it->second;
  btVector3 rel = bt(p) - body->getCenterOfMassPosition();
  v = eig(body->getVelocityInLocalPoint(rel));
  w = eig(body->getAngularVelocity());
  return true;
}

bool World::robotPointVelocity(const std::string& pathOrId, int link, const Eigen::Vector3d& p, Eigen::Vector3d& v,
                               Eigen::Vector3d& w) const {
  auto it = impl_->robotByName.find(pathOrId);
  if (it == impl_->robotByName.end()) return false;
  const SimRobot& r = *impl_->robots[static_cast<std::size_t>(it->second)];
  const std::vector<int>& bodyOf = r.layout().bodyOfLink;
  int body = link >= 0 && std::size_t(link) < bodyOf.size() ? bodyOf[std::size_t(link)] : 0;
  v = r.pointVelocity(body, p, &w);
  return true;
}

std::optional<Pose> World::bodyPose(const std::string& pathOrId) const {
  auto it = impl_->byName.find(pathOrId);
  if (it == impl_->byName.end()) return std::nullopt;
  for (const Simulated& s : impl_->simulated)  // a few pointer compares per sensor and step
    if (s.body == it->second) return pose(s.body->getWorldTransform() * s.toRecord);
  return std::nullopt;
}

std::optional<Pose> World::robotLinkPose(const std::string& pathOrId, int link) const {
  auto it = impl_->robotByName.find(pathOrId);
  if (it == impl_->robotByName.end()) return std::nullopt;
  const SimRobot& r = *impl_->robots[static_cast<std::size_t>(it->second)];
  const RobotLayout& layout = r.layout();
  if (link < 0 || std::size_t(link) >= layout.bodyOfLink.size()) return r.bodyPose(0);
  int body = layout.bodyOfLink[std::size_t(link)];
  const RobotBody& b = layout.bodies[std::size_t(body)];
  for (std::size_t k = 0; k < b.links.size(); ++k)
    if (b.links[k] == link) return r.bodyPose(body) * b.linkInBody[k];
  return r.bodyPose(body);
}

const btCollisionWorld& World::collisionWorld() const { return *impl_->world; }
BulletSurfaces* World::particleSurfaces() { return impl_->surfaces.get(); }

std::vector<const btCollisionObject*> World::rayTargets() const {
  std::vector<const btCollisionObject*> out;
  const btCollisionObjectArray& all = impl_->world->getCollisionObjectArray();
  for (int i = 0; i < all.size(); ++i) {
    const btCollisionObject* o = all[i];
    int k = o->getUserIndex();
    if (k < 0 || std::size_t(k) >= impl_->info.size()) continue;
    const BodyInfo& bi = impl_->info[std::size_t(k)];
    if (bi.group == 0 || bi.mask == 0) continue;  // collides with nothing (collidable=false)
    if (o->getCollisionShape()->getShapeType() == EMPTY_SHAPE_PROXYTYPE) continue;
    out.push_back(o);
  }
  return out;
}

const btCollisionObject* World::collisionObject(const std::string& pathOrId) const {
  auto it = impl_->byName.find(pathOrId);
  return it == impl_->byName.end() ? nullptr : it->second;
}

const btCollisionObject* World::robotCollisionObject(const std::string& pathOrId, int link) const {
  auto it = impl_->robotByName.find(pathOrId);
  if (it == impl_->robotByName.end()) return nullptr;
  const SimRobot& r = *impl_->robots[static_cast<std::size_t>(it->second)];
  const std::vector<int>& bodyOf = r.layout().bodyOfLink;
  int body = link >= 0 && std::size_t(link) < bodyOf.size() ? bodyOf[std::size_t(link)] : 0;
  return r.colliders()[static_cast<std::size_t>(body)];
}

int World::robotIndex(const std::string& pathOrId) const {
  auto it = impl_->robotByName.find(pathOrId);
  return it == impl_->robotByName.end() ? -1 : it->second;
}

const robot::RobotInstance& World::robotInstance(int robot) const {
  return impl_->robots[static_cast<std::size_t>(robot)]->instance();
}

void World::robotState(int robot, Eigen::VectorXd& q, Eigen::VectorXd& u) const {
  const Impl& w = *impl_;
  const SimRobot& r = *w.robots[static_cast<std::size_t>(robot)];
  bool set = static_cast<std::size_t>(robot) < w.robotStateSet.size() && w.robotStateSet[static_cast<std::size_t>(robot)];
  if (w.stepCount == 0 && !set) {  // what the record says, not its round trip through Bullet's frames
    q = r.instance().q;
    u = r.instance().u;
  } else {
    r.state(q, u);
  }
}

namespace {

std::string sizeError(const char* what, Eigen::Index got, int want, const char* layout) {
  return std::string(what) + " has " + std::to_string(got) + " entries; the robot's " + layout + " has " +
         std::to_string(want);
}

// "" or what is wrong with the quaternions of `q` (RaiSim's layout).
std::string quaternionError(const robot::RobotInstance& in, const Eigen::VectorXd& q, const char* what) {
  const robot::Model& m = *in.model;
  const robot::Coordinates& c = in.coordinates;
  if (m.floatingBase && !(q.segment<4>(3).norm() > 1e-12))
    return std::string(what) + ": the base quaternion (entries 3..6) is zero";
  for (std::size_t j = 0; j < m.joints.size(); ++j)
    if (m.joints[j].type == robot::JointType::Spherical && c.coordinateIndex[j] >= 0 &&
        !(q.segment<4>(c.coordinateIndex[j]).norm() > 1e-12))
      return std::string(what) + ": the quaternion of joint '" + m.joints[j].name + "' is zero";
  return {};
}

}  // namespace

std::string World::setRobotPd(int robot, const Eigen::VectorXd& qTarget, const Eigen::VectorXd& uTarget,
                              const Eigen::VectorXd& kp, const Eigen::VectorXd& kd) {
  SimRobot& r = *impl_->robots[static_cast<std::size_t>(robot)];
  const robot::Coordinates& c = r.instance().coordinates;
  if (qTarget.size() != c.coordinateDim) return sizeError("the position target", qTarget.size(), c.coordinateDim, "q");
  if (uTarget.size() != 0 && uTarget.size() != c.velocityDim)
    return sizeError("the velocity target", uTarget.size(), c.velocityDim, "u");
  if (kp.size() != c.velocityDim) return sizeError("kp", kp.size(), c.velocityDim, "u");
  if (kd.size() != c.velocityDim) return sizeError("kd", kd.size(), c.velocityDim, "u");
  if (!qTarget.allFinite() || !uTarget.allFinite()) return "a target is not finite";
  if (!kp.allFinite() || !kd.allFinite() || (kp.array() < 0).any() || (kd.array() < 0).any())
    return "gains must be finite and >= 0";
  if (std::string e = quaternionError(r.instance(), qTarget, "the position target"); !e.empty()) return e;
  r.setPdGains(kp, kd);
  r.setPdTarget(qTarget, uTarget.size() ? uTarget : Eigen::VectorXd(Eigen::VectorXd::Zero(c.velocityDim)));
  return {};
}

std::string World::setRobotGeneralizedForce(int robot, const Eigen::VectorXd& tau) {
  SimRobot& r = *impl_->robots[static_cast<std::size_t>(robot)];
  const robot::Coordinates& c = r.instance().coordinates;
  if (tau.size() != c.velocityDim) return sizeError("the generalized force", tau.size(), c.velocityDim, "u");
  if (!tau.allFinite()) return "the generalized force is not finite";
  r.setGeneralizedForce(tau);
  return {};
}

std::string World::setRobotState(int robot, const Eigen::VectorXd& q, const Eigen::VectorXd& u) {
  Impl& w = *impl_;
  SimRobot& r = *w.robots[static_cast<std::size_t>(robot)];
  const robot::Coordinates& c = r.instance().coordinates;
  if (q.size() != c.coordinateDim) return sizeError("q", q.size(), c.coordinateDim, "q");
  if (u.size() != c.velocityDim) return sizeError("u", u.size(), c.velocityDim, "u");
  if (!q.allFinite() || !u.allFinite()) return "the state is not finite";
  if ((q.array().abs() > 1e12).any() || (u.array().abs() > 1e12).any()) return "a state entry is beyond 1e12";
  if (std::string e = quaternionError(r.instance(), q, "q"); !e.empty()) return e;
  r.setState(q, u);
  r.multiBody()->wakeUp();
  if (w.robotStateSet.size() < w.robots.size()) w.robotStateSet.resize(w.robots.size(), 0);
  w.robotStateSet[static_cast<std::size_t>(robot)] = 1;
  return {};
}

std::vector<World::Contact> World::contacts() const {
  const Impl& w = *impl_;
  std::vector<Contact> out;
  auto who = [&](const btCollisionObject* o, int& record, std::string& link) {
    int index = o->getUserIndex();
    if (index < 0 || static_cast<std::size_t>(index) >= w.info.size()) return;
    const BodyInfo& bi = w.info[static_cast<std::size_t>(index)];
    record = bi.recordIndex;
    if (bi.robot < 0) return;
    const SimRobot& r = *w.robots[static_cast<std::size_t>(bi.robot)];
    const RobotBody& b = r.layout().bodies[static_cast<std::size_t>(bi.body)];
    if (!b.links.empty()) link = r.instance().model->links[static_cast<std::size_t>(b.links.front())].name;
  };
  for (int i = 0, m = w.dispatcher.getNumManifolds(); i < m; ++i) {
    const btPersistentManifold* manifold = w.dispatcher.getManifoldByIndexInternal(i);
    if (manifold->getNumContacts() == 0) continue;
    Contact base;
    who(manifold->getBody0(), base.recordA, base.linkA);
    who(manifold->getBody1(), base.recordB, base.linkB);
    for (int k = 0; k < manifold->getNumContacts(); ++k) {
      const btManifoldPoint& p = manifold->getContactPoint(k);
      Contact c = base;
      c.position = eig(p.getPositionWorldOnB());
      c.normal = eig(p.m_normalWorldOnB);
      c.depth = -double(p.getDistance());
      c.impulse = p.getAppliedImpulse();
      out.push_back(std::move(c));
    }
  }
  return out;
}

bool World::setLinearVelocity(const std::string& pathOrId, const Eigen::Vector3d& velocity) {
  btRigidBody* body = dynamicBody(*impl_, pathOrId);
  if (!body || !velocity.allFinite()) return false;
  body->setLinearVelocity(bt(velocity));
  body->activate(true);
  return true;
}

bool World::setAngularVelocity(const std::string& pathOrId, const Eigen::Vector3d& velocity) {
  btRigidBody* body = dynamicBody(*impl_, pathOrId);
  if (!body || !velocity.allFinite()) return false;
  body->setAngularVelocity(bt(velocity));
  body->activate(true);
  return true;
}

void World::writeBack(Document& doc) const {
  std::string num;
  for (const Simulated& s : impl_->simulated) {
    if (!s.dynamic) continue;  // kinematic bodies have no velocity in the format: they stay put
    btTransform t = s.body->getWorldTransform() * s.toRecord;
    Pose world{eig(t.getOrigin()), eig(t.getRotation()).normalized()};
    Pose local = s.parentFrame.inverse() * world;
    if (local.orientation.w() < 0) local.orientation.coeffs() *= -1;  // one spelling per rotation
    const Record& rec = doc.records[static_cast<std::size_t>(s.recordIndex)];
    double values[7] = {local.position.x(), local.position.y(), local.position.z(), local.orientation.w(),
                        local.orientation.x(), local.orientation.y(), local.orientation.z()};
    for (int k = 0; k < 7; ++k) {
      const Field* f = doc.positional(rec, static_cast<std::uint32_t>(s.positionToken + k));
      if (!f) continue;
      num.clear();
      appendNumber(num, values[k] == 0 ? 0.0 : values[k]);  // no "-0"
      doc.setValue(static_cast<std::uint32_t>(f - doc.fields.data()), num);
    }
  }
  for (const RobotState& r : robotStates()) writeRobot(doc, r);
  impl_->particles.writeBack(doc);
}

std::vector<ParticleState> World::particleStates() const { return impl_->particles.states(); }
std::optional<ParticleFailure> World::particleFailure() const { return impl_->particles.failure(); }
std::optional<ParticleFailure> World::particlesUnwritable() const {
  return impl_->particles.unwritable(impl_->surfaces.get());
}
const ParticleSystems& World::particleSystems() const { return impl_->particles; }

void World::writeRobot(Document& doc, const RobotState& state) {
  const robot::RobotInstance& in = *state.instance;
  const robot::Model& model = *in.model;
  Eigen::VectorXd q = state.q;
  // One spelling per rotation: quaternions with w >= 0 (base and spherical joints).
  auto canonical = [&](int at) {
    if (q[at] < 0) q.segment<4>(at) *= -1;
  };
  if (model.floatingBase) canonical(3);
  for (int j : in.coordinates.joints)
    if (model.joints[static_cast<std::size_t>(j)].type == robot::JointType::Spherical)
      canonical(in.coordinates.coordinateIndex[static_cast<std::size_t>(j)]);
  auto list = [](const Eigen::VectorXd& v) {
    std::string out;
    for (Eigen::Index i = 0; i < v.size(); ++i) {
      if (i) out += ',';
      appendNumber(out, v[i] == 0 ? 0.0 : v[i]);
    }
    return out;
  };
  std::size_t index = static_cast<std::size_t>(state.recordIndex);
  doc.setKey(index, "generalizedCoordinate", list(q));
  doc.setKey(index, "generalizedVelocity", list(state.u));
  if (!model.floatingBase || in.record->positionToken < 0) return;
  // The positional pose of a floating base is q's base, in the record's parent frame.
  const Articulated& a = *in.record;
  Pose world{q.head<3>(), Eigen::Quaterniond(q[3], q[4], q[5], q[6])};
  Pose local = (a.world * a.local.inverse()).inverse() * world;
  if (local.orientation.w() < 0) local.orientation.coeffs() *= -1;
  double values[7] = {local.position.x(), local.position.y(), local.position.z(), local.orientation.w(),
                      local.orientation.x(), local.orientation.y(), local.orientation.z()};
  std::string num;
  const Record& rec = doc.records[index];
  for (int k = 0; k < 7; ++k) {
    const Field* f = doc.positional(rec, static_cast<std::uint32_t>(a.positionToken + k));
    if (!f) continue;
    num.clear();
    appendNumber(num, values[k] == 0 ? 0.0 : values[k]);
    doc.setValue(static_cast<std::uint32_t>(f - doc.fields.data()), num);
  }
}

}  // namespace rscene::sim
