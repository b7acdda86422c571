#include "scene/validate.hpp"

#include <algorithm>
#include <set>
#include <tuple>

#include "core/loader.hpp"
#include "scene/check.hpp"
#include "scene/scene.hpp"

namespace rscene {
namespace {

// Merges `extra` into `out` by line and column (core's findings come in
// record order, each record's in column order; ties keep core's first),
// leaving out one whose code `out` already has on that line.  Linear after
// sorting `extra`, so a scene with a million findings stays fast.
void merge(Diagnostics& out, Diagnostics extra) {
  if (extra.empty()) return;
  std::set<std::pair<std::uint32_t, std::string>> seen;  // copies: `out` is moved from below
  for (const Diagnostic& d : out) seen.emplace(d.line, d.code);
  std::stable_sort(extra.begin(), extra.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return std::tie(a.line, a.column) < std::tie(b.line, b.column);
  });
  Diagnostics merged;
  merged.reserve(out.size() + extra.size());
  std::size_t i = 0;
  auto before = [](const Diagnostic& o, const Diagnostic& d) {
    return o.line < d.line || (o.line == d.line && o.column <= d.column);
  };
  for (Diagnostic& d : extra) {
    if (seen.count({d.line, d.code})) continue;
    while (i < out.size() && before(out[i], d)) merged.push_back(std::move(out[i++]));
    merged.push_back(std::move(d));
  }
  while (i < out.size()) merged.push_back(std::move(out[i++]));
  out = std::move(merged);
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
