// writeOutputFile(): one test per kind of thing at the output path
// (lib/core/output_file.hpp), in a fresh temporary folder each.
#include "core/output_file.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/temp_files.hpp"

namespace fs = std::filesystem;
using namespace rscene;

namespace {

class OutputFile : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string tmpl = (fs::temp_directory_path() / "rscene-output-XXXXXX").string();
    ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override {
    std::error_code ec;
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(dir_, ec);
  }

  std::string at(const std::string& name) const { return (dir_ / name).string(); }

  static void put(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }
  static std::string get(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  static bool write(const std::string& path, const std::string& text, std::string* error) {
    return writeOutputFile(path, [&](Sink& s) { s.write(text); return true; }, error);
  }
  static struct stat lstatOf(const std::string& path) {
    struct stat st {};
    EXPECT_EQ(::lstat(path.c_str(), &st), 0) << path;
    return st;
  }

  // Names in `d` that look like our temporary files.
  static std::vector<std::string> temporaries(const fs::path& d) {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(d)) {
      std::string n = e.path().filename().string();
      if (n.size() > 1 && n[0] == '.' && n.find(".tmp") != std::string::npos) out.push_back(n);
    }
    return out;
  }

  fs::path dir_;
};

TEST_F(OutputFile, CreatesANewFileWithTheUmaskApplied) {
  mode_t mask = ::umask(022);
  std::string err;
  EXPECT_TRUE(write(at("new.rscene"), "hello\n", &err)) << err;
  ::umask(mask);
  EXPECT_EQ(get(at("new.rscene")), "hello\n");
  EXPECT_EQ(lstatOf(at("new.rscene")).st_mode & 07777, 0644u);
  EXPECT_TRUE(temporaries(dir_).empty());
}

TEST_F(OutputFile, ReplacesARegularFileAtomicallyKeepingItsMode) {
  std::string path = at("a.rscene");
  put(path, "old\n");
  ASSERT_EQ(::chmod(path.c_str(), 0640), 0);
  ino_t before = lstatOf(path).st_ino;
  std::string err;
  ASSERT_TRUE(write(path, "new\n", &err)) << err;
  struct stat st = lstatOf(path);
  EXPECT_EQ(get(path), "new\n");
  EXPECT_EQ(st.st_mode & 07777, 0640u);
  EXPECT_NE(st.st_ino, before) << "a new inode: the file was replaced, not rewritten in place";
  EXPECT_TRUE(temporaries(dir_).empty());
}

TEST_F(OutputFile, KeepsOwnerAndGroupAsRoot) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to give files away";
  std::string path = at("owned.rscene");
  put(path, "old\n");
  ASSERT_EQ(::chown(path.c_str(), 65534, 65534), 0);
  ASSERT_EQ(::chmod(path.c_str(), 02664), 0);  // set-gid: chown would clear it if done after chmod
  std::string err;
  ASSERT_TRUE(write(path, "new\n", &err)) << err;
  struct stat st = lstatOf(path);
  EXPECT_EQ(st.st_uid, 65534u);
  EXPECT_EQ(st.st_gid, 65534u);
  EXPECT_EQ(st.st_mode & 07777, 02664u);
  EXPECT_EQ(get(path), "new\n");
}

TEST_F(OutputFile, ASymlinkStaysALinkAndItsTargetIsRewrittenInItsOwnFolder) {
  fs::create_directory(dir_ / "real");
  put(at("real/t.rscene"), "old\n");
  ASSERT_EQ(::symlink("real/t.rscene", at("hop").c_str()), 0);
  ASSERT_EQ(::symlink("hop", at("link.rscene").c_str()), 0);  // a chain of two links
  std::string err;
  ASSERT_TRUE(write(at("link.rscene"), "new\n", &err)) << err;
  EXPECT_TRUE(S_ISLNK(lstatOf(at("link.rscene")).st_mode));
  EXPECT_TRUE(S_ISLNK(lstatOf(at("hop")).st_mode));
  EXPECT_EQ(fs::read_symlink(at("link.rscene")), "hop");
  EXPECT_EQ(get(at("real/t.rscene")), "new\n");
  EXPECT_TRUE(temporaries(dir_).empty());
  EXPECT_TRUE(temporaries(dir_ / "real").empty());
}

