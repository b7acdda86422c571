// File access behind one interface, so that the libraries read assets the
// same way and tests can use an in-memory disk (ninja's DiskInterface).
// Reads are whole files with a size cap; only regular files are read, so
// a path naming /dev/zero, a FIFO or a directory is refused at once
// instead of hanging or reading without end.  Nothing here prints.
#pragma once
#include <cstdint>
#include <map>
#include <string>

namespace rscene {

enum class FileKind { Missing, Regular, Directory, Other };

struct FileStatus {
  FileKind kind = FileKind::Missing;
  std::uint64_t size = 0;  // bytes, for regular files
  // Why a path is Missing, as errno says: ENOENT (or 0) when nothing is
  // there; ELOOP, EACCES, ENOTDIR... when something is in the way.
  int error = 0;
};

class FileSystem {
 public:
  virtual ~FileSystem() = default;
  // What `path` names (symbolic links followed).
  virtual FileStatus stat(const std::string& path) const = 0;
  // The whole regular file `path` into `out`.  False with `error` set
  // ("no such file", "not a regular file", "file larger than N bytes", or
  // the system's reason) when it cannot; `out` is then unspecified.
  virtual bool read(const std::string& path, std::string& out, std::string* error,
                    std::uint64_t maxBytes = kDefaultMaxBytes) const = 0;

  bool exists(const std::string& path) const { return stat(path).kind != FileKind::Missing; }

  static constexpr std::uint64_t kDefaultMaxBytes = std::uint64_t{1} << 30;  // 1 GiB
};

// The real disk.  Opens without blocking (a FIFO with no writer does not
// hang the open) and checks the kind on the opened descriptor, so a file
// swapped between stat and open is still refused.
class DiskFileSystem : public FileSystem {
 public:
  FileStatus stat(const std::string& path) const override;
  bool read(const std::string& path, std::string& out, std::string* error,
            std::uint64_t maxBytes = kDefaultMaxBytes) const override;
};

// The process's disk, for callers that take a `const FileSystem&`.
const FileSystem& diskFileSystem();

// "file larger than N bytes": what a capped read says past its cap.
std::string fileTooLarge(std::uint64_t maxBytes);

// Files held in memory, for tests.  A directory exists when it was added
// or when a file lies below it.
class MemoryFileSystem : public FileSystem {
 public:
  void addFile(const std::string& path, std::string bytes) { files_[path] = std::move(bytes); }
  // A path that exists but is neither a file nor a directory (a device).
  void addOther(const std::string& path) { others_[path] = true; }
  FileStatus stat(const std::string& path) const override;
  bool read(const std::string& path, std::string& out, std::string* error,
            std::uint64_t maxBytes = kDefaultMaxBytes) const override;
  // How many read() calls succeeded: tests use it to see what a cache saved.
  int reads() const { return reads_; }

 private:
  std::map<std::string, std::string> files_;
  std::map<std::string, bool> others_;
  mutable int reads_ = 0;
};

}  // namespace rscene
