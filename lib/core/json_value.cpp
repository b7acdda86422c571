#include "core/json_value.hpp"

#include <cmath>

#include "core/text.hpp"

namespace rscene::json {
namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }

// RFC 8259 number grammar: -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?
bool isJsonNumber(std::string_view s) {
  std::size_t i = 0, n = s.size();
  if (i < n && s[i] == '-') ++i;
  if (i >= n) return false;
  if (s[i] == '0') {
    ++i;
  } else if (isDigit(s[i])) {
    while (i < n && isDigit(s[i])) ++i;
  } else {
    return false;
  }
  if (i < n && s[i] == '.') {
    std::size_t start = ++i;
    while (i < n && isDigit(s[i])) ++i;
    if (i == start) return false;
  }
  if (i < n && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < n && (s[i] == '+' || s[i] == '-')) ++i;
    std::size_t start = i;
    while (i < n && isDigit(s[i])) ++i;
    if (i == start) return false;
  }
  return i == n;
}

}  // namespace

Shape shapeOf(ValueType t) {
  switch (t) {
    case ValueType::Vec2:
    case ValueType::Vec3:
    case ValueType::Quat:
    case ValueType::Color:
    case ValueType::NumberList:
    case ValueType::IntegerList:
      return Shape::Flat;
    case ValueType::Vec3List:
    case ValueType::ColorList:
    case ValueType::TransformList:
      return Shape::Nested;
    case ValueType::StringList:
      return Shape::Strings;
    default:
      return Shape::Scalar;
  }
}

// Fast path for the common case: plain decimal text in JSON's grammar with
// no exponent and a sane number of digits is a finite double (and, with at
// most 15 digits, an exact integer), so it is copied without parsing.
// Returns 1 when copied, 0 to take the slow path.
int copyPlain(std::string& out, std::string_view s, bool integer) {
  std::size_t i = 0, n = s.size(), digits = 0;
  bool negative = false, nonZero = false;
  if (i < n && s[i] == '-') {
    negative = true;
    ++i;
  }
  if (i >= n || !isDigit(s[i]) || (s[i] == '0' && i + 1 < n && isDigit(s[i + 1]))) return 0;
  for (; i < n && isDigit(s[i]); ++i, ++digits) nonZero |= s[i] != '0';
  if (i < n) {
    if (integer || s[i] != '.' || ++i >= n) return 0;
    std::size_t start = i;
    for (; i < n && isDigit(s[i]); ++i, ++digits) nonZero |= s[i] != '0';
    if (i != n || i == start) return 0;
  }
  if (negative && !nonZero) return 0;  // -0 stays a string; integers take the slow path
  if (digits > (integer ? 15u : 300u)) return 0;
  out.append(s);
  return 1;
}

bool appendNumberItem(std::string& out, std::string_view item, bool integer) {
  if (copyPlain(out, item, integer)) return true;
  if (integer) {
    auto v = parseInteger(item);
    if (!v || *v > kMaxExactInteger || *v < -kMaxExactInteger) return false;
    appendInteger(out, *v);
    return true;
  }
  auto v = parseNumber(item);
  if (!v || (*v == 0 && std::signbit(*v))) return false;
  // Any JSON spelling of the same double reads back to it (nlohmann and
  // jq both round correctly), so text already in JSON form is copied.
  if (isJsonNumber(item))
    out.append(item);
  else
    appendNumber(out, *v);
  return true;
}

bool validUtf8(std::string_view s) {
  const auto* p = reinterpret_cast<const unsigned char*>(s.data());
  std::size_t n = s.size(), i = 0;
  while (i < n) {
    unsigned char c = p[i];
    if (c < 0x80) {
      ++i;
      continue;
    }
    std::size_t len;
    std::uint32_t cp;
    if (c >= 0xc2 && c <= 0xdf) { len = 2; cp = c & 0x1f; }
    else if (c >= 0xe0 && c <= 0xef) { len = 3; cp = c & 0x0f; }
    else if (c >= 0xf0 && c <= 0xf4) { len = 4; cp = c & 0x07; }
    else return false;
    if (i + len > n) return false;
    for (std::size_t k = 1; k < len; ++k) {
      if ((p[i + k] & 0xc0) != 0x80) return false;
      cp = (cp << 6) | (p[i + k] & 0x3f);
    }
    if ((len == 3 && cp < 0x800) || (len == 4 && (cp < 0x10000 || cp > 0x10ffff)) || (cp >= 0xd800 && cp <= 0xdfff))
      return false;
    i += len;
  }
  return true;
}

void appendString(std::string& out, std::string_view s) {
  static const char* hex = "0123456789abcdef";
  out.push_back('"');
  std::size_t start = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    unsigned char c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c != '"' && c != '\\') continue;
    out.append(s.substr(start, i - start));
    start = i + 1;
    switch (c) {
      case '"': out.append("\\\""); break;
      case '\\': out.append("\\\\"); break;
      case '\n': out.append("\\n"); break;
      case '\t': out.append("\\t"); break;
      case '\r': out.append("\\r"); break;
      default:
        out.append("\\u00");
        out.push_back(hex[c >> 4]);
        out.push_back(hex[c & 15]);
    }
  }
  out.append(s.substr(start));
  out.push_back('"');
}

}  // namespace rscene::json
