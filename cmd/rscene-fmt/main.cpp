// rscene-fmt: writes scenes in the canonical form (DESIGN.md).
#include <CLI/CLI.hpp>
#include <iostream>

#include "common/cli.hpp"
#include "core/io.hpp"
#include "core/loader.hpp"
#include "core/writer.hpp"
#include "rscene-fmt/unified_diff.hpp"

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
};

// Formats one input; returns its exit code.
int formatOne(const std::string& operand, const Options& opt, bool color) {
  cli::Input in;
  if (!cli::readInput(operand, opt.stdinName, in)) return cli::kTrouble;
  // The document takes the text over; the original bytes stay at the start
  // of its buffer, so nothing is copied.
  const std::size_t size = in.text.size();
  LoadResult loaded = parse(std::move(in.text));
  const Document& doc = loaded.document;
  const std::string_view original = std::string_view(doc.buffer()).substr(0, size);
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
  if (changed && opt.diff) std::cout << fmt::unifiedDiff(original, canonicalText(doc), in.display);
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
  cli::addStdinFilename(app, opt.stdinName, false);
  if (int rc = cli::parseArgs(app, argc, argv); rc >= 0) return rc;

  if (opt.files.empty()) opt.files.push_back("-");
  if (opt.inPlace && (opt.check || opt.diff || !opt.output.empty())) {
    cli::error("--in-place cannot be combined with --check, --diff or --output");
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
    cli::error("a directory operand needs --check, --diff or --in-place");
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
