#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <random>

#include "core/text.hpp"

using namespace rscene;

namespace {
std::string canon(std::string_view raw, ValueType t, int version = 1) {
  std::string out;
  appendCanonical(out, raw, t, version);
  return out;
}
}  // namespace

TEST(PercentCodec, DecodesEitherCaseAndDashAsEmpty) {
  EXPECT_EQ(percentDecode("A%20label%20with%20spaces"), "A label with spaces");
  EXPECT_EQ(percentDecode("a%3db%3Dc"), "a=b=c");
  EXPECT_EQ(percentDecode("-"), "");
  EXPECT_EQ(percentDecode("%2D"), "-");
  EXPECT_EQ(percentDecode("--"), "--");
}

TEST(PercentCodec, FindsMalformedEscapes) {
  EXPECT_EQ(findBadEscape("ok%41"), std::string_view::npos);
  EXPECT_EQ(findBadEscape("%G1"), 0u);
  EXPECT_EQ(findBadEscape("abc%4"), 3u);
  EXPECT_EQ(findBadEscape("abc%"), 3u);
}

TEST(PercentCodec, EncodesPerVersion) {
  std::string v1, v2;
  percentEncode("a b;c=d%", 1, v1);
  percentEncode("a b;c=d%", 2, v2);
  EXPECT_EQ(v1, "a%20b;c%3Dd%25");
  EXPECT_EQ(v2, "a%20b%3Bc%3Dd%25");
  std::string empty, dash;
  percentEncode("", 2, empty);
  percentEncode("-", 2, dash);
  EXPECT_EQ(empty, "-");
  EXPECT_EQ(dash, "%2D");
  std::string ctl;
  percentEncode(std::string("a\tb\x7f", 4), 1, ctl);
  EXPECT_EQ(ctl, "a%09b%7F");
}

TEST(PercentCodec, InvalidUtf8StaysEscaped) {
  // Found by the fuzzer: %97 decoded to a raw byte the loader then refused.
  EXPECT_EQ(canon("A%97B", ValueType::Text, 1), "A%97B");
  EXPECT_EQ(canon("d%C3%A9j%C3%A0", ValueType::Text, 1), "d\xc3\xa9j\xc3\xa0");
  EXPECT_EQ(canon("%E2%82", ValueType::Text, 2), "%E2%82");
}

TEST(Numbers, ParseIsStrict) {
  EXPECT_EQ(parseNumber("1e-07"), 1e-07);
  EXPECT_EQ(parseNumber("-0.5"), -0.5);
  EXPECT_FALSE(parseNumber("nan"));
  EXPECT_FALSE(parseNumber("inf"));
  EXPECT_FALSE(parseNumber("1.5x"));
  EXPECT_FALSE(parseNumber(""));
  EXPECT_FALSE(parseNumber("1e999"));
  EXPECT_EQ(parseInteger("-12"), -12);
  EXPECT_FALSE(parseInteger("1.0"));
  EXPECT_EQ(parseGroup("18446744073709551615"), UINT64_MAX);
  EXPECT_FALSE(parseGroup("18446744073709551616"));
  EXPECT_FALSE(parseGroup("-1"));
}

TEST(Numbers, FlagsAcceptTheDocumentedSpellingsOnly) {
  for (const char* t : {"true", "1", "yes", "on"}) EXPECT_EQ(parseFlag(t), true) << t;
  for (const char* f : {"false", "0", "no", "off"}) EXPECT_EQ(parseFlag(f), false) << f;
  EXPECT_FALSE(parseFlag("TRUE"));
  EXPECT_FALSE(parseFlag("2"));
}

TEST(Numbers, ListsSplitOnCommaAndSemicolon) {
  std::vector<double> v;
  EXPECT_TRUE(parseNumberList("1,2;3", v));
  EXPECT_EQ(v, (std::vector<double>{1, 2, 3}));
  v.clear();
  EXPECT_TRUE(parseNumberList("", v));
  EXPECT_TRUE(v.empty());
  EXPECT_FALSE(parseNumberList("1,,2", v));
  EXPECT_FALSE(parseNumberList("1,2,", v));
}

