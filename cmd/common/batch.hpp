// Batches of scenes: `rscene-sim -o 'out/{stem}.rscene' scenes/`.  What a
// tool taking several scenes with outputs named by patterns shares: the
// patterns ({stem}, {dir}: core/scene_pattern.hpp) checked and expanded,
// every scene's outputs checked against each other before any work, the
// progress line on a terminal, the first error of a scene (for its report
// line) and the summary at the end.
#pragma once
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "common/cli.hpp"

namespace rscene::cli {

// Whether `operands` (as written) are a batch: more than one, or a folder
// or an Engine 2 project.  `onePattern`: the project operand alone is its
// default scene unless the output is a pattern (README, "Engine 2
// projects": where one scene is meant, a project is its default scene).
bool isBatch(const std::vector<std::string>& operands, bool outputIsPattern);

// A batch's output `pattern` for `flag` must name each scene's own file:
// it must hold {stem} or {dir}.  Prints the usage error and returns false
// when it does not (standard output, `-`, cannot take several scenes).
bool requireScenePattern(const char* flag, const std::string& pattern, std::size_t scenes);

// `pattern` for the scene `scene` (its {stem} and {dir}); a pattern
// without them is returned as written.  Prints `flag: error` and returns
// false on an unknown field or an unmatched brace.
bool scenePath(const char* flag, const std::string& pattern, const std::string& scene, std::string& out);

// The outputs of one scene of a batch (checkOutputs() form).
struct SceneOutputs {
  std::string scene;  // as named in messages
  std::string file;   // the scene's file; "" for standard input
  std::vector<NamedOutput> outputs;  // checked by checkOutputs()
  std::vector<NamedOutput> folders;  // folders it writes into (--sensors): only compared between scenes
};
// No output replaces a scene being read: an output that is one of the
// scenes' files (the same file, by identity: a hard link too) is refused,
// except `inPlace`'s output of its own scene (rscene-sim -o 'x/{stem}.rscene'
// x/ writes each scene back once it is read, as rscene-fmt -i does).  In a
// batch, one scene's output would otherwise replace a later scene before
// it is read.  Prints the problem and returns false.
bool checkInputsKept(const std::vector<SceneOutputs>& scenes, const char* inPlace);

// The missing folders on the way to `outputs` (those written), made as
// `mkdir -p` would: outputs named by a pattern ({stem}, {dir}) go where no
// one made a folder yet.  Prints the error and returns false when one
// cannot be made.
bool makeOutputFolders(const std::vector<NamedOutput>& outputs);

// Before any work: checkInputsKept() (`inPlace` as there), no two scenes
// writing one file (or one folder), then
// each scene's output folders made (makeOutputFolders()) and its outputs
// checked as checkOutputs() checks them.  Prints the first problem, naming
// both scenes, with clashHint() of the flag's pattern (`patterns`: each
// flag with its pattern as given).
bool checkBatchOutputs(const std::vector<SceneOutputs>& scenes, const std::vector<NamedOutput>& patterns,
                       const char* inPlace);

// What to change in `pattern` when the scenes `a` and `b` have one file
// by it: the field it lacks ({dir} for two scenes of one name in two
// folders, {stem} for two scenes of one folder), or that one scene was
// named twice.
std::string clashHint(const std::string& pattern, const std::string& a, const std::string& b);

// While it lives, and stderr is a terminal, a progress line
// `tool: scene k/N` (with the step count of the scene stepping), erased
// before anything else is printed on stderr.  It also remembers the first
// error line printed on stderr since scene() (for a scene's report line).
class BatchProgress {
 public:
  explicit BatchProgress(std::size_t total);
  ~BatchProgress();
  BatchProgress(const BatchProgress&) = delete;
  BatchProgress& operator=(const BatchProgress&) = delete;

  void scene(std::size_t index);  // 0-based; shows `scene index+1/N`
  void step(std::uint64_t done, std::uint64_t of);
  void stepsDone();  // back to `scene k/N`
  void clear();      // erases the line (before the summary)
  bool terminal() const { return terminal_; }
  // The first line holding "error:" printed on stderr since scene(),
  // without color; empty when none.
  std::string firstError() const;

 private:
  class Tee;
  void show(const std::string& line);
  std::size_t total_, index_ = 0;
  bool terminal_, stepShown_ = false;
  std::unique_ptr<Tee> tee_;
  std::streambuf* original_ = nullptr;
};

// The last line of a batch on stderr: `tool: N scenes: D VERB`, and `, K
// failed: a.rscene, b.rscene` (the first ten named) when some did.
// `unnamed`: operands that could not be read (a folder, a project), said
// after it.
void batchSummary(std::size_t total, std::size_t done, const std::vector<std::string>& failed,
                  std::size_t unnamed, const char* verb);

// The line of a batch a stop signal ended: how far it got, and that the
// finished scenes' outputs stay.
void batchStopped(std::size_t finished, std::size_t total);
// Before each scene (and with finished == total at the end): the same
// line for a signal that ends the tool at once, inside a write
// (setStopNote()).
void batchReached(std::size_t finished, std::size_t total);

}  // namespace rscene::cli
