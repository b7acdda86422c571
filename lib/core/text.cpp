#include <cstdio>
#include "core/text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>

namespace rscene {
namespace {

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

bool isSeparator(char c) { return c == ',' || c == ';'; }

}  // namespace

std::size_t utf8SequenceLength(std::string_view text, std::size_t i) {
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  unsigned char c = s[i];
  std::size_t len;
  std::uint32_t cp;
  if (c < 0x80) return 1;
  if (c >= 0xc2 && c <= 0xdf) { len = 2; cp = c & 0x1f; }
  else if (c >= 0xe0 && c <= 0xef) { len = 3; cp = c & 0x0f; }
  else if (c >= 0xf0 && c <= 0xf4) { len = 4; cp = c & 0x07; }
  else return 0;
  if (i + len > n) return 0;
  for (std::size_t k = 1; k < len; ++k) {
    if ((s[i + k] & 0xc0) != 0x80) return 0;
    cp = (cp << 6) | (s[i + k] & 0x3f);
  }
  if ((len == 3 && cp < 0x800) || (len == 4 && (cp < 0x10000 || cp > 0x10ffff)) || (cp >= 0xd800 && cp <= 0xdfff))
    return 0;
  return len;
}

namespace {

bool needsEscape(unsigned char c, int version) {
  return c < 0x20 || c == 0x7f || c == ' ' || c == '%' || c == '=' || (version >= 2 && c == ';');
}

// Calls f(item, separatorOrZero) for each item of a `,`/`;` list.
template <class F>
void forEachItem(std::string_view s, F&& f) {
  std::size_t start = 0;
  for (std::size_t i = 0; i <= s.size(); ++i) {
    if (i == s.size() || isSeparator(s[i])) {
      f(s.substr(start, i - start), i == s.size() ? '\0' : s[i]);
      start = i + 1;
    }
  }
}

void appendEscaped(std::string& out, unsigned char c) {
  static const char* hex = "0123456789ABCDEF";
  out.push_back('%');
  out.push_back(hex[c >> 4]);
  out.push_back(hex[c & 15]);
}

// Encodes without the empty/dash rules (used inside lists).
// Bytes that are not valid UTF-8 (from an escape like %97) stay escaped, so
// the output is always text our own loader reads back.
void encodeBytes(std::string_view value, int version, std::string& out) {
  std::size_t run = 0;  // start of the pending run of bytes that need no escape
  for (std::size_t i = 0; i < value.size(); ++i) {
    unsigned char c = static_cast<unsigned char>(value[i]);
    if (c >= 0x80) {
      if (std::size_t len = utf8SequenceLength(value, i)) {
        i += len - 1;
        continue;
      }
    } else if (!needsEscape(c, version)) {
      continue;
    }
    out.append(value.substr(run, i - run));
    appendEscaped(out, c);
    run = i + 1;
  }
  out.append(value.substr(run));
}

// Whether `s` is already what std::to_chars writes for its value, decided
// from the text alone.  A decimal with at most 15 significant digits reads
// back from a double digit for digit (DBL_DIG), so no shorter spelling of
// the same value exists; what remains is to_chars' choice between fixed and
// scientific notation (the shorter one, fixed on a tie; scientific as
// `1.5e-07`: a sign and at least two exponent digits).  This skips
// from_chars/to_chars for nearly every number a writer saved.
//
// scanShortest reads the number at `p` up to the first byte that cannot
// continue it (`end`, a list separator ...) and returns where it stopped,
// or nullptr when the text is not to_chars' spelling.  Lists are checked
// in one pass this way.
const char* scanShortest(const char* p, const char* const end) {
  const char* const start = p;
  const bool neg = p != end && *p == '-';
  p += neg;
  const char* const intStart = p;
  while (p != end && static_cast<unsigned>(*p - '0') < 10) ++p;
  const auto intLen = static_cast<std::size_t>(p - intStart);
  if (intLen == 0 || (intLen > 1 && *intStart == '0')) return nullptr;
  const char* fracStart = p;
  std::size_t fracLen = 0;
  if (p != end && *p == '.') {
    fracStart = ++p;
    while (p != end && static_cast<unsigned>(*p - '0') < 10) ++p;
    fracLen = static_cast<std::size_t>(p - fracStart);
    if (fracLen == 0 || p[-1] == '0') return nullptr;
  }
  // Significant digits and the decimal exponent of the first one.
  std::size_t sig;
  int exponent;
  if (p != end && *p == 'e') {
    // Scientific: d[.ddd]e(+|-)XX, chosen only where it is shorter.
    if (intLen != 1 || *intStart == '0' || end - p < 4 || (p[1] != '+' && p[1] != '-')) return nullptr;
    const char* const e = p + 2;
    int value = 0;
    for (p = e; p != end && static_cast<unsigned>(*p - '0') < 10 && value <= 400; ++p) value = value * 10 + (*p - '0');
    if (p - e != (value >= 100 ? 3 : 2)) return nullptr;  // no extra leading zeros
    exponent = e[-1] == '-' ? -value : value;
    sig = 1 + fracLen;
    // Subnormals keep fewer digits, and near the top the value may not be
    // finite: those take the long way.
    if (sig > 15 || exponent < -307 || exponent > 307) return nullptr;
    const auto digitsBefore = static_cast<std::size_t>(exponent) + 1;  // when exponent >= 0
    std::size_t fixedLen = exponent >= 0 ? digitsBefore + (sig > digitsBefore ? 1 + sig - digitsBefore : 0)
                                         : 2 + static_cast<std::size_t>(-exponent - 1) + sig;
    return static_cast<std::size_t>(p - start) < fixedLen + (neg ? 1 : 0) ? p : nullptr;
  }
  if (*intStart != '0') {
    std::size_t intDigits = intLen;
    if (fracLen == 0)
      while (intDigits > 1 && intStart[intDigits - 1] == '0') --intDigits;
    sig = intDigits + fracLen;
    exponent = static_cast<int>(intLen) - 1;
  } else {
    if (fracLen == 0) return p;  // "0" or "-0"
    std::size_t zeros = 0;
    while (fracStart[zeros] == '0') ++zeros;
    sig = fracLen - zeros;
    exponent = -static_cast<int>(zeros) - 1;
  }
  if (sig > 15) return nullptr;
  int absExp = exponent < 0 ? -exponent : exponent;
  std::size_t sciLen = (neg ? 1 : 0) + sig + (sig > 1 ? 1 : 0) + 2 + (absExp >= 100 ? 3 : 2);
  return static_cast<std::size_t>(p - start) <= sciLen ? p : nullptr;
}

bool isShortestNumber(std::string_view s) {
  const char* end = s.data() + s.size();
  return scanShortest(s.data(), end) == end;
}

bool isCanonicalInteger(std::string_view s) {
  std::size_t i = s.size() && s[0] == '-' ? 1 : 0;
  if (i == s.size() || s.size() > 18) return false;
  if (s[i] == '0') return s.size() == 1;  // "0"; "-0" and "007" are not
  for (; i < s.size(); ++i)
    if (s[i] < '0' || s[i] > '9') return false;
  return true;
}

void appendCanonicalNumberItem(std::string& out, std::string_view item, bool integer) {
  if (integer ? isCanonicalInteger(item) : isShortestNumber(item)) return out.append(item), void();
  if (integer) {
    if (auto v = parseInteger(item)) return appendInteger(out, *v);
  } else if (auto v = parseNumber(item)) {
    return appendNumber(out, *v);
  }
  encodeBytes(item, 1, out);  // not a number: keep as written, validate reports it
}

bool sameItem(std::string_view a, std::string_view b) {
  auto x = parseNumber(a), y = parseNumber(b);
  if (x && y) return std::memcmp(&*x, &*y, sizeof(double)) == 0;
  if (x || y) {
    // An integer beyond double precision parses on both sides identically.
    return false;
  }
  return a == b;
}

}  // namespace

std::vector<std::string_view> splitWords(std::string_view s) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && s[i] == ' ') ++i;
    std::size_t start = i;
    while (i < s.size() && s[i] != ' ') ++i;
    if (i > start) words.push_back(s.substr(start, i - start));
  }
  return words;
}