TEST(Canonical, NumbersAreShortestRoundTrip) {
  EXPECT_EQ(canon("0.10", ValueType::Number), "0.1");
  EXPECT_EQ(canon("0.0", ValueType::Number), "0");
  EXPECT_EQ(canon("-0.0", ValueType::Number), "-0");
  EXPECT_EQ(canon("29.999999999999996", ValueType::Number), "29.999999999999996");
  EXPECT_EQ(canon("1e-7", ValueType::Number), "1e-07");
  EXPECT_EQ(canon("1000000", ValueType::Number), "1e+06");
  EXPECT_EQ(canon("2.0", ValueType::Number), "2");
  // Text that is not a number is kept (the validator reports it).
  EXPECT_EQ(canon("nan", ValueType::Number), "nan");
  EXPECT_EQ(canon("1.5x", ValueType::Number), "1.5x");
}

TEST(Canonical, IntegersGroupsAndFlags) {
  EXPECT_EQ(canon("007", ValueType::Integer), "7");
  EXPECT_EQ(canon("200000", ValueType::Integer), "200000");
  EXPECT_EQ(canon("18446744073709551615", ValueType::Group), "18446744073709551615");
  EXPECT_EQ(canon("yes", ValueType::Flag), "true");
  EXPECT_EQ(canon("off", ValueType::Flag), "false");
  EXPECT_EQ(canon("maybe", ValueType::Flag), "maybe");
}

TEST(Canonical, ListsKeepTheirSeparators) {
  EXPECT_EQ(canon("1.0,0.50,-0.0", ValueType::Vec3), "1,0.5,-0");
  EXPECT_EQ(canon("1.0,0,0,1,0,0,0,1,1,1;2.50,0,0,1,0,0,0,1,1,1", ValueType::TransformList),
            "1,0,0,1,0,0,0,1,1,1;2.5,0,0,1,0,0,0,1,1,1");
  EXPECT_EQ(canon("0,3,1000000", ValueType::IntegerList), "0,3,1000000");
  EXPECT_EQ(canon("", ValueType::NumberList), "");
}

TEST(Canonical, TextAndStringListsReEncodeForTheVersion) {
  EXPECT_EQ(canon("a%3bb", ValueType::Text, 1), "a;b");
  EXPECT_EQ(canon("a%3bb", ValueType::Text, 2), "a%3Bb");
  EXPECT_EQ(canon("%2D", ValueType::Text, 2), "%2D");
  EXPECT_EQ(canon("%2d", ValueType::Text, 1), "%2D");
  EXPECT_EQ(canon("-", ValueType::Path, 2), "-");
  EXPECT_EQ(canon("", ValueType::Path, 1), "-");
  EXPECT_EQ(canon("object;light;camera", ValueType::StringList, 2), "object;light;camera");
  EXPECT_EQ(canon("a%3Bb;c", ValueType::StringList, 2), "a%3Bb;c");
  EXPECT_EQ(canon("", ValueType::StringList, 1), "");
  EXPECT_EQ(canon("%41%62", ValueType::Name, 1), "Ab");
}

TEST(SameValue, ComparesTypedValues) {
  EXPECT_TRUE(sameValue("0.10", "0.1", ValueType::Number));
  EXPECT_FALSE(sameValue("0", "-0", ValueType::Number));
  EXPECT_FALSE(sameValue("0.1", "0.2", ValueType::Number));
  EXPECT_TRUE(sameValue("yes", "true", ValueType::Flag));
  EXPECT_TRUE(sameValue("-", "", ValueType::Text));
  EXPECT_FALSE(sameValue("-", "%2D", ValueType::Text));
  EXPECT_TRUE(sameValue("1.0,2", "1,2.0", ValueType::Vec2));
  EXPECT_FALSE(sameValue("1,2", "1;2", ValueType::Vec2));
  EXPECT_TRUE(sameValue("a;b", "%61;b", ValueType::StringList));
}

