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

// Resolves `path` as written in a scene whose file lives in `sceneDir` and
// whose asset_root is `assetRoot` (decoded; empty means "."):
//   empty or absolute -> as is;
//   relative -> sceneDir/path if that exists, else
//               (absolute assetRoot, or sceneDir/assetRoot)/path.
std::string resolveAsset(const std::string& sceneDir, const std::string& assetRoot, const std::string& path,
                         const FileExists& exists = fileExistsOnDisk);

// The decoded asset_root of a document (last asset_root record), or ".".
std::string assetRootOf(const Document& doc);

}  // namespace rscene
