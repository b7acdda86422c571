// rscene-validate's full check of one scene: lib/core's validator (syntax,
// types, references, sizes, files, profiles) plus the scene model's checks
// (scene/check.hpp), i.e. everything rscene-sim and rscene-render refuse.
// It lives here because lib/core cannot see the scene model.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/check.hpp"
#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "scene/triangle_surface.hpp"

namespace rscene {

struct Scene;

// A finding of a check a layer above lib/scene adds (rscene-validate
// composes lib/robot's robot checks this way: lib/scene cannot see
// lib/robot), with the scene line it is listed at: its own line, or, for a
// finding inside another file (Diagnostic::file: a robot's URDF), the line
// of the scene record that named that file.
struct SceneFinding {
  std::uint32_t sceneLine = 0;
  Diagnostic diagnostic;
};
// Runs after the scene model's checks, on the same scene model (built with
// SceneOptions::bodiesOnly, which includes the articulated records).
using ExtraSceneCheck = std::function<void(const Document&, const Scene&, std::vector<SceneFinding>&)>;

// Loads `text` and checks it.  The loader's errors stop the check, as in
// validateText().  Scene-model findings are merged in by line, and one that
// repeats a core finding (same line and code) is dropped, so a condition is
// reported once.  `doc` receives the parsed scene.
Diagnostics validateScene(std::string text, const CheckOptions& options, Document& doc);
// The same findings in the same order, handed to `sink` one at a time: the
// core's are not held, so a caller that keeps few holds little.  `doc`
// holds the text from the first call of the sink on, for source lines.
// `extra`'s findings merge with the scene model's.
// `readSurface` and `readMesh`, when given with options.checkFiles, judge
// each deformable with its mesh and read every body and foliage mesh, as
// rscene-sim and rscene-render do (SceneCheckOptions::readSurface, readMesh).
void validateScene(std::string text, const CheckOptions& options, Document& doc, DiagnosticSink& sink,
                   const ExtraSceneCheck& extra = {}, const SurfaceReader& readSurface = {},
                   const MeshReader& readMesh = {});

// lib/core's checks of `doc` as rscene-validate runs them (syntax, types,
// references, sizes; no files, the Engine 2 profile), errors only.  A tool
// that interprets the scene (rscene-sim, rscene-render, rscene-to-xml) runs
// this before it builds the scene model, so that it stops at the finding
// validate reports, with its code and column, and the model never judges a
// value that does not parse (a scale written `1x` is RS2001, not also a
// zero-size box).  When there are errors, `out` gets validate's findings
// (warnings too) in validate's order (with `extra`'s, lib/robot's robot checks).  False when
// it added an error.
bool checkDocument(const Document& doc, const std::string& sceneDir, Diagnostics& out,
                   const ExtraSceneCheck& extra = {});

}  // namespace rscene
