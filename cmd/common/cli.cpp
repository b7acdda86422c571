#include "common/cli.hpp"

#include <signal.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <tuple>

#include "core/codes.hpp"
#include "core/io.hpp"
#include "core/output_file.hpp"
#include "core/report.hpp"
#include "core/temp_files.hpp"

namespace rscene::cli {
namespace {

std::string gTool = "rscene";

// Inside writeOutput(), on this thread.  Per thread: rscene-render's writer
// threads write while the drawing thread only sets the stop flag, and a
// signal (which lands on a thread that does not block it) must be judged
// by what the thread it interrupts is doing.
thread_local volatile std::sig_atomic_t gWriting = 0;
volatile std::sig_atomic_t* gStopFlag = nullptr;     // stopOnInterrupt()
// setStopNote(): written by the handler when a stop signal ends the tool at once.
char gStopNote[512];
volatile std::sig_atomic_t gStopNoteLength = 0;

constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGALRM, SIGQUIT, SIGUSR1, SIGUSR2};

// Dies of `sig` itself rather than exit(128+sig): the status a shell
// reports is the same, and a calling script's loop stops on it too.
// Async-signal-safe.
void dieBySignal(int sig) {
  struct sigaction fallback {};
  fallback.sa_handler = SIG_DFL;
  sigemptyset(&fallback.sa_mask);
  ::sigaction(sig, &fallback, nullptr);
  sigset_t only;
  sigemptyset(&only);
  sigaddset(&only, sig);
  ::sigprocmask(SIG_UNBLOCK, &only, nullptr);
  ::raise(sig);
}

extern "C" void onTerminatingSignal(int sig) {
  if (gStopFlag && !gWriting) {
    if (!*gStopFlag) *gStopFlag = sig;
    return;
  }
  removeTemporaryFiles();
  if (gStopNoteLength > 0) {
    ssize_t unused = ::write(2, gStopNote, static_cast<std::size_t>(gStopNoteLength));
    (void)unused;
  }
  dieBySignal(sig);
  ::_exit(128 + sig);
}

void installSignalHandlers() {
  struct sigaction action {};
  action.sa_handler = onTerminatingSignal;
  action.sa_flags = SA_RESTART;
  sigemptyset(&action.sa_mask);
  for (int sig : kStopSignals) sigaddset(&action.sa_mask, sig);
  for (int sig : kStopSignals) {
    struct sigaction old {};
    if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    ::sigaction(sig, &action, nullptr);
  }
  // Past a file size limit (ulimit -f) a write then fails with EFBIG, which
  // is reported and cleaned up, instead of killing the tool mid-write.
  std::signal(SIGXFSZ, SIG_IGN);
}

// Marks the span of a write for the signal handler.
struct WritingScope {
  WritingScope() { gWriting = 1; }
  ~WritingScope() { gWriting = 0; }
};

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
    WritingScope reading;  // as below: a stop signal ends a tool waiting for its input
    if (!readFile("/dev/stdin", in.text, &err)) {
      error("cannot read standard input: " + err);
      return false;
    }
    return true;
  }
  std::string file = operand;
  if (!defaultSceneOf(operand, file)) return false;
  in.display = file;
  in.path = file;
  std::string err;
  // Nothing is written yet: a stop signal ends the tool at once, even one
  // blocked opening a FIFO that no writer opens (the stop flag alone would
  // wait for the open, forever).
  WritingScope reading;
  if (!readFile(file, in.text, &err)) {
    error("cannot read '" + file + "': " + err);
    return false;
  }
  return true;
}

bool checkOutputs(const std::vector<NamedOutput>& outputs) {
  auto isStdout = [](const std::string& p) { return p == "-"; };
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const NamedOutput& a = outputs[i];
    if (a.path.empty()) continue;
    for (std::size_t j = i + 1; j < outputs.size(); ++j) {
      const NamedOutput& b = outputs[j];
      if (b.path.empty()) continue;
      if (isStdout(a.path) && isStdout(b.path)) {
        error(std::string(a.flag) + " and " + b.flag + " would both write standard output; send one to a file");
        return false;
      }
      if (!isStdout(a.path) && !isStdout(b.path) && sameOutputFile(a.path, b.path)) {
        error(std::string(a.flag) + " '" + a.path + "' and " + b.flag + " '" + b.path +
              "' are the same file; one would overwrite the other");
        return false;
      }
    }
  }
  for (const NamedOutput& o : outputs) {
    std::string err;
    if (o.path.empty() || isStdout(o.path) || !o.written) continue;
    if (!checkOutputFile(o.path, &err)) {
      error(o.path + ": " + err);
      return false;
    }
  }
  return true;
}

