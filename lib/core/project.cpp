#include "core/project.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "core/codes.hpp"
#include "core/filesystem.hpp"
#include "core/find_scenes.hpp"
#include "core/text.hpp"

namespace rscene {
namespace fs = std::filesystem;

namespace {

// A path stat() found nothing at: missing, or unreachable (a symlink loop,
// a folder without search permission), which "does not exist" would hide.
std::string missingWhy(const FileStatus& st) {
  if (st.error == 0 || st.error == ENOENT) return "does not exist";
  return std::string("cannot be reached: ") + std::strerror(st.error);
}

Diagnostic finding(const char* code, Severity severity, std::uint32_t line, std::uint32_t column, std::string message,
                   std::string hint = {}) {
  Diagnostic d;
  d.code = code;
  d.severity = severity;
  d.line = line;
  d.column = column;
  d.message = std::move(message);
  d.hint = std::move(hint);
  return d;
}

bool endsWith(std::string_view s, std::string_view end) {
  return s.size() >= end.size() && s.substr(s.size() - end.size()) == end;
}

// The text's first NUL byte or bad UTF-8 sequence, as the scene loader
// refuses them (RS1004, RS1005); true when there is none.
bool cleanText(std::string_view text, Diagnostics& out) {
  std::uint32_t line = 1;
  std::size_t lineStart = 0;
  for (std::size_t i = 0; i < text.size();) {
    unsigned char c = static_cast<unsigned char>(text[i]);
    auto column = static_cast<std::uint32_t>(i - lineStart + 1);
    if (c == 0) {
      out.push_back(finding(rs::RS1004, Severity::Error, line, column, "project file contains a NUL byte"));
      return false;
    }
    if (c == '\n') {
      ++line;
      lineStart = ++i;
      continue;
    }
    std::size_t n = utf8SequenceLength(text, i);
    if (n == 0) {
      out.push_back(finding(rs::RS1005, Severity::Error, line, column, "invalid UTF-8 in the project file"));
      return false;
    }
    i += n;
  }
  return true;
}

struct Line {
  std::uint32_t number;
  std::string_view key, value;
  std::uint32_t valueColumn;
};

// Splits the text into records: `key value...`, blank lines and `#`
// comments skipped, a trailing CR and surrounding blanks trimmed.
std::vector<Line> records(std::string_view text) {
  std::vector<Line> out;
  std::uint32_t number = 0;
  for (std::size_t start = 0; start < text.size() || (start == text.size() && number == 0);) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    ++number;
    start = end + 1;
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.remove_suffix(1);
    std::size_t k = line.find_first_not_of(" \t");
    if (k == std::string_view::npos || line[k] == '#') {
      if (end == text.size()) break;
      continue;
    }
    std::size_t keyEnd = line.find_first_of(" \t", k);
    if (keyEnd == std::string_view::npos) keyEnd = line.size();
    std::size_t v = line.find_first_not_of(" \t", keyEnd);
    if (v == std::string_view::npos) v = line.size();
    out.push_back({number, line.substr(k, keyEnd - k), line.substr(v), static_cast<std::uint32_t>(v + 1)});
    if (end == text.size()) break;
  }
  return out;
}

std::string parentOf(const std::string& dir) {
  fs::path p = (fs::path(dir) / "..").lexically_normal();
  std::string s = p.string();
  while (s.size() > 1 && s.back() == '/') s.pop_back();
  return s.empty() ? "." : s;
}

// `inner` lies at or below `outer` (both as they resolve on the disk).
bool within(const std::string& inner, const std::string& outer) {
  std::error_code ec;
  fs::path i = fs::weakly_canonical(inner, ec);
  if (ec) return false;
  fs::path o = fs::weakly_canonical(outer, ec);
  if (ec) return false;
  auto [oi, ii] = std::mismatch(o.begin(), o.end(), i.begin(), i.end());
  return oi == o.end() || (std::next(oi) == o.end() && oi->empty());  // "a/b/" ends in an empty element
}

}  // namespace

std::string Project::under(const std::string& path) const {
  if (path.empty() || path.front() == '/') return path;
  std::string joined = joinPath(root, path);
  while (joined.size() > 1 && joined.back() == '/') joined.pop_back();
  return joined;
}

ProjectPlace Project::place() const { return {root, assetDirectory.empty() ? std::string() : under(assetDirectory)}; }

