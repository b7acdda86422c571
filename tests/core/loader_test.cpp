#include <gtest/gtest.h>

#include "core/check.hpp"
#include "core/io.hpp"
#include "core/text.hpp"
#include "test_util.hpp"

using namespace rscene;
using namespace std::string_literals;
using rscene::test::firstCode;
using rscene::test::load;

namespace {
const char* kObject25 =
    "object /World/Props/CrateA box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 1.0 default mat_box false true false - dynamic "
    "true 1 18446744073709551615 id=object_cratea parentGroupId=folder_props";
}

TEST(Loader, AcceptsBothVersions) {
  EXPECT_EQ(load("raisim_engine_scene 1\n").document.version, 1);
  EXPECT_EQ(load("raisim_engine_scene 2\n").document.version, 2);
}

TEST(Loader, RefusesAMissingHeaderWithItsLine) {
  LoadResult r = load("# comment\n\ntime_step 0.01\n");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(firstCode(r), "RS1001");
  EXPECT_EQ(r.diagnostics[0].message, "missing raisim_engine_scene header");
  EXPECT_EQ(r.diagnostics[0].line, 3u);
  EXPECT_EQ(r.diagnostics[0].column, 1u);
  std::string err;
  Document doc;
  EXPECT_FALSE(loadString("time_step 0.01\n", doc, &err));
  EXPECT_EQ(err, "line 1: missing raisim_engine_scene header");
  EXPECT_EQ(firstCode(load("")), "RS1001");
}

TEST(Loader, RefusesOtherVersions) {
  for (const char* text : {"raisim_engine_scene 3\n", "raisim_engine_scene 1.0\n", "raisim_engine_scene\n"}) {
    LoadResult r = load(text);
    EXPECT_EQ(firstCode(r), "RS1002") << text;
    EXPECT_NE(r.diagnostics[0].message.find("unsupported rscene version"), std::string::npos);
  }
}

TEST(Loader, ReadsCrlfTabsAndComments) {
  LoadResult r = load("# before\r\nraisim_engine_scene 1\r\n\r\n\ttime_step\t0.01 \r\n  # indented\r\ngravity 0 0 -9.81\r\n# end\r\n");
  ASSERT_TRUE(r.ok());
  const Document& d = r.document;
  ASSERT_EQ(d.records.size(), 3u);
  EXPECT_EQ(d.records[0].commentCount, 1u);
  EXPECT_EQ(d.commentText(d.records[0].firstComment), "# before");
  EXPECT_EQ(d.positionalText(d.records[1], 0), "0.01");
  EXPECT_EQ(d.records[2].commentCount, 1u);
  EXPECT_EQ(d.commentText(d.records[2].firstComment), "# indented");
  EXPECT_EQ(d.trailingCommentCount, 1u);
  EXPECT_EQ(d.records[2].line, 6u);
}

TEST(Loader, AcceptsAllThreeObjectLayouts) {
  std::string obj19 = "object /World/A box 0 0 0 1 0 0 0 1 1 1 0.5 1 1 default engine_default true false";
  std::string obj17 = "object /World/B box 0 0 0 1 0 0 0 1 1 1 0.5 1 1 default engine_default";
  LoadResult r = load("raisim_engine_scene 1\n" + std::string(kObject25) + "\n" + obj19 + "\n" + obj17 + "\n");
  ASSERT_TRUE(r.ok()) << r.diagnostics[0].message;
  EXPECT_EQ(r.document.records[1].positionalCount, 25u);
  EXPECT_EQ(r.document.records[2].positionalCount, 19u);
  EXPECT_EQ(r.document.records[3].positionalCount, 17u);
}

TEST(Loader, ATruncatedRecordIsAnErrorAtItsEnd) {
  LoadResult r = load("raisim_engine_scene 1\nobject /World/A box 0 0 0 1 0 0\n");
  ASSERT_EQ(firstCode(r), "RS1007");
  EXPECT_EQ(r.diagnostics[0].line, 2u);
  EXPECT_EQ(r.diagnostics[0].column, 32u);  // just after the last token
  EXPECT_EQ(r.diagnostics[0].message, "object has 8 positional fields, expected 25, 19 or 17");
}

TEST(Loader, BadBytesAreErrorsWithColumns) {
  EXPECT_EQ(firstCode(load("raisim_engine_scene 1\nasset_root a%G1\n")), "RS1003");
  EXPECT_EQ(load("raisim_engine_scene 1\nasset_root a%G1\n").diagnostics[0].column, 13u);
  EXPECT_EQ(firstCode(load(std::string("raisim_engine_scene 1\nasset_root a\0b\n", 37))), "RS1004");
  EXPECT_EQ(firstCode(load("raisim_engine_scene 1\nasset_root a\xff\n")), "RS1005");
  EXPECT_EQ(firstCode(load("raisim_engine_scene 1\nasset_root a\xc3\n")), "RS1005");
  EXPECT_EQ(firstCode(load("raisim_engine_scene 1\nasset_root a\x01\n")), "RS1006");
  EXPECT_TRUE(load("raisim_engine_scene 1\nasset_root d\xc3\xa9j\xc3\xa0\n").ok());  // valid UTF-8
  EXPECT_TRUE(load("raisim_engine_scene 1\n# 100% sure\tok\n").ok());            // comments are free text
}

