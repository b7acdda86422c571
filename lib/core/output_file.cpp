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

namespace {

// What is at an output path once its symlink chain is followed: the one
// classification that writing, checking and comparing outputs share.
struct Resolved {
  enum Kind { Descriptor, New, Regular, Through, Refused } kind = Refused;
  int fd = -1;          // Descriptor
  std::string target;   // New, Regular, Through: the path at the end of the chain
  struct stat st {};    // Regular, Through
  std::string why;      // Refused
};

Resolved resolveOutput(const std::string& path) {
  Resolved r;
  if (path.empty()) {
    r.why = errorText(ENOENT);
    return r;
  }
  // Follow a symlink chain one hop at a time: the chain may lead to an open
  // descriptor (/dev/stdout -> /proc/self/fd/1), and a dangling link is
  // named by what it points to.
  std::string p = path, lastLink;
  for (int hops = 0;; ++hops) {
    if (int fd = descriptorNamed(p); fd >= 0) {
      r.kind = Resolved::Descriptor;
      r.fd = fd;
      return r;
    }
    if (::lstat(p.c_str(), &r.st) != 0) {
      int e = errno;
      if (e == ENOENT && hops > 0) {
        r.why = "is a dangling symbolic link to '" + lastLink + "'; create the target or remove the link";
      } else if (e == ENOENT) {
        r.kind = Resolved::New;
        r.target = p;
      } else {
        r.why = errorText(e);
      }
      return r;
    }
    if (!S_ISLNK(r.st.st_mode)) break;
    if (hops == kMaxSymlinkHops) {
      r.why = errorText(ELOOP);
      return r;
    }
    std::string target(static_cast<std::size_t>(r.st.st_size > 0 ? r.st.st_size : 4095) + 1, '\0');
    ssize_t n = ::readlink(p.c_str(), target.data(), target.size());
    if (n <= 0 || static_cast<std::size_t>(n) >= target.size()) {
      r.why = errorText(n < 0 ? errno : n == 0 ? ENOENT : ENAMETOOLONG);
      return r;
    }
    target.resize(static_cast<std::size_t>(n));
    lastLink = target;
    p = target.front() == '/' ? target : directoryOf(p) + "/" + target;
  }
  r.target = p;
  if (S_ISREG(r.st.st_mode)) r.kind = Resolved::Regular;
  else if (S_ISCHR(r.st.st_mode) || S_ISFIFO(r.st.st_mode)) r.kind = Resolved::Through;
  else if (S_ISDIR(r.st.st_mode)) r.why = errorText(EISDIR);
  else if (S_ISBLK(r.st.st_mode)) r.why = "is a block device; refusing to write over it";
  else if (S_ISSOCK(r.st.st_mode)) r.why = "is a socket";
  else r.why = "is not a regular file, device or FIFO";
  return r;
}

}  // namespace

bool writeOutputFile(const std::string& path, const std::function<bool(Sink&)>& produce, std::string* error) {
  Resolved r = resolveOutput(path);
  switch (r.kind) {
    case Resolved::Descriptor: return writeToDescriptor(r.fd, produce, error);
    case Resolved::New: return replaceAtomically(path, r.target, nullptr, produce, error);
    case Resolved::Regular: return replaceAtomically(path, r.target, &r.st, produce, error);
    case Resolved::Through: return writeThrough(r.target, r.st, produce, error);
    case Resolved::Refused: break;
  }
  return fail(error, r.why);
}

bool checkOutputFile(const std::string& path, std::string* error) {
  Resolved r = resolveOutput(path);
  switch (r.kind) {
    case Resolved::Refused: return fail(error, r.why);
    case Resolved::Regular:
      if (std::string why = refusal(path, r.target, r.st); !why.empty()) return fail(error, why);
      [[fallthrough]];
    case Resolved::New: {
      if (baseOf(r.target).empty()) return fail(error, errorText(EISDIR));
      std::string dir = directoryOf(r.target);
      if (::faccessat(AT_FDCWD, dir.c_str(), W_OK | X_OK, AT_EACCESS) != 0)
        return fail(error, std::string(r.kind == Resolved::New ? "cannot create a file in '" :
                                                                   "cannot create a temporary file in '") +
                               dir + "': " + errorText(errno));
      return true;
    }
    case Resolved::Descriptor:
    case Resolved::Through: return true;
  }
  return true;
}

bool sameOutputFile(const std::string& a, const std::string& b) {
  Resolved ra = resolveOutput(a), rb = resolveOutput(b);
  if (ra.kind == Resolved::Descriptor || rb.kind == Resolved::Descriptor) {
    struct stat sa {}, sb {};
    auto statOf = [](const Resolved& r, struct stat& st) {
      if (r.kind == Resolved::Descriptor) return ::fstat(r.fd, &st) == 0;
      if (r.kind == Resolved::Regular || r.kind == Resolved::Through) return (st = r.st), true;
      return false;
    };
    return statOf(ra, sa) && statOf(rb, sb) && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino &&
           !S_ISCHR(sa.st_mode);  // two outputs to one terminal or /dev/null are harmless
  }
  if (ra.kind == Resolved::Refused || rb.kind == Resolved::Refused) return false;
  bool aExists = ra.kind != Resolved::New, bExists = rb.kind != Resolved::New;
  if (aExists && bExists)
    return ra.st.st_dev == rb.st.st_dev && ra.st.st_ino == rb.st.st_ino && !S_ISCHR(ra.st.st_mode);
  if (aExists != bExists) return false;
  // Two new files: the same name in the same directory (compared by the
  // directory's identity, so "x" and "./x" and "dir/../x" agree).
  struct stat da {}, db {};
  return baseOf(ra.target) == baseOf(rb.target) && ::stat(directoryOf(ra.target).c_str(), &da) == 0 &&
         ::stat(directoryOf(rb.target).c_str(), &db) == 0 && da.st_dev == db.st_dev && da.st_ino == db.st_ino;
}

}  // namespace rscene
