// Engine 2 projects (rscene-format.txt, "Relationship To Projects And
// Scripts"): a folder whose `raisim_engine2_project` file names the
// project's scene folder, asset folder and default scene:
//
//   raisim_engine2_project 1
//   name RaiSim Engine 2 Built-in Project
//   asset_directory assets
//   scene_directory examples
//   default_scene examples/warehouse_scene.rscene
//   description Built-in scenes and assets shipped with raisim_engine2.
//
// One record per line: a key, white space, then the rest of the line as
// its value (names and descriptions hold spaces).  Paths are relative to
// the project folder, or absolute.  Reading goes through a FileSystem, so
// tests use an in-memory one; nothing here prints.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/assets.hpp"
#include "core/diagnostic.hpp"

namespace rscene {

class FileSystem;

inline constexpr const char* kProjectFileName = "raisim_engine2_project";
inline constexpr std::uint64_t kMaxProjectFileBytes = 1 << 20;  // a handful of lines; 1 MiB is already absurd

struct Project {
  std::string root;  // the folder holding the project file, as given
  std::string file;  // root/raisim_engine2_project
  std::string name, description;
  // As written (relative to root, or absolute); "" when the record is absent.
  std::string assetDirectory, sceneDirectory, defaultScene;
  // The line of each path record, 0 when absent (for messages).
  std::uint32_t assetLine = 0, sceneLine = 0, defaultLine = 0;

  // `path` of this project, joined to its root unless absolute.
  std::string under(const std::string& path) const;
  // Where relative asset paths of its scenes fall back to.
  ProjectPlace place() const;
};

struct ProjectRead {
  Project project;
  Diagnostics diagnostics;  // in `project.file`; an error makes the project unusable
  bool ok() const { return !hasErrors(diagnostics); }
};

// Reads and checks the project file of the folder `root`: its header, its
// records, and that its folders and default scene exist.  `text`, when
// given, gets the file's bytes (empty when it cannot be read), for a
// report that shows the lines of its findings.
ProjectRead readProject(const std::string& root, const FileSystem& files, std::string* text = nullptr);

// Reads project text already in memory (tests; `root` places its paths).
ProjectRead parseProject(std::string_view text, const std::string& root, const FileSystem& files);

// Whether `path` is a project: a folder holding a project file, or the
// project file itself.  Sets `root` to the folder.
bool isProject(const std::string& path, const FileSystem& files, std::string& root);

// The project a scene in folder `sceneDir` belongs to, as its assets need
// it: the nearest folder at or above it that holds a project file whose
// scene_directory contains the scene's folder (or whose default_scene is
// in it), read once.  Empty when there is none, or when that project file
// has errors.  A scene outside the project's scene folder is not the
// project's (a project file in a home folder does not capture every scene
// below it).
ProjectPlace projectPlaceOf(const std::string& sceneDir, const FileSystem& files);

// The project's scene files: *.rscene under scene_directory (the order of
// findScenes), and the default scene when it lies outside that folder.
// Errors reading folders go to `errors`.
std::vector<std::string> projectScenes(const Project& project, std::vector<std::string>& errors);

}  // namespace rscene