ProjectRead parseProject(std::string_view text, const std::string& root, const FileSystem& files) {
  ProjectRead r;
  Project& p = r.project;
  p.root = root.empty() ? "." : root;
  p.file = joinPath(p.root, kProjectFileName);
  Diagnostics& ds = r.diagnostics;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") {
    ds.push_back(finding(rs::RS1201, Severity::Error, 1, 1, "project file starts with a UTF-8 byte order mark",
                         "save it without one: the first bytes are `raisim_engine2_project 1`"));
    return r;
  }
  if (!cleanText(text, ds)) return r;
  std::vector<Line> lines = records(text);
  const std::string header = std::string(kProjectFileName);
  if (lines.empty() || lines.front().key != header) {
    std::uint32_t at = lines.empty() ? 1 : lines.front().number;
    ds.push_back(finding(rs::RS1201, Severity::Error, at, 1, "missing " + header + " header",
                         "the first line of a project file is `" + header + " 1`"));
    return r;
  }
  if (lines.front().value != "1") {
    ds.push_back(finding(rs::RS1201, Severity::Error, lines.front().number, lines.front().valueColumn,
                         "unsupported project version '" + std::string(lines.front().value) + "' (only 1 exists)"));
    return r;
  }
  struct Known {
    const char* key;
    std::string* value;
    std::uint32_t* line;
    bool path;
  };
  std::uint32_t nameLine = 0, descriptionLine = 0;
  const Known known[] = {{"name", &p.name, &nameLine, false},
                         {"description", &p.description, &descriptionLine, false},
                         {"asset_directory", &p.assetDirectory, &p.assetLine, true},
                         {"scene_directory", &p.sceneDirectory, &p.sceneLine, true},
                         {"default_scene", &p.defaultScene, &p.defaultLine, true}};
  std::vector<std::uint32_t> columns(5, 0);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const Line& l = lines[i];
    auto it = std::find_if(std::begin(known), std::end(known), [&](const Known& k) { return l.key == k.key; });
    if (it == std::end(known)) {
      ds.push_back(finding(rs::RS1202, Severity::Warning, l.number, 1,
                           "unknown project record '" + std::string(l.key) + "' (ignored)",
                           "known records: name, asset_directory, scene_directory, default_scene, description"));
      continue;
    }
    if (it->path && l.value.empty()) {
      ds.push_back(finding(rs::RS1203, Severity::Error, l.number, 1, "project record '" + std::string(l.key) + "' has no value",
                           "write a path relative to the project folder"));
      continue;
    }
    if (*it->line != 0) {
      ds.push_back(finding(rs::RS1204, Severity::Error, l.number, 1,
                           "project record '" + std::string(l.key) + "' given twice (first at line " +
                               std::to_string(*it->line) + ")"));
      continue;
    }
    *it->line = l.number;
    *it->value = std::string(l.value);
    columns[static_cast<std::size_t>(it - std::begin(known))] = l.valueColumn;
  }
  if (p.sceneLine == 0 && !hasErrors(ds)) {
    ds.push_back(finding(rs::RS1205, Severity::Error, lines.front().number, 1, "the project has no scene_directory record",
                         "add `scene_directory FOLDER`: the folder of the project's scenes"));
  }
  auto folder = [&](const std::string& value, std::uint32_t line, std::uint32_t column, const char* key) {
    if (line == 0) return;
    std::string path = p.under(value);
    FileStatus st = files.stat(path);
    if (st.kind == FileKind::Directory) return;
    ds.push_back(finding(rs::RS1206, Severity::Error, line, column,
                         std::string(key) + " '" + value + "' " +
                             (st.kind == FileKind::Missing ? missingWhy(st) : "is not a folder") + " (looked for '" +
                             path + "')"));
  };
  folder(p.assetDirectory, p.assetLine, columns[2], "asset_directory");
  folder(p.sceneDirectory, p.sceneLine, columns[3], "scene_directory");
  if (p.defaultLine != 0) {
    std::string path = p.under(p.defaultScene);
    FileStatus st = files.stat(path);
    FileKind kind = st.kind;
    std::string why = kind == FileKind::Missing     ? missingWhy(st)
                      : kind != FileKind::Regular   ? "is not a regular file"
                      : !endsWith(path, ".rscene") ? "is not a .rscene file"
                                                    : "";
    if (!why.empty())
      ds.push_back(finding(rs::RS1207, Severity::Error, p.defaultLine, columns[4],
                           "default_scene '" + p.defaultScene + "' " + why + " (looked for '" + path + "')"));
  } else if (!hasErrors(ds)) {
    ds.push_back(finding(rs::RS1208, Severity::Warning, lines.front().number, 1, "the project has no default_scene record",
                         "tools given the project where one scene is meant (rscene-to-json PROJECT) need one"));
  }
  return r;
}

