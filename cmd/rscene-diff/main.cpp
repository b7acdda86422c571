// rscene-diff: semantic diff of two scenes; also git's external diff driver.
#include <CLI/CLI.hpp>
#include <iostream>
#include <thread>

#include "common/cli.hpp"
#include "core/diff.hpp"
#include "core/loader.hpp"
#include "rscene-diff/render.hpp"

namespace {

using namespace rscene;

struct Side {
  cli::Input in;
  LoadResult loaded;
  bool read = false;
};

// Reads one side; git passes /dev/null for a file that does not exist on
// that side, which is an empty scene here.
bool readSide(const std::string& operand, const std::string& stdinName, bool git, Side& s) {
  if (git && operand == "/dev/null") {
    s.in.display = operand;
    s.read = true;
    return true;
  }
  s.read = cli::readInput(operand, stdinName, s.in);
  return s.read;
}

void load(Side& s) {
  if (s.in.display == "/dev/null" && s.in.text.empty()) return;  // empty scene
  s.loaded = parse(std::move(s.in.text));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Compare two .rscene scenes by record identity and show what changed."};
  cli::setup(app, "rscene-diff");
  std::vector<std::string> files;
  std::string format = "text", stdinName, ignoreList;
  bool statOnly = false, quiet = false;
  DiffOptions opt;
  app.add_option("files", files,
                 "OLD NEW (- reads standard input), or git's seven arguments: PATH OLD-FILE OLD-HEX OLD-MODE "
                 "NEW-FILE NEW-HEX NEW-MODE")
      ->type_name("FILE")
      ->required()
      ->expected(2, 7);
  app.add_flag("--stat", statOnly, "Print counts of added, removed and changed records per kind");
  app.add_option("--format", format, "Output format: text (default) or json")
      ->type_name("FORMAT")
      ->check(CLI::IsMember({"text", "json"}));
  app.add_option("--tolerance", opt.tolerance, "Numbers (also in vectors and lists) that differ by at most ABS are equal")
      ->type_name("ABS")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--rel-tolerance", opt.relTolerance, "Numbers that differ by at most REL times the larger are equal")
      ->type_name("REL")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--ignore-editor-state", opt.ignoreEditorState,
               "Skip snapping, editor_ux, render_bake and the locked, expanded and selection* fields");
  app.add_option("--ignore", ignoreList, "Skip these fields (NAME or TAG.NAME, comma-separated)")->type_name("KEY,...");
  app.add_flag("-q,--quiet", quiet, "Print nothing; the exit status tells whether the scenes differ");
  cli::addStdinFilename(app, stdinName, false);
  if (int rc = cli::parseArgs(app, argc, argv); rc >= 0) return rc;

  bool git = files.size() == 7;
  if (files.size() != 2 && !git) {
    cli::error("expected OLD NEW, or git's seven external-diff arguments; got " + std::to_string(files.size()));
    return cli::kTrouble;
  }
  for (std::size_t start = 0; start < ignoreList.size();) {
    std::size_t comma = ignoreList.find(',', start);
    if (comma == std::string::npos) comma = ignoreList.size();
    if (comma > start) opt.ignore.push_back(ignoreList.substr(start, comma - start));
    start = comma + 1;
  }
  const std::string& oldFile = git ? files[1] : files[0];
  const std::string& newFile = git ? files[4] : files[1];
  if (oldFile == "-" && newFile == "-") {
    cli::error("only one of OLD and NEW can be standard input");
    return cli::kTrouble;
  }
  // In git mode a failure is reported but git goes on to the next file.
  const int trouble = git ? cli::kSuccess : cli::kTrouble;
  Side a, b;
  if (!readSide(oldFile, stdinName, git, a) || !readSide(newFile, stdinName, git, b)) return trouble;
  std::thread loader([&] { load(a); });
  load(b);
  loader.join();
  bool color = cli::colorFor(2);
  cli::printDiagnostics(a.loaded.diagnostics, a.in.display, a.loaded.document.buffer(), color);
  cli::printDiagnostics(b.loaded.diagnostics, b.in.display, b.loaded.document.buffer(), color);
  if (!a.loaded.ok() || !b.loaded.ok()) return trouble;
  for (const std::string& entry : opt.ignore)
    if (auto problem = checkIgnoreName(entry, a.loaded.document, b.loaded.document)) {
      cli::error("--ignore: " + *problem);
      return trouble;
    }

  DiffResult result = diff(a.loaded.document, b.loaded.document, opt);
  if (!quiet) {
    std::string out;
    if (format == "json") {
      out = diffToJson(result);
    } else if (!result.same()) {
      if (git) out = "rscene-diff a/" + files[0] + " b/" + files[0] + "\n";
      out += statOnly ? diffout::stat(result) : diffout::blocks(result, cli::colorFor(1));
    }
    std::cout << out << std::flush;
    if (!std::cout) {
      cli::error("cannot write standard output");
      return cli::kTrouble;
    }
  }
  if (git) return cli::kSuccess;
  return result.same() ? cli::kSuccess : cli::kFindings;
}
