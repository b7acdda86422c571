// Engine 2 project files (core/project.hpp): what is read, what is
// refused where, and where a project's scenes find their assets.
#include "core/project.hpp"

#include <gtest/gtest.h>

#include <set>

#include "core/filesystem.hpp"

namespace rscene {
namespace {

MemoryFileSystem builtIn() {
  MemoryFileSystem fs;
  fs.addFile("p/assets/meshes/crate.obj", "v 0 0 0\n");
  fs.addFile("p/examples/warehouse_scene.rscene", "raisim_engine_scene 2\n");
  return fs;
}

const char* kBuiltIn =
    "raisim_engine2_project 1\n"
    "name RaiSim Engine 2 Built-in Project\n"
    "asset_directory assets\n"
    "scene_directory examples\n"
    "default_scene examples/warehouse_scene.rscene\n"
    "description Built-in scenes and assets shipped with raisim_engine2.\n";

TEST(Project, ReadsTheFormatDescriptionsExample) {
  MemoryFileSystem fs = builtIn();
  ProjectRead r = parseProject(kBuiltIn, "p", fs);
  EXPECT_TRUE(r.diagnostics.empty()) << r.diagnostics.front().message;
  EXPECT_EQ(r.project.name, "RaiSim Engine 2 Built-in Project");  // the rest of the line, spaces and all
  EXPECT_EQ(r.project.description, "Built-in scenes and assets shipped with raisim_engine2.");
  EXPECT_EQ(r.project.under(r.project.defaultScene), "p/examples/warehouse_scene.rscene");
  EXPECT_EQ(r.project.place().root, "p");
  EXPECT_EQ(r.project.place().assets, "p/assets");
  EXPECT_EQ(r.project.file, "p/raisim_engine2_project");
}

TEST(Project, CrlfCommentsAndBlankLinesAreNotRecords) {
  MemoryFileSystem fs = builtIn();
  std::string text = "raisim_engine2_project 1\r\n# a comment\r\n\r\nscene_directory examples\r\n"
                     "default_scene examples/warehouse_scene.rscene\r\n";
  ProjectRead r = parseProject(text, "p", fs);
  EXPECT_TRUE(r.ok());
  EXPECT_TRUE(r.diagnostics.empty());
  EXPECT_EQ(r.project.sceneDirectory, "examples");
  EXPECT_EQ(r.project.sceneLine, 4u);
}

struct Case {
  const char* text;
  const char* code;
  unsigned line, column;
};

TEST(Project, EachDefectAtItsLineAndColumn) {
  MemoryFileSystem fs = builtIn();
  const Case cases[] = {
      {"raisim_engine_scene 1\n", "RS1201", 1, 1},
      {"", "RS1201", 1, 1},
      {"raisim_engine2_project 2\nscene_directory examples\n", "RS1201", 1, 24},
      {"raisim_engine2_project 1\nscene_directory examples\ndefault_scene examples/warehouse_scene.rscene\nicon x.png\n",
       "RS1202", 4, 1},
      {"raisim_engine2_project 1\nscene_directory\n", "RS1203", 2, 1},
      {"raisim_engine2_project 1\nscene_directory examples\nscene_directory other\n", "RS1204", 3, 1},
      {"raisim_engine2_project 1\nname x\n", "RS1205", 1, 1},
      {"raisim_engine2_project 1\nscene_directory scenes\n", "RS1206", 2, 17},
      {"raisim_engine2_project 1\nscene_directory examples\nasset_directory  assets/meshes/crate.obj\n", "RS1206", 3, 18},
      {"raisim_engine2_project 1\nscene_directory examples\ndefault_scene examples/none.rscene\n", "RS1207", 3, 15},
      {"raisim_engine2_project 1\nscene_directory examples\ndefault_scene assets/meshes/crate.obj\n", "RS1207", 3, 15},
      {"raisim_engine2_project 1\nscene_directory examples\n", "RS1208", 1, 1},
      {"raisim_engine2_project 1\nname \xff\n", "RS1005", 2, 6},
  };
  for (const Case& c : cases) {
    ProjectRead r = parseProject(c.text, "p", fs);
    ASSERT_FALSE(r.diagnostics.empty()) << c.text;
    const Diagnostic& d = r.diagnostics.front();
    EXPECT_EQ(d.code, c.code) << c.text << ": " << d.message;
    EXPECT_EQ(d.line, c.line) << c.text;
    EXPECT_EQ(d.column, c.column) << c.text;
  }
}

TEST(Project, NulByteIsRefusedAtItsColumn) {
  MemoryFileSystem fs = builtIn();
  const char text[] = "raisim_engine2_project 1\nname a\0b\n";
  ProjectRead r = parseProject(std::string_view(text, sizeof text - 1), "p", fs);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.diagnostics.front().code, "RS1004");
  EXPECT_EQ(r.diagnostics.front().line, 2u);
  EXPECT_EQ(r.diagnostics.front().column, 7u);
}

TEST(Project, WarningsLeaveItUsable) {
  MemoryFileSystem fs = builtIn();
  ProjectRead r = parseProject("raisim_engine2_project 1\nscene_directory examples\nthumbnail t.png\n", "p", fs);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.diagnostics.size(), 2u);  // RS1202, RS1208
}

