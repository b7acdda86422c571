#include "core/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <charconv>
#include <cstdint>
#include <cstring>

#include "core/temp_files.hpp"

namespace rscene {
namespace {

constexpr int kMaxSymlinkHops = 40;           // the kernel's own limit (ELOOP)
constexpr std::size_t kMaxTempBaseBytes = 200;  // ".NAME.tmpXXXXXX" must fit NAME_MAX (255)

class FdSink : public Sink {
 public:
  explicit FdSink(int fd) : fd_(fd) {}
  void write(std::string_view chunk) override {
    while (errno_ == 0 && !chunk.empty()) {
      ssize_t n = ::write(fd_, chunk.data(), chunk.size());
      if (n < 0) {
        if (errno == EINTR) continue;
        errno_ = errno;
        return;
      }
      chunk.remove_prefix(static_cast<std::size_t>(n));
    }
  }
  int error() const { return errno_; }

 private:
  int fd_;
  int errno_ = 0;
};

// strerror() text in the project's message style: lower-case start.
std::string errorText(int e) {
  std::string s = std::strerror(e);
  if (s.size() > 1 && s[0] >= 'A' && s[0] <= 'Z' && !(s[1] >= 'A' && s[1] <= 'Z')) s[0] = static_cast<char>(s[0] - 'A' + 'a');
  return s;
}

bool fail(std::string* error, std::string message) {
  if (error) *error = std::move(message);
  return false;
}

std::string directoryOf(const std::string& path) {
  std::size_t slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::string baseOf(const std::string& path) {
  std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// The names that mean an already open descriptor; -1 for any other path.
int descriptorNamed(std::string_view path) {
  if (path == "/dev/stdout") return 1;
  if (path == "/dev/stderr") return 2;
  for (std::string_view prefix : {std::string_view("/dev/fd/"), std::string_view("/proc/self/fd/")}) {
    if (path.substr(0, prefix.size()) != prefix) continue;
    std::string_view digits = path.substr(prefix.size());
    int fd = -1;
    auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), fd);
    if (ec == std::errc() && end == digits.data() + digits.size() && fd >= 0) return fd;
  }
  return -1;
}

// Runs produce() into `fd`; returns 0 or the errno of the first failure
// (-1 when produce() cancelled).
int produceInto(int fd, const std::function<bool(Sink&)>& produce) {
  FdSink sink(fd);
  bool produced = produce(sink);
  if (sink.error()) return sink.error();
  return produced ? 0 : -1;
}

bool reportWriteFailure(int err, std::string* error) {
  return fail(error, err < 0 ? "write cancelled" : errorText(err));
}

bool writeToDescriptor(int fd, const std::function<bool(Sink&)>& produce, std::string* error) {
  struct stat st {};
  if (::fstat(fd, &st) != 0) return fail(error, errorText(errno));
  if (int err = produceInto(fd, produce)) return reportWriteFailure(err, error);
  return true;
}

// A device or FIFO: written through, never truncated, never replaced.
bool writeThrough(const std::string& path, const struct stat& st, const std::function<bool(Sink&)>& produce,
                  std::string* error) {
  int flags = O_WRONLY | O_CLOEXEC | O_NOCTTY;
  int fd = -1;
  if (S_ISFIFO(st.st_mode)) {
    // A FIFO with no reader fails a non-blocking open with ENXIO; then wait
    // for a reader like a shell redirection (an interrupt ends the wait).
    fd = ::open(path.c_str(), flags | O_NONBLOCK);
    if (fd >= 0) {
      ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    } else if (errno == ENXIO) {
      do fd = ::open(path.c_str(), flags);
      while (fd < 0 && errno == EINTR);
    }
  } else {
    fd = ::open(path.c_str(), flags);
  }
  if (fd < 0) return fail(error, errorText(errno));
  int err = produceInto(fd, produce);
  if (::close(fd) != 0 && err == 0 && errno != EINTR) err = errno;
  if (err) return reportWriteFailure(err, error);
  return true;
}

std::string randomSuffix() {
  static std::atomic<std::uint64_t> counter{0};
  std::uint64_t x = static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count()) ^
                    (static_cast<std::uint64_t>(::getpid()) << 32) ^
                    (counter.fetch_add(1) * 0x9E3779B97F4A7C15ull);
  // splitmix64's finaliser, so neighbouring inputs give unrelated names
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  x ^= x >> 31;
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
  std::string s(6, 'X');
  for (char& c : s) {
    c = kAlphabet[x % 62];
    x /= 62;
  }
  return s;
}

// Owns the temporary file from before it exists until it is renamed or
// removed, registered for signal handlers all the while.
class TemporaryFile {
 public:
  // Creates `.BASE.tmpXXXXXX` beside `target`; fd() < 0 and errno set on failure.
  TemporaryFile(const std::string& target, mode_t mode) {
    std::string prefix = directoryOf(target) + "/." + baseOf(target).substr(0, kMaxTempBaseBytes) + ".tmp";
    for (int attempt = 0; attempt < 100; ++attempt) {
      path_ = prefix + randomSuffix();
      slot_ = registerTemporaryFile(path_);
      fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, mode);
      if (fd_ >= 0) {
        created_ = true;
        return;
      }
      int e = errno;
      forgetTemporaryFile(slot_);
      slot_ = -1;
      errno = e;
      if (e != EEXIST) return;
    }
  }
  ~TemporaryFile() {
    if (fd_ >= 0) ::close(fd_);
    if (created_ && !renamed_) ::unlink(path_.c_str());
    forgetTemporaryFile(slot_);
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  int fd() const { return fd_; }
  // Flushes, closes and renames onto `target`; 0 or an errno.
  int commit(const std::string& target) {
    int err = ::fsync(fd_) == 0 ? 0 : errno;
    int closed = ::close(fd_);
    fd_ = -1;
    if (err == 0 && closed != 0 && errno != EINTR) err = errno;
    if (err == 0 && ::rename(path_.c_str(), target.c_str()) != 0) err = errno;
    renamed_ = err == 0;
    return err;
  }

 private:
  std::string path_;
  int fd_ = -1;
  int slot_ = -1;
  bool created_ = false;  // a failed O_EXCL open names someone else's file
  bool renamed_ = false;
};

// Keeps what the replaced file had: owner and group where allowed, then the
// mode (chown clears set-id bits, so the mode comes last).
int keepAttributes(int fd, const struct stat& old) {
  struct stat now {};
  if (::fstat(fd, &now) != 0) return errno;
  if (now.st_uid != old.st_uid || now.st_gid != old.st_gid) {
    // Only root may give a file away; a user may still keep its group.
    if (::fchown(fd, old.st_uid, old.st_gid) != 0 && now.st_gid != old.st_gid)
      (void)::fchown(fd, static_cast<uid_t>(-1), old.st_gid);
  }
  return ::fchmod(fd, old.st_mode & 07777) == 0 ? 0 : errno;
}

// Why an existing regular file may not be replaced, or "" when it may.
std::string refusal(const std::string& userPath, const std::string& target, const struct stat& st) {
  // No write bit for anyone refuses root too: root's access() would say yes.
  if ((st.st_mode & 0222) == 0) return "permission denied";
  if (::faccessat(AT_FDCWD, target.c_str(), W_OK, AT_EACCESS) != 0) {
    if (errno == EACCES || errno == EPERM) return "permission denied";
    if (errno == EROFS) return errorText(EROFS);
  }
  if (st.st_nlink > 1) {
    return "has " + std::to_string(st.st_nlink) +
           " hard links; refusing to split them (to write it, make it a file of its own first: cp " + userPath +
           " tmp && mv tmp " + userPath + ")";
  }
  return {};
}

// `existing` is null for a new file.
bool replaceAtomically(const std::string& userPath, const std::string& target, const struct stat* existing,
                       const std::function<bool(Sink&)>& produce, std::string* error) {
  if (baseOf(target).empty()) return fail(error, errorText(EISDIR));
  if (existing) {
    if (std::string why = refusal(userPath, target, *existing); !why.empty()) return fail(error, why);
  }
  // A new file gets 0666 less the umask from open(2) itself; a replacement
  // starts private and receives the old mode once its owner is right.
  TemporaryFile tmp(target, existing ? 0600 : 0666);
  if (tmp.fd() < 0) {
    return fail(error, std::string(existing ? "cannot create a temporary file in '" : "cannot create a file in '") +
                           directoryOf(target) + "': " + errorText(errno));
  }
  if (existing) {
    if (int err = keepAttributes(tmp.fd(), *existing)) return fail(error, "cannot set mode: " + errorText(err));
  }
  if (int err = produceInto(tmp.fd(), produce)) return reportWriteFailure(err, error);
  if (int err = tmp.commit(target)) return fail(error, errorText(err));
  // The rename is durable once the directory is (failure here loses nothing).
  int dir = ::open(directoryOf(target).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir >= 0) {
    (void)::fsync(dir);
    ::close(dir);
  }
  return true;
}

}  // namespace