TEST_F(OutputFile, ADanglingSymlinkIsRefusedAndNothingIsCreated) {
  ASSERT_EQ(::symlink("missing.rscene", at("link.rscene").c_str()), 0);
  std::string err;
  EXPECT_FALSE(write(at("link.rscene"), "x\n", &err));
  EXPECT_EQ(err, "is a dangling symbolic link to 'missing.rscene'; create the target or remove the link");
  EXPECT_FALSE(fs::exists(at("missing.rscene")));
  EXPECT_TRUE(S_ISLNK(lstatOf(at("link.rscene")).st_mode));
}

TEST_F(OutputFile, ASymlinkLoopIsAnError) {
  ASSERT_EQ(::symlink("b", at("a").c_str()), 0);
  ASSERT_EQ(::symlink("a", at("b").c_str()), 0);
  std::string err;
  EXPECT_FALSE(write(at("a"), "x\n", &err));
  EXPECT_EQ(err, "too many levels of symbolic links");
}

TEST_F(OutputFile, DevNullIsWrittenThroughAndStaysADevice) {
  std::string err;
  EXPECT_TRUE(write("/dev/null", "discarded\n", &err)) << err;
  EXPECT_TRUE(S_ISCHR(lstatOf("/dev/null").st_mode));
}

TEST_F(OutputFile, DevFullReportsNoSpace) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  std::string err;
  EXPECT_FALSE(write("/dev/full", "x\n", &err));
  EXPECT_EQ(err, "no space left on device");
}

TEST_F(OutputFile, AFifoStaysAFifoAndItsReaderGetsTheBytes) {
  std::string fifo = at("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  std::string received;
  // The reader opens late: the writer waits for it instead of failing.
  std::thread reader([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    received = get(fifo);
  });
  std::string err;
  bool ok = write(fifo, "through the pipe\n", &err);
  reader.join();
  EXPECT_TRUE(ok) << err;
  EXPECT_EQ(received, "through the pipe\n");
  EXPECT_TRUE(S_ISFIFO(lstatOf(fifo).st_mode));
}

TEST_F(OutputFile, DevFdNamesAnOpenDescriptor) {
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  std::string err;
  EXPECT_TRUE(write("/dev/fd/" + std::to_string(fds[1]), "via fd\n", &err)) << err;
  ::close(fds[1]);
  char buf[64];
  ssize_t n = ::read(fds[0], buf, sizeof buf);
  ::close(fds[0]);
  EXPECT_EQ(std::string(buf, static_cast<std::size_t>(std::max<ssize_t>(n, 0))), "via fd\n");
}

TEST_F(OutputFile, AReadOnlyFileIsRefusedEvenForRoot) {
  std::string path = at("ro.rscene");
  put(path, "keep\n");
  ASSERT_EQ(::chmod(path.c_str(), 0444), 0);
  ino_t before = lstatOf(path).st_ino;
  std::string err;
  EXPECT_FALSE(write(path, "new\n", &err));
  EXPECT_EQ(err, "permission denied");
  EXPECT_EQ(get(path), "keep\n");
  EXPECT_EQ(lstatOf(path).st_ino, before);
  EXPECT_TRUE(temporaries(dir_).empty());
}

// Runs `body` as user nobody in a child process; the child's exit code
// is the number of failed checks.
int asNobody(const std::function<int()>& body) {
  pid_t pid = ::fork();
  if (pid == 0) {
    if (::setresgid(65534, 65534, 65534) != 0 || ::setresuid(65534, 65534, 65534) != 0) ::_exit(100);
    ::_exit(body());
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 200;
}

TEST_F(OutputFile, AFileTheUserMayNotWriteIsRefusedThoughTheFolderIsWritable) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to switch to user nobody";
  fs::permissions(dir_, fs::perms::all);  // nobody may create files here...
  std::string path = at("theirs.rscene");
  put(path, "keep\n");
  ASSERT_EQ(::chmod(path.c_str(), 0644), 0);  // ...but not write this one
  std::string err;
  int failures = asNobody([&] {
    std::string e;
    bool ok = write(path, "new\n", &e);
    return (ok ? 1 : 0) + (e == "permission denied" ? 0 : 2);
  });
  EXPECT_EQ(failures, 0);
  EXPECT_EQ(get(path), "keep\n");
  EXPECT_TRUE(temporaries(dir_).empty());
}

TEST_F(OutputFile, ANewFileInAFolderTheUserMayNotWriteIsAClearError) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to switch to user nobody";
  fs::permissions(dir_, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                            fs::perms::others_read | fs::perms::others_exec);
  std::string path = at("new.rscene");
  std::string expected = "cannot create a file in '" + dir_.string() + "': permission denied";
  int failures = asNobody([&] {
    std::string e;
    bool ok = write(path, "new\n", &e);
    return (ok ? 1 : 0) + (e == expected ? 0 : 2);
  });
  EXPECT_EQ(failures, 0);
  EXPECT_FALSE(fs::exists(path));
}

