// rscene-fmt: writes scenes in the canonical form (DESIGN.md).
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <iostream>
#include <optional>

#include "common/cli.hpp"
#include "core/assets.hpp"
#include "core/diff_lines.hpp"
#include "core/io.hpp"
#include "core/loader.hpp"
#include "core/report.hpp"
#include "core/writer.hpp"

namespace {

using namespace rscene;

// Compares formatter output with the input as it streams by.
class CompareSink : public Sink {
 public:
  explicit CompareSink(std::string_view original) : original_(original) {}
  void write(std::string_view chunk) override {
    if (same_ && original_.substr(offset_, chunk.size()) != chunk) same_ = false;
    offset_ += chunk.size();
  }
  bool same() const { return same_ && offset_ == original_.size(); }

 private:
  std::string_view original_;
  std::size_t offset_ = 0;
  bool same_ = true;
};

struct Options {
  std::vector<std::string> files;
  std::string output;
  std::string stdinName;
  bool inPlace = false;
  bool check = false;
  bool diff = false;
  bool textconv = false;
};

// git runs textconv on a committed version as a temporary copy,
// $TMPDIR/git-blob-XXXXXX/NAME (older git: $TMPDIR/XXXXXX_NAME), and tells
// it neither the repository path nor the commit: no argument, no
// environment variable.  Returns NAME for such a copy, else nothing.
std::optional<std::string> gitCopyName(std::string_view path) {
  std::size_t slash = path.rfind('/');
  if (slash == std::string_view::npos) return std::nullopt;  // git passes worktree files by repository path
  std::string_view dir = path.substr(0, slash), name = path.substr(slash + 1);
  std::string_view parent = dir.substr(dir.rfind('/') + 1);
  auto random = [](std::string_view s) {
    return s.size() == 6 && std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)); });
  };
  if (parent.size() == 15 && parent.substr(0, 9) == "git-blob-" && random(parent.substr(9)) && !name.empty())
    return std::string(name);
  const char* tmp = std::getenv("TMPDIR");
  std::string_view tmpdir = tmp && *tmp ? std::string_view(tmp) : std::string_view("/tmp");
  while (tmpdir.size() > 1 && tmpdir.back() == '/') tmpdir.remove_suffix(1);
  if (dir == tmpdir && name.size() > 7 && random(name.substr(0, 6)) && name[6] == '_') return std::string(name.substr(7));
  return std::nullopt;
}

// git's textconv must not fail (git would stop `git log -p` there): a scene
// that does not parse is shown as written, with one warning.
int showAsWritten(std::string_view original, const std::string& display, const Diagnostics& ds,
                  const std::string& output) {
  auto error = std::find_if(ds.begin(), ds.end(), [](const Diagnostic& d) { return d.severity == Severity::Error; });
  Diagnostic w = error != ds.end() ? *error : Diagnostic{};
  w.severity = Severity::Warning;
  w.message += "; shown as written";
  w.hint.clear();  // one line per file in `git log -p`
  // Not git's temporary path, which would send people looking for a file
  // that is gone: the scene's name, and what is not known.
  std::string name = display;
  if (auto copy = gitCopyName(display)) {
    name = ".../" + *copy;
    w.message += " (a committed version: git gives textconv no folder or commit)";
  }
  std::cerr << formatDiagnostic(w, name, {}, cli::colorFor(2));
  bool ok = cli::writeOutput(output, [&](Sink& s) {
    s.write(original);
    return true;
  });
  return ok ? cli::kSuccess : cli::kTrouble;
}

// git appends the file to the textconv command; a scene at the top of a
// repository named `-x.rscene` must not be taken for an option (git would
// stop), so with --textconv a last argument that is no option gets `--`.
std::vector<char*> textconvOperand(const CLI::App& app, int argc, char** argv) {
  std::vector<char*> args(argv, argv + argc);
  const std::string_view last = argc > 2 ? argv[argc - 1] : "";
  auto has = [&](std::string_view word) {
    return std::find_if(argv + 1, argv + argc, [&](const char* a) { return word == a; }) != argv + argc;
  };
  const bool textconv = has("--textconv") && !has("--");
  if (textconv && last.size() > 1 && last[0] == '-' && !app.get_option_no_throw(std::string(last))) {
    static char separator[] = "--";
    args.insert(args.end() - 1, separator);
  }
  return args;
}