TEST(Project, ReadsThroughTheFileSystemWithACap) {
  MemoryFileSystem fs = builtIn();
  fs.addFile("p/raisim_engine2_project", kBuiltIn);
  EXPECT_TRUE(readProject("p", fs).ok());
  fs.addFile("q/raisim_engine2_project", std::string(kMaxProjectFileBytes + 1, '#'));
  ProjectRead big = readProject("q", fs);
  ASSERT_FALSE(big.ok());
  EXPECT_EQ(big.diagnostics.front().code, "RS1201");
  EXPECT_NE(big.diagnostics.front().message.find("larger"), std::string::npos);
}

TEST(Project, IsAFolderWithAProjectFileOrThatFile) {
  MemoryFileSystem fs = builtIn();
  fs.addFile("p/raisim_engine2_project", kBuiltIn);
  std::string root;
  EXPECT_TRUE(isProject("p", fs, root));
  EXPECT_EQ(root, "p");
  EXPECT_TRUE(isProject("p/", fs, root));
  EXPECT_EQ(root, "p");
  EXPECT_TRUE(isProject("p/raisim_engine2_project", fs, root));
  EXPECT_EQ(root, "p");
  EXPECT_FALSE(isProject("p/examples", fs, root));
  EXPECT_FALSE(isProject("p/examples/warehouse_scene.rscene", fs, root));
  EXPECT_FALSE(isProject("-", fs, root));
}

// The rule written in the README ("Engine 2 projects").
TEST(Project, AssetsResolveSceneFolderThenAssetRootThenAssetDirectory) {
  std::set<std::string> files = {"p/examples/local.png", "p/textures/t.png", "p/examples/textures/u.png",
                                 "p/assets/meshes/crate.obj"};
  FileExists exists = [&](const std::string& f) { return files.count(f) > 0; };
  ProjectPlace place{"p", "p/assets"};
  // 1. beside the scene
  EXPECT_EQ(resolveAsset("p/examples", place, 2, ".", "local.png", exists), "p/examples/local.png");
  // 2. asset_root: from the project folder in version 1, from the scene's in version 2
  EXPECT_EQ(resolveAsset("p/examples", place, 1, "textures", "t.png", exists), "p/textures/t.png");
  EXPECT_EQ(resolveAsset("p/examples", place, 2, "textures", "u.png", exists), "p/examples/textures/u.png");
  // 3. the project's asset_directory
  EXPECT_EQ(resolveAsset("p/examples", place, 2, ".", "meshes/crate.obj", exists), "p/assets/meshes/crate.obj");
  // nowhere: where the scene asked for it, for the message
  EXPECT_EQ(resolveAsset("p/examples", place, 2, "textures", "none.png", exists), "p/examples/textures/none.png");
  // no project: the rule of compat-notes.md
  EXPECT_EQ(resolveAsset("p/examples", ProjectPlace{}, 1, ".", "meshes/crate.obj", exists), "p/examples/./meshes/crate.obj");
}

}  // namespace
}  // namespace rscene
