#include "common/batch.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <map>
#include <streambuf>
#include <tuple>

#include "core/assets.hpp"
#include "core/filesystem.hpp"
#include "core/project.hpp"
#include "core/scene_pattern.hpp"

namespace rscene::cli {

bool isBatch(const std::vector<std::string>& operands, bool outputIsPattern) {
  if (operands.size() > 1) return true;
  if (operands.empty() || operands[0] == "-") return false;
  std::string root;
  if (isProject(operands[0], diskFileSystem(), root)) return outputIsPattern;
  std::error_code ec;
  return std::filesystem::is_directory(operands[0], ec);
}

bool requireScenePattern(const char* flag, const std::string& pattern, std::size_t scenes) {
  if (hasSceneFields(pattern)) return true;
  std::string n = std::to_string(scenes) + (scenes == 1 ? " scene" : " scenes");
  if (pattern == "-")
    error(std::string(flag) + " - (standard output) cannot take several scenes (" + n +
          "): name each scene's output with a pattern, e.g. " + flag + " 'out/{stem}.rscene'");
  else
    error(std::string(flag) + " '" + pattern + "' names one file for " + n +
          ": put {stem} (the scene's file name without .rscene) or {dir} (its folder) in it");
  return false;
}

bool scenePath(const char* flag, const std::string& pattern, const std::string& scene, std::string& out) {
  if (!hasSceneFields(pattern)) {
    out = pattern;
    return true;
  }
  std::string why;
  if (expandScenePattern(pattern, sceneFields(scene), out, &why)) return true;
  error(std::string(flag) + ": " + why);
  return false;
}

namespace {

// Where an output ends, for comparing many at once (cli::checkOutputs
// compares pairs with sameOutputFile, quadratic in a batch of hundreds):
// an existing file by its identity, a new one by its folder's identity
// and its name, else (a folder that does not exist yet) by the path.
using Place = std::tuple<dev_t, ino_t, std::string>;
bool placeOf(const std::string& path, Place& out) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISCHR(st.st_mode)) return false;  // /dev/null, a terminal: writing both there loses nothing
    out = {st.st_dev, st.st_ino, ""};
    return true;
  }
  std::string dir = directoryOf(path);
  std::string name = path.substr(path.rfind('/') == std::string::npos ? 0 : path.rfind('/') + 1);
  if (!name.empty() && name != "." && name != ".." && ::stat(dir.c_str(), &st) == 0) {
    out = {st.st_dev, st.st_ino, name};
    return true;
  }
  std::error_code ec;
  out = {0, 0, std::filesystem::absolute(path, ec).lexically_normal().string()};
  return true;
}

}  // namespace

std::string clashHint(const std::string& pattern, const std::string& a, const std::string& b) {
  std::error_code ec;
  if (std::filesystem::weakly_canonical(a, ec) == std::filesystem::weakly_canonical(b, ec))
    return "the scene is named twice: name it once";
  SceneFields fa = sceneFields(a), fb = sceneFields(b);
  bool stem = pattern.find("{stem}") != std::string::npos, dir = pattern.find("{dir}") != std::string::npos;
  if (fa.stem == fb.stem && !dir) return "they share a file name in different folders: put {dir} in it as well";
  if (fa.dir == fb.dir && !stem) return "they are in one folder: put {stem} in it as well";
  return "name each scene's output apart, with {stem} and {dir}";
}

bool makeOutputFolders(const std::vector<NamedOutput>& outputs) {
  for (const NamedOutput& o : outputs) {
    if (o.path.empty() || o.path == "-" || !o.written) continue;
    std::filesystem::path parent = std::filesystem::path(o.path).parent_path();
    std::error_code ec;
    if (parent.empty() || std::filesystem::is_directory(parent, ec)) continue;
    std::filesystem::create_directories(parent, ec);
    if (ec || !std::filesystem::is_directory(parent, ec)) {
      error(std::string(o.flag) + ": cannot create the folder '" + parent.string() +
            "': " + (ec ? ec.message() : std::string("something else is there")));
      return false;
    }
  }
  return true;
}

bool checkInputsKept(const std::vector<SceneOutputs>& scenes, const char* inPlace) {
  std::map<std::pair<dev_t, ino_t>, std::size_t> inputs;  // a scene file's identity -> its scene
  struct stat st {};
  for (std::size_t i = 0; i < scenes.size(); ++i)
    if (!scenes[i].file.empty() && ::stat(scenes[i].file.c_str(), &st) == 0 && S_ISREG(st.st_mode))
      inputs.emplace(std::make_pair(st.st_dev, st.st_ino), i);
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    for (const NamedOutput& o : scenes[i].outputs) {
      if (o.path.empty() || o.path == "-" || !o.written || ::stat(o.path.c_str(), &st) != 0) continue;
      auto in = inputs.find({st.st_dev, st.st_ino});
      if (in == inputs.end()) continue;
      if (in->second == i && std::string(o.flag) == inPlace) continue;  // the scene written back
      std::string whose = scenes.size() > 1 ? " (of " + scenes[i].scene + ")" : "";
      std::string what = in->second == i ? "the scene itself: it would be replaced by what " + std::string(o.flag) + " writes"
                                         : "the scene " + scenes[in->second].scene +
                                               ", another input: it would be replaced before it is read";
      error(std::string(o.flag) + " '" + o.path + "'" + whose + " is " + what + "; write it elsewhere");
      return false;
    }
  }
  return true;
}