std::size_t findBadEscape(std::string_view token) {
  for (std::size_t i = token.find('%'); i != std::string_view::npos; i = token.find('%', i + 1)) {
    if (i + 2 >= token.size()) return i;
    if (hexValue(token[i + 1]) < 0 || hexValue(token[i + 2]) < 0) return i;
    i += 2;
  }
  return std::string_view::npos;
}

void percentDecode(std::string_view token, std::string& out) {
  if (token == "-") return;
  std::size_t i = 0;
  while (i < token.size()) {
    std::size_t pct = token.find('%', i);
    if (pct == std::string_view::npos) {
      out.append(token.substr(i));
      return;
    }
    out.append(token.substr(i, pct - i));
    if (pct + 2 >= token.size()) {  // truncated escape: keep as is
      out.append(token.substr(pct));
      return;
    }
    int hi = hexValue(token[pct + 1]), lo = hexValue(token[pct + 2]);
    if (hi < 0 || lo < 0) {
      out.push_back('%');
      i = pct + 1;
      continue;
    }
    out.push_back(static_cast<char>(hi * 16 + lo));
    i = pct + 3;
  }
}

std::string percentDecode(std::string_view token) {
  std::string out;
  percentDecode(token, out);
  return out;
}

void percentEncode(std::string_view value, int version, std::string& out) {
  if (value.empty()) {
    out.push_back('-');
  } else if (value == "-") {
    // A bare `-` would read back as empty; `%2D` keeps the dash in both
    // versions (version-1 writers lose it, we do not).
    out.append("%2D");
  } else {
    encodeBytes(value, version, out);
  }
}

