#include "core/scene_pattern.hpp"

#include "core/assets.hpp"

namespace rscene {
namespace {

std::string doubledBraces(const std::string& s) {
  std::string out;
  for (char c : s) {
    out += c;
    if (c == '{' || c == '}') out += c;
  }
  return out;
}

// Walks `pattern`: `field(name)` gives a field's text, or false for a
// field it does not know; `literal(c)` writes a brace written twice.
template <class Field, class Literal>
bool walk(const std::string& pattern, std::string& out, std::string* error, Field field, Literal literal) {
  out.clear();
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    char c = pattern[i];
    if (c != '{' && c != '}') {
      out += c;
      continue;
    }
    if (i + 1 < pattern.size() && pattern[i + 1] == c) {
      literal(out, c);
      ++i;
      continue;
    }
    std::size_t end = c == '{' ? pattern.find('}', i) : std::string::npos;
    if (end == std::string::npos) {
      if (error)
        *error = std::string("unmatched '") + c + "' in output pattern '" + pattern + "' (write " + c + c + " for a brace)";
      return false;
    }
    std::string name = pattern.substr(i + 1, end - i - 1);
    if (!field(name, out)) {
      if (error) *error = "unknown field {" + name + "} in output pattern '" + pattern + "' (fields: {stem}, {dir})";
      return false;
    }
    i = end;
  }
  return true;
}

}  // namespace

SceneFields sceneFields(const std::string& path) {
  if (path.empty() || path == "-") return {"stdin", "."};
  std::string name = path.substr(path.rfind('/') == std::string::npos ? 0 : path.rfind('/') + 1);
  const std::string ext = ".rscene";
  if (name.size() > ext.size() && name.compare(name.size() - ext.size(), ext.size(), ext) == 0)
    name.resize(name.size() - ext.size());
  return {name, directoryOf(path)};
}

bool hasSceneFields(const std::string& pattern) {
  bool found = false;
  std::string ignored;
  walk(
      pattern, ignored, nullptr,
      [&](const std::string& name, std::string&) {
        found = found || name == "stem" || name == "dir";
        return true;
      },
      [](std::string&, char) {});
  return found;
}

std::string withSceneFields(const std::string& pattern, const SceneFields& f) {
  std::string out;
  bool ok = walk(
      pattern, out, nullptr,
      [&](const std::string& name, std::string& o) {
        if (name == "stem") o += doubledBraces(f.stem);
        else if (name == "dir") o += doubledBraces(f.dir);
        else o += "{" + name + "}";
        return true;
      },
      [](std::string& o, char c) { o += std::string(2, c); });
  return ok ? out : pattern;  // an unmatched brace: left for the tool's own expansion to report
}

bool expandScenePattern(const std::string& pattern, const SceneFields& f, std::string& out, std::string* error) {
  return walk(
      pattern, out, error,
      [&](const std::string& name, std::string& o) {
        if (name == "stem") o += f.stem;
        else if (name == "dir") o += f.dir;
        else return false;
        return true;
      },
      [](std::string& o, char c) { o += c; });
}

}  // namespace rscene
