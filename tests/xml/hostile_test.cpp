// Hostile world XML: entity expansion, deep nesting, huge loops, include
// cycles and bombs, parameter blow-ups.  Each is refused with a clear
// error.  That the work stays bounded is shown by what the loader reports,
// never by a clock (machines are shared): the error is at the element where
// a limit is passed, the limit's own figure is in the message, nothing is
// built, and a smaller limit refuses a smaller input at its boundary.
// bench/xml/hostile.cpp times the same inputs (hostile_inputs.hpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "hostile_inputs.hpp"
#include "xml_test_util.hpp"

namespace rscene::xml {
namespace {

using test::errors;
using test::loadText;

// The first diagnostic as "message [code]".
std::string first(const LoadResult& r) {
  return r.diagnostics.empty() ? std::string() : r.diagnostics[0].message + " [" + r.diagnostics[0].code + "]";
}

TEST(Hostile, BillionLaughsDoctypeIsRefused) {
  LoadResult r = loadText(hostile::billionLaughs());
  EXPECT_FALSE(r.ok());
  // Refused at the declaration, and the one use of &lol9; is an error of
  // its own, not expanded: two errors and no tree.
  EXPECT_EQ(errors(r),
            "w.xml:2:1: DOCTYPE declares entities: entity declarations are refused (they can expand without bound) "
            "[RS8102]\n"
            "w.xml:14:32: &lol9; is no XML entity: only &amp; &lt; &gt; &quot; &apos; and &#...; are read (DOCTYPE "
            "entities are not expanded) [RS8102]\n");
  EXPECT_FALSE(r.root.has_value());
}

TEST(Hostile, UnknownEntityIsNeverKeptAsText) {
  LoadResult r = loadText("<raisim>\n<objects><sphere name=\"a&lol;b\"/></objects></raisim>");
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(errors(r),
            "w.xml:2:25: &lol; is no XML entity: only &amp; &lt; &gt; &quot; &apos; and &#...; are read "
            "(DOCTYPE entities are not expanded) [RS8102]\n");
  // The five predefined entities and numeric references are read.
  r = loadText("<raisim><objects><sphere name=\"&lt;&amp;&#65;&#x42;&quot;\"/></objects></raisim>");
  ASSERT_TRUE(r.ok()) << errors(r);
  EXPECT_EQ(r.root->children[0].children[0].attributes[0].value, "<&AB\"");
  // In a comment or CDATA '&' is no reference.
  r = loadText("<raisim><!-- &lol; --><objects/></raisim>");
  EXPECT_TRUE(r.ok()) << errors(r);
  // A DOCTYPE without an internal subset declares nothing and is allowed.
  r = loadText("<!DOCTYPE raisim>\n<raisim/>");
  EXPECT_TRUE(r.ok()) << errors(r);
}

TEST(Hostile, DeepNestingIsRefusedAtTheLimit) {
  // 10^5 deep: refused at the 65th element's '<', not at the end, once.
  LoadResult r = loadText(hostile::deepNesting(100000));
  EXPECT_EQ(first(r), "elements nested deeper than 64 [RS8107]");
  EXPECT_EQ(r.diagnostics[0].column, 1u + 8 + 3 * 63);
  EXPECT_EQ(r.diagnostics.size(), 1u) << errors(r);
  EXPECT_FALSE(r.root.has_value());
  // The boundary: 64 deep (<raisim> and 63 <a>) is read, 65 is not.
  EXPECT_TRUE(loadText(hostile::deepNesting(63)).ok());
  EXPECT_EQ(first(loadText(hostile::deepNesting(64))), "elements nested deeper than 64 [RS8107]");
}

TEST(Hostile, LoopOfABillionIsRefusedAtOnce) {
  // One error at the array and no tree: refused from its bounds, before
  // an iteration ran.
  LoadResult r = loadText(hostile::billionLoop());
  EXPECT_EQ(errors(r), "w.xml:2:1: <array>: the loops here run more than 1000000 iterations, the limit [RS8107]\n");
  EXPECT_FALSE(r.root.has_value());
  // The limit is the count: with 10 allowed, 10 iterations make 10
  // spheres and 11 are refused.
  LoadLimits ten;
  ten.maxLoopIterations = 10;
  auto loop = [](int end) {
    return "<raisim><objects><array idx=\"@@i\" start=\"0\" end=\"" + std::to_string(end) +
           "\" increment=\"1\"><sphere/></array></objects></raisim>";
  };
  r = loadText(loop(10), {}, ten);
  ASSERT_TRUE(r.ok()) << errors(r);
  EXPECT_EQ(test::childrenNamed(r.root->children[0], "sphere").size(), 10u);
  EXPECT_EQ(first(loadText(loop(11), {}, ten)), "<array>: the loops here run more than 10 iterations, the limit [RS8107]");
  // Counting down from the top of int64 to the bottom does not overflow.
  r = loadText(
      "<raisim><objects><array idx=\"@@i\" start=\"9223372036854775807\" end=\"-9223372036854775808\" "
      "increment=\"-1\"><sphere/></array></objects></raisim>");
  EXPECT_EQ(first(r), "<array>: the loops here run more than 1000000 iterations, the limit [RS8107]");
}

TEST(Hostile, NestedLoopsAreRefusedByTheElementLimitBeforeBuilding) {
  LoadResult r = loadText(hostile::nestedLoops());
  EXPECT_EQ(first(r), "<array>: the loops here make more than 1000000 elements, the limit [RS8107]");
  EXPECT_EQ(r.diagnostics.size(), 1u) << errors(r);
  EXPECT_FALSE(r.root.has_value());
  // The limit is the caller's: a smaller one refuses a smaller world.
  LoadLimits limits;
  limits.maxElements = 50;
  r = loadText("<raisim><objects><array idx=\"@@i\" start=\"0\" end=\"30\" increment=\"1\"><sphere/></array>"
               "<array idx=\"@@i\" start=\"0\" end=\"30\" increment=\"1\"><box/></array></objects></raisim>",
               {}, limits);
  EXPECT_EQ(first(r), "<array>: the loops here make more than 50 elements, the limit [RS8107]");
}

TEST(Hostile, ManyEmptyLoopsInsideALongOneAreBounded) {
  // 10^8 loops entered, none running: the iteration limit counts the
  // loops entered too (10^5 outer iterations alone are under it), so the
  // work stops at 10^6 of them.
  LoadResult r = loadText(hostile::manyEmptyLoops());
  EXPECT_EQ(first(r), "<array>: the loops here run more than 1000000 iterations, the limit [RS8107]");
  EXPECT_EQ(r.diagnostics.size(), 1u) << errors(r);
  EXPECT_FALSE(r.root.has_value());
}

TEST(Hostile, ParameterBlowUpsAreBounded) {
  // Each parameter twice the next: 2^30 copies of "xxxxxxxx" if nothing
  // stopped it.  Each blow-up stops at a cap its message names, with one
  // error and no tree.
  LoadLimits limits;
  limits.maxFileBytes = 1 << 20;
  LoadResult r = loadText(hostile::parameterDoubling(30, "xxxxxxxx"), {}, limits);
  EXPECT_EQ(first(r), "<box> name: value longer than 1048576 bytes after substituting parameters [RS8104]");
  EXPECT_EQ(r.diagnostics.size(), 1u) << errors(r);
  EXPECT_FALSE(r.root.has_value());
  // With an empty last value it makes no text, only work.
  r = loadText(hostile::parameterDoubling(30, ""));
  EXPECT_EQ(first(r), "<box> name: more than 1048576 parameter substitutions in one value [RS8104]");
  EXPECT_EQ(r.diagnostics.size(), 1u) << errors(r);
  r = loadText(hostile::parameterDoubling(40, "x"));
  EXPECT_EQ(first(r), "<box> name: parameters refer to parameters more than 32 deep [RS8104]");
  EXPECT_EQ(r.diagnostics.size(), 1u) << errors(r);
  // The value cap is the caller's: 2^10 copies of "x" pass a cap of 1024
  // bytes and 2^11 do not.
  limits.maxFileBytes = 1024;
  r = loadText(hostile::parameterDoubling(10, "x"), {}, limits);
  ASSERT_TRUE(r.ok()) << errors(r);
  std::vector<const Element*> objects = test::childrenNamed(*r.root, "objects");
  ASSERT_EQ(objects.size(), 1u);
  ASSERT_EQ(objects[0]->children.size(), 1u);
  EXPECT_EQ(objects[0]->children[0].attributes.at(0).value, std::string(1024, 'x'));
  EXPECT_EQ(first(loadText(hostile::parameterDoubling(11, "x"), {}, limits)),
            "<box> name: value longer than 1024 bytes after substituting parameters [RS8104]");
}

TEST(Hostile, TooManyBytesOfAttributes) {
  LoadLimits limits;
  limits.maxExpandedBytes = 100000;
  LoadResult r = loadText("<raisim><params><v value=\"" + std::string(1000, 'v') +
                              "\"/></params><objects><array idx=\"@@i\" start=\"0\" end=\"1000\" increment=\"1\">"
                              "<box name=\"@@v\"/></array></objects></raisim>",
                          {}, limits);
  EXPECT_EQ(first(r), "<box> name: the expansion makes more than 100000 bytes of attributes, the limit [RS8107]");
  // Empty attributes count too: a thousand of them a thousand times.
  std::string many;
  for (int i = 0; i < 1000; ++i) many += " a" + std::to_string(i) + "=\"\"";
  r = loadText("<raisim><objects><array idx=\"@@i\" start=\"0\" end=\"1000\" increment=\"1\"><box" + many +
                   "/></array></objects></raisim>",
               {}, limits);
  // ... refused within the first box, whose attributes alone pass the limit.
  EXPECT_EQ(r.diagnostics.size(), 1u);
  EXPECT_EQ(first(r).rfind("<box> a", 0), 0u) << first(r);
  EXPECT_NE(first(r).find(": the expansion makes more than 100000 bytes of attributes, the limit [RS8107]"),
            std::string::npos);
  EXPECT_EQ(r.diagnostics[0].line, 1u);
}

TEST(Hostile, ErrorsAreCappedInsteadOfOnePerElement) {
  std::string many;
  for (int i = 0; i < 1000; ++i) many += "<box name=\"@@unset\"/>";
  LoadResult r = loadText("<raisim><objects>" + many + "</objects></raisim>");
  EXPECT_FALSE(r.ok());
  EXPECT_LE(r.diagnostics.size(), 20u);
}

class HostileFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("rscene_xml_hostile_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  std::filesystem::path dir_;
};

TEST_F(HostileFiles, IncludeDiamondBombIsBounded) {
  // Each level includes the next ten times: 10^12 reads without a bound.
  std::filesystem::path top = hostile::writeIncludeDiamond(dir_);
  LoadOptions options;
  options.limits.maxElements = 10000;
  LoadResult r = loadWorld(top.string(), options);
  EXPECT_FALSE(r.ok());
  EXPECT_NE(first(r).find("elements together, the limit [RS8107]"), std::string::npos) << errors(r);
  EXPECT_FALSE(r.root.has_value());
  EXPECT_EQ(r.diagnostics.size(), 1u) << errors(r);
  // Every file read holds at least its <raisim>, so the element limit
  // bounds the reads: thousands, not 10^12.
  EXPECT_LE(r.files.size(), options.limits.maxElements);
}

TEST_F(HostileFiles, IncludeDepthAndNonRegularFiles) {
  // A chain of 20 distinct files: deeper than the include limit of 16.
  for (int i = 0; i < 20; ++i)
    write("c" + std::to_string(i) + ".xml", "<raisim><include file=\"c" + std::to_string(i + 1) + ".xml\"/></raisim>");
  write("c20.xml", "<raisim/>");
  LoadResult r = loadWorld((dir_ / "c0.xml").string(), {});
  EXPECT_EQ(first(r), "<include> file: includes nested deeper than 16 [RS8103]");
  // /dev/zero is refused for what it is, before a byte of it is read.
  std::string dev = write("dev.xml", "<raisim><include file=\"/dev/zero\"/></raisim>");
  r = loadWorld(dev, {});
  EXPECT_EQ(first(r), "<include> file: cannot read '/dev/zero': not a regular file [RS8103]");
  r = loadWorld("/dev/zero", {});
  EXPECT_EQ(first(r), "cannot read: not a regular file [RS8101]");
}

TEST_F(HostileFiles, FileSizeLimit) {
  std::string big = write("big.xml", "<raisim>" + std::string(5000, ' ') + "</raisim>");
  LoadOptions options;
  options.limits.maxFileBytes = 1000;
  LoadResult r = loadWorld(big, options);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.diagnostics.at(0).code, "RS8101");
  EXPECT_NE(r.diagnostics[0].message.find("1000"), std::string::npos) << errors(r);
}

// tinyxml2 said "w.xml:3: not well-formed XML (mismatched element)" at the
// line of the opening tag, with no column and no element.
TEST(Hostile, MismatchedEndTagNamesBothElementsAtTheEndTag) {
  EXPECT_EQ(errors(loadText("<raisim>\n  <objects>\n    <sphere name=\"a\">\n  </objects>\n</raisim>\n")),
            "w.xml:4:3: not well-formed XML: </objects> closes <sphere> opened at 3:5 [RS8101]\n");
  EXPECT_EQ(errors(loadText("<raisim>\n  <objects/>\n</objects>\n</raisim>\n")),
            "w.xml:3:1: not well-formed XML: </objects> closes <raisim> opened at 1:1 [RS8101]\n");
  EXPECT_EQ(errors(loadText("<raisim>\n  <objects>\n")),
            "w.xml:2:3: not well-formed XML: <objects> is never closed [RS8101]\n");
  EXPECT_EQ(errors(loadText("<raisim/>\n</raisim>")),
            "w.xml:2:1: not well-formed XML: </raisim> closes no open element [RS8101]\n");
  // End tags with spaces before '>', comments and CDATA holding tags are fine.
  LoadResult r = loadText("<raisim ><objects ><!-- </sphere> --><![CDATA[</x>]]></objects  ></raisim>");
  EXPECT_TRUE(r.ok()) << errors(r);
}

TEST(Hostile, DuplicateAttributeIsReportedAtTheSecondOne) {
  EXPECT_EQ(errors(loadText("<raisim>\n<objects>\n  <sphere name=\"a\" mass=\"1\"\n          name=\"b\"/>\n</objects></raisim>")),
            "w.xml:4:11: not well-formed XML: attribute 'name' written twice (first at 3:11) [RS8101]\n");
  // Past 16 attributes the check goes through a set: same answer.
  std::string many = "<raisim a0=\"0\"";
  for (int i = 1; i < 40; ++i) many += " a" + std::to_string(i) + "=\"" + std::to_string(i) + "\"";
  EXPECT_TRUE(loadText(many + "/>").ok());
  EXPECT_EQ(errors(loadText(many + " a30=\"x\"/>")),
            "w.xml:1:" + std::to_string(many.size() + 2) +
                ": not well-formed XML: attribute 'a30' written twice (first at 1:" +
                std::to_string(many.find(" a30=") + 2) + ") [RS8101]\n");
}

// XML 1.0's Char production: &#0; used to cut a name short, &#x1; to make
// a name rscene-to-xml then refused.
TEST(Hostile, ForbiddenCharacterReferencesAreRefusedAtTheirColumn) {
  const char* kWhy =
      " is a character XML 1.0 forbids (controls other than tab, LF and CR, surrogates, U+FFFE, U+FFFF and values "
      "past U+10FFFF) [RS8102]\n";
  for (const std::string ref : {"&#0;", "&#x1;", "&#31;", "&#xD800;", "&#xDFFF;", "&#xFFFE;", "&#x110000;",
                                "&#99999999999999999999;"}) {
    LoadResult r = loadText("<raisim>\n<objects><sphere name=\"a" + ref + "b\"/></objects></raisim>");
    EXPECT_FALSE(r.ok()) << ref;
    EXPECT_EQ(errors(r), "w.xml:2:25: " + ref + kWhy) << ref;
  }
  // In text between elements too.
  EXPECT_EQ(errors(loadText("<raisim>&#x7;</raisim>")), "w.xml:1:9: &#x7;" + std::string(kWhy));
  EXPECT_EQ(errors(loadText("<raisim><objects><sphere name=\"&#;\"/></objects></raisim>")),
            "w.xml:1:32: &#;: not a character reference (&#digits; or &#xhex;) [RS8102]\n");
  // Tab, LF, CR and the rest of Unicode are read.
  LoadResult ok = loadText("<raisim><objects><sphere name=\"&#9;&#xA;&#13;&#233;&#x10FFFF;&#xE000;\"/></objects></raisim>");
  ASSERT_TRUE(ok.ok()) << errors(ok);
  EXPECT_EQ(ok.root->children[0].children[0].attributes[0].value, "\t\n\r\xC3\xA9\xF4\x8F\xBF\xBF\xEE\x80\x80");
}

// The limit held for included files only: the top file's text (standard
// input, as rscene-from-xml passes it) was read whatever its size.
TEST(Hostile, TopTextPastTheFileSizeLimitIsRefused) {
  LoadLimits limits;
  limits.maxFileBytes = 1000;
  LoadResult r = loadText("<raisim>" + std::string(5000, ' ') + "</raisim>", {}, limits);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(errors(r), "w.xml:0:0: cannot read: file larger than 1000 bytes [RS8101]\n");
  EXPECT_TRUE(loadText("<raisim>" + std::string(900, ' ') + "</raisim>", {}, limits).ok());
}

TEST(Hostile, NotWorldXml) {
  EXPECT_EQ(errors(loadText("<raisim><objects></raisim>")),
            "w.xml:1:18: not well-formed XML: </raisim> closes <objects> opened at 1:9 [RS8101]\n");
  EXPECT_EQ(errors(loadText("\n<world/>")), "w.xml:2:1: the top element is <world>, not <raisim> [RS8101]\n");
  EXPECT_EQ(errors(loadText("")), "w.xml:0:0: not well-formed XML (empty document) [RS8101]\n");
  EXPECT_EQ(first(loadText("<raisim><objects><params><x value=\"1\"/></params></objects></raisim>")),
            "<params>: belongs directly under <raisim> [RS8104]");
  EXPECT_EQ(first(loadText("<raisim><params><x/></params></raisim>")),
            "<x>: no value (write <x value=\"...\"/>) [RS8104]");
  EXPECT_EQ(first(loadText("<raisim/>", {{"a b", "1"}})),
            "--param 'a b': a parameter name is letters, digits and '_' [RS8104]");
}

}  // namespace
}  // namespace rscene::xml