// The fast path that skips from_chars/to_chars must agree with them.
TEST(Canonical, FastPathAgreesWithToChars) {
  const char* samples[] = {"0", "-0", "1", "10", "100", "1000", "10000", "100000", "123456", "0.5", "0.05",
                           "0.005", "0.0005", "0.00005", "1.5", "-2.25", "12345.678", "0.1", "0.001", "1e-07",
                           "0.4117647058823529", "123456789012345", "1234567890123456", "0.000123", "3.14159",
                           "-0.0001", "-1000000", "2500", "1.10", "01", "1.", ".5", "100.5", "0.30000000000000004",
                           "99999", "999999", "1000001", "0.00012345678901234"};
  for (const char* s : samples) {
    std::string viaFast, viaSlow;
    appendCanonical(viaFast, s, ValueType::Number, 1);
    if (auto v = parseNumber(s)) appendNumber(viaSlow, *v);
    else viaSlow = s;
    EXPECT_EQ(viaFast, viaSlow) << s;
  }
  for (double v = -3e5; v < 3e5; v += 7.031) {
    std::string t;
    appendNumber(t, v);
    std::string again;
    appendCanonical(again, t, ValueType::Number, 1);
    EXPECT_EQ(again, t);
  }
}

// parseNumber's fast path for plain decimals must give from_chars' double,
// bit for bit, and refuse exactly what from_chars refuses.
TEST(Numbers, FastPathGivesFromCharsDouble) {
  auto reference = [](std::string_view s) -> std::optional<double> {
    double v = 0;
    auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || p != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
    return v;
  };
  std::mt19937_64 rng(3);
  std::vector<std::string> samples = {"0", "-0", "1.", ".5", "-.5", "00.10", "123456789012345", "0.000000000000001",
                                      "999999999999999", "-4.2", "3.14159265358979", "", "-", ".", "-.", "+1", "1e5",
                                      "1e400", "inf", "nan", "0x1", "1.2.3", "--1", "1-", std::string(120, '1'),
                                      "0." + std::string(400, '0') + "1", std::string(400, '9')};
  for (int i = 0; i < 20000; ++i) {
    std::string s = (rng() % 2 ? "-" : "") + std::to_string(rng() % 100000000);
    std::size_t dot = rng() % (s.size() + 1);
    if (s[0] != '-' || dot > 0) s.insert(dot, ".");
    samples.push_back(s);
  }
  for (const std::string& s : samples) {
    auto want = reference(s), got = parseNumber(s);
    ASSERT_EQ(got.has_value(), want.has_value()) << s;
    if (got) {
      ASSERT_EQ(std::memcmp(&*got, &*want, sizeof(double)), 0) << s;
    }
  }
}

TEST(Text, DecimalMultipleIsTheProductOfTheWrittenStep) {
  auto shortest = [](double v) {
    std::string s;
    appendNumber(s, v);
    return s;
  };
  EXPECT_EQ(shortest(14 * 0.1), "1.4000000000000001");  // why this exists
  EXPECT_EQ(shortest(decimalMultiple(14, 0.1)), "1.4");
  EXPECT_EQ(shortest(decimalMultiple(3, 0.1)), "0.3");
  EXPECT_EQ(shortest(decimalMultiple(400, 0.0025)), "1");
  EXPECT_EQ(shortest(decimalMultiple(12345, 0.001)), "12.345");
  EXPECT_EQ(shortest(decimalMultiple(7, 1.0 / 3)), "2.333333333333333");  // 7 x 0.3333333333333333
  EXPECT_EQ(shortest(decimalMultiple(1000000007, 1e-07)), "100.0000007");
  EXPECT_EQ(shortest(decimalMultiple(2, -0.25)), "-0.5");
  EXPECT_EQ(decimalMultiple(0, 0.1), 0.0);
  EXPECT_EQ(decimalMultiple(5, 0.0), 0.0);
  // The largest count and a large step still give one rounding, no overflow.
  EXPECT_EQ(decimalMultiple(UINT64_MAX, 1.0), 18446744073709551615.0);
  EXPECT_EQ(decimalMultiple(10, 1e308), 10 * 1e308);  // inf, as the plain product
  // Every count of a common step agrees with the decimal product.
  for (std::uint64_t n = 0; n < 2000; ++n) {
    double want = 0;
    std::string text = std::to_string(n) + "e-3";
    std::from_chars(text.data(), text.data() + text.size(), want);
    ASSERT_EQ(decimalMultiple(n, 0.001), want) << n;
  }
}

