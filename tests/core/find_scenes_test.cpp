// Directory operands: which files a folder stands for, in which order.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/find_scenes.hpp"

using namespace rscene;
namespace fs = std::filesystem;

namespace {

class FindScenes : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("rscene_find_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override {
    fs::permissions(root_ / "locked", fs::perms::owner_all, fs::perm_options::add, ec_);
    fs::remove_all(root_);
  }
  void touch(const std::string& rel) {
    fs::create_directories((root_ / rel).parent_path());
    std::ofstream(root_ / rel) << "raisim_engine_scene 1\n";
  }
  std::vector<std::string> relative(const SceneSearch& s) const {
    std::vector<std::string> out;
    for (const std::string& f : s.files) out.push_back(f.substr(root_.string().size() + 1));
    return out;
  }
  fs::path root_;
  std::error_code ec_;
};

}  // namespace

TEST_F(FindScenes, SortedDepthFirstSkippingHiddenAndOtherFiles) {
  for (const char* f : {"b/z.rscene", "b/a/y.rscene", "a.rscene", "B.rscene", "c/.hidden.rscene", ".git/x.rscene",
                        "notes.txt", "c/scene.rscene.bak", "c/.rscene", "d/e/f/deep.rscene"})
    touch(f);
  fs::create_directories(root_ / "empty");
  SceneSearch s = findScenes(root_.string());
  EXPECT_TRUE(s.errors.empty());
  EXPECT_EQ(relative(s), (std::vector<std::string>{"B.rscene", "a.rscene", "b/a/y.rscene", "b/z.rscene",
                                                   "d/e/f/deep.rscene"}));
  // A trailing slash is not doubled; `.` lists names without `./`.
  EXPECT_EQ(findScenes(root_.string() + "/").files, s.files);
  fs::path cwd = fs::current_path();
  fs::current_path(root_ / "b");
  EXPECT_EQ(findScenes(".").files, (std::vector<std::string>{"a/y.rscene", "z.rscene"}));
  fs::current_path(cwd);
}

TEST_F(FindScenes, FollowsLinksToFilesButNotToFolders) {
  touch("real/s.rscene");
  fs::create_directory_symlink("..", root_ / "real" / "loop");
  fs::create_directory_symlink(root_ / "real", root_ / "alias");
  fs::create_symlink(root_ / "real" / "s.rscene", root_ / "link.rscene");
  fs::create_symlink(root_ / "missing.rscene", root_ / "dangling.rscene");
  EXPECT_EQ(relative(findScenes(root_.string())), (std::vector<std::string>{"link.rscene", "real/s.rscene"}));
}

TEST_F(FindScenes, AnUnreadableFolderIsAnErrorAndTheWalkGoesOn) {
  if (::geteuid() == 0) GTEST_SKIP() << "root reads every folder";
  touch("locked/s.rscene");
  touch("open/t.rscene");
  fs::permissions(root_ / "locked", fs::perms::none);
  SceneSearch s = findScenes(root_.string());
  EXPECT_EQ(relative(s), (std::vector<std::string>{"open/t.rscene"}));
  ASSERT_EQ(s.errors.size(), 1u);
  EXPECT_EQ(s.errors[0], "cannot read directory '" + (root_ / "locked").string() + "': Permission denied");
}

TEST_F(FindScenes, AMissingFolderIsAnError) {
  SceneSearch s = findScenes((root_ / "nope").string());
  EXPECT_TRUE(s.files.empty());
  ASSERT_EQ(s.errors.size(), 1u);
  EXPECT_EQ(s.errors[0], "cannot read directory '" + (root_ / "nope").string() + "': No such file or directory");
}