bool checkBatchOutputs(const std::vector<SceneOutputs>& scenes, const std::vector<NamedOutput>& patterns,
                       const char* inPlace) {
  if (!checkInputsKept(scenes, inPlace)) return false;
  struct Seen {
    std::size_t scene;
    const NamedOutput* output;
  };
  std::map<Place, Seen> seen;
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    for (const std::vector<NamedOutput>* list : {&scenes[i].outputs, &scenes[i].folders}) {
      for (const NamedOutput& o : *list) {
        if (o.path.empty() || o.path == "-" || !o.written) continue;
        Place p;
        if (!placeOf(o.path, p)) continue;
        auto [at, fresh] = seen.emplace(p, Seen{i, &o});
        if (fresh || at->second.scene == i) continue;  // within one scene: checkOutputs' and SensorFiles' call
        const Seen& first = at->second;
        std::string pattern;
        for (const NamedOutput& named : patterns)
          if (std::string(named.flag) == o.flag) pattern = named.path;
        error("scenes '" + scenes[first.scene].scene + "' and '" + scenes[i].scene + "' would both write '" +
              o.path + "' (" + first.output->flag + (std::string(first.output->flag) == o.flag ? "" : std::string(" and ") + o.flag) +
              "): " + clashHint(pattern, scenes[first.scene].scene, scenes[i].scene));
        return false;
      }
    }
  }
  // No two scenes clash: the folders of the outputs are made, then each
  // scene's outputs are checked as a single run checks its own.
  for (const SceneOutputs& s : scenes)
    if (!makeOutputFolders(s.outputs) || !checkOutputs(s.outputs)) return false;
  return true;
}

// Forwards stderr to the stream it had, erasing the progress line before
// the first character of anything else, and keeps the first error line.
class BatchProgress::Tee : public std::streambuf {
 public:
  explicit Tee(std::streambuf* to) : to_(to) {}
  bool progressShown = false;
  bool capturing = false;
  std::string firstError;

  void raw(const std::string& s) { to_->sputn(s.data(), static_cast<std::streamsize>(s.size())); to_->pubsync(); }

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    char ch = traits_type::to_char_type(c);
    xsputn(&ch, 1);
    return c;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (progressShown && n > 0) {
      progressShown = false;
      raw("\r\033[K");
    }
    for (std::streamsize i = 0; i < n; ++i) take(s[i]);
    return to_->sputn(s, n);
  }
  int sync() override { return to_->pubsync(); }

 private:
  void take(char c) {
    if (!capturing || !firstError.empty()) return;
    if (c != '\n') {
      if (line_.size() < 4096) line_ += c;
      return;
    }
    std::string plain;  // without color
    for (std::size_t i = 0; i < line_.size(); ++i) {
      if (line_[i] == '\033' && i + 1 < line_.size() && line_[i + 1] == '[') {
        i += 2;
        while (i < line_.size() && !(line_[i] >= '@' && line_[i] <= '~')) ++i;
        continue;
      }
      plain += line_[i];
    }
    line_.clear();
    if (plain.find("error:") != std::string::npos) firstError = plain;
  }
  std::streambuf* to_;
  std::string line_;
};

BatchProgress::BatchProgress(std::size_t total) : total_(total), terminal_(::isatty(2) == 1) {
  original_ = std::cerr.rdbuf();
  tee_ = std::make_unique<Tee>(original_);
  std::cerr.rdbuf(tee_.get());
}

BatchProgress::~BatchProgress() {
  clear();
  std::cerr.rdbuf(original_);
}

void BatchProgress::show(const std::string& line) {
  if (!terminal_) return;
  tee_->raw("\r\033[K" + toolName() + ": " + line);
  tee_->progressShown = true;
}

void BatchProgress::scene(std::size_t index) {
  index_ = index;
  tee_->capturing = true;
  tee_->firstError.clear();
  show("scene " + std::to_string(index + 1) + "/" + std::to_string(total_));
}

void BatchProgress::step(std::uint64_t done, std::uint64_t of) {
  stepShown_ = true;
  show("scene " + std::to_string(index_ + 1) + "/" + std::to_string(total_) + ", step " + std::to_string(done) + "/" +
       std::to_string(of));
}

void BatchProgress::stepsDone() {
  if (!stepShown_) return;
  stepShown_ = false;
  show("scene " + std::to_string(index_ + 1) + "/" + std::to_string(total_));
}

void BatchProgress::clear() {
  if (!tee_->progressShown) return;
  tee_->progressShown = false;
  tee_->raw("\r\033[K");
}

std::string BatchProgress::firstError() const { return tee_->firstError; }

void batchSummary(std::size_t total, std::size_t done, const std::vector<std::string>& failed,
                  std::size_t unnamed, const char* verb) {
  std::string line = toolName() + ": " + std::to_string(total) + (total == 1 ? " scene: " : " scenes: ") +
                     std::to_string(done) + " " + verb;
  if (!failed.empty()) {
    line += ", " + std::to_string(failed.size()) + " failed";
    constexpr std::size_t kNamed = 10;
    for (std::size_t i = 0; i < failed.size() && i < kNamed; ++i) line += (i ? ", " : ": ") + failed[i];
    if (failed.size() > kNamed) line += ", ...";
  }
  if (unnamed > 0) line += "; " + std::to_string(unnamed) + (unnamed == 1 ? " operand" : " operands") + " could not be read";
  std::cerr << line << '\n';
}

namespace {
std::string stoppedText(std::size_t finished, std::size_t total) {
  return "stopped by a signal after " + std::to_string(finished) + " of " + std::to_string(total) +
         " scenes; the finished scenes' outputs are written";
}
}  // namespace

void batchStopped(std::size_t finished, std::size_t total) { error(stoppedText(finished, total)); }

void batchReached(std::size_t finished, std::size_t total) {
  setStopNote(finished < total ? toolName() + ": error: " + stoppedText(finished, total) + "\n" : std::string());
}

}  // namespace rscene::cli
