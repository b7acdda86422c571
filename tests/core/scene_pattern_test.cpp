// Batch output patterns (core/scene_pattern.hpp).
#include "core/scene_pattern.hpp"

#include <gtest/gtest.h>

namespace rscene {
namespace {

TEST(ScenePattern, FieldsOfAScenePath) {
  EXPECT_EQ(sceneFields("a/b/warehouse.rscene").stem, "warehouse");
  EXPECT_EQ(sceneFields("a/b/warehouse.rscene").dir, "a/b");
  EXPECT_EQ(sceneFields("x.rscene").dir, ".");
  EXPECT_EQ(sceneFields("notes.txt").stem, "notes.txt");  // only .rscene is taken off
  EXPECT_EQ(sceneFields(".rscene").stem, ".rscene");       // never an empty stem
  EXPECT_EQ(sceneFields("-").stem, "stdin");
}

TEST(ScenePattern, ExpandsStemAndDir) {
  std::string out, error;
  ASSERT_TRUE(expandScenePattern("out/{dir}/{stem}.settled.rscene", {"w", "s/a"}, out, &error)) << error;
  EXPECT_EQ(out, "out/s/a/w.settled.rscene");
  ASSERT_TRUE(expandScenePattern("{{{stem}}}.rscene", {"w", "."}, out, &error));
  EXPECT_EQ(out, "{w}.rscene");
  EXPECT_FALSE(expandScenePattern("{frame}.rscene", {"w", "."}, out, &error));
  EXPECT_NE(error.find("unknown field {frame}"), std::string::npos);
  EXPECT_FALSE(expandScenePattern("{stem.rscene", {"w", "."}, out, &error));
  EXPECT_NE(error.find("unmatched '{'"), std::string::npos);
  EXPECT_FALSE(expandScenePattern("stem}.rscene", {"w", "."}, out, &error));
}

TEST(ScenePattern, LeavesOtherFieldsForTheToolsOwnExpansion) {
  EXPECT_TRUE(hasSceneFields("t/{stem}-{name}.png"));
  EXPECT_TRUE(hasSceneFields("t/{dir}/x.png"));
  EXPECT_FALSE(hasSceneFields("t/{name}.png"));
  EXPECT_FALSE(hasSceneFields("t/{{stem}}.png"));  // a literal
  EXPECT_EQ(withSceneFields("t/{stem}-{name}-{{x}}.png", {"w", "."}), "t/w-{name}-{{x}}.png");
  // A brace in a file name stays a literal through the second expansion.
  EXPECT_EQ(withSceneFields("t/{stem}.png", {"a{b}", "."}), "t/a{{b}}.png");
}

}  // namespace
}  // namespace rscene