// Formats one input; returns its exit code.
int formatOne(const std::string& operand, const Options& opt, bool color) {
  // In place means replacing a file: a FIFO or device would block the read
  // or make no sense to rewrite, and a refused file is refused before the read.
  if (opt.inPlace && !fileExistsOnDisk(operand) && access(operand.c_str(), F_OK) == 0) {
    cli::error(operand + ": --in-place needs a regular file; it " + whyNotAFile(operand));
    return cli::kTrouble;
  }
  cli::Input in;
  if (!cli::readInput(operand, opt.stdinName, in)) return cli::kTrouble;
  // The document takes the text over; the original bytes stay at the start
  // of its buffer, so nothing is copied.
  const std::size_t size = in.text.size();
  LoadResult loaded = parse(std::move(in.text));
  const Document& doc = loaded.document;
  const std::string_view original = std::string_view(doc.buffer()).substr(0, size);
  if (opt.textconv && !loaded.ok()) return showAsWritten(original, in.display, loaded.diagnostics, opt.output);
  cli::printDiagnostics(loaded.diagnostics, in.display, original, color);
  if (!loaded.ok()) return cli::kTrouble;

  auto produce = [&](Sink& s) {
    writeCanonical(doc, s);
    return true;
  };
  if (!opt.check && !opt.diff && !opt.inPlace) return cli::writeOutput(opt.output, produce) ? cli::kSuccess : cli::kTrouble;

  CompareSink compare(original);
  writeCanonical(doc, compare);
  const bool changed = !compare.same();
  if (opt.inPlace) {
    if (!changed) return cli::kSuccess;  // leave the file (and its mtime) alone
    return cli::writeOutput(in.path, produce) ? cli::kSuccess : cli::kTrouble;
  }
  if (changed && opt.diff) std::cout << unifiedDiff(original, canonicalText(doc), in.display, in.display + " (formatted)");
  else if (changed) std::cout << in.display << '\n';
  return changed && opt.check ? cli::kFindings : cli::kSuccess;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Write .rscene scenes in canonical form."};
  cli::setup(app, "rscene-fmt");
  Options opt;
  cli::addInputOperands(app, opt.files);
  cli::addOutputOption(app, opt.output, "Write the result to FILE (atomically) instead of standard output");
  app.add_flag("-i,--in-place", opt.inPlace, "Rewrite each file in place; canonical files are not touched");
  app.add_flag("--check", opt.check, "Write nothing; list files that are not canonical and exit 1 if any");
  app.add_flag("--diff", opt.diff, "Print a unified diff of what formatting would change");
  app.add_flag("--textconv", opt.textconv,
               "For git's diff.<driver>.textconv: canonical text, or a file that does not parse as written "
               "(one warning, exit 0)");
  cli::addStdinFilename(app, opt.stdinName, false);
  std::vector<char*> args = textconvOperand(app, argc, argv);
  if (int rc = cli::parseArgs(app, static_cast<int>(args.size()), args.data()); rc >= 0) return rc;

  if (opt.files.empty()) opt.files.push_back("-");
  if (opt.inPlace && (opt.check || opt.diff || !opt.output.empty())) {
    cli::error("--in-place cannot be combined with --check, --diff or --output");
    return cli::kTrouble;
  }
  if (opt.textconv && (opt.inPlace || opt.check || opt.diff)) {
    cli::error("--textconv cannot be combined with --in-place, --check or --diff");
    return cli::kTrouble;
  }
  if (opt.inPlace)
    for (const std::string& f : opt.files)
      if (f == "-") {
        cli::error("--in-place needs file operands, not standard input");
        return cli::kTrouble;
      }
  // Many scenes' canonical text on one stdout would be of no use.
  if (!opt.inPlace && !opt.check && !opt.diff && cli::anyDirectory(opt.files)) {
    cli::error("a directory or project operand needs --check, --diff or --in-place");
    return cli::kTrouble;
  }
  cli::Operands operands = cli::expandOperands(opt.files);
  if (!opt.output.empty() && operands.files.size() > 1) {
    cli::error("--output takes a single input");
    return cli::kTrouble;
  }

  bool color = cli::colorFor(2);
  int status = operands.ok ? cli::kSuccess : cli::kTrouble;
  for (const std::string& f : operands.files) status = std::max(status, formatOne(f, opt, color));
  return status;
}
