#include <gtest/gtest.h>

#include "core/io.hpp"
#include "test_util.hpp"

using namespace rscene;
using rscene::test::fmt;

TEST(Writer, OrdersRecordsBySectionAndKeepsChildrenWithParents) {
  std::string in =
      "raisim_engine_scene 1\n"
      "object /World/A box 0 0 0 1 0 0 0 1 1 1 0.5 1 1 default engine_default\n"
      "compound /World/C 0 0 0 1 0 0 0 1 1 1 1 dynamic true true\n"
      "light /World/L 0 0 -1 1\n"
      "compound_child /World/C box 0 0 0 1 0 0 0 1 1 1\n"
      "gravity 0 0 -9.81\n"
      "time_step 0.01\n";
  EXPECT_EQ(fmt(in),
            "raisim_engine_scene 1\n"
            "time_step 0.01\n"
            "gravity 0 0 -9.81\n"
            "light /World/L 0 0 -1 1\n"
            "object /World/A box 0 0 0 1 0 0 0 1 1 1 0.5 1 1 default engine_default\n"
            "compound /World/C 0 0 0 1 0 0 0 1 1 1 1 dynamic true true\n"
            "compound_child /World/C box 0 0 0 1 0 0 0 1 1 1\n");
}

TEST(Writer, UnknownTagsAndCommentsTravelWithTheirRecords) {
  std::string in =
      "# header comment\n"
      "raisim_engine_scene 1\n"
      "# about the light\n"
      "light /World/L 0 0 -1 1\n"
      "future_thing a b=c\n"
      "time_step 0.01\n"
      "# the end\n";
  EXPECT_EQ(fmt(in),
            "# header comment\n"
            "raisim_engine_scene 1\n"
            "time_step 0.01\n"
            "# about the light\n"
            "light /World/L 0 0 -1 1\n"
            "future_thing a b=c\n"
            "# the end\n");
}

TEST(Writer, CanonicalTokensKeepKeyOrderAndUint64Digits) {
  std::string in =
      "raisim_engine_scene 1\n"
      "object  /World/A\tbox 0 0 0.50 1.0 0 0 0 1 1 1 0.5 1 1 default engine_default no yes off - movable on 1 "
      "18446744073709551615 zeta=1 id=a castShadow=on futureKey=0.50 emptyKey= dashKey=-\n";
  EXPECT_EQ(fmt(in),
            "raisim_engine_scene 1\n"
            "object /World/A box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false - movable "
            "true 1 18446744073709551615 zeta=1 id=a castShadow=true futureKey=0.50 emptyKey= dashKey=-\n");
}

TEST(Writer, VersionTwoEscapingIsKept) {
  std::string in = "raisim_engine_scene 2\nasset a%3Bb mesh %2D id=x%3by importWarnings=w1%3Bx;w2\n";
  EXPECT_EQ(fmt(in), "raisim_engine_scene 2\nasset a%3Bb mesh %2D id=x%3By importWarnings=w1%3Bx;w2\n");
  // Version 1 has no `;` escape: the decoded value is written literally.
  EXPECT_EQ(fmt("raisim_engine_scene 1\nasset a%3Bb mesh p\n"), "raisim_engine_scene 1\nasset a;b mesh p\n");
}

TEST(Writer, IsIdempotentAndKeepsTheParse) {
  std::string in =
      "raisim_engine_scene 1\r\n"
      "instanced_visual /World/I sphere instances=1.0,0,0,1,0,0,0,1,1,1;2.0,0,0,1,0,0,0,1,1,1 colorWeights=0.50,1\n"
      "gravity 0 0 -9.810\n"
      "editor_ux selectionFilterKinds=\n";
  std::string once = fmt(in);
  EXPECT_EQ(fmt(once), once);
  LoadResult a = parse(in), b = parse(once);
  std::string why;
  EXPECT_TRUE(sameDocument(a.document, b.document, &why)) << why;
}