bool writeOutput(const std::string& path, const std::function<bool(Sink&)>& produce, Cancel cancel) {
  WritingScope writing;
  if (path.empty() || path == "-") {
    StdoutSink sink;
    bool ok = produce(sink);
    if (std::fflush(stdout) != 0) sink.ok_ = false;
    if (!sink.ok_) error("cannot write standard output");
    return ok && sink.ok_;
  }
  // /dev/stdout and /dev/fd/1 are written straight to the descriptor.
  std::fflush(stdout);
  std::string err;
  bool cancelled = false;
  auto producer = [&](Sink& s) {
    cancelled = !produce(s);
    return !cancelled;
  };
  if (!writeOutputFile(path, producer, &err)) {
    // A write an interrupted tool cancelled is no error of its own: the
    // exit status (130) says it; nor is one its producer cancelled after
    // saying why.  A failure of the write itself is always said.
    bool quiet = (gStopFlag && *gStopFlag) || (cancel == Cancel::Quiet && cancelled && err == "write cancelled");
    if (!quiet) error(path + ": " + err);
    return false;
  }
  return true;
}

void stopOnInterrupt(volatile std::sig_atomic_t* flag) { gStopFlag = flag; }

void setStopNote(std::string_view line) {
  gStopNoteLength = 0;  // the handler reads no half-copied note
  std::size_t n = std::min(line.size(), sizeof gStopNote);
  std::memcpy(gStopNote, line.data(), n);
  gStopNoteLength = static_cast<std::sig_atomic_t>(n);
}

sigset_t stopSignals() {
  sigset_t set;
  sigemptyset(&set);
  for (int sig : kStopSignals) sigaddset(&set, sig);
  return set;
}

int endBySignal(int sig) {
  if (sig == SIGINT || sig <= 0) return kInterrupted;
  std::fflush(nullptr);
  dieBySignal(sig);
  return 128 + sig;
}

InterruptibleScope::InterruptibleScope() : saved_(gWriting) { gWriting = 0; }
InterruptibleScope::~InterruptibleScope() { gWriting = saved_; }

bool colorFor(int fd) {
  const char* noColor = std::getenv("NO_COLOR");
  if (noColor && *noColor) return false;
  const char* term = std::getenv("TERM");
  if (term && std::string_view(term) == "dumb") return false;
  return ::isatty(fd) == 1;
}

void printDiagnostics(const Diagnostics& found, std::string_view display, std::string_view text, bool color) {
  // In line order, as rscene-validate prints them (sim and render find
  // things body kind by body kind); findings inside other files (a robot's
  // URDF) after the scene's.
  Diagnostics ds = found;
  std::stable_sort(ds.begin(), ds.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return std::tuple(!a.file.empty(), a.file, a.line, a.column) < std::tuple(!b.file.empty(), b.file, b.line, b.column);
  });
  // The same finding twice (one value read by two checks) is printed once.
  auto same = [](const Diagnostic& a, const Diagnostic& b) {
    return a.code == b.code && a.line == b.line && a.column == b.column && a.message == b.message && a.file == b.file;
  };
  ds.erase(std::unique(ds.begin(), ds.end(), same), ds.end());
  LineCursor lines(text);  // one pass over the text for findings in line order
  for (const Diagnostic& d : ds)
    std::cerr << (d.file.empty() ? formatDiagnostic(d, display, lines(d.line), color)
                                 : formatDiagnostic(d, d.file, {}, color));
}

void hintStdinPaths(const Input& in, const std::string& baseDir, Diagnostics& ds) {
  if (!in.isStdin || !in.path.empty() || !baseDir.empty()) return;
  for (Diagnostic& d : ds)
    if (d.code == rs::RS5001 && d.hint.empty())
      d.hint = "standard input has no folder, so relative paths resolve against the current one: "
               "name the scene with --stdin-filename PATH or give --base-dir DIR";
}

void setup(CLI::App& app, const char* tool) {
  gTool = tool;
  installSignalHandlers();
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

namespace {
// `-o ""` would otherwise mean standard output (or nothing) without a word.
const CLI::Validator nonEmptyPath(
    [](std::string& value) { return value.empty() ? std::string("an empty path names no file") : std::string(); },
    "", "nonEmptyPath");
}  // namespace

void addOutputOption(CLI::App& app, std::string& output, const char* what) {
  app.add_option("-o,--output", output, what)->type_name("FILE")->check(nonEmptyPath);
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
