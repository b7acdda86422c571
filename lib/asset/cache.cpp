#include "asset/cache.hpp"

namespace rscene::asset {
namespace {

// The cached value of `entry`, loading it on first use.
template <class T, class Entry, class Load>
std::shared_ptr<const T> cached(Entry& entry, bool fresh, std::string* error, Load&& load) {
  if (fresh) {
    auto value = std::make_shared<T>();
    if (load(*value, &entry.error)) entry.value = std::move(value);
  }
  if (!entry.value && error) *error = entry.error;
  return entry.value;
}

}  // namespace

std::shared_ptr<const Mesh> AssetCache::mesh(const std::string& path, MeshContent content, std::string* error) {
  auto [it, fresh] = meshes_.try_emplace({path, content});
  return cached<Mesh>(it->second, fresh, error, [&](Mesh& m, std::string* err) {
    return loadMesh(fs_, path, content, m, err, limits_,
                    [this](const std::string& p, std::string* e) { return image(p, e); });
  });
}

std::shared_ptr<const Image> AssetCache::image(const std::string& path, std::string* error) {
  auto [it, fresh] = images_.try_emplace(path);
  return cached<Image>(it->second, fresh, error, [&](Image& im, std::string* err) {
    std::string bytes;
    return fs_.read(path, bytes, err, limits_.maxFileBytes) && decodeImage(bytes, im, err, limits_.image);
  });
}

std::shared_ptr<const FloatImage> AssetCache::floatImage(const std::string& path, std::string* error) {
  auto [it, fresh] = floatImages_.try_emplace(path);
  return cached<FloatImage>(it->second, fresh, error, [&](FloatImage& im, std::string* err) {
    std::string bytes;
    return fs_.read(path, bytes, err, limits_.maxFileBytes) && decodeFloatImage(bytes, im, err, limits_.image);
  });
}

MeshReader AssetCache::meshReader(MeshContent content) {
  return [this, content](const std::string& path, std::string& error) { return mesh(path, content, &error) != nullptr; };
}

}  // namespace rscene::asset