namespace {

// Plain decimals (`-12.5`, `.5`, `3.`) with at most 15 digits: the mantissa
// is exact in a double and one correctly rounded division by an exact power
// of ten gives the double std::from_chars gives (Clinger's fast path).  Most
// numbers in scenes take this path; the rest go to from_chars.
bool fastDecimal(std::string_view s, double& out) {
  static constexpr double kPow10[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                      1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
  const char* p = s.data();
  const char* e = p + s.size();
  bool neg = p != e && *p == '-';
  p += neg;
  std::uint64_t m = 0;
  int digits = 0, frac = 0;
  for (; p != e && static_cast<unsigned>(*p - '0') < 10; ++p, ++digits) m = m * 10 + static_cast<unsigned>(*p - '0');
  if (p != e && *p == '.') {
    for (++p; p != e && static_cast<unsigned>(*p - '0') < 10; ++p, ++digits, ++frac)
      m = m * 10 + static_cast<unsigned>(*p - '0');
  }
  if (p != e || digits == 0 || digits > 15) return false;
  double v = static_cast<double>(m);
  if (frac) v /= kPow10[frac];
  out = neg ? -v : v;
  return true;
}

}  // namespace

std::optional<double> parseNumber(std::string_view s) {
  double v = 0;
  if (fastDecimal(s, v)) return v;
  const char* end = s.data() + s.size();
  auto [p, ec] = std::from_chars(s.data(), end, v);
  if (ec != std::errc() || p != end || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<std::int64_t> parseInteger(std::string_view s) {
  std::int64_t v = 0;
  const char* end = s.data() + s.size();
  auto [p, ec] = std::from_chars(s.data(), end, v);
  if (ec != std::errc() || p != end) return std::nullopt;
  return v;
}

std::optional<std::uint64_t> parseGroup(std::string_view s) {
  std::uint64_t v = 0;
  const char* end = s.data() + s.size();
  if (s.empty() || s[0] == '-') return std::nullopt;
  auto [p, ec] = std::from_chars(s.data(), end, v);
  if (ec != std::errc() || p != end) return std::nullopt;
  return v;
}

std::optional<bool> parseFlag(std::string_view s) {
  if (s == "true" || s == "1" || s == "yes" || s == "on") return true;
  if (s == "false" || s == "0" || s == "no" || s == "off") return false;
  return std::nullopt;
}

bool parseNumberList(std::string_view s, std::vector<double>& out) {
  if (s.empty()) return true;
  bool ok = true;
  forEachItem(s, [&](std::string_view item, char) {
    auto v = parseNumber(item);
    if (!v) ok = false;
    else out.push_back(*v);
  });
  return ok;
}

std::vector<std::string> parseStringList(std::string_view raw) {
  std::vector<std::string> out;
  if (raw.empty() || raw == "-") return out;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= raw.size(); ++i) {
    if (i == raw.size() || raw[i] == ';') {
      std::string_view item = raw.substr(start, i - start);
      std::string decoded;
      if (item != "-") percentDecode(item, decoded);
      out.push_back(std::move(decoded));
      start = i + 1;
    }
  }
  return out;
}

std::string roundedNumber(double v, int digits) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

std::string numberText(double v) {
  std::string s;
  appendNumber(s, v);
  return s;
}

void appendNumber(std::string& out, double v) {
  char buf[32];
  auto [p, ec] = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, p);
}

void appendInteger(std::string& out, std::int64_t v) {
  char buf[24];
  auto [p, ec] = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, p);
}

