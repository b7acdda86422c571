// rscene-validate: lints scenes (syntax, types, references, sizes, files)
// and reports the findings as text, JSON or SARIF.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <set>

#include "common/cli.hpp"
#include "core/check.hpp"
#include "robot/check.hpp"
#include "asset/cache.hpp"
#include "asset/obj_surface.hpp"
#include "scene/validate.hpp"
#include "rscene-validate/output.hpp"

namespace {

using namespace rscene;

struct Options {
  std::vector<std::string> files;
  std::string format = "text";
  std::string profile = "engine2";
  std::string color = "auto";
  std::vector<std::string> ignore, only;
  std::size_t maxIssues = 0;  // 0 = all
  bool strict = false;
  bool listChecks = false;
  bool checkFiles = false;
  std::string baseDir;
  std::string stdinName;
};

// Every code any tool emits (the registry in core/check_codes.cpp), with
// the tools that report it.
void listChecks() {
  for (const CheckInfo& c : checkTable())
    std::cout << c.code << "  " << (c.severity == Severity::Error ? "error  " : "warning") << "  " << std::left
              << std::setw(19) << c.tools << "  " << c.summary << '\n';
}

// Every code named by --ignore/--only must exist, so a typo is not silent.
bool knownCodes(const std::vector<std::string>& codes, const char* flag) {
  for (const std::string& c : codes)
    if (!checkInfo(c)) {
      cli::error(std::string("unknown code '") + c + "' in " + flag + " (see --list-checks)");
      return false;
    }
  return true;
}

struct Run {
  const Options& opt;
  validate::Reporter& reporter;
  std::set<std::string> ignore, only;
  validate::Totals totals;
  bool failed = false;  // findings at failing severity

  bool wanted(const Diagnostic& d) const {
    if (ignore.count(d.code)) return false;
    return only.empty() || only.count(d.code);
  }

  // Counts every wanted finding as it is found and keeps only those
  // --max-issues lets through, so memory does not grow with the count.
  // A streaming reporter prints them at once instead.
  struct Keep : DiagnosticSink {
    Run& run;
    const std::string& name;
    const Document* doc;    // its buffer holds the text while the check runs
    std::string_view text;  // or the text itself (a project file)
    validate::FileCounts counts;
    Diagnostics shown;
    Keep(Run& r, const std::string& n, const Document& d) : run(r), name(n), doc(&d) {}
    Keep(Run& r, const std::string& n, std::string_view t) : run(r), name(n), doc(nullptr), text(t) {}
    std::string_view buffer() const { return doc ? doc->buffer() : text; }
    void add(Diagnostic d) override {
      if (!run.wanted(d)) return;
      bool error = d.severity == Severity::Error;
      (error ? counts.errors : counts.warnings)++;
      if (error || run.opt.strict) run.failed = true;
      if (run.opt.maxIssues == 0 || run.totals.shown < run.opt.maxIssues) {
        ++run.totals.shown;
        if (run.reporter.streams()) run.reporter.finding(name, buffer(), d);
        else shown.push_back(std::move(d));
      }
    }
  };

  // Checks one operand; false on an I/O error.
  bool file(const std::string& operand) {
    cli::Input in;
    if (!cli::readInput(operand, opt.stdinName, in)) return false;
    CheckOptions co;
    co.profile = opt.profile == "raisim" ? Profile::RaiSim : Profile::Engine2;
    co.checkFiles = opt.checkFiles;
    co.sceneDir = in.isStdin && !opt.baseDir.empty() ? opt.baseDir : directoryOf(in.path);
    co.project = cli::projectPlace(in, opt.baseDir);
    Document doc;
    Keep keep(*this, in.display, doc);
    // Robots are checked against their models (lib/robot, above lib/scene):
    // one model cache per scene, so each scene reports its robots' files.
    robot::ModelCache models;
    asset::AssetCache meshes;  // --check-files reads each mesh once, as sim would
    robot::RobotCheckOptions ro{co.checkFiles, co.fileExists, meshes.meshReader(asset::MeshContent::Geometry)};
    validateScene(std::move(in.text), co, doc, keep,
                  [&](const Document& d, const Scene& s, std::vector<SceneFinding>& out) {
                    robot::checkRobots(d, s, ro, models, out);
                  },
                  asset::objSurfaceReader(diskFileSystem()), meshes.meshReader(asset::MeshContent::Geometry));
    totals.errors += keep.counts.errors;
    totals.warnings += keep.counts.warnings;
    ++totals.files;
    reporter.file(in.display, doc.buffer(), keep.shown, keep.counts);
    return true;
  }

