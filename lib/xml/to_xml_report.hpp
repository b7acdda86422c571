// What rscene-to-xml leaves out, for the one warning line: the record
// kinds a RaiSim world XML has no element for, counted, in a fixed order
// (lights, cameras, materials' looks, environment, weather, render
// settings, groups, editor state, sensors, visual-only bodies,
// deformables, granular, instanced visuals, point clouds, probes, decals,
// fog volumes, IK targets, terrain layers, wires not simulated, unknown
// records), then the solver keys with no XML attribute that differ from
// the schema's default.
#pragma once
#include <string>
#include <vector>

#include "core/document.hpp"
#include "scene/scene.hpp"

namespace rscene::xml {

void listRecordsNotExported(const Document& doc, const Scene& scene, std::vector<std::string>& out);
void listSolverNotExported(const Document& doc, const Scene& scene, std::vector<std::string>& out);

// Whether rscene-sim simulates the body (the same tests as lib/sim's
// World::create): visual-only objects and compounds (bodyMode
// visual_only, or collidable=false), compounds without children and
// non-collidable terrains are not bodies there, so not in the XML either.
inline bool simulated(const Object& o) { return o.bodyMode != BodyMode::VisualOnly; }
inline bool simulated(const Compound& c) { return c.bodyMode != BodyMode::VisualOnly && !c.children.empty(); }
inline bool simulated(const Terrain& t) { return t.collidable; }

}  // namespace rscene::xml