namespace {

// Bytes that stop a token from being plain text: `%` and what
// percentEncode escapes (one table with `;`, for version-2 text, and one
// without), and non-ASCII (looked at more closely).
struct PlainBytes {
  bool stop[2][256] = {};
  PlainBytes() {
    for (int c = 0; c < 256; ++c)
      for (int v = 0; v < 2; ++v)
        stop[v][c] = c == '%' || c >= 0x80 || needsEscape(static_cast<unsigned char>(c), v + 1);
  }
};
const PlainBytes kPlain;

// Plain text that percentEncode leaves as it is: no escape, no byte that
// needs one (`stringList`: `;` separates elements and is no such byte).
bool isPlainText(std::string_view raw, int version, bool stringList) {
  const bool* stop = kPlain.stop[version >= 2 && !stringList ? 1 : 0];
  const auto* s = reinterpret_cast<const unsigned char*>(raw.data());
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (!stop[s[i]]) continue;
    if (s[i] < 0x80) return false;
    std::size_t len = utf8SequenceLength(raw, i);
    if (!len) return false;
    i += len - 1;
  }
  return true;
}

bool isCanonicalNumberList(std::string_view raw, bool integer) {
  const char* p = raw.data();
  const char* end = p + raw.size();
  if (!integer) {
    for (;;) {
      p = scanShortest(p, end);
      if (!p || (p != end && *p != ',' && *p != ';')) return false;
      if (p++ == end) return true;
    }
  }
  for (;;) {
    const char* sep = p;
    while (sep != end && *sep != ',' && *sep != ';') ++sep;
    std::string_view item(p, static_cast<std::size_t>(sep - p));
    if (!(integer ? isCanonicalInteger(item) : isShortestNumber(item))) return false;
    if (sep == end) return true;
    p = sep + 1;
  }
}

}  // namespace

bool isCanonicalToken(std::string_view raw, ValueType type, int version) {
  switch (type) {
    case ValueType::Number:
      return isShortestNumber(raw);
    case ValueType::Integer:
      return isCanonicalInteger(raw);
    case ValueType::Flag:
      return raw == "true" || raw == "false";
    case ValueType::StringList:
      // An element `-` would decode to empty and be written as nothing.
      if (raw == "-" || raw.rfind("-;", 0) == 0 || raw.find(";-;") != std::string_view::npos ||
          (raw.size() >= 2 && raw.substr(raw.size() - 2) == ";-"))
        return false;
      return isPlainText(raw, version, true);
    default:
      if (isNumericList(type)) return raw.empty() || isCanonicalNumberList(raw, type == ValueType::IntegerList);
      // `-` is the empty text and stays `-`; an empty token becomes `-`.
      return raw == "-" || (!raw.empty() && raw != "-" && isPlainText(raw, version, false));
  }
}

