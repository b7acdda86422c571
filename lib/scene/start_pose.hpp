// Where bodies start: the rules about a start pose that the scene model
// decides once, so that rscene-validate and rscene-sim give one verdict.
#pragma once
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

// RS7013 for a dynamic body that starts `depth` m inside another record
// (`otherRecord` < 0: a robot's link), at the body record's position: the
// one wording of validate and sim.
Diagnostic startOverlapDiagnostic(const Document& doc, int bodyRecord, int otherRecord, double depth);

// Appends RS7013 for groundStarts(scene).
void checkGroundStarts(const Document& doc, const Scene& scene, Diagnostics& diagnostics);

}  // namespace rscene
