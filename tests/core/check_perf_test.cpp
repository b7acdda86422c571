// The validator's fast paths give the answers of the plain ones: number
// checks without std::from_chars, the bounded "did you mean" search and its
// cache, fields resolved once per record, the open-addressing node index.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

#include "core/check.hpp"
#include "core/check_context.hpp"
#include "core/suggest.hpp"
#include "core/text.hpp"

namespace rscene {
namespace {

Diagnostics run(const std::string& text, CheckOptions o = {}) {
  Document doc;
  return validateText(text, o, doc);
}

std::vector<std::string> codes(const Diagnostics& ds) {
  std::vector<std::string> out;
  for (const Diagnostic& d : ds) out.push_back(d.code);
  return out;
}

// Optimal string alignment, the textbook way, for comparison.
std::size_t referenceDistance(std::string_view a, std::string_view b) {
  auto low = [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; };
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      std::size_t cost = low(a[i - 1]) == low(b[j - 1]) ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && low(a[i - 1]) == low(b[j - 2]) && low(a[i - 2]) == low(b[j - 1]))
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

TEST(CheckFast, EditDistanceMatchesTheTextbookOnRandomWords) {
  std::mt19937 rng(5);
  const std::string alphabet = "abcAB_";
  auto word = [&](std::size_t maxLen) {
    std::string w(rng() % (maxLen + 1), 'a');
    for (char& c : w) c = alphabet[rng() % alphabet.size()];
    return w;
  };
  for (int i = 0; i < 3000; ++i) {
    std::string a = word(i % 10 == 0 ? 90 : 12), b = word(i % 7 == 0 ? 80 : 12);  // some past the stack rows
    ASSERT_EQ(editDistance(a, b), referenceDistance(a, b)) << a << " / " << b;
  }
}

TEST(CheckFast, ClosestNameIsTheFirstNearestWithinALimit) {
  std::mt19937 rng(9);
  std::vector<std::string> pool = {"color", "colorMode", "castShadow", "radius", "radiance", "mass", "material",
                                   "materialA", "colour", "colr", "rdius", "shadow"};
  for (int i = 0; i < 500; ++i) {
    std::vector<std::string_view> cands;
    for (int k = 0; k < 5; ++k) cands.push_back(pool[rng() % pool.size()]);
    std::string_view word = pool[rng() % pool.size()];
    // The plain rule: smallest distance within a third of the length; the
    // first candidate wins a tie.
    std::size_t limit = std::max<std::size_t>(1, (word.size() + 1) / 3), best = limit + 1;
    std::string want;
    for (std::string_view c : cands) {
      std::size_t d = referenceDistance(word, c);
      if (d < best) best = d, want = std::string(c);
    }
    ASSERT_EQ(closestName(word, cands), want) << word;
  }
}

TEST(CheckFast, IsNumberAgreesWithParseNumber) {
  std::mt19937_64 rng(3);
  std::vector<std::string> samples = {"0", "-0", "1.", ".5", "-.5", "00.10", "123456789012345", "0.000000000000001",
                                      "999999999999999", "-4.2", "3.14159265358979"};
  for (int i = 0; i < 20000; ++i) {
    std::string s = (rng() % 2 ? "-" : "") + std::to_string(rng() % 100000000);
    std::size_t dot = rng() % (s.size() + 1);
    if (s[0] != '-' || dot > 0) s.insert(dot, ".");
    samples.push_back(s);
  }
  for (const std::string& s : samples) ASSERT_EQ(checks::isNumber(s), parseNumber(s).has_value()) << s;
  for (const std::string& s : std::vector<std::string>{"", "-", ".", "-.", "+1", "1e5", "1e400", "inf", "nan", "0x1", "1.2.3", "--1", "1-",
                        std::string(120, '1'), "0." + std::string(400, '0') + "1", std::string(400, '9')}) {
    ASSERT_EQ(checks::isNumber(s), parseNumber(s).has_value()) << s;
  }
}

TEST(CheckFast, ListsReportTheFirstBadItemAndEmptyEntries) {
  const std::string H = "raisim_engine_scene 2\n";
  const std::string iv = "instanced_visual /World/i box instances=";
  Diagnostics ds = run(H + iv + "0,0,0,1,0,0,0,1,1,x\n");
  ASSERT_EQ(codes(ds), std::vector<std::string>{"RS2001"});
  EXPECT_EQ(ds[0].column, 1u + iv.size() + 18);
  ds = run(H + iv + "0,0,0,1e999,0,0,0,1,1,y\n");
  ASSERT_EQ(codes(ds), std::vector<std::string>{"RS2002"});  // only the first bad item
  ds = run(H + iv + "0,0,0,1,0,,0,1,1,1\n");
  ASSERT_EQ(codes(ds), std::vector<std::string>{"RS2009"});
  EXPECT_TRUE(run(H + iv + ".5,-.5,5.,1,0,0,0,1,1,1\n").empty());
  ds = run(H + iv + "0,0,0,1,0,0,0,1,1\n");
  ASSERT_EQ(codes(ds), std::vector<std::string>{"RS4004"});
}

TEST(CheckFast, RepeatedKeysAndTheLastValueWin) {
  const std::string H = "raisim_engine_scene 2\n";
  const std::string iv = "instanced_visual /World/i box instances=0,0,0,1,0,0,0,1,1,1";
  EXPECT_EQ(codes(run(H + iv + " size=-1,1,1 size=1,1,1\n")), std::vector<std::string>{"RS1101"});
  EXPECT_EQ(codes(run(H + iv + " size=1,1,1 size=-1,1,1\n")), (std::vector<std::string>{"RS1101", "RS4011"}));
  // Unknown keys repeat only themselves, also past the short-record scan.
  std::string many;
  for (int i = 0; i < 40; ++i) many += " k" + std::to_string(i) + "=1";
  std::vector<std::string> found = codes(run(H + iv + many + " k3=2 size=1,1,1\n"));
  EXPECT_EQ(std::count(found.begin(), found.end(), "RS1101"), 1);
  EXPECT_EQ(std::count(found.begin(), found.end(), "RS3002"), 41);
}

TEST(CheckFast, SuggestionsAreRememberedPerKind) {
  const std::string H = "raisim_engine_scene 2\n";
  std::string text = H;
  for (int i = 0; i < 50; ++i) text += "light /World/l" + std::to_string(i) + " 0 0 -1 1 colour=1,1,1\n";
  text += "instanced_visual /World/i box instances=0,0,0,1,0,0,0,1,1,1 colour=1,1,1\n";
  Diagnostics ds = run(text);
  ASSERT_EQ(ds.size(), 51u);
  for (int i = 0; i < 50; ++i) EXPECT_EQ(ds[static_cast<std::size_t>(i)].hint, "did you mean `color`?");
  // The other kind's hint comes from its own keys.
  std::vector<std::string_view> keys;
  for (const FieldDef& k : Schema::get().kind("instanced_visual")->keys) keys.push_back(k.name);
  std::string best = closestName("colour", keys);
  EXPECT_EQ(ds[50].hint, best.empty() ? "" : "did you mean `" + best + "`?");
}

TEST(CheckFast, ManyNodesDuplicatesAndReferences) {
  std::string text = "raisim_engine_scene 2\n";
  for (int i = 0; i < 3000; ++i) text += "group /World/g" + std::to_string(i) + " id=g" + std::to_string(i) + "\n";
  text += "group /World/g7 id=other\n";                        // duplicate path
  text += "group /World/x id=g9\n";                            // duplicate id
  text += "group /World/y parentId=g2999\n";                   // by id
  text += "group /World/z parentId=/World/g1234\n";            // by path
  text += "group /World/w parentId=nothing\n";                 // names nothing
  Diagnostics ds = run(text);
  ASSERT_EQ(codes(ds), (std::vector<std::string>{"RS3003", "RS3004", "RS3006"}));
  EXPECT_EQ(ds[0].message, "duplicate path '/World/g7'; first used on line 9");
  EXPECT_EQ(ds[1].message, "duplicate id 'g9'; first used on line 11");
}

}  // namespace
}  // namespace rscene