TEST_F(OutputFile, AMissingFolderIsAClearError) {
  std::string err;
  EXPECT_FALSE(write(at("no/such/x.rscene"), "x\n", &err));
  EXPECT_EQ(err, "cannot create a file in '" + at("no/such") + "': no such file or directory");
}

TEST_F(OutputFile, AHardLinkedFileIsRefusedNamingTheCountAndTheWayOut) {
  put(at("a.rscene"), "keep\n");
  ASSERT_EQ(::link(at("a.rscene").c_str(), at("b.rscene").c_str()), 0);
  std::string err;
  EXPECT_FALSE(write(at("a.rscene"), "new\n", &err));
  std::string p = at("a.rscene");
  EXPECT_EQ(err, "has 2 hard links; refusing to split them (to write it, make it a file of its own first: cp " + p +
                     " tmp && mv tmp " + p + ")");
  EXPECT_EQ(get(at("a.rscene")), "keep\n");
  EXPECT_EQ(get(at("b.rscene")), "keep\n");
  EXPECT_EQ(lstatOf(at("a.rscene")).st_nlink, 2u);
}

TEST_F(OutputFile, DirectoriesBlockDevicesAndSocketsAreRefused) {
  std::string err;
  EXPECT_FALSE(write(dir_.string(), "x\n", &err));
  EXPECT_EQ(err, "is a directory");

  std::string sock = at("sock");
  int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  ASSERT_LT(sock.size(), sizeof addr.sun_path);
  std::memcpy(addr.sun_path, sock.c_str(), sock.size() + 1);
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  EXPECT_FALSE(write(sock, "x\n", &err));
  EXPECT_EQ(err, "is a socket");
  ::close(fd);

  if (::geteuid() == 0 && ::mknod(at("blk").c_str(), S_IFBLK | 0600, makedev(7, 0)) == 0) {
    EXPECT_FALSE(write(at("blk"), "x\n", &err));
    EXPECT_EQ(err, "is a block device; refusing to write over it");
  }
}

TEST_F(OutputFile, ACancelledWriteLeavesTheOriginalAndNoTemporary) {
  std::string path = at("a.rscene");
  put(path, "keep\n");
  std::string err;
  bool ok = writeOutputFile(path, [](Sink& s) { s.write("half"); return false; }, &err);
  EXPECT_FALSE(ok);
  EXPECT_EQ(err, "write cancelled");
  EXPECT_EQ(get(path), "keep\n");
  EXPECT_TRUE(temporaries(dir_).empty());
}

TEST_F(OutputFile, ALongNameStillGetsATemporaryBesideIt) {
  std::string name(250, 'n');
  std::string err;
  EXPECT_TRUE(write(at(name), "x\n", &err)) << err;
  EXPECT_EQ(get(at(name)), "x\n");
  EXPECT_TRUE(temporaries(dir_).empty());
}

// A signal in the middle of a write: a handler like cmd/common's removes
// the registered temporary, and the original is untouched.
extern "C" void removeAndExit(int sig) {
  removeTemporaryFiles();
  ::_exit(128 + sig);
}

TEST_F(OutputFile, AnInterruptedWriteLeavesTheOriginalAndNoTemporary) {
  std::string path = at("big.rscene");
  put(path, "original\n");
  EXPECT_EXIT(
      {
        std::signal(SIGTERM, removeAndExit);
        writeOutputFile(path, [](Sink& s) {
          std::string chunk(1 << 20, 'x');
          s.write(chunk);
          std::raise(SIGTERM);
          s.write(chunk);
          return true;
        }, nullptr);
        ::_exit(0);
      },
      ::testing::ExitedWithCode(128 + SIGTERM), "");
  EXPECT_EQ(get(path), "original\n");
  EXPECT_TRUE(temporaries(dir_).empty());
}

