// The two invariants of the canonical form on every fixture we have: the
// bundled tests/data and examples scenes, and ../shared/corpus when present.
#include <gtest/gtest.h>

#include "core/io.hpp"
#include "test_util.hpp"

using namespace rscene;
namespace fs = std::filesystem;

namespace {

const fs::path kCorpus = fs::path(RSCENE_SHARED_DIR) / "corpus";

void checkInvariants(const fs::path& file) {
  SCOPED_TRACE(file.string());
  std::string text = test::readAll(file);
  LoadResult first = parse(text);
  if (!first.ok()) return;  // fixtures of bad input are tested elsewhere
  std::string once = canonicalText(first.document);
  LoadResult second = parse(once);
  ASSERT_TRUE(second.ok()) << second.diagnostics[0].message;
  EXPECT_EQ(canonicalText(second.document), once) << "fmt(fmt(x)) != fmt(x)";
  std::string why;
  EXPECT_TRUE(sameDocument(first.document, second.document, &why)) << why;
}

}  // namespace

TEST(Corpus, EngineTwoOutputIsAFixedPoint) {
  fs::path forest = kCorpus / "rayrai_forest_head.rscene";
  if (!fs::exists(forest)) GTEST_SKIP() << "../shared/corpus is absent";
  std::string text = test::readAll(forest);
  EXPECT_EQ(test::fmt(text), text);
}

TEST(Corpus, RealFilesLoadAndKeepTheirParse) {
  auto files = test::scenesIn(kCorpus);
  if (files.empty()) GTEST_SKIP() << "../shared/corpus is absent";
  for (const fs::path& f : files) {
    LoadResult r = parse(test::readAll(f));
    EXPECT_TRUE(r.ok()) << f << ": " << (r.diagnostics.empty() ? "" : r.diagnostics[0].message);
    checkInvariants(f);
  }
}

TEST(Corpus, VersionTwoFilesStayVersionTwo) {
  fs::path warehouse = kCorpus / "rayrai_warehouse.rscene";
  if (!fs::exists(warehouse)) GTEST_SKIP() << "../shared/corpus is absent";
  std::string out = test::fmt(test::readAll(warehouse));
  EXPECT_EQ(out.rfind("raisim_engine_scene 2\n", 0), 0u);
}

TEST(Corpus, BundledFixturesKeepTheInvariants) {
  auto files = test::scenesIn(RSCENE_TEST_DATA);
  auto examples = test::scenesIn(fs::path(RSCENE_TEST_DATA) / ".." / ".." / "examples");
  files.insert(files.end(), examples.begin(), examples.end());
  for (const fs::path& f : files) checkInvariants(f);
}
