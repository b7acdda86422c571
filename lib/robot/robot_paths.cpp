#include "robot/robot_paths.hpp"

#include <filesystem>
#include <system_error>

namespace rscene::robot {
namespace fs = std::filesystem;

namespace {

std::string join(const std::string& dir, const std::string& rest) {
  if (dir.empty() || dir == ".") return fs::path(rest).lexically_normal().string();
  return (fs::path(dir) / rest).lexically_normal().string();
}

bool startsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// Directories from `dir` up to the file-system root (absolute, so that a
// relative URDF path still walks above the working directory).
std::vector<std::string> upwards(const std::string& dir) {
  std::error_code ec;
  fs::path p = fs::absolute(dir.empty() ? fs::path(".") : fs::path(dir), ec);
  if (ec) p = fs::path(dir);
  p = p.lexically_normal();
  std::vector<std::string> out;
  // A path has at most as many parents as characters: the bound keeps a
  // malformed path from looping.
  for (std::size_t guard = 0; guard < 4096; ++guard) {
    std::string s = p.string();
    if (s.size() > 1 && s.back() == '/') s.pop_back();
    if (!s.empty()) out.push_back(s);
    fs::path parent = p.parent_path();
    if (parent.empty() || parent == p) break;
    p = parent;
  }
  return out;
}

}  // namespace

std::string parentDirectory(const std::string& path) {
  std::string dir = fs::path(path).parent_path().string();
  return dir.empty() ? "." : dir;
}

namespace {

// Calls `visit` with each candidate in order until it returns true.
template <typename Visit>
void forEachCandidate(const RobotPaths& paths, const std::string& elementDirectory, const std::string& uri,
                      Visit&& visit) {
  if (uri.empty()) return;
  if (startsWith(uri, "file://")) {
    visit(uri.substr(7));
    return;
  }
  for (const char* scheme : {"package://", "model://"}) {
    if (!startsWith(uri, scheme)) continue;
    std::string rest = uri.substr(std::char_traits<char>::length(scheme));
    std::size_t slash = rest.find('/');
    std::string name = slash == std::string::npos ? rest : rest.substr(0, slash);
    std::string tail = slash == std::string::npos ? "" : rest.substr(slash + 1);
    if (tail.empty()) return;  // names a package, not a file
    const std::string named = name + "/" + tail;
    if (!paths.resourceDirectory.empty() &&
        (visit(join(paths.resourceDirectory, tail)) || visit(join(paths.resourceDirectory, named))))
      return;
    for (const std::string& dir : upwards(paths.robotDirectory))
      if (visit(join(dir, tail)) || visit(join(dir, named))) return;
    return;
  }
  if (uri.front() == '/') {
    visit(uri);
    return;
  }
  if (visit(join(elementDirectory, uri))) return;
  if (!paths.resourceDirectory.empty()) visit(join(paths.resourceDirectory, uri));
}

}  // namespace

std::vector<std::string> meshCandidates(const RobotPaths& paths, const std::string& elementDirectory,
                                        const std::string& uri) {
  std::vector<std::string> out;
  forEachCandidate(paths, elementDirectory, uri, [&](std::string c) {
    out.push_back(std::move(c));
    return false;
  });
  return out;
}

std::string resolveRobotFile(const RobotPaths& paths, const std::string& elementDirectory, const std::string& uri,
                             const FileExists& exists) {
  std::string found;
  forEachCandidate(paths, elementDirectory, uri, [&](std::string c) {
    if (!exists(c)) return false;
    found = std::move(c);
    return true;
  });
  return found;
}

std::vector<std::string> moduleCandidates(const RobotPaths& paths, const std::string& module) {
  if (!module.empty() && module.front() == '/') return {module};
  const std::string& base = paths.resourceDirectory.empty() ? paths.robotDirectory : paths.resourceDirectory;
  return {join(base, module),           join(base, "modules/" + module), join(base, "../modules/" + module),
          join(base, "module/" + module), join(base, "../module/" + module)};
}

}  // namespace rscene::robot
