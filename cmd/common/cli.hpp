// Shared by every tool's main(): the exit-code table, reading inputs,
// writing outputs atomically, color policy and diagnostic printing.  This
// is the only layer that looks at the terminal and the environment.
#pragma once
#include <csignal>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostic.hpp"
#include "core/project.hpp"
#include "core/writer.hpp"

namespace CLI {
class App;
class Validator;
}

namespace rscene::cli {

// The same table in every man page.
enum ExitCode : int {
  kSuccess = 0,      // nothing to report
  kFindings = 1,     // lint errors, needs formatting, differences, image mismatch
  kTrouble = 2,      // usage, I/O or parse error
  kInterrupted = 130,
};

struct Input {
  std::string display;  // name in messages: the path, or --stdin-filename, or <stdin>
  std::string path;     // file to resolve assets against (may be empty for stdin)
  bool isStdin = false;
  std::string text;
};

// A scene read from standard input without --stdin-filename or --base-dir
// has no folder: its relative asset and robot paths resolve against the
// current one, which is rarely what a pipe (`rscene-sim ... | rscene-render`)
// meant.  Adds that hint to each file-not-found finding (RS5001) without one.
void hintStdinPaths(const Input& in, const std::string& baseDir, Diagnostics& ds);

// Reads `operand` ("-" = stdin).  On failure prints `tool: error: ...`.
// An Engine 2 project is read as its default scene (project.cpp).
bool readInput(const std::string& operand, const std::string& stdinName, Input& in);

// Engine 2 projects (project.cpp).  The project file of `root`, read and
// checked (false, printed, when it cannot be read).
bool readProjectFile(const std::string& root, std::string& text, ProjectRead& read);
// The project of `root` when its file has no errors; else prints them.
bool openProject(const std::string& root, Project& project);
// The project the scene `in` lies in, for its asset paths (stdin: from
// --base-dir's folder); empty when none.
ProjectPlace projectPlace(const Input& in, const std::string& baseDir);
// When `operand` is a project, sets `scene` to its default scene (false,
// printed, when it has none or its file has errors); else leaves `scene`.
bool defaultSceneOf(const std::string& operand, std::string& scene);

// Writes `produce`'s output to `path` ("-" = stdout) through the library's
// one output routine (core/output_file.hpp: atomic replacement, links kept,
// devices written through, read-only and hard-linked files refused).  On
// failure prints `tool: error: PATH: why`.  With Cancel::Quiet, produce()
// returning false cancels the write without that line: the producer has
// already said why (rscene-sim's failed run), and "write cancelled" after
// it would only repeat it.
enum class Cancel { Say, Quiet };
bool writeOutput(const std::string& path, const std::function<bool(Sink&)>& produce, Cancel cancel = Cancel::Say);

// One output (or an input that must not be overwritten) of a tool:
// `flag` names it in messages, `path` is "-" for standard output and ""
// when not requested; `written` false marks an input (a reference image)
// that only has to differ from every output.
struct NamedOutput {
  const char* flag;
  std::string path;
  bool written = true;
};
// Before any work: refuses (with a message) two outputs to standard output,
// two that end at the same file, and any output writeOutput() would
// refuse, so a run never fails after replacing some of its outputs.
bool checkOutputs(const std::vector<NamedOutput>& outputs);

// setup() makes every signal that ends a run (INT, TERM, HUP, PIPE, ALRM,
// QUIT, USR1, USR2) remove the temporary file of an output being written,
// then end the tool by that signal (a shell reports 128+signal, 130 for
// SIGINT); signals that were ignored when the tool started stay ignored
// (nohup, `cmd &`).  A tool with a long loop of its own passes a flag
// here: such a signal then only sets it (to the signal's number), except
// while an output is being written; the tool cleans up what its run made
// and calls endBySignal().
void stopOnInterrupt(volatile std::sig_atomic_t* flag);

// A line (ending in a newline) that a stop signal ending the tool at once,
// inside a write, prints on stderr before the tool ends: a batch keeps it
// saying how far it got (the flag path prints that itself).  "" clears it.
void setStopNote(std::string_view line);

// The signals above, for a tool that blocks them around a write.
sigset_t stopSignals();

// Ends the tool by signal `sig` (the flag stopOnInterrupt() set), after its
// cleanup: a script sees the status it would have seen without the flag.
// SIGINT returns kInterrupted instead, as the tools always have.
int endBySignal(int sig);

// While one lives, a stop signal only sets stopOnInterrupt()'s flag even inside a
// writeOutput() (a tool whose long loop runs inside the callback of the
// outputs it streams, as rscene-sim's does): the loop then stops and
// cancels its outputs itself.  Restores the previous state when it ends.
class InterruptibleScope {
 public:
  InterruptibleScope();
  ~InterruptibleScope();
  InterruptibleScope(const InterruptibleScope&) = delete;
  InterruptibleScope& operator=(const InterruptibleScope&) = delete;