  // Checks an Engine 2 project's file (its scenes are operands of their
  // own); false on an I/O error.
  bool project(const std::string& root) {
    std::string text;
    ProjectRead read;
    if (!cli::readProjectFile(root, text, read)) return false;
    const std::string& name = read.project.file;
    Keep keep(*this, name, text);
    for (Diagnostic& d : read.diagnostics) keep.add(std::move(d));
    totals.errors += keep.counts.errors;
    totals.warnings += keep.counts.warnings;
    ++totals.files;
    reporter.file(name, text, keep.shown, keep.counts);
    return true;
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Check .rscene scenes for syntax, type, reference, size and file errors."};
  cli::setup(app, "rscene-validate");
  Options opt;
  cli::addInputOperands(app, opt.files);
  app.add_option("--format", opt.format, "Output format: text, json or sarif")
      ->check(CLI::IsMember({"text", "json", "sarif"}))
      ->type_name("FORMAT");
  app.add_flag("--strict", opt.strict, "Fail (exit 1) on warnings too");
  app.add_option("--ignore", opt.ignore, "Do not report these codes")->delimiter(',')->type_name("CODE,...")->allow_extra_args(false);
  app.add_option("--only", opt.only, "Report only these codes")->delimiter(',')->type_name("CODE,...")->allow_extra_args(false);
  app.add_option("--max-issues", opt.maxIssues, "Show at most N findings (the summary counts all)")
      ->type_name("N")
      ->check(cli::count(1));
  app.add_flag("--list-checks", opt.listChecks, "List every code any tool emits, with its severity, tools and meaning, then exit");
  app.add_option("--profile", opt.profile, "engine2 (what Engine 2 loads) or raisim (also what RaiSim refuses)")
      ->check(CLI::IsMember({"engine2", "raisim"}))
      ->type_name("PROFILE");
  app.add_flag("--check-files", opt.checkFiles, "Check that every referenced asset file exists, and read robot files (URDF, MJCF)");
  cli::addBaseDir(app, opt.baseDir, "Resolve standard input's asset paths from DIR");
  cli::addStdinFilename(app, opt.stdinName, true);
  app.add_option("--color", opt.color, "Color the text output: auto, always or never")
      ->check(CLI::IsMember({"auto", "always", "never"}))
      ->type_name("WHEN");
  if (int rc = cli::parseArgs(app, argc, argv); rc >= 0) return rc;

  if (opt.listChecks) {
    listChecks();
    return cli::kSuccess;
  }
  if (!knownCodes(opt.ignore, "--ignore") || !knownCodes(opt.only, "--only")) return cli::kTrouble;
  if (opt.files.empty()) opt.files.push_back("-");
  if (std::count(opt.files.begin(), opt.files.end(), "-") > 1) {
    cli::error("standard input can be read only once");
    return cli::kTrouble;
  }

  bool color = opt.color == "always" || (opt.color == "auto" && cli::colorFor(1));
  std::unique_ptr<validate::Reporter> reporter = opt.format == "json"    ? validate::jsonReporter()
                                                 : opt.format == "sarif" ? validate::sarifReporter()
                                                                         : validate::textReporter(color);
  cli::Operands operands = cli::expandOperands(opt.files, false);
  Run run{opt, *reporter, {opt.ignore.begin(), opt.ignore.end()}, {opt.only.begin(), opt.only.end()}, {}, false};
  bool trouble = !operands.ok;
  for (const std::string& p : operands.projects) trouble = !run.project(p) || trouble;
  for (const std::string& f : operands.files) trouble = !run.file(f) || trouble;
  if (!reporter->finish(run.totals)) {
    cli::error("cannot write standard output");
    return cli::kTrouble;
  }
  if (trouble) return cli::kTrouble;
  return run.failed ? cli::kFindings : cli::kSuccess;
}
