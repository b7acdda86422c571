// readFile's optional cap (rscene-from-xml reads its top file and standard
// input with it): a file or pipe past the cap is an error, one at or under
// it is read whole.
#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include "core/io.hpp"

namespace rscene {
namespace {

std::string tempFile(const std::string& content) {
  std::string path = (std::filesystem::temp_directory_path() / ("rscene_read_" + std::to_string(::getpid()))).string();
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

TEST(ReadFile, CapRefusesALongerFileAndReadsAShorterOne) {
  std::string path = tempFile(std::string(1000, 'x'));
  std::string text, err;
  EXPECT_FALSE(readFile(path, text, &err, 999));
  EXPECT_EQ(err, "file larger than 999 bytes");
  EXPECT_TRUE(readFile(path, text, &err, 1000)) << err;
  EXPECT_EQ(text.size(), 1000u);
  EXPECT_TRUE(readFile(path, text, &err)) << err;  // no cap
  EXPECT_EQ(text.size(), 1000u);
  std::remove(path.c_str());
}

TEST(ReadFile, CapRefusesALongerPipe) {
  std::signal(SIGPIPE, SIG_IGN);  // the writer outlives a reader that stopped at the cap
  for (std::size_t size : {100000u, 300000u}) {
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    std::thread writer([&] {
      std::string chunk(size, 'y');
      std::size_t done = 0;
      while (done < chunk.size()) {
        ssize_t n = ::write(fds[1], chunk.data() + done, chunk.size() - done);
        if (n <= 0) break;  // the reader stopped early
        done += static_cast<std::size_t>(n);
      }
      ::close(fds[1]);
    });
    std::string text, err;
    bool ok = readFile("/dev/fd/" + std::to_string(fds[0]), text, &err, 200000);
    ::close(fds[0]);
    writer.join();
    if (size <= 200000) {
      EXPECT_TRUE(ok) << err;
      EXPECT_EQ(text.size(), size);
    } else {
      EXPECT_FALSE(ok);
      EXPECT_EQ(err, "file larger than 200000 bytes");
    }
  }
}

}  // namespace
}  // namespace rscene