 private:
  std::sig_atomic_t saved_;
};

// Color on stderr/stdout: only on a terminal, never with NO_COLOR.
bool colorFor(int fd);

// Prints diagnostics of one input to stderr in the shared format.
void printDiagnostics(const Diagnostics& ds, std::string_view display, std::string_view text, bool color);

// `tool: error: message` on stderr.
void error(std::string_view message);
void warning(std::string_view message);

// Sets the tool name, --version and the common help footer.
void setup(CLI::App& app, const char* tool);
const std::string& toolName();

// The operands and options every tool shares, declared once so their
// spelling and help stay the same across tools.
void addInputOperand(CLI::App& app, std::string& file, const char* what = "Scene file");
void addInputOperands(CLI::App& app, std::vector<std::string>& files);

// The operands of a tool that takes several scenes: `-` and files stay, a
// directory becomes the *.rscene files under it (core/find_scenes.hpp:
// sorted, hidden entries and links to folders skipped).  An unreadable
// folder is printed as an error (ok = false), a folder without scenes as a
// warning (operands.cpp).
//
// An Engine 2 project (a folder holding `raisim_engine2_project`, or that
// file) becomes its scenes (core/project.hpp: projectScenes); its root is
// listed in `projects`.  With `checkProjects` a project file with errors
// is printed and its scenes left out (ok = false); without, the caller
// (rscene-validate) reports the project file itself.
struct Operands {
  std::vector<std::string> files;
  std::vector<std::string> projects;  // project folders among the operands
  bool hadDirectory = false;
  bool ok = true;
};
Operands expandOperands(const std::vector<std::string>& operands, bool checkProjects = true);
// Whether an operand is a folder or an Engine 2 project (its folder or its file).
bool anyDirectory(const std::vector<std::string>& operands);
void addOutputOption(CLI::App& app, std::string& output, const char* what);
// `assets`: stdin's name also places relative asset paths.
void addStdinFilename(CLI::App& app, std::string& name, bool assets);
void addBaseDir(CLI::App& app, std::string& dir, const char* help);

// Runs app.parse(); on --help/--version prints and returns kSuccess, on a
// usage error prints it and returns kTrouble; -1 when the tool should go on.
// A mistyped long option gets "did you mean" (args.cpp).
int parseArgs(CLI::App& app, int argc, char** argv);

// Validators whose messages name the expected form: seconds as a plain
// number >= 0 (`2`, `0.5`, not `2s`); a finite number >= 0; a whole number >= min.
CLI::Validator seconds();
CLI::Validator nonNegative();
// A number from 0 to 1 (CLI::Range lets NaN through).
CLI::Validator fraction();
CLI::Validator count(long long min);
// CLI::Range of whole numbers without its description: --help would
// otherwise show "--width INT:INT in [1 - 16384]"; the help text says the
// bounds in words where a user needs them, and a value out of range still
// gets "Value 0 not in range 1 to 16384".
CLI::Validator range(long long min, long long max);

}  // namespace rscene::cli
