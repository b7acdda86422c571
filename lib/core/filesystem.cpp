#include "core/filesystem.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace rscene {
namespace {

bool fail(std::string* error, const std::string& why) {
  if (error) *error = why;
  return false;
}

FileKind kindOf(mode_t mode) {
  if (S_ISREG(mode)) return FileKind::Regular;
  if (S_ISDIR(mode)) return FileKind::Directory;
  return FileKind::Other;
}

// Closes the descriptor on every path out of read().
struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

FileStatus DiskFileSystem::stat(const std::string& path) const {
  struct stat st {};
  if (path.empty()) return {};
  if (::stat(path.c_str(), &st) != 0) return {FileKind::Missing, 0, errno};
  return {kindOf(st.st_mode), S_ISREG(st.st_mode) ? static_cast<std::uint64_t>(st.st_size) : 0};
}

bool DiskFileSystem::read(const std::string& path, std::string& out, std::string* error,
                          std::uint64_t maxBytes) const {
  if (path.empty()) return fail(error, "empty path");
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer.
  Fd f{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
  if (f.fd < 0) return fail(error, std::strerror(errno));
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) return fail(error, std::strerror(errno));
  if (S_ISDIR(st.st_mode)) return fail(error, "is a directory");
  if (!S_ISREG(st.st_mode)) return fail(error, "not a regular file");
  auto size = static_cast<std::uint64_t>(st.st_size);
  if (size > maxBytes) return fail(error, fileTooLarge(maxBytes));
  out.resize(static_cast<std::size_t>(size));
  std::size_t used = 0;
  while (used < out.size()) {
    ssize_t n = ::read(f.fd, out.data() + used, out.size() - used);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return fail(error, std::strerror(errno));
    if (n == 0) break;  // the file shrank since fstat
    used += static_cast<std::size_t>(n);
  }
  out.resize(used);
  // A file that grew since fstat: read on, still under the cap.
  char chunk[1 << 14];
  for (;;) {
    ssize_t n = ::read(f.fd, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return fail(error, std::strerror(errno));
    if (n == 0) return true;
    if (out.size() + static_cast<std::size_t>(n) > maxBytes) return fail(error, fileTooLarge(maxBytes));
    out.append(chunk, static_cast<std::size_t>(n));
  }
}

std::string fileTooLarge(std::uint64_t maxBytes) { return "file larger than " + std::to_string(maxBytes) + " bytes"; }

const FileSystem& diskFileSystem() {
  static const DiskFileSystem disk;
  return disk;
}

FileStatus MemoryFileSystem::stat(const std::string& path) const {
  if (auto it = files_.find(path); it != files_.end()) return {FileKind::Regular, it->second.size()};
  if (others_.count(path)) return {FileKind::Other, 0};
  std::string dir = path.empty() || path.back() == '/' ? path : path + "/";
  auto below = files_.lower_bound(dir);
  if (!dir.empty() && below != files_.end() && below->first.compare(0, dir.size(), dir) == 0)
    return {FileKind::Directory, 0};
  return {};
}

bool MemoryFileSystem::read(const std::string& path, std::string& out, std::string* error,
                            std::uint64_t maxBytes) const {
  FileStatus st = stat(path);
  if (st.kind == FileKind::Missing) return fail(error, std::strerror(ENOENT));
  if (st.kind == FileKind::Directory) return fail(error, "is a directory");
  if (st.kind == FileKind::Other) return fail(error, "not a regular file");
  if (st.size > maxBytes) return fail(error, fileTooLarge(maxBytes));
  out = files_.at(path);
  ++reads_;
  return true;
}

}  // namespace rscene