bool writeOutputFile(const std::string& path, const std::function<bool(Sink&)>& produce, std::string* error) {
  if (path.empty()) return fail(error, errorText(ENOENT));
  // Follow a symlink chain one hop at a time: the chain may lead to an open
  // descriptor (/dev/stdout -> /proc/self/fd/1), and a dangling link is
  // named by what it points to.
  std::string p = path, lastLink;
  struct stat st {};
  for (int hops = 0;; ++hops) {
    if (int fd = descriptorNamed(p); fd >= 0) return writeToDescriptor(fd, produce, error);
    if (::lstat(p.c_str(), &st) != 0) {
      int e = errno;
      if (e == ENOENT && hops > 0)
        return fail(error, "is a dangling symbolic link to '" + lastLink + "'; create the target or remove the link");
      if (e == ENOENT) return replaceAtomically(path, p, nullptr, produce, error);
      return fail(error, errorText(e));
    }
    if (!S_ISLNK(st.st_mode)) break;
    if (hops == kMaxSymlinkHops) return fail(error, errorText(ELOOP));
    std::string target(static_cast<std::size_t>(st.st_size > 0 ? st.st_size : 4095) + 1, '\0');
    ssize_t n = ::readlink(p.c_str(), target.data(), target.size());
    if (n <= 0) return fail(error, errorText(n < 0 ? errno : ENOENT));
    if (static_cast<std::size_t>(n) >= target.size()) return fail(error, errorText(ENAMETOOLONG));
    target.resize(static_cast<std::size_t>(n));
    lastLink = target;
    p = target.front() == '/' ? target : directoryOf(p) + "/" + target;
  }
  if (S_ISREG(st.st_mode)) return replaceAtomically(path, p, &st, produce, error);
  if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return writeThrough(p, st, produce, error);
  if (S_ISDIR(st.st_mode)) return fail(error, errorText(EISDIR));
  if (S_ISBLK(st.st_mode)) return fail(error, "is a block device; refusing to write over it");
  if (S_ISSOCK(st.st_mode)) return fail(error, "is a socket");
  return fail(error, "is not a regular file, device or FIFO");
}

}  // namespace rscene
