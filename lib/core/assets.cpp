#include "core/assets.hpp"

#include <sys/stat.h>

#include "core/filesystem.hpp"
#include "core/text.hpp"

namespace rscene {
namespace {

std::string join(const std::string& dir, const std::string& path) {
  if (dir.empty() || dir == ".") return path;
  if (dir.back() == '/') return dir + path;
  return dir + "/" + path;
}

}  // namespace

std::string joinPath(const std::string& dir, const std::string& path) { return join(dir, path); }

bool fileExistsOnDisk(const std::string& path) {
  return diskFileSystem().stat(path).kind == FileKind::Regular;  // the one classification of paths
}

std::string whyNotAFile(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return "does not exist";
  if (S_ISDIR(st.st_mode)) return "is a directory, not a file";
  if (S_ISFIFO(st.st_mode)) return "is a FIFO, not a regular file";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "is a device, not a regular file";
  if (!S_ISREG(st.st_mode)) return "is not a regular file";
  return "does not exist";  // a file an in-memory FileExists does not know
}

std::string directoryOf(std::string_view scenePath) {
  std::size_t slash = scenePath.rfind('/');
  if (slash == std::string_view::npos) return ".";
  if (slash == 0) return "/";
  return std::string(scenePath.substr(0, slash));
}

std::string resolveAsset(const std::string& sceneDir, const std::string& assetRoot, const std::string& path,
                         const FileExists& exists) {
  if (path.empty() || path.front() == '/') return path;
  std::string direct = join(sceneDir, path);
  if (exists(direct)) return direct;
  std::string root = assetRoot.empty() ? "." : assetRoot;
  std::string base = root.front() == '/' ? root : join(sceneDir, root);
  return join(base, path);
}

std::string resolveAsset(const std::string& sceneDir, const ProjectPlace& project, int version,
                         const std::string& assetRoot, const std::string& path, const FileExists& exists) {
  if (project.empty()) return resolveAsset(sceneDir, assetRoot, path, exists);
  if (path.empty() || path.front() == '/') return path;
  std::string direct = join(sceneDir, path);
  if (exists(direct)) return direct;
  std::string root = assetRoot.empty() ? "." : assetRoot;
  std::string base = root.front() == '/' ? root : join(version == 1 ? project.root : sceneDir, root);
  std::string asked = join(base, path);
  if (exists(asked) || project.assets.empty()) return asked;
  std::string shared = join(project.assets, path);
  return exists(shared) ? shared : asked;
}

std::string assetRootOf(const Document& doc) {
  std::string root = ".";
  for (const Record& r : doc.records)
    if (r.kind && r.kind->tag == "asset_root" && r.positionalCount > 0) root = percentDecode(doc.positionalText(r, 0));
  return root.empty() ? "." : root;
}

}  // namespace rscene
