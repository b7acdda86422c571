#include "scene/validate.hpp"

#include <algorithm>
#include <set>
#include <tuple>

#include "core/loader.hpp"
#include "scene/check.hpp"
#include "scene/scene.hpp"

namespace rscene {
namespace {

// Inserts each of `extra` after the last finding of `out` at or before its
// line and column (core's findings come in record order, each record's in
// column order), unless `out` already has its code on that line.
void merge(Diagnostics& out, Diagnostics extra) {
  std::set<std::pair<std::uint32_t, std::string>> seen;
  for (const Diagnostic& d : out) seen.emplace(d.line, d.code);
  for (Diagnostic& d : extra) {
    if (!seen.emplace(d.line, d.code).second) continue;
    auto at = std::find_if(out.rbegin(), out.rend(), [&](const Diagnostic& o) {
      return o.line < d.line || (o.line == d.line && o.column <= d.column);
    });
    out.insert(at.base(), std::move(d));
  }
}

}  // namespace

Diagnostics validateScene(std::string text, const CheckOptions& options, Document& doc) {
  LoadResult loaded = parse(std::move(text));
  doc = std::move(loaded.document);
  if (!loaded.ok()) return std::move(loaded.diagnostics);
  Diagnostics out = std::move(loaded.diagnostics);
  Diagnostics found = check(doc, options);
  hintContinuations(loaded.continuedLines, found);
  out.insert(out.end(), std::make_move_iterator(found.begin()), std::make_move_iterator(found.end()));

  SceneOptions so;
  so.sceneDir = options.sceneDir;
  so.exists = options.fileExists;
  so.bodiesOnly = true;  // the rest is lib/core's to check; keeps validate fast on large scenes
  Scene scene;
  Diagnostics model;
  buildScene(doc, so, scene, model);
  SceneCheckOptions sc;
  sc.checkFiles = options.checkFiles;
  sc.exists = options.fileExists;
  checkScene(doc, scene, sc, model);
  hintContinuations(loaded.continuedLines, model);
  merge(out, std::move(model));
  return out;
}

}  // namespace rscene
