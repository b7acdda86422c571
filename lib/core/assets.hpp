// Asset path resolution (compat-notes.md, "Asset path resolution"), shared
// by validate --check-files, sim and render.  File existence is asked
// through a callback so tests can use an in-memory file set.
#pragma once
#include <functional>
#include <string>
#include <string_view>

#include "core/document.hpp"

namespace rscene {

using FileExists = std::function<bool(const std::string&)>;

// Real file-system check: a regular file exists at `path` (through links).
// Directories, devices (/dev/zero) and FIFOs are not asset files: reading
// them would never end or would mean nothing.
bool fileExistsOnDisk(const std::string& path);

// Why `path` is not an asset file, for messages: "does not exist", "is a
// directory, not a file", "is a FIFO, not a regular file" ...
std::string whyNotAFile(const std::string& path);

// Directory of a scene file path ("" -> ".").
std::string directoryOf(std::string_view scenePath);

// The Engine 2 project a scene belongs to (core/project.hpp), as asset
// resolution needs it; empty members: the scene is in no project.
struct ProjectPlace {
  std::string root;    // the project folder
  std::string assets;  // its asset_directory, joined to root ("" when absent)
  bool empty() const { return root.empty(); }
};

// Resolves `path` as written in a scene whose file lives in `sceneDir` and
// whose asset_root is `assetRoot` (decoded; empty means "."):
//   empty or absolute -> as is;
//   relative -> sceneDir/path if that exists, else
//               (absolute assetRoot, or sceneDir/assetRoot)/path.
std::string resolveAsset(const std::string& sceneDir, const std::string& assetRoot, const std::string& path,
                         const FileExists& exists = fileExistsOnDisk);

// The same for a scene of version `version` in `project` (README, "Engine 2
// projects"): a relative path is tried
//   1. against the scene's folder;
//   2. against asset_root, which a version-1 scene in a project reads from
//      the project folder (compat-notes.md, "Versions") and every other
//      scene from its own folder;
//   3. against the project's asset_directory;
// and the first that exists wins.  When none does, the answer is 2, the
// place the scene itself asked for, so a message names that.
std::string resolveAsset(const std::string& sceneDir, const ProjectPlace& project, int version,
                         const std::string& assetRoot, const std::string& path,
                         const FileExists& exists = fileExistsOnDisk);

// Joins a folder and a relative path ("." and "" add nothing).
std::string joinPath(const std::string& dir, const std::string& path);

// The decoded asset_root of a document (last asset_root record), or ".".
std::string assetRootOf(const Document& doc);

}  // namespace rscene
