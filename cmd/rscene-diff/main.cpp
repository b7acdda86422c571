// rscene-diff: semantic diff of two scenes; also git's external diff driver.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <functional>
#include <iostream>
#include <thread>

#include "common/cli.hpp"
#include "core/assets.hpp"
#include "core/diff.hpp"
#include "core/diff_lines.hpp"
#include "core/loader.hpp"
#include "core/report.hpp"
#include "rscene-diff/render.hpp"
#include "rscene-diff/review.hpp"
#include "robot/entry_names.hpp"

namespace {

using namespace rscene;

struct Side {
  cli::Input in;
  std::size_t size = 0;  // the input's bytes stay at the start of the document's buffer
  LoadResult loaded;
  bool empty = false;    // git's /dev/null: the file does not exist on this side
  std::string_view text() const { return std::string_view(loaded.document.buffer()).substr(0, size); }
};

// Reads one side; git passes /dev/null for a file that does not exist on
// that side, which is an empty scene here.
bool readSide(const std::string& operand, const std::string& stdinName, bool git, Side& s) {
  if (git && operand == "/dev/null") {
    s.in.display = operand;
    s.empty = true;
    return true;
  }
  return cli::readInput(operand, stdinName, s.in);
}

void load(Side& s) {
  if (s.empty) return;
  s.size = s.in.text.size();
  s.loaded = parse(std::move(s.in.text));
}

// git mode, a side that does not parse: git must go on (a non-zero exit
// stops `git diff` and `git log -p` for good), so say why on stderr and
// show what changed as lines.
std::string lineDiff(const Side& a, const Side& b, const std::string& oldName, const std::string& newName) {
  for (const Side* s : {&a, &b}) {
    const Diagnostics& ds = s->loaded.diagnostics;
    auto error = std::find_if(ds.begin(), ds.end(), [](const Diagnostic& d) { return d.severity == Severity::Error; });
    if (s->empty || error == ds.end()) continue;
    Diagnostic w = *error;
    w.severity = Severity::Warning;
    w.message += "; showing a line diff";
    w.hint.clear();
    std::cerr << formatDiagnostic(w, s == &a ? oldName : newName, {}, cli::colorFor(2));
  }
  std::string out = "rscene-diff " + oldName + " " + newName + "\n";
  if (looksBinary(a.text()) || looksBinary(b.text()))
    return a.text() == b.text() ? std::string() : out + "Binary files " + oldName + " and " + newName + " differ\n";
  std::string lines = unifiedDiff(a.text(), b.text(), oldName, newName);
  return lines.empty() ? lines : out + lines;
}

bool isHex(std::string_view s) {
  return s == "." || ((s.size() == 40 || s.size() == 64) && s.find_first_not_of("0123456789abcdef") == s.npos);
}
bool isMode(std::string_view s) { return s == "." || (s.size() == 6 && s.find_first_not_of("01234567") == s.npos); }

// git's operands may start with `-` (a scene named `-x.rscene`), which
// the option parser would refuse, and git would stop.  When the arguments
// end in git's 7 or 9 operands, `--` goes before them.
std::vector<char*> separateGitOperands(int argc, char** argv) {
  std::vector<char*> args(argv, argv + argc);
  for (int n : {7, 9}) {
    int s = argc - n;
    if (s < 1 || std::string_view(argv[s - 1]) == "--") continue;
    if (isHex(argv[s + 2]) && isMode(argv[s + 3]) && isHex(argv[s + 5]) && isMode(argv[s + 6])) {
      static char separator[] = "--";
      args.insert(args.begin() + s, separator);
      break;
    }
  }
  return args;
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
                 "NEW-FILE NEW-HEX NEW-MODE (nine for a rename: then NEW-PATH MESSAGE)")
      ->type_name("FILE")
      ->required()
      ->expected(2, 9);
  app.add_flag("--stat", statOnly, "Print counts of added, removed and changed records per kind");
  app.add_option("--format", format, "Output format: text (default) or json")
      ->type_name("FORMAT")
      ->check(CLI::IsMember({"text", "json"}));
  app.add_option("--tolerance", opt.tolerance, "Numbers (also in vectors and lists) that differ by at most ABS are equal")
      ->type_name("ABS")
      ->check(cli::nonNegative());
  app.add_option("--rel-tolerance", opt.relTolerance, "Numbers that differ by at most REL times the larger are equal")
      ->type_name("REL")
      ->check(cli::nonNegative());
  app.add_flag("--ignore-editor-state", opt.ignoreEditorState,
               "Skip snapping, editor_ux, render_bake and the locked, expanded and selection* fields");
  app.add_option("--ignore", ignoreList,
                 "Skip these fields (NAME or TAG.NAME, comma-separated); id (or TAG.id) also matches records "
                 "by path or name instead of id")->type_name("KEY,...");
  app.add_flag("-q,--quiet", quiet, "Print nothing; the exit status tells whether the scenes differ");
  diffout::ReviewOptions review;
#ifdef RSCENE_DIFF_REVIEW  // a text-only build (no lib/render) has no --review
  app.add_option("--review", review.dir,
                 "Write before.png, after.png, changes.png, review.md and index.html into DIR (made when missing): "
                 "both scenes from one camera, the changes marked, a page for a pull request")
      ->type_name("DIR");
  app.add_option("--camera", review.camera,
                 "With --review: the camera by path or id, auto for a three-quarter view of both scenes, or changes "
                 "for a view framing what changed (default: the scenes' shared camera, else changes)")
      ->type_name("PATH|ID|auto|changes");
  app.add_option("--width", review.width, "With --review: image width in pixels (default: the camera's, else 1280)")
      ->type_name("PIXELS")
      ->check(cli::range(1, 16384));
  app.add_option("--height", review.height, "With --review: image height in pixels (default: the camera's, else 720)")
      ->type_name("PIXELS")
      ->check(cli::range(1, 16384));
#endif
  cli::addStdinFilename(app, stdinName, false);
  std::vector<char*> args = separateGitOperands(argc, argv);
  if (int rc = cli::parseArgs(app, static_cast<int>(args.size()), args.data()); rc >= 0) return rc;

