// Directory operands: `rscene-fmt --check .`, `rscene-validate scenes/`.
#include <filesystem>

#include "common/cli.hpp"
#include "core/filesystem.hpp"
#include "core/find_scenes.hpp"
#include "core/project.hpp"

namespace rscene::cli {

bool anyDirectory(const std::vector<std::string>& operands) {
  std::error_code ec;
  std::string root;
  // A project's file stands for the project's folder (its scenes), as the folder does.
  for (const std::string& op : operands)
    if (op != "-" && (std::filesystem::is_directory(op, ec) || isProject(op, diskFileSystem(), root))) return true;
  return false;
}

Operands expandOperands(const std::vector<std::string>& operands, bool checkProjects) {
  Operands out;
  for (const std::string& op : operands) {
    std::error_code ec;
    if (std::string root; isProject(op, diskFileSystem(), root)) {
      out.hadDirectory = true;
      out.projects.push_back(root);
      Project project;
      if (checkProjects) {
        if (!openProject(root, project)) {
          out.ok = false;
          continue;
        }
      } else {
        std::string text;
        ProjectRead read;
        if (!readProjectFile(root, text, read)) {
          out.ok = false;
          continue;
        }
        project = std::move(read.project);
      }
      std::vector<std::string> errors;
      std::vector<std::string> scenes = projectScenes(project, errors);
      for (const std::string& e : errors) error(e);
      out.ok = out.ok && errors.empty();
      if (scenes.empty() && errors.empty() && !project.sceneDirectory.empty())
        warning("no .rscene files in project '" + root + "'");
      out.files.insert(out.files.end(), scenes.begin(), scenes.end());
      continue;
    }
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
