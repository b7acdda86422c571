// Directory operands: `rscene-fmt --check .`, `rscene-validate scenes/`.
#include <filesystem>

#include "common/cli.hpp"
#include "core/find_scenes.hpp"

namespace rscene::cli {

bool anyDirectory(const std::vector<std::string>& operands) {
  std::error_code ec;
  for (const std::string& op : operands)
    if (op != "-" && std::filesystem::is_directory(op, ec)) return true;
  return false;
}

Operands expandOperands(const std::vector<std::string>& operands) {
  Operands out;
  for (const std::string& op : operands) {
    std::error_code ec;
    if (op == "-" || !std::filesystem::is_directory(op, ec)) {
      out.files.push_back(op);  // a missing file is reported when it is read
      continue;
    }
    out.hadDirectory = true;
    SceneSearch found = findScenes(op);
    for (const std::string& e : found.errors) error(e);
    out.ok = out.ok && found.errors.empty();
    // Like black ("No Python files are present"), a folder without scenes
    // is no error: a hook run over a tree without scenes passes.
    if (found.files.empty() && found.errors.empty()) warning("no .rscene files under '" + op + "'");
    out.files.insert(out.files.end(), std::make_move_iterator(found.files.begin()),
                     std::make_move_iterator(found.files.end()));
  }
  return out;
}

}  // namespace rscene::cli