TEST(Writer, SameDocumentNoticesRealChanges) {
  LoadResult a = parse("raisim_engine_scene 1\ngravity 0 0 -9.81\n");
  LoadResult b = parse("raisim_engine_scene 1\ngravity 0 0 -9.8\n");
  LoadResult c = parse("raisim_engine_scene 1\n# note\ngravity 0 0 -9.81\n");
  std::string why;
  EXPECT_FALSE(sameDocument(a.document, b.document, &why));
  EXPECT_NE(why.find("differs"), std::string::npos);
  EXPECT_FALSE(sameDocument(a.document, c.document, &why));
}

TEST(Writer, EditsAppendToTheBufferAndKeepOtherFields) {
  LoadResult r = parse("raisim_engine_scene 1\nlight /World/L 0 0 -1 1 id=l\ngravity 0 0 -9.81\n");
  ASSERT_TRUE(r.ok());
  Document& d = r.document;
  d.setValue(d.records[1].firstField + 4, "2.5");
  d.setKey(1, "color", "1,0,0");
  d.setKey(1, "id", "l2");
  EXPECT_EQ(canonicalText(d),
            "raisim_engine_scene 1\ngravity 0 0 -9.81\nlight /World/L 0 0 -1 2.5 id=l2 color=1,0,0\n");
}

TEST(Writer, AnOrphanChildKeepsItsPlaceBeforeALaterParent) {
  // Found by the fuzzer: the orphan used to travel with the record before
  // it, and met its parent only on the second pass.
  std::string in =
      "raisim_engine_scene 1\n"
      "wire /World/Tether stiff a b 2\n"
      "compound_child /World/Cart box 0 0 0 1 0 0 0 1 1 1\n"
      "compound /World/Cart 1.5 0 0.3 1 0 0 0 1 1 1 12 dynamic true true\n";
  std::string once = fmt(in);
  EXPECT_EQ(once,
            "raisim_engine_scene 1\n"
            "compound_child /World/Cart box 0 0 0 1 0 0 0 1 1 1\n"
            "compound /World/Cart 1.5 0 0.3 1 0 0 0 1 1 1 12 dynamic true true\n"
            "wire /World/Tether stiff a b 2\n");
  EXPECT_EQ(fmt(once), once);
}

// The writer copies a line whole only when it is canonical as written;
// every way a line can be almost canonical must still be formatted.
TEST(Writer, OnlyCanonicalLinesAreCopiedWhole) {
  const std::string h = "raisim_engine_scene 1\n";
  const std::string g = "gravity 0 0 -9.81\n";
  for (const char* in : {"gravity  0 0 -9.81\n", "\tgravity 0 0 -9.81\n", " gravity 0 0 -9.81\n",
                         "gravity 0 0 -9.81  \n", "gravity 0 0 -9.81\r\n", "gravity 0 0\t-9.81\n",
                         "gravity 0 0 -9.810\n", "gravity 0 0 -9.81"})
    EXPECT_EQ(fmt(h + in), h + g) << in;
  // Tokens: escapes, `=` inside a value, flags, empty values.
  const std::string m = "material m 1 1 1 1 0 0.5 0 0 0 0 false - - - - - -";
  EXPECT_EQ(fmt(h + m + " id=a=b\n"), h + m + " id=a%3Db\n");
  EXPECT_EQ(fmt(h + m + " id=a%3db\n"), h + m + " id=a%3Db\n");
  EXPECT_EQ(fmt(h + "material m 1 1 1 1 0 0.5 0 0 0 0 no - - - - - -\n"), h + m + "\n");
  EXPECT_EQ(fmt(h + m + " uvScale=1.0,2\n"), h + m + " uvScale=1,2\n");
  EXPECT_EQ(fmt(h + m + " uvScale=1e-4,2\n"), h + m + " uvScale=1e-04,2\n");
  EXPECT_EQ(fmt(h + m + " id=\n"), h + m + " id=-\n");
  EXPECT_EQ(fmt(h + m + " futureKey=\n"), h + m + " futureKey=\n");  // unknown keys keep `key=`
  // A canonical file is a fixed point, byte for byte.
  const std::string canonical = h + g + m + " uvScale=1e-04,2.5 id=a%3Db futureKey=x\n";
  EXPECT_EQ(fmt(canonical), canonical);
}
