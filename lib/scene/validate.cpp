#include "scene/validate.hpp"

#include <algorithm>
#include <string_view>
#include <tuple>
#include <unordered_map>

#include "core/loader.hpp"
#include "scene/check.hpp"
#include "scene/scene.hpp"

namespace rscene {
namespace {

// The scene model's findings, sorted by the scene line they are listed at
// and column.  A finding with a code of lib/core's layer (a value that does
// not parse, a reference to no node, a missing file ...) is left out:
// lib/core's validator checks that condition itself and reports it at the
// same field, so keeping the model's copy would double it.  (This replaces
// a second pass of core's checks that used to find the repeats.)  A finding
// inside another file (a robot's URDF: its RS5001 for a mesh is no core
// finding) is kept, listed after its scene record's own findings.
struct ModelFindings {
  Diagnostics list;
  std::vector<std::uint32_t> lines;  // per finding: the scene line it is listed at

  explicit ModelFindings(std::vector<SceneFinding> found) {
    std::stable_sort(found.begin(), found.end(), [](const SceneFinding& a, const SceneFinding& b) {
      return std::tuple(a.sceneLine, !a.diagnostic.file.empty(), a.diagnostic.column) <
             std::tuple(b.sceneLine, !b.diagnostic.file.empty(), b.diagnostic.column);
    });
    auto core = [](const Diagnostic& d) {
      const CheckInfo* info = checkInfo(d.code);
      return d.file.empty() && info && info->layer == CheckLayer::Core;
    };
    for (SceneFinding& f : found) {
      if (core(f.diagnostic)) continue;
      lines.push_back(f.sceneLine);
      list.push_back(std::move(f.diagnostic));
    }
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
  bool next_model() const { return i_ < model_.list.size(); }
  ModelFindings& model_;
  DiagnosticSink& next_;
  std::size_t i_ = 0;
};

// A field whose value does not parse is not judged again by the model:
// the model read a fallback there (a scale written `1x` would also be a
// zero-size box).  One typo, one error (the reader's, which is core's code
// and which core reports itself).  A model finding is dropped when a
// reader error of its line falls inside the token it points at.
void dropJudgedAgain(const Document& doc, Diagnostics& found) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> unparsed;  // (line, column)
  for (const Diagnostic& d : found) {
    const CheckInfo* info = checkInfo(d.code);
    if (d.file.empty() && d.severity == Severity::Error && info && info->layer == CheckLayer::Core)
      unparsed.emplace_back(d.line, d.column);
  }
  if (unparsed.empty()) return;
  std::sort(unparsed.begin(), unparsed.end());
  std::unordered_map<std::uint32_t, const Record*> byLine;
  for (const Record& r : doc.records) byLine.emplace(r.line, &r);
  auto judgedAgain = [&](const Diagnostic& d) {
    const CheckInfo* info = checkInfo(d.code);
    if (!d.file.empty() || !info || info->layer == CheckLayer::Core || d.column == 0) return false;
    auto it = byLine.find(d.line);
    if (it == byLine.end()) return false;
    std::string_view text = doc.sourceLine(*it->second);
    std::size_t end = text.find_first_of(" \t", d.column - 1);
    auto last = static_cast<std::uint32_t>(end == std::string_view::npos ? text.size() : end);
    auto lo = std::lower_bound(unparsed.begin(), unparsed.end(), std::pair{d.line, d.column});
    return lo != unparsed.end() && lo->first == d.line && lo->second <= last;
  };
  found.erase(std::remove_if(found.begin(), found.end(), judgedAgain), found.end());
}

}  // namespace

void validateScene(std::string text, const CheckOptions& options, Document& doc, DiagnosticSink& sink,
                   const ExtraSceneCheck& extra, const SurfaceReader& readSurface, const MeshReader& readMesh) {
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
  so.project = options.project;
  so.exists = options.fileExists;
  so.bodiesOnly = true;  // the rest is lib/core's to check; keeps validate fast on large scenes
  Scene scene;
  Diagnostics found;
  buildScene(doc, so, scene, found);
  SceneCheckOptions sc;
  sc.checkFiles = options.checkFiles;
  sc.exists = options.fileExists;
  if (options.checkFiles) {
    sc.readSurface = readSurface;
    sc.readMesh = readMesh;
    sc.visualAssets = true;
  }
  checkScene(doc, scene, sc, found);
  hintContinuations(loaded.continuedLines, found);
  dropJudgedAgain(doc, found);
  std::vector<SceneFinding> listed;
  listed.reserve(found.size());
  for (Diagnostic& d : found) listed.push_back({d.line, std::move(d)});
  if (extra) extra(doc, scene, listed);
  ModelFindings model(std::move(listed));

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

bool checkDocument(const Document& doc, const std::string& sceneDir, Diagnostics& out, const ExtraSceneCheck& extra) {
  struct Errors : DiagnosticSink {
    Diagnostics* out;
    bool warnings = false;  // keep warnings too
    bool any = false;
    void add(Diagnostic d) override {
      if (d.severity == Severity::Error) any = true;
      else if (!warnings) return;
      if (out) out->push_back(std::move(d));
    }
  };
  CheckOptions options;
  options.sceneDir = sceneDir;
  Errors core;
  core.out = nullptr;
  check(doc, options, core);
  if (!core.any) return true;
  // The findings, and their order, are rscene-validate's: core's merged
  // with the model's and the robots' by line and column, warnings too.  Only a scene
  // with errors pays for this second reading.
  Errors all;
  all.out = &out;
  all.warnings = true;  // validate's whole list: its warnings too
  Document again;
  validateScene(std::string(doc.buffer()), options, again, all, extra);
  return false;
}

}  // namespace rscene