  // git runs an external diff with 7 arguments, 9 for a rename or copy.
  const bool git = files.size() == 7 || files.size() == 9;
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
  const bool reviewing = !review.dir.empty();
#ifdef RSCENE_DIFF_REVIEW
  if (app.count("--review") && review.dir.empty()) {
    cli::error("--review: give a folder, not an empty string");
    return cli::kTrouble;
  }
  if (!reviewing && (app.count("--camera") || app.count("--width") || app.count("--height"))) {
    cli::error("--camera, --width and --height go with --review DIR");
    return cli::kTrouble;
  }
  if (reviewing) {
    if (git) {
      cli::error("--review takes OLD NEW, not git's external-diff arguments");
      return cli::kTrouble;
    }
    if (!diffout::prepareReviewDir(review.dir)) return cli::kTrouble;
  }
#endif
  const std::string& oldFile = git ? files[1] : files[0];
  const std::string& newFile = git ? files[4] : files[1];
  if (oldFile == "-" && newFile == "-") {
    cli::error("only one of OLD and NEW can be standard input");
    return cli::kTrouble;
  }
  // In git mode a failure is reported but git goes on to the next file.
  const int trouble = git ? cli::kSuccess : cli::kTrouble;
  Side a, b;
  // A review of an added or deleted scene (a range in git) compares with /dev/null too.
  if (!readSide(oldFile, stdinName, git || reviewing, a) || !readSide(newFile, stdinName, git || reviewing, b))
    return trouble;
  std::thread loader([&] { load(a); });
  load(b);
  loader.join();
  // git names the scene by its repository path (its operands are
  // temporary copies); a side that does not exist is /dev/null, as in
  // git's own `--- /dev/null`.
  const std::string oldName = !git ? a.in.display : a.empty ? "/dev/null" : "a/" + files[0];
  const std::string newName = !git ? b.in.display : b.empty ? "/dev/null" : "b/" + files[files.size() == 9 ? 7 : 0];
  const bool parsed = a.loaded.ok() && b.loaded.ok();
  std::string out;
  bool different = false;
  int reviewStatus = -1;
  if ((git || reviewing) && !parsed) {
    out = lineDiff(a, b, oldName, newName);
#ifdef RSCENE_DIFF_REVIEW
    if (reviewing) reviewStatus = diffout::writeLineReview(review, oldName, newName, out);
#endif
  } else {
    bool color = cli::colorFor(2);
    cli::printDiagnostics(a.loaded.diagnostics, oldName, a.text(), color);
    cli::printDiagnostics(b.loaded.diagnostics, newName, b.text(), color);
    if (!parsed) return trouble;
    for (const std::string& entry : opt.ignore)
      if (auto problem = checkIgnoreName(entry, a.loaded.document, b.loaded.document)) {
        cli::error("--ignore: " + *problem);
        return trouble;
      }
    // generalizedCoordinate[LF_KFE]: entries named by joint where the robot
    // model is readable.  git's old side is a temporary file: its robot
    // files resolve from the repository path (git runs this at the top).
    robot::EntryNames joints;
    joints.addSide(a.loaded.document, directoryOf(git ? files[0] : a.in.path));
    joints.addSide(b.loaded.document, directoryOf(git ? files[files.size() == 9 ? 7 : 0] : b.in.path));
    opt.entryNames = std::ref(joints);
    DiffResult result = diff(a.loaded.document, b.loaded.document, opt);
    different = !result.same();
    if (format == "json") {
      out = diffToJson(result);
    } else if (different) {
      if (git) out = "rscene-diff " + oldName + " " + newName + "\n";
      out += statOnly ? diffout::stat(result) : diffout::blocks(result, cli::colorFor(1));
    }
#ifdef RSCENE_DIFF_REVIEW
    if (reviewing) {
      diffout::ReviewSide before{a.in, a.loaded.document, a.text(), oldName, a.empty};
      diffout::ReviewSide after{b.in, b.loaded.document, b.text(), newName, b.empty};
      reviewStatus = diffout::writeReview(review, before, after, result);
    }
#endif
  }
  if (!quiet) {
    std::cout << out << std::flush;
    if (!std::cout) {
      cli::error("cannot write standard output");
      return trouble;
    }
  }
  if (reviewStatus == cli::kTrouble) return cli::kTrouble;
  return git || !different ? cli::kSuccess : cli::kFindings;
}
