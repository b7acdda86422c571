// Where bodies start: the rules about a start pose that the scene model
// decides once, so that rscene-validate and rscene-sim give one verdict.
#pragma once
#include <cstdint>
#include <vector>

#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "scene/scene.hpp"

namespace rscene {

// Closer than this is contact, not a mistake (m).
inline constexpr double kStartOverlapDepth = 0.01;

// A dynamic primitive object (box, sphere, capsule, cylinder) whose start
// reaches below a ground or half_space it collides with (rscene-sim's
// planes: horizontal, at the record's height) by more than
// kStartOverlapDepth.
struct GroundStart {
  int body = -1;    // Scene::objects index of the dynamic body
  int ground = -1;  // Scene::objects index of the plane
  double depth = 0;  // m below the plane
};

// True for an object the ground rule judges (dynamic primitive), and for a
// plane it judges against: rscene-sim leaves such a pair's start overlap
// to the scene model.
bool groundRuleBody(const Object& o);
bool groundRulePlane(const Object& o);

// Every pair past kStartOverlapDepth, in object order.
std::vector<GroundStart> groundStarts(const Scene& scene);

// How deep the lowest point of a primitive body lies below height z (<= 0:
// above it).
double depthBelow(const Object& body, double z);

// Two dynamic primitive bodies that start inside each other by more than
// kStartOverlapDepth: their groups meet (each group in the other's mask),
// and no stiff wire joins them (rscene-sim does not collide the two ends
// of a stiff wire).  The pair rule judges the shapes it has an exact
// penetration depth for: box, sphere and capsule objects (sphere and
// capsule pairs by segment distance, boxes by separating axes).
// Cylinders, meshes, compounds, robots, and static or kinematic partners
// are left to rscene-sim, which warns from its first step's contacts:
// validate's bodiesOnly build skips plain static and kinematic objects
// (scene_builder.hpp plainBody(), which keeps its memory near the file's
// size), so judging them here would need a compact list of them first.
struct BodyStart {
  int body = -1;   // Scene::objects index of a dynamic body of the pair (the later one when both are)
  int other = -1;  // Scene::objects index of the other
  double depth = 0;  // m: how far one must move to leave the other
};

// True for an object the pair rule judges (a dynamic box, sphere or
// capsule): rscene-sim leaves the start overlap of two such objects to the
// scene model.
bool pairRuleBody(const Object& o);

// The penetration depth of two pair-rule bodies (<= 0: apart, touching at
// 0); NaN for shapes the rule does not judge.
double overlapDepth(const Object& a, const Object& b);

// Candidate pairs bodyStarts() looks at, at most (a pile of thousands of
// bodies in one place; about a second of work).
inline constexpr std::uint64_t kMaxStartPairVisits = 200'000'000;

// For each dynamic body in a pair past kStartOverlapDepth, the deepest
// such pair (one per body: a pile of n bodies is n warnings, not n^2), in
// body order.  A sweep over bounding boxes along the axis the bodies
// spread most on finds the candidates: pairs of two non-dynamic bodies
// are never visited, so a city of static boxes costs a sort.
std::vector<BodyStart> bodyStarts(const Scene& scene);

// Most two touching dynamic bodies' masses may differ by (RS7014): an
// iterative contact solver (Bullet's sequential impulses) converges too
// slowly past it to hold a heavy body on a light one.
inline constexpr double kMaxContactMassRatio = 100;

// A pair of dynamic pair-rule bodies that start touching or inside each
// other (depth >= -kStartOverlapDepth) with masses more than
// kMaxContactMassRatio apart.
struct MassRatioStart {
  int heavy = -1;  // Scene::objects index
  int light = -1;
  double ratio = 0;  // heavy / light
};

// One per heavier body (its largest ratio), in body order.
std::vector<MassRatioStart> massRatioStarts(const Scene& scene);

// How far below the lowest static geometry a dynamic body has left the
// world (rscene-sim's WorldOptions::leaveMargin).
inline constexpr double kLeaveMargin = 10;

// A dynamic object or compound whose position starts more than
// kLeaveMargin under the lowest ground or half_space (rscene-sim's floor
// counts every plane, whatever its collision filter): rscene-sim would
// take it out of the world at its first step.  Lower static geometry,
// terrain and the broadphase bounds are rscene-sim's to judge, with the
// same code, before its first step.
struct BelowWorldStart {
  int record = -1;  // the body's record
  int ground = -1;  // Scene::objects index of the lowest plane
  double z = 0;      // where it starts
  double bound = 0;  // the lowest plane's height - kLeaveMargin
};

// Every such body, in record order.
std::vector<BelowWorldStart> belowWorldStarts(const Scene& scene);

// RS7013 for a dynamic body that starts `depth` m inside another record
// (`otherRecord` < 0: a robot's link), at the body record's position: the
// one wording of validate and sim.
Diagnostic startOverlapDiagnostic(const Document& doc, int bodyRecord, int otherRecord, double depth);

// Appends RS7015 (error) for belowWorldStarts(scene), RS7013 for
// groundStarts(scene) and bodyStarts(scene) (not for a body RS7015
// refuses), then RS7014 for massRatioStarts(scene).
void checkGroundStarts(const Document& doc, const Scene& scene, Diagnostics& diagnostics);

}  // namespace rscene