TEST(Loader, PositionalAfterKeyAndEmptyKeyAreErrors) {
  EXPECT_EQ(firstCode(load("raisim_engine_scene 1\ngravity 0 0 x=1 -9.81\n")), "RS1008");
  EXPECT_EQ(firstCode(load("raisim_engine_scene 1\nscene_graph =1\n")), "RS1009");
  // Unknown tags keep their tokens in written order instead.
  LoadResult r = load("raisim_engine_scene 1\nfuture_thing a k=v b\n");
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r.document.records[1].interleaved);
  EXPECT_EQ(r.document.positionalText(r.document.records[1], 1), "b");
}

TEST(Loader, KeepsUnknownTagsKeysAndExactText) {
  LoadResult r = load("raisim_engine_scene 1\n" + std::string(kObject25) + " brandNewKey=0.50\nfuture_record x y=z\n");
  ASSERT_TRUE(r.ok());
  const Document& d = r.document;
  EXPECT_EQ(d.records[1].kind->tag, "object");
  EXPECT_EQ(d.value(d.records[1], "brandNewKey"), "0.50");
  EXPECT_EQ(d.positionalText(d.records[1], 24), "18446744073709551615");
  EXPECT_EQ(d.records[2].kind, nullptr);
  EXPECT_EQ(d.tag(d.records[2]), "future_record");
  EXPECT_EQ(nodeId(d, d.records[1]), "object_cratea");
}

TEST(Loader, DefaultIdsFollowCompatNotes) {
  LoadResult r = load(
      "raisim_engine_scene 1\nmaterial mat_a 1 1 1 1 0 0.5 0 0 0 0 false - - - - - -\n"
      "group /World/Props parentId=folder_world\n"
      "object /World/X box 0 0 0 1 0 0 0 1 1 1 0.5 1 1 default engine_default\n");
  ASSERT_TRUE(r.ok());
  const Document& d = r.document;
  EXPECT_EQ(nodeId(d, d.records[1]), "mat_a");
  EXPECT_EQ(nodeId(d, d.records[2]), "folder_/World/Props");
  EXPECT_EQ(nodeId(d, d.records[3]), "object_/World/X");
}

TEST(Loader, HugeClaimsDoNotAllocate) {
  // A terrain that claims 10^9 samples loads as text; counts are checked by
  // the validator without allocating by the claim.
  LoadResult r = load("raisim_engine_scene 1\nterrain_region /World/T 31623 31623 10 10 0 0 0 heights=0,1\n");
  EXPECT_TRUE(r.ok());
}

TEST(Loader, StopsAfterManyErrors) {
  std::string text = "raisim_engine_scene 1\n";
  for (int i = 0; i < 1000; ++i) text += "gravity 0 0\n";
  LoadResult r = load(text);
  EXPECT_EQ(r.diagnostics.size(), 50u);
}

TEST(Loader, NamesAByteOrderMarkInsteadOfAnInvisibleCaret) {
  LoadResult r = load("\xEF\xBB\xBFraisim_engine_scene 1\ngravity 0 0 -9.81\n");
  ASSERT_EQ(r.diagnostics.size(), 1u);
  const Diagnostic& d = r.diagnostics[0];
  EXPECT_EQ(d.code, "RS1001");
  EXPECT_EQ(d.message, "file starts with a UTF-8 byte order mark (EF BB BF); remove it");
  EXPECT_EQ(d.line, 1u);
  EXPECT_EQ(d.column, 1u);
  EXPECT_EQ(load("\xFF\xFEr\0a"s).diagnostics.at(0).message,
            "file starts with a UTF-16 byte order mark (FF FE); save it as UTF-8");
  // The same bytes later in the file are text like any other.
  EXPECT_TRUE(load("raisim_engine_scene 1\n# \xEF\xBB\xBF\n").ok());
}

TEST(Loader, HintsThatThereAreNoContinuationLines) {
  LoadResult r = load("raisim_engine_scene 1\n# a comment may end with \\\ngravity 0 0 \\\n  -9.81\n"
                      "material m 1 1 1 1 0 0.5 0 0 0 0 false - - - - - path\\\n");
  EXPECT_EQ(r.continuedLines, (std::vector<std::uint32_t>{3}));  // not a comment, not `path\`
  // The loader's own errors get the hint (the record on the line, and the
  // line after it).
  r = load("raisim_engine_scene 1\nmaterial m 1 1 1 1 0 0.5 0 0 0 0 false - - - - - - \\\n  id=m\n");
  ASSERT_EQ(r.diagnostics.size(), 1u);
  EXPECT_EQ(r.diagnostics[0].code, "RS1007");
  EXPECT_EQ(r.diagnostics[0].hint,
            "line 2 ends with `\\`, but the format has no continuation lines: write each record on one line");
  // validate's findings on those lines get it too, others keep theirs.
  Document doc;
  Diagnostics ds = validateText("raisim_engine_scene 1\ngravity 0 0 \\\n -9.81\ntime_step x\n", {}, doc);
  ASSERT_EQ(ds.size(), 3u);
  EXPECT_EQ(ds[0].line, 2u);
  EXPECT_EQ(ds[1].line, 3u);
  EXPECT_NE(ds[0].hint.find("line 2 ends with `\\`"), std::string::npos);
  EXPECT_EQ(ds[1].hint, ds[0].hint);
  EXPECT_EQ(ds[2].line, 4u);
  EXPECT_EQ(ds[2].hint.find("continuation"), std::string::npos);
}
