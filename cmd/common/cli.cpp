#include "common/cli.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "core/io.hpp"
#include "core/report.hpp"

namespace rscene::cli {
namespace {

std::string gTool = "rscene";

class StdoutSink : public Sink {
 public:
  void write(std::string_view chunk) override {
    if (ok_ && std::fwrite(chunk.data(), 1, chunk.size(), stdout) != chunk.size()) ok_ = false;
  }
  bool ok_ = true;
};

}  // namespace

const std::string& toolName() { return gTool; }

void error(std::string_view message) { std::cerr << gTool << ": error: " << message << '\n'; }
void warning(std::string_view message) { std::cerr << gTool << ": warning: " << message << '\n'; }

bool readInput(const std::string& operand, const std::string& stdinName, Input& in) {
  in = Input{};
  if (operand.empty() || operand == "-") {
    in.isStdin = true;
    in.display = stdinName.empty() ? "<stdin>" : stdinName;
    in.path = stdinName;
    std::string err;
    if (!readFile("/dev/stdin", in.text, &err)) {
      error("cannot read standard input: " + err);
      return false;
    }
    return true;
  }
  in.display = operand;
  in.path = operand;
  std::string err;
  if (!readFile(operand, in.text, &err)) {
    error("cannot read '" + operand + "': " + err);
    return false;
  }
  return true;
}

bool writeOutput(const std::string& path, const std::function<bool(Sink&)>& produce) {
  if (path.empty() || path == "-") {
    StdoutSink sink;
    bool ok = produce(sink);
    if (std::fflush(stdout) != 0) sink.ok_ = false;
    if (!sink.ok_) error("cannot write standard output");
    return ok && sink.ok_;
  }
  std::string err;
  if (!writeFileAtomic(path, produce, &err)) {
    error("cannot write '" + path + "': " + err);
    return false;
  }
  return true;
}

bool colorFor(int fd) {
  const char* noColor = std::getenv("NO_COLOR");
  if (noColor && *noColor) return false;
  const char* term = std::getenv("TERM");
  if (term && std::string_view(term) == "dumb") return false;
  return ::isatty(fd) == 1;
}

void printDiagnostics(const Diagnostics& ds, std::string_view display, std::string_view text, bool color) {
  for (const Diagnostic& d : ds) std::cerr << formatDiagnostic(d, display, lineOf(text, d.line), color);
}

void setup(CLI::App& app, const char* tool) {
  gTool = tool;
  app.name(tool);
  app.set_version_flag("--version", std::string(tool) + " " RSCENE_VERSION);
  app.footer("Exit status: 0 success, 1 findings, 2 usage, I/O or parse error.\nSee " + std::string(tool) + "(1).");
}

void addInputOperand(CLI::App& app, std::string& file, const char* what) {
  app.add_option("file", file, std::string(what) + "; none or - reads standard input")->type_name("FILE");
}

void addInputOperands(CLI::App& app, std::vector<std::string>& files) {
  app.add_option("files", files, "Scene files, or folders to search for *.rscene; none or - reads standard input")
      ->type_name("FILE");
}

void addOutputOption(CLI::App& app, std::string& output, const char* what) {
  app.add_option("-o,--output", output, what)->type_name("FILE");
}

void addStdinFilename(CLI::App& app, std::string& name, bool assets) {
  app.add_option("--stdin-filename", name,
                 assets ? "Name standard input PATH in messages and for asset paths"
                        : "Name standard input PATH in messages")
      ->type_name("PATH");
}

void addBaseDir(CLI::App& app, std::string& dir, const char* help) {
  app.add_option("--base-dir", dir, help)->type_name("DIR");
}

}  // namespace rscene::cli
