// The validator's bounded reporting (issue 10): check() hands findings to a
// sink record by record, so a caller can count millions of them while
// keeping none, and LineCursor finds the lines under messages by walking
// from the last one instead of scanning from the top per finding.
#include <gtest/gtest.h>

#include <chrono>
#include <random>
#include <string>

#include "core/check.hpp"
#include "core/loader.hpp"
#include "core/report.hpp"

namespace rscene {
namespace {

// Counts by severity and keeps the first few, like rscene-validate.
struct CountSink : DiagnosticSink {
  std::size_t errors = 0, warnings = 0, keep = 0;
  Diagnostics kept;
  void add(Diagnostic d) override {
    (d.severity == Severity::Error ? errors : warnings)++;
    if (kept.size() < keep) kept.push_back(std::move(d));
  }
};

std::string repeated(const std::string& line, std::size_t n) {
  std::string s = "raisim_engine_scene 2\n";
  s.reserve(s.size() + line.size() * n);
  for (std::size_t i = 0; i < n; ++i) s += line;
  return s;
}

TEST(CheckStream, ASinkSeesTheFindingsOfTheVectorApiInTheirOrder) {
  // Several kinds of findings: unknown tags and keys, bad types, a repeated
  // singleton, a broken reference and a parent cycle (reported after the
  // records), so the order across records and passes is pinned.
  const std::string text =
      "raisim_engine_scene 2\n"
      "time_step x\n"
      "frob 1 2\n"
      "time_step 0.01\n"
      "group /World/a parent=/World/b\n"
      "group /World/b parent=/World/a\n"
      "light /World/l 0 0 -1 1 colour=1,1,1 intensity=y\n"
      "group /World/c parent=/World/nothing\n";
  LoadResult loaded = parse(text);
  ASSERT_TRUE(loaded.ok());
  Diagnostics all = check(loaded.document, {});
  ASSERT_GE(all.size(), 6u);
  CountSink sink;
  sink.keep = 3;
  check(loaded.document, {}, sink);
  EXPECT_EQ(sink.errors + sink.warnings, all.size());
  ASSERT_EQ(sink.kept.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(sink.kept[i].line, all[i].line);
    EXPECT_EQ(sink.kept[i].column, all[i].column);
    EXPECT_EQ(sink.kept[i].code, all[i].code);
    EXPECT_EQ(sink.kept[i].message, all[i].message);
  }
}

TEST(CheckStream, CountsRepeatedTimeStepsWithoutKeepingThem) {
  // Issue 10's reproducer, scaled (the bats test runs a million under
  // ulimit -v; a sanitizer build runs this one): each repeat is RS3016.
  const std::size_t n = 200000;
  LoadResult loaded = parse(repeated("time_step 0.0025\n", n));
  ASSERT_TRUE(loaded.ok());
  CountSink sink;
  sink.keep = 2;
  check(loaded.document, {}, sink);
  EXPECT_EQ(sink.errors, 0u);
  EXPECT_EQ(sink.warnings, n - 1);
  ASSERT_EQ(sink.kept.size(), 2u);
  EXPECT_EQ(sink.kept[0].code, "RS3016");
  EXPECT_EQ(sink.kept[0].line, 3u);
  EXPECT_EQ(sink.kept[1].line, 4u);
}

TEST(LineCursor, AgreesWithLineOfOnEveryLineInAnyOrder) {
  std::mt19937 rng(10);
  const char* pieces[] = {"a", "bc", "\n", "\r\n", "\n\n", " x\t", "\r"};
  for (int round = 0; round < 200; ++round) {
    std::string text;
    for (int i = rng() % 30; i > 0; --i) text += pieces[rng() % 7];
    std::vector<std::uint32_t> lines;
    for (std::uint32_t l = 0; l < 40; ++l) lines.push_back(l);
    std::shuffle(lines.begin(), lines.end(), rng);
    lines.push_back(lines.front());  // a line asked twice
    LineCursor cursor(text);
    for (std::uint32_t l : lines) ASSERT_EQ(cursor(l), lineOf(text, l)) << "line " << l << " of '" << text << "'";
  }
}

TEST(LineCursor, WalksAHalfMillionLinesInOnePass) {
  // lineOf() for each would scan ~1.25e11 bytes (minutes); walking is
  // milliseconds, so even a slow sanitizer build stays far under the bound.
  // A jump back to the top and forward again (parent cycles are reported
  // after every record) costs one more pass, not one per line.
  const std::size_t n = 500000;
  std::string text = repeated("x\n", n);
  auto start = std::chrono::steady_clock::now();
  LineCursor cursor(text);
  std::size_t found = 0;
  for (std::uint32_t l = 2; l <= n + 1; ++l) found += cursor(l) == "x";
  EXPECT_EQ(cursor(1), "raisim_engine_scene 2");
  for (std::uint32_t l = 2; l <= n + 1; l += 2) found += cursor(l) == "x";
  EXPECT_EQ(cursor(n + 2), "");  // after the final newline: empty, as lineOf says
  EXPECT_EQ(cursor(n + 3), "");
  EXPECT_EQ(cursor(n), "x");
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(found, n + n / 2);
  EXPECT_LT(seconds, 5.0);
}

}  // namespace
}  // namespace rscene