// isCanonicalToken lets the writer copy a token (or a whole line) without
// formatting it, so it must never say yes where appendCanonical would
// change the text.
TEST(Canonical, ACanonicalTokenIsOneAppendCanonicalKeepsAsIs) {
  std::mt19937_64 rng(7);
  std::vector<std::string> tokens = {
      "0", "-0", "1", "10", "1e+06", "1e-07", "1.5e-07", "-6e-04", "1e-04", "0.0001", "1e+05", "100000",
      "123456789012345", "1.23456789012345e+20", "1e+21", "1.5e+00", "1e+5", "1e5", "1E-07", "1e-007",
      "01e-07", "1.50e-07", "10e-07", "1e+308", "1e+307", "5e-324", "1e-308", "1e-307", "2.5e-320",
      "29.999999999999996", "0.30000000000000004", "1.0", "007", "-", "", "%31", "1,2", "a=b", "a;b", "x y",
      "-;a", "a;-", "a;-;b", "a;b", "true", "yes", "1,2;3", "1,,2", "1,2,", "-1e-04,2;3e+05"};
  const char alphabet[] = "0123456789.-+e,;%=abXY";
  for (int i = 0; i < 20000; ++i) {
    std::string t;
    for (std::size_t n = rng() % 9; n > 0; --n) t.push_back(alphabet[rng() % (sizeof alphabet - 1)]);
    tokens.push_back(t);
    double x = std::ldexp(static_cast<double>(rng() >> 11), static_cast<int>(rng() % 2100) - 1100);
    char buf[40];
    tokens.emplace_back(buf, std::to_chars(buf, buf + sizeof buf, (rng() & 1) ? -x : x).ptr);
  }
  const ValueType types[] = {ValueType::Number, ValueType::Integer,  ValueType::Flag,       ValueType::Text,
                             ValueType::Name,   ValueType::Group,    ValueType::NumberList, ValueType::Vec3,
                             ValueType::IntegerList, ValueType::StringList, ValueType::Path};
  std::size_t yes = 0;
  for (const std::string& t : tokens)
    for (ValueType type : types)
      for (int version : {1, 2})
        if (isCanonicalToken(t, type, version)) {
          ++yes;
          ASSERT_EQ(canon(t, type, version), t) << "type " << typeName(type) << " v" << version;
        }
  EXPECT_GT(yes, 20000u);
}

TEST(Canonical, NumbersToCharsWroteAreRecognisedWithoutParsing) {
  // Up to 15 significant digits in the normal range: what writers save.
  std::mt19937_64 rng(11);
  for (int i = 0; i < 20000; ++i) {
    std::string text = std::to_string(rng() % 1000000000000000ull) + "e" + std::to_string(static_cast<int>(rng() % 580) - 300);  // 1e-300 .. 1e+294
    double v = 0;
    std::from_chars(text.data(), text.data() + text.size(), v);
    char buf[40];
    std::string shortest(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
    // Big integers in fixed notation show all their digits (5973654460118720512),
    // more than 15: those are formatted the long way.
    if (shortest.find('e') == std::string::npos && std::fabs(v) >= 1e15) continue;
    ASSERT_TRUE(isCanonicalToken(shortest, ValueType::Number, 1)) << shortest;
  }
  EXPECT_TRUE(isCanonicalToken("-6e-04,1.5,0.25;1e+20", ValueType::NumberList, 1));
  EXPECT_FALSE(isCanonicalToken("1e-4", ValueType::Number, 1));    // to_chars writes 1e-04
  EXPECT_FALSE(isCanonicalToken("1e+03", ValueType::Number, 1));   // 1000 is shorter
  EXPECT_FALSE(isCanonicalToken("0.0001", ValueType::Number, 1));  // 1e-04 is shorter
  EXPECT_TRUE(isCanonicalToken("0.001", ValueType::Number, 1));    // a tie: fixed
  EXPECT_FALSE(isCanonicalToken("a=b", ValueType::Text, 1));
  EXPECT_FALSE(isCanonicalToken("a;b", ValueType::Text, 2));
  EXPECT_TRUE(isCanonicalToken("a;b", ValueType::Text, 1));
  EXPECT_TRUE(isCanonicalToken("-", ValueType::Text, 2));
  EXPECT_FALSE(isCanonicalToken("", ValueType::Text, 1));  // written as -
}