double decimalMultiple(std::uint64_t n, double step) {
  if (!std::isfinite(step) || step == 0 || n == 0) return static_cast<double>(n) * step;
  // step = digits x 10^exp with at most 17 digits; n * digits < 2^64 * 10^17
  // fits in 128 bits, so the product is exact until the one rounding of
  // from_chars.
  char buf[40];
  const char* end = std::to_chars(buf, buf + sizeof buf, step, std::chars_format::scientific).ptr;
  const char* p = buf;
  bool negative = *p == '-';
  p += negative;
  unsigned __int128 digits = 0;
  int fraction = 0;
  for (bool afterPoint = false; *p != 'e'; ++p) {
    if (*p == '.') {
      afterPoint = true;
      continue;
    }
    digits = digits * 10 + static_cast<unsigned>(*p - '0');
    fraction += afterPoint;
  }
  int exponent = 0;
  std::from_chars(p + 1 + (p[1] == '+'), end, exponent);
  unsigned __int128 product = digits * n;
  std::string number;
  do {
    number.push_back(static_cast<char>('0' + static_cast<unsigned>(product % 10)));
    product /= 10;
  } while (product);
  if (negative) number.push_back('-');
  std::reverse(number.begin(), number.end());
  number += 'e' + std::to_string(exponent - fraction);
  double v = 0;
  if (std::from_chars(number.data(), number.data() + number.size(), v).ec != std::errc())
    return static_cast<double>(n) * step;  // beyond double's range
  return v;
}

void appendCanonical(std::string& out, std::string_view raw, ValueType type, int version) {
  std::string decodedStorage;
  std::string_view value = raw;
  if (raw.find('%') != std::string_view::npos || raw == "-") {
    percentDecode(raw, decodedStorage);
    value = decodedStorage;
  }
  switch (type) {
    case ValueType::Number:
      if (isShortestNumber(value)) return out.append(value), void();
      if (auto v = parseNumber(value)) return appendNumber(out, *v);
      break;
    case ValueType::Integer:
      if (isCanonicalInteger(value)) return out.append(value), void();
      if (auto v = parseInteger(value)) return appendInteger(out, *v);
      break;
    case ValueType::Flag:
      if (auto v = parseFlag(value)) {
        out.append(*v ? "true" : "false");
        return;
      }
      break;
    case ValueType::StringList: {
      // Elements are encoded one by one; `;` between them stays literal.
      if (value.empty()) return;
      std::size_t start = 0;
      for (std::size_t i = 0; i <= raw.size(); ++i) {
        if (i == raw.size() || raw[i] == ';') {
          std::string_view item = raw.substr(start, i - start);
          if (start) out.push_back(';');
          std::string decoded = percentDecode(item);
          encodeBytes(decoded, version, out);
          start = i + 1;
        }
      }
      return;
    }
    default:
      if (isNumericList(type)) {
        if (value.empty()) return;
        bool integer = type == ValueType::IntegerList;
        forEachItem(value, [&](std::string_view item, char sep) {
          appendCanonicalNumberItem(out, item, integer);
          if (sep) out.push_back(sep);
        });
        return;
      }
      break;
  }
  percentEncode(value, version, out);
}

bool sameValue(std::string_view a, std::string_view b, ValueType type) {
  std::string da = percentDecode(a), db = percentDecode(b);
  switch (type) {
    case ValueType::Number:
      return sameItem(da, db);
    case ValueType::Integer: {
      auto x = parseInteger(da), y = parseInteger(db);
      if (x && y) return *x == *y;
      return da == db;
    }
    case ValueType::Flag: {
      auto x = parseFlag(da), y = parseFlag(db);
      if (x && y) return *x == *y;
      return da == db;
    }
    case ValueType::StringList:
      return parseStringList(a) == parseStringList(b);
    default:
      break;
  }
  if (isNumericList(type)) {
    std::vector<std::string_view> ia, ib;
    std::vector<char> sa, sb;
    forEachItem(da, [&](std::string_view s, char c) { ia.push_back(s); sa.push_back(c); });
    forEachItem(db, [&](std::string_view s, char c) { ib.push_back(s); sb.push_back(c); });
    if (ia.size() != ib.size() || sa != sb) return false;
    for (std::size_t i = 0; i < ia.size(); ++i) {
      if (type == ValueType::IntegerList) {
        auto x = parseInteger(ia[i]), y = parseInteger(ib[i]);
        if (x && y ? *x != *y : ia[i] != ib[i]) return false;
      } else if (!sameItem(ia[i], ib[i])) {
        return false;
      }
    }
    return true;
  }
  return da == db;
}

}  // namespace rscene
