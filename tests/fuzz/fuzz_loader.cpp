// Feeds arbitrary bytes to the loader.  Whatever loads must satisfy the two
// invariants of the canonical form (DESIGN.md): formatting is a fixed
// point, and the formatted text parses back to the same scene record for
// record.  A violation aborts with the input's first difference, so that
// libFuzzer saves the input as a crash artifact.
//
// Every input that loads is also validated (rscene::check with the engine2
// and raisim profiles, file checks off, and validateScene from the bytes,
// which adds the scene model's checks as rscene-validate runs them), and
// the full scene model is built and checked as sim and render do: none may
// crash or throw, and each finding must carry a known code, a line of the
// input and a column inside that line, and render.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "core/check.hpp"
#include "core/io.hpp"
#include "core/loader.hpp"
#include "scene/check.hpp"
#include "scene/scene.hpp"
#include "scene/validate.hpp"
#include "core/report.hpp"
#include "core/writer.hpp"

namespace {

[[noreturn]] void fail(const char* invariant, const std::string& detail) {
  std::fprintf(stderr, "fuzz_loader: invariant broken: %s\n%s\n", invariant, detail.c_str());
  std::abort();
}

// The first line where two texts differ, quoted from both.
std::string firstDifference(std::string_view a, std::string_view b) {
  std::size_t i = 0, line = 1, start = 0;
  while (i < a.size() && i < b.size() && a[i] == b[i]) {
    if (a[i] == '\n') {
      ++line;
      start = i + 1;
    }
    ++i;
  }
  auto lineAt = [&](std::string_view s) {
    std::string_view rest = s.substr(std::min(start, s.size()));
    return std::string(rest.substr(0, std::min(rest.find('\n'), std::size_t{200})));
  };
  return "line " + std::to_string(line) + ":\n  fmt(x):      " + lineAt(a) + "\n  fmt(fmt(x)): " + lineAt(b);
}

// Validates a loaded document under one profile and checks each finding.
void validate(const rscene::Document& doc, rscene::Profile profile) {
  rscene::CheckOptions options;
  options.profile = profile;
  options.checkFiles = false;
  rscene::Diagnostics found = rscene::check(doc, options);
  if (found.empty()) return;
  std::vector<const rscene::Record*> byLine(doc.records.back().line + 1, nullptr);
  for (const rscene::Record& r : doc.records) byLine[r.line] = &r;
  for (const rscene::Diagnostic& d : found) {
    if (!rscene::checkInfo(d.code)) fail("findings have a known code", d.code + ": " + d.message);
    if (d.line == 0 || d.line >= byLine.size() || !byLine[d.line])
      fail("findings name the line of a record", d.code + " on line " + std::to_string(d.line));
    std::string_view line = doc.sourceLine(*byLine[d.line]);
    if (d.column > line.size() + 1)
      fail("findings point inside their line",
           d.code + " at column " + std::to_string(d.column) + " of a line of " + std::to_string(line.size()));
    if (rscene::formatDiagnostic(d, "fuzz.rscene", line, false).empty()) fail("findings render", d.code);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rscene::LoadResult first = rscene::parse(std::string(reinterpret_cast<const char*>(data), size));
  if (!first.ok()) return 0;  // refused input: the loader's only duty was not to crash
  validate(first.document, rscene::Profile::Engine2);
  validate(first.document, rscene::Profile::RaiSim);
  {
    rscene::Document doc;
    rscene::CheckOptions options;
    rscene::validateScene(std::string(reinterpret_cast<const char*>(data), size), options, doc);
    rscene::SceneOptions sceneOptions;
    sceneOptions.exists = [](const std::string&) { return false; };
    rscene::Scene scene;
    rscene::Diagnostics diagnostics;
    rscene::buildScene(first.document, sceneOptions, scene, diagnostics);
    rscene::checkScene(first.document, scene, {}, diagnostics);
    for (const rscene::Diagnostic& d : diagnostics)
      if (!rscene::checkInfo(d.code)) fail("scene model codes are registered", d.code + ": " + d.message);
  }
  std::string once = rscene::canonicalText(first.document);
  rscene::LoadResult second = rscene::parse(once);
  if (!second.ok())
    fail("parse(fmt(x)) succeeds", rscene::firstError(second.diagnostics) + "\nfmt(x):\n" + once.substr(0, 2000));
  std::string twice = rscene::canonicalText(second.document);
  if (twice != once) fail("fmt(fmt(x)) == fmt(x)", firstDifference(once, twice));
  std::string why;
  if (!rscene::sameDocument(first.document, second.document, &why))
    fail("sameDocument(parse(x), parse(fmt(x)))", why);
  return 0;
}
