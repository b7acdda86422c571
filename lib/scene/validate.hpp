// rscene-validate's full check of one scene: lib/core's validator (syntax,
// types, references, sizes, files, profiles) plus the scene model's checks
// (scene/check.hpp), i.e. everything rscene-sim and rscene-render refuse.
// It lives here because lib/core cannot see the scene model.
#pragma once
#include <string>

#include "core/check.hpp"
#include "core/diagnostic.hpp"
#include "core/document.hpp"

namespace rscene {

// Loads `text` and checks it.  The loader's errors stop the check, as in
// validateText().  Scene-model findings are merged in by line, and one that
// repeats a core finding (same line and code) is dropped, so a condition is
// reported once.  `doc` receives the parsed scene.
Diagnostics validateScene(std::string text, const CheckOptions& options, Document& doc);
// The same findings in the same order, handed to `sink` one at a time: the
// core's are not held, so a caller that keeps few holds little.  `doc`
// holds the text from the first call of the sink on, for source lines.
void validateScene(std::string text, const CheckOptions& options, Document& doc, DiagnosticSink& sink);

}  // namespace rscene
