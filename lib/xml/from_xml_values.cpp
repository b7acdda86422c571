// The typed attribute readers, names and paths of rscene-from-xml's
// mapping (from_xml_context.hpp).
#include <algorithm>
#include <charconv>
#include <filesystem>

#include "core/text.hpp"
#include "xml/from_xml_context.hpp"

namespace rscene::xml::detail {

Line& Line::text(std::string_view value) {
  s_ += ' ';
  percentEncode(value, 1, s_);
  return *this;
}
Line& Line::raw(std::string_view token) {
  s_ += ' ';
  s_ += token;
  return *this;
}
// One spelling of zero both ways: RaiSim's files write "-0.000000" (its
// maps/office1.xml's quaternions), which is written "0" here as rscene-to-xml
// writes it, so from-xml | to-xml | from-xml is byte-identical.
static double oneZero(double v) { return v == 0 ? 0.0 : v; }

Line& Line::num(double v) {
  s_ += ' ';
  appendNumber(s_, oneZero(v));
  return *this;
}
Line& Line::u64(std::uint64_t v) { return raw(std::to_string(v)); }
Line& Line::key(std::string_view name, std::string_view rawValue) {
  s_ += ' ';
  s_ += name;
  s_ += '=';
  s_ += rawValue;
  return *this;
}
Line& Line::keyText(std::string_view name, std::string_view value) {
  std::string v;
  percentEncode(value, 1, v);
  return key(name, v);
}
Line& Line::keyNum(std::string_view name, double v) { return key(name, numberText(oneZero(v))); }
Line& Line::keyNums(std::string_view name, const double* v, std::size_t n) {
  s_ += ' ';
  s_ += name;
  s_ += '=';
  for (std::size_t i = 0; i < n; ++i) {
    if (i) s_ += ',';
    appendNumber(s_, oneZero(v[i]));
  }
  return *this;
}
Line& Line::keyList(std::string_view name, const std::vector<std::string>& items) {
  std::string v;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i) v += ';';
    percentEncode(items[i], 1, v);
  }
  return key(name, v.empty() ? "-" : v);
}

std::string labelOf(const Element& e) {
  const Attribute* name = e.attribute("name");
  return name && !name->value.empty() ? e.name + " '" + name->value + "'" : e.name;
}

void Context::error(const char* c, const Element& e, std::string message) {
  result.diagnostics.push_back(elementDiagnostic(Severity::Error, c, e, std::move(message)));
}
void Context::error(const char* c, const Element& e, const Attribute& a, std::string message) {
  result.diagnostics.push_back(attributeDiagnostic(Severity::Error, c, e, a, std::move(message)));
}
void Context::warning(const char* c, const Element& e, std::string message) {
  result.diagnostics.push_back(elementDiagnostic(Severity::Warning, c, e, std::move(message)));
}
void Context::lost(std::string what) {
  if (notConverted.insert(what).second) result.notConverted.push_back(std::move(what));
}

namespace {
std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\n' || s.front() == '\r'))
    s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\n' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}
bool separator(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ','; }
}  // namespace

std::optional<double> Context::number(const Element& e, const Attribute* a) {
  if (!a) return std::nullopt;
  std::optional<double> v = parseNumber(trim(a->value));
  if (!v) error(code::kBadValue, e, *a, "'" + a->value + "' is not a finite number");
  return v;
}

bool Context::numbers(const Element& e, const Attribute& a, std::vector<double>& out) {
  out.clear();
  std::string_view s = a.value;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && separator(s[i])) ++i;
    std::size_t j = i;
    while (j < s.size() && !separator(s[j])) ++j;
    if (j == i) break;
    std::optional<double> v = parseNumber(s.substr(i, j - i));
    if (!v) {
      error(code::kBadValue, e, a, "'" + std::string(s.substr(i, j - i)) + "' is not a finite number");
      return false;
    }
    out.push_back(*v);
    i = j;
  }
  return true;
}

std::optional<std::int64_t> Context::integer(const Element& e, const Attribute* a, std::int64_t min,
                                             std::int64_t max) {
  if (!a) return std::nullopt;
  std::optional<std::int64_t> v = parseInteger(trim(a->value));
  if (!v || *v < min || *v > max) {
    error(code::kBadValue, e, *a,
          "'" + a->value + "' is not a whole number from " + std::to_string(min) + " to " + std::to_string(max));
    return std::nullopt;
  }
  return v;
}