TEST(TemporaryFiles, RegisteredPathsAreRemovedUntilForgotten) {
  std::string tmpl = (fs::temp_directory_path() / "rscene-tmpreg-XXXXXX").string();
  ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
  fs::path d = tmpl;
  std::ofstream(d / "a") << "a";
  std::ofstream(d / "b") << "b";
  int a = registerTemporaryFile((d / "a").string());
  int b = registerTemporaryFile((d / "b").string());
  ASSERT_GE(a, 0);
  ASSERT_GE(b, 0);
  EXPECT_NE(a, b);
  forgetTemporaryFile(b);
  EXPECT_EQ(removeTemporaryFiles(), 1);
  EXPECT_FALSE(fs::exists(d / "a"));
  EXPECT_TRUE(fs::exists(d / "b"));
  forgetTemporaryFile(a);
  EXPECT_EQ(removeTemporaryFiles(), 0);
  EXPECT_EQ(registerTemporaryFile(std::string(kTemporaryPathBytes, 'x')), -1);
  EXPECT_EQ(registerTemporaryFile(""), -1);
  fs::remove_all(d);
}

TEST(TemporaryFiles, AFullRegistrySaysSoInsteadOfOverwritingASlot) {
  std::vector<int> slots;
  for (std::size_t i = 0; i < kTemporaryFileSlots; ++i) slots.push_back(registerTemporaryFile("/nonexistent/x"));
  for (int s : slots) EXPECT_GE(s, 0);
  EXPECT_EQ(registerTemporaryFile("/nonexistent/y"), -1);
  for (int s : slots) forgetTemporaryFile(s);
  int again = registerTemporaryFile("/nonexistent/z");
  EXPECT_GE(again, 0);
  forgetTemporaryFile(again);
}

}  // namespace

// checkOutputFile() refuses what writeOutputFile() would, with the same
// words, and writes nothing: tools check every output before the first.
TEST_F(OutputFile, CheckingAnOutputRefusesWhatWritingWouldAndWritesNothing) {
  std::string ro = at("ro.rscene"), fresh = at("new.rscene"), linked = at("a.rscene");
  put(ro, "keep\n");
  ASSERT_EQ(::chmod(ro.c_str(), 0444), 0);
  put(linked, "x\n");
  ASSERT_EQ(::link(linked.c_str(), at("b.rscene").c_str()), 0);
  std::string checked, written;
  EXPECT_FALSE(checkOutputFile(ro, &checked));
  EXPECT_FALSE(write(ro, "new\n", &written));
  EXPECT_EQ(checked, written);
  EXPECT_FALSE(checkOutputFile(linked, &checked));
  EXPECT_NE(checked.find("has 2 hard links"), std::string::npos) << checked;
  EXPECT_FALSE(checkOutputFile(dir_.string(), &checked));
  EXPECT_FALSE(checkOutputFile(at("missing/x.png"), &checked));
  EXPECT_TRUE(checkOutputFile(fresh, &checked)) << checked;
  EXPECT_FALSE(fs::exists(fresh));
  EXPECT_TRUE(checkOutputFile("/dev/null", &checked));
  EXPECT_EQ(get(ro), "keep\n");
  EXPECT_TRUE(temporaries(dir_).empty());
}

TEST_F(OutputFile, SameOutputFileSeesThroughLinksAndDotsButNotDevices) {
  std::string a = at("a.png");
  put(a, "x");
  ASSERT_EQ(::symlink("a.png", at("l.png").c_str()), 0);
  ASSERT_EQ(::mkdir(at("d").c_str(), 0755), 0);
  EXPECT_TRUE(sameOutputFile(a, at("l.png")));
  EXPECT_TRUE(sameOutputFile(a, at("d/../a.png")));
  EXPECT_FALSE(sameOutputFile(a, at("b.png")));
  // Two files that do not exist yet: the same name in the same folder.
  EXPECT_TRUE(sameOutputFile(at("new.png"), at("d/../new.png")));
  EXPECT_FALSE(sameOutputFile(at("new.png"), at("d/new.png")));
  EXPECT_FALSE(sameOutputFile("/dev/null", "/dev/null"));
}
