// The validation pass: everything wrong with a scene, as Diagnostics with
// stable codes (check_codes.cpp holds the table of every code).  Pure: file
// existence is asked through a callback, nothing is printed.
#pragma once
#include <span>
#include <string>
#include <string_view>

#include "core/assets.hpp"
#include "core/diagnostic.hpp"
#include "core/document.hpp"

namespace rscene {

enum class Profile {
  Engine2,  // what Engine 2 loads
  RaiSim,   // also what RaiSim 2.7.1's stricter reader refuses (RS6xxx)
};

struct CheckOptions {
  Profile profile = Profile::Engine2;
  bool checkFiles = false;     // RS5xxx: asset paths must name existing files
  std::string sceneDir = ".";  // directory relative asset paths start from
  ProjectPlace project;        // the Engine 2 project the scene is in (core/assets.hpp), if any
  FileExists fileExists = fileExistsOnDisk;
};

// Receives findings one at a time, in the order they are reported, so a
// caller can count every finding but keep only some: rscene-validate
// --max-issues keeps memory bounded on a file with millions of findings.
class DiagnosticSink {
 public:
  virtual ~DiagnosticSink() = default;
  virtual void add(Diagnostic d) = 0;
};

// A sink that keeps every finding, for callers that want them all.
class CollectDiagnostics : public DiagnosticSink {
 public:
  void add(Diagnostic d) override { all.push_back(std::move(d)); }
  Diagnostics all;
};

// Checks a loaded document.  Findings come in record order.
Diagnostics check(const Document& doc, const CheckOptions& options);
// The same findings in the same order, handed to `sink` as each record is
// done: memory holds one record's findings, not the file's.
void check(const Document& doc, const CheckOptions& options, DiagnosticSink& sink);

// Loads `text` and checks it: the loader's own errors (RS1xxx) are findings
// too, and stop the check of that text.  `doc` receives the parsed scene
// (its buffer holds the source lines for carets).
Diagnostics validateText(std::string text, const CheckOptions& options, Document& doc);

// Where a condition is checked: the layer that owns the check.
enum class CheckLayer {
  Core,    // lib/core's validator (check(), the loader before it)
  Scene,   // lib/scene: scene/check.hpp, called by validate, sim and render
  Sim,     // lib/sim: what only building the Bullet world finds
  Json,    // lib/core's JSON reader (rscene-from-json)
  Xml,     // lib/xml: RaiSim world XML both ways (rscene-from-xml, rscene-to-xml)
  Render,  // lib/render: what only drawing finds
  Robot,   // lib/robot: reading a URDF or MJCF model, and what the model says of a record
};

// One row of the registry of every diagnostic code any tool emits: used by
// `rscene-validate --list-checks`, the man pages and the tests (a test
// greps lib/ and cmd/ for codes and asserts each is here).
struct CheckInfo {
  std::string_view code;
  Severity severity;
  CheckLayer layer;
  std::string_view tools;    // the tools that report it, e.g. "validate sim render"
  std::string_view summary;  // one line, lower-case, no final period
};
std::span<const CheckInfo> checkTable();
const CheckInfo* checkInfo(std::string_view code);

}  // namespace rscene
