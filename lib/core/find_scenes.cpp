#include "core/find_scenes.hpp"

#include <algorithm>
#include <filesystem>
#include <system_error>

namespace rscene {
namespace fs = std::filesystem;

namespace {

bool isScene(const std::string& name) {
  constexpr std::string_view kExt = ".rscene";
  return name.size() > kExt.size() && name.compare(name.size() - kExt.size(), kExt.size(), kExt) == 0;
}

// `dir/name`, without a doubled slash, and without `./` for the current
// folder so that `rscene-fmt --check .` lists `a.rscene` like prettier.
std::string join(const std::string& dir, const std::string& name) {
  if (dir == ".") return name;
  return dir.back() == '/' ? dir + name : dir + '/' + name;
}

struct Entry {
  std::string path;
  bool isDir;
};

}  // namespace

SceneSearch findScenes(const std::string& dir) {
  SceneSearch out;
  // Depth-first with an explicit stack (no recursion limit on deep trees):
  // popping a folder pushes its entries in reverse name order.
  std::vector<Entry> stack{{dir, true}};
  while (!stack.empty()) {
    Entry e = std::move(stack.back());
    stack.pop_back();
    if (!e.isDir) {
      out.files.push_back(std::move(e.path));
      continue;
    }
    std::error_code ec;
    fs::directory_iterator it(e.path.empty() ? "." : e.path, ec), end;
    std::vector<std::pair<std::string, bool>> children;
    for (; !ec && it != end; it.increment(ec)) {
      std::string name = it->path().filename().string();
      if (name.empty() || name[0] == '.') continue;
      std::error_code typeError;
      // symlink_status: a link to a folder is not walked into.
      fs::file_type own = it->symlink_status(typeError).type();
      if (own == fs::file_type::directory) {
        children.emplace_back(std::move(name), true);
      } else if (isScene(name) && fs::is_regular_file(it->status(typeError))) {
        children.emplace_back(std::move(name), false);
      }
    }
    if (ec) {
      out.errors.push_back("cannot read directory '" + e.path + "': " + ec.message());
      continue;
    }
    std::sort(children.begin(), children.end());
    for (auto c = children.rbegin(); c != children.rend(); ++c) stack.push_back({join(e.path, c->first), c->second});
  }
  return out;
}

}  // namespace rscene
