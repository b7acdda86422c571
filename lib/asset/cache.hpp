// One cache of loaded assets, keyed by resolved path and by what is
// extracted, so that ten objects naming one large mesh read and import it
// once (in rscene-sim as in rscene-render).  Failures are cached too: a
// missing file is asked for once and every asker gets the same reason.
// Not thread-safe; one per tool run.
#pragma once
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "asset/image.hpp"
#include "asset/mesh.hpp"
#include "core/filesystem.hpp"
#include "scene/triangle_surface.hpp"

namespace rscene::asset {

class AssetCache {
 public:
  explicit AssetCache(const FileSystem& fs = diskFileSystem(), AssetLimits limits = {})
      : fs_(fs), limits_(limits) {}

  // Null with `error` set when the file cannot be read or decoded.
  std::shared_ptr<const Mesh> mesh(const std::string& path, MeshContent content, std::string* error);
  std::shared_ptr<const Image> image(const std::string& path, std::string* error);            // PNG, JPEG
  std::shared_ptr<const FloatImage> floatImage(const std::string& path, std::string* error);  // HDR, PNG, JPEG

  const FileSystem& fileSystem() const { return fs_; }
  // mesh() as the scene model's MeshReader (SceneCheckOptions::readMesh):
  // a mesh read for the check stays cached for the tool's own use.
  MeshReader meshReader(MeshContent content);
  const AssetLimits& limits() const { return limits_; }

 private:
  template <class T>
  struct Entry {
    std::shared_ptr<const T> value;
    std::string error;
  };
  const FileSystem& fs_;
  AssetLimits limits_;
  std::map<std::pair<std::string, MeshContent>, Entry<Mesh>> meshes_;
  std::map<std::string, Entry<Image>> images_;
  std::map<std::string, Entry<FloatImage>> floatImages_;
};

}  // namespace rscene::asset