ProjectRead readProject(const std::string& root, const FileSystem& files, std::string* textOut) {
  std::string file = joinPath(root.empty() ? "." : root, kProjectFileName);
  std::string own, error;
  std::string& text = textOut ? *textOut : own;
  if (!files.read(file, text, &error, kMaxProjectFileBytes)) {
    text.clear();
    ProjectRead r;
    r.project.root = root.empty() ? "." : root;
    r.project.file = file;
    r.diagnostics.push_back(finding(rs::RS1201, Severity::Error, 0, 0, "cannot read the project file: " + error));
    return r;
  }
  return parseProject(text, root, files);
}

bool isProject(const std::string& path, const FileSystem& files, std::string& root) {
  if (path.empty() || path == "-") return false;
  FileKind kind = files.stat(path).kind;
  if (kind == FileKind::Directory) {
    // Whatever holds the name makes the folder a project, so that a FIFO,
    // a folder or a link loop there is refused as a project file (RS1201)
    // instead of the folder being taken for a plain folder of scenes.
    std::string file = joinPath(path, kProjectFileName);
    std::error_code ec;
    if (files.stat(file).kind == FileKind::Missing && !fs::is_symlink(file, ec)) return false;
    root = path;
    while (root.size() > 1 && root.back() == '/') root.pop_back();
    return true;
  }
  std::string_view name = path;
  if (std::size_t slash = name.rfind('/'); slash != std::string_view::npos) name.remove_prefix(slash + 1);
  if (kind != FileKind::Regular || name != kProjectFileName) return false;
  root = directoryOf(path);
  return true;
}

ProjectPlace projectPlaceOf(const std::string& sceneDir, const FileSystem& files) {
  std::error_code ec;
  fs::path absolute = fs::absolute(sceneDir.empty() ? "." : sceneDir, ec).lexically_normal();
  if (ec) return {};
  // "/a/scenes/." normalises to "/a/scenes/", whose parent is "/a/scenes"
  // again: without its empty last element each step goes one folder up.
  if (!absolute.has_filename() && absolute.has_parent_path() && absolute != absolute.root_path())
    absolute = absolute.parent_path();
  std::string dir = sceneDir.empty() ? "." : sceneDir;
  for (fs::path at = absolute;; at = at.parent_path()) {
    if (files.stat((at / kProjectFileName).string()).kind == FileKind::Regular) {
      ProjectRead read = readProject(dir, files);
      if (read.ok() && !read.project.sceneDirectory.empty()) {
        const Project& p = read.project;
        if (within(sceneDir, p.under(p.sceneDirectory))) return p.place();
        if (!p.defaultScene.empty() && within(sceneDir, directoryOf(p.under(p.defaultScene))) &&
            within(directoryOf(p.under(p.defaultScene)), sceneDir))
          return p.place();
      }
      return {};  // the nearest project decides, even when the scene is not one of its scenes
    }
    if (at == at.parent_path() || at.empty()) return {};
    dir = parentOf(dir);
  }
}

std::vector<std::string> projectScenes(const Project& project, std::vector<std::string>& errors) {
  std::vector<std::string> out;
  std::error_code ec;
  // A scene_directory that is not a folder is the project file's finding (RS1206), not a second one.
  if (!project.sceneDirectory.empty() && fs::is_directory(project.under(project.sceneDirectory), ec)) {
    SceneSearch found = findScenes(project.under(project.sceneDirectory));
    out = std::move(found.files);
    errors.insert(errors.end(), found.errors.begin(), found.errors.end());
  }
  if (!project.defaultScene.empty()) {
    std::string scene = project.under(project.defaultScene);
    auto same = [&](const std::string& f) { return fs::equivalent(f, scene, ec); };
    // Not a .rscene file: the project file's finding (RS1207), not a scene to read.
    if (std::none_of(out.begin(), out.end(), same) && fs::is_regular_file(scene, ec) && endsWith(scene, ".rscene"))
      out.push_back(scene);
  }
  return out;
}

}  // namespace rscene
