// Line diffs for what a semantic diff cannot compare (rscene-fmt --diff,
// rscene-diff's git mode when a side does not parse).
#include <gtest/gtest.h>

#include "core/diff_lines.hpp"

using namespace rscene;

TEST(DiffLines, UnifiedDiffWithHeadersAndContext) {
  EXPECT_EQ(unifiedDiff("a\nb\n", "a\nb\n", "x", "y"), "");
  EXPECT_EQ(unifiedDiff("a\nb\nc\n", "a\nB\nc\n", "a/s.rscene", "b/s.rscene"),
            "--- a/s.rscene\n+++ b/s.rscene\n@@ -1,3 +1,3 @@\n a\n-b\n+B\n c\n");
}

TEST(DiffLines, EmptySidesUseTheLineBeforeLikeDiff) {
  // An added or deleted file: patch(1) reads `-0,0`, not dtl's `-1,0`.
  EXPECT_EQ(unifiedDiff("", "x\n", "/dev/null", "b/n"), "--- /dev/null\n+++ b/n\n@@ -0,0 +1,1 @@\n+x\n");
  EXPECT_EQ(unifiedDiff("x\ny\n", "", "a/o", "/dev/null"), "--- a/o\n+++ /dev/null\n@@ -1,2 +0,0 @@\n-x\n-y\n");
}

TEST(DiffLines, BinaryIsANulByteInTheFirst8000Bytes) {
  using namespace std::string_literals;
  EXPECT_FALSE(looksBinary("raisim_engine_scene 1\n"));
  EXPECT_TRUE(looksBinary("junk\0\1"s));
  EXPECT_FALSE(looksBinary(std::string(8000, 'a') + '\0'));
}