std::optional<std::uint64_t> Context::group(const Element& e, const Attribute* a) {
  if (!a) return std::nullopt;
  constexpr std::uint64_t kAll = ~std::uint64_t{0};
  std::string_view s = trim(a->value);
  auto bad = [&](const std::string& why) -> std::optional<std::uint64_t> {
    error(code::kBadValue, e, *a, "'" + a->value + "' " + why);
    return std::nullopt;
  };
  if (s == "-1") return kAll;
  // RaiSim keeps groups in signed integers too (laikago.xml writes
  // collisionGroup="-2147483648"): a negative whole number is the uint64
  // of its int64 two's complement, so -1 stays all bits.
  if (!s.empty() && s.front() == '-') {
    std::optional<std::int64_t> n = parseInteger(s);
    if (!n) return bad("is not a collision group: a whole number from -2^63 to 2^64-1, or collision[i|j|...]");
    return static_cast<std::uint64_t>(*n);
  }
  if (s.substr(0, 10) == "collision[") {
    if (s.back() != ']') return bad("has no closing ']'");
    std::string_view inner = s.substr(10, s.size() - 11);
    std::uint64_t bits = 0;
    std::size_t i = 0;
    while (true) {
      std::size_t bar = inner.find('|', i);
      std::string_view item = trim(inner.substr(i, bar == std::string_view::npos ? std::string_view::npos : bar - i));
      std::optional<std::int64_t> n = parseInteger(item);
      if (!n || *n < -1 || *n > 63) return bad("names a group outside 0..63 (or -1 for all)");
      bits |= *n == -1 ? kAll : std::uint64_t{1} << *n;
      if (bar == std::string_view::npos) break;
      i = bar + 1;
    }
    return bits;
  }
  std::uint64_t v = 0;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size())
    return bad("is not a collision group: a whole number from -2^63 to 2^64-1, or collision[i|j|...]");
  return v;
}

const Attribute* Context::require(const Element& e, std::string_view name, std::string_view alias) {
  const Attribute* a = e.attribute(name, alias);
  if (!a) error(code::kMissing, e, "'" + std::string(name) + "' is required");
  return a;
}

const Attribute* Context::requirePath(const Element& e, std::string_view name, std::string_view alias) {
  const Attribute* a = require(e, name, alias);
  if (a && a->value.find_first_not_of(" \t\r\n") == std::string::npos) {
    error(code::kBadValue, e, *a, "is empty: a file is required");
    return nullptr;
  }
  return a;
}

const Element* Context::requireChild(const Element& e, std::string_view name, std::string_view alias) {
  const Element* c = e.child(name, alias);
  if (!c) error(code::kMissing, e, "<" + std::string(name) + "> is required");
  return c;
}

namespace {
bool listed(std::initializer_list<std::string_view> names, std::string_view n) {
  return std::find(names.begin(), names.end(), n) != names.end();
}
}  // namespace

void Context::checkAttributes(const Element& e, const std::string& label,
                              std::initializer_list<std::string_view> known,
                              std::initializer_list<std::string_view> lostNames) {
  for (const Attribute& a : e.attributes) {
    if (listed(known, a.name)) continue;
    if (!listed(lostNames, a.name))
      result.diagnostics.push_back(
          attributeDiagnostic(Severity::Warning, code::kNotConverted, e, a, "unknown attribute, not converted"));
    lost(label + ": " + a.name);
  }
}

bool Context::visible(const Element& e, const std::string& label) {
  const Attribute* a = e.attribute("appearance");
  if (!a) return true;
  if (a->value == "hidden") return false;
  lost(label + ": appearance");
  return true;
}

void Context::checkChildren(const Element& e, const std::string& label,
                            std::initializer_list<std::string_view> known,
                            std::initializer_list<std::string_view> lostNames) {
  for (const Element& c : e.children) {
    if (listed(known, c.name)) continue;
    if (!listed(lostNames, c.name))
      result.diagnostics.push_back(
          elementDiagnostic(Severity::Warning, code::kNotConverted, c, "unknown element, not converted"));
    lost(label + ": <" + c.name + ">");
  }
}

std::string Context::takePath(const Element& e) {
  const Attribute* name = e.attribute("name");
  std::string want = !name || name->value.empty() ? "/World/" + e.name
                     : name->value.front() == '/' ? name->value
                                                  : "/World/" + name->value;
  if (paths.insert(want).second) return want;
  auto [it, first] = renames.try_emplace(want, renamed.size(), 2);
  if (first) renamed.push_back({want, {}});
  std::string path;
  do path = want + "_" + std::to_string(it->second.second++);
  while (!paths.insert(path).second);
  renamed[it->second.first].second.push_back(path);
  return path;
}

std::string Context::assetPath(const std::string& written) const {
  namespace fs = std::filesystem;
  if (written.empty()) return written;
  std::error_code ec;
  fs::path abs = fs::absolute(fs::path(written), ec).lexically_normal();
  if (ec) return written;
  if (options.absolutePaths) return abs.generic_string();
  fs::path base = fs::absolute(fs::path(options.outputDir.empty() ? "." : options.outputDir), ec).lexically_normal();
  if (ec) return abs.generic_string();
  if (!base.has_filename() && base.has_relative_path()) base = base.parent_path();  // "/a/b/" -> "/a/b"
  fs::path rel = abs.lexically_relative(base);
  return rel.empty() ? abs.generic_string() : rel.generic_string();
}

}  // namespace rscene::xml::detail
