// Engine 2 projects as operands (core/project.hpp): a project where one
// scene is meant is its default scene; where a tool takes several, it is
// every scene under its scene_directory.  A scene's project (for asset
// paths) is found from the scene's folder, so `rscene-render PROJECT/` and
// `rscene-render PROJECT/examples/x.rscene` resolve the same files.
#include <map>

#include "common/cli.hpp"
#include "core/filesystem.hpp"
#include "core/project.hpp"

namespace rscene::cli {

bool readProjectFile(const std::string& root, std::string& text, ProjectRead& read) {
  // Through the FileSystem: a FIFO, a device or a folder in the project
  // file's place is refused at once (RS1201), and a read stops at the cap.
  read = readProject(root, diskFileSystem(), &text);
  return true;
}

bool openProject(const std::string& root, Project& project) {
  std::string text;
  ProjectRead read;
  if (!readProjectFile(root, text, read)) return false;
  Diagnostics errors;
  for (const Diagnostic& d : read.diagnostics)
    if (d.severity == Severity::Error) errors.push_back(d);
  if (!errors.empty()) {
    printDiagnostics(errors, read.project.file, text, colorFor(2));
    return false;
  }
  project = std::move(read.project);
  return true;
}

ProjectPlace projectPlace(const Input& in, const std::string& baseDir) {
  std::string dir = in.isStdin ? baseDir : directoryOf(in.path);
  if (dir.empty()) return {};
  // One walk up the folders per scene folder: a batch of scenes in one
  // folder asks the disk once.
  static std::map<std::string, ProjectPlace> known;
  if (auto it = known.find(dir); it != known.end()) return it->second;
  return known[dir] = projectPlaceOf(dir, diskFileSystem());
}

bool defaultSceneOf(const std::string& operand, std::string& scene) {
  std::string root;
  if (!isProject(operand, diskFileSystem(), root)) return true;
  Project project;
  if (!openProject(root, project)) return false;
  if (project.defaultScene.empty()) {
    error("project '" + root + "' has no default_scene: name one of its scenes");
    return false;
  }
  scene = project.under(project.defaultScene);
  return true;
}

}  // namespace rscene::cli
