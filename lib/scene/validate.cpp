#include "scene/validate.hpp"

#include <algorithm>
#include <map>
#include <string_view>
#include <tuple>

#include "core/loader.hpp"
#include "scene/check.hpp"
#include "scene/scene.hpp"

namespace rscene {
namespace {

// The scene model's findings, sorted by the scene line they are listed at
// and column, with the ones that repeat a core finding (same line and code)
// to be dropped.  A finding inside another file (a robot's URDF) is listed
// after its scene record's own findings and never repeats a core finding.
struct ModelFindings {
  Diagnostics list;
  std::vector<std::uint32_t> lines;  // per finding: the scene line it is listed at
  std::vector<bool> dropped;
  std::multimap<std::pair<std::uint32_t, std::string_view>, std::size_t> byLineCode;

  explicit ModelFindings(std::vector<SceneFinding> found) {
    std::stable_sort(found.begin(), found.end(), [](const SceneFinding& a, const SceneFinding& b) {
      return std::tuple(a.sceneLine, !a.diagnostic.file.empty(), a.diagnostic.column) <
             std::tuple(b.sceneLine, !b.diagnostic.file.empty(), b.diagnostic.column);
    });
    for (SceneFinding& f : found) {
      lines.push_back(f.sceneLine);
      list.push_back(std::move(f.diagnostic));
    }
    dropped.assign(list.size(), false);
    for (std::size_t i = 0; i < list.size(); ++i)
      if (list[i].file.empty()) byLineCode.emplace(std::pair{list[i].line, std::string_view(list[i].code)}, i);
  }
  void dropRepeatsOf(const Diagnostic& core) {
    auto [from, to] = byLineCode.equal_range({core.line, std::string_view(core.code)});
    for (auto it = from; it != to; ++it) dropped[it->second] = true;
  }
  // Where finding i sorts among core findings: its scene line, and its
  // column (after every column when it is in another file).
  std::pair<std::uint32_t, std::uint32_t> place(std::size_t i) const {
    return {lines[i], list[i].file.empty() ? list[i].column : UINT32_MAX};
  }
};

// Adds the loader's line-continuation hint to each core finding on its way.
class HintSink : public DiagnosticSink {
 public:
  HintSink(const std::vector<std::uint32_t>& continued, DiagnosticSink& next) : continued_(continued), next_(next) {}
  void add(Diagnostic d) override {
    if (!continued_.empty()) {
      Diagnostics one{std::move(d)};
      hintContinuations(continued_, one);
      d = std::move(one.front());
    }
    next_.add(std::move(d));
  }

 private:
  const std::vector<std::uint32_t>& continued_;
  DiagnosticSink& next_;
};

// First pass when the model found something: which of its findings a core
// finding repeats.  Keeps nothing.
class MarkRepeats : public DiagnosticSink {
 public:
  explicit MarkRepeats(ModelFindings& model) : model_(model) {}
  void add(Diagnostic d) override { model_.dropRepeatsOf(d); }

 private:
  ModelFindings& model_;
};

// Merges the model's findings into the stream of core findings by line and
// column (ties keep core's first), as they pass: a model finding goes out
// just before the first core finding that is not before it.
class MergeSink : public DiagnosticSink {
 public:
  MergeSink(ModelFindings& model, DiagnosticSink& next) : model_(model), next_(next) {}
  void add(Diagnostic o) override {
    while (next_model() && !before(o, model_.place(i_))) next_.add(std::move(model_.list[i_++]));
    next_.add(std::move(o));
  }
  // Sends the model's findings after the last core finding.
  void finish() {
    while (next_model()) next_.add(std::move(model_.list[i_++]));
  }

 private:
  static bool before(const Diagnostic& o, std::pair<std::uint32_t, std::uint32_t> d) {
    return o.line < d.first || (o.line == d.first && o.column <= d.second);
  }
  // Skips dropped findings; whether one is left.
  bool next_model() {
    while (i_ < model_.list.size() && model_.dropped[i_]) ++i_;
    return i_ < model_.list.size();
  }
  ModelFindings& model_;
  DiagnosticSink& next_;
  std::size_t i_ = 0;
};

}  // namespace

void validateScene(std::string text, const CheckOptions& options, Document& doc, DiagnosticSink& sink,
                   const ExtraSceneCheck& extra) {
  LoadResult loaded = parse(std::move(text));
  doc = std::move(loaded.document);
  if (!loaded.ok()) {
    for (Diagnostic& d : loaded.diagnostics) sink.add(std::move(d));
    return;
  }

  // The scene model's checks first: their findings are few (bodies only)
  // and must be known to merge them into core's as those stream past.
  SceneOptions so;
  so.sceneDir = options.sceneDir;
  so.exists = options.fileExists;
  so.bodiesOnly = true;  // the rest is lib/core's to check; keeps validate fast on large scenes
  Scene scene;
  Diagnostics found;
  buildScene(doc, so, scene, found);
  SceneCheckOptions sc;
  sc.checkFiles = options.checkFiles;
  sc.exists = options.fileExists;
  checkScene(doc, scene, sc, found);
  hintContinuations(loaded.continuedLines, found);
  std::vector<SceneFinding> listed;
  listed.reserve(found.size());
  for (Diagnostic& d : found) listed.push_back({d.line, std::move(d)});
  if (extra) extra(doc, scene, listed);
  ModelFindings model(std::move(listed));

  // A model finding is dropped when any core finding repeats it, even one
  // that streams past after it.  Knowing that takes a pass over core's
  // findings before the one that reports: checking twice (only when the
  // model found something) costs time, holding core's findings would cost
  // memory without bound.
  if (!model.list.empty()) {
    MarkRepeats marks(model);
    for (const Diagnostic& d : loaded.diagnostics) marks.add(d);
    check(doc, options, marks);
  }
  MergeSink merge(model, sink);
  for (Diagnostic& d : loaded.diagnostics) merge.add(std::move(d));
  loaded.diagnostics.clear();
  HintSink hinted(loaded.continuedLines, merge);
  check(doc, options, hinted);
  merge.finish();
}

Diagnostics validateScene(std::string text, const CheckOptions& options, Document& doc) {
  CollectDiagnostics all;
  validateScene(std::move(text), options, doc, all);
  return std::move(all.all);
}

}  // namespace rscene
