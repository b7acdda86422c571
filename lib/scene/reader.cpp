#include "scene/reader.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "core/codes.hpp"
#include "scene/scene.hpp"
#include "core/text.hpp"

namespace rscene {

RecordReader::RecordReader(const Document& doc, std::size_t recordIndex, Diagnostics& diagnostics)
    : doc_(doc), rec_(&doc.records[recordIndex]), kind_(rec_->kind), diags_(diagnostics) {
  if (kind_) layout_ = kind_->layoutFor(rec_->positionalCount);
}

RecordReader::RecordReader(const Document& doc, const KindDef& kind, Diagnostics& diagnostics)
    : doc_(doc), kind_(&kind), diags_(diagnostics) {}

RecordReader::Located RecordReader::locate(std::string_view name) const {
  Located loc;
  if (!kind_) return loc;
  if (!rec_) {  // an absent record: the field's definition, for its default
    loc.def = kind_->key(name);
    for (const Layout& layout : kind_->layouts)
      for (const FieldDef& f : layout.fields)
        if (!loc.def && f.name == name) loc.def = &f;
    return loc;
  }
  if (layout_) {
    for (std::size_t t = 0; t < layout_->tokens.size(); ++t) {
      const FieldDef& f = layout_->fields[layout_->tokens[t].first];
      if (f.name == name && layout_->tokens[t].second == 0) {
        loc.def = &f;
        loc.firstToken = static_cast<int>(t);
        return loc;
      }
    }
  }
  loc.def = kind_->key(name);
  loc.key = doc_.find(*rec_, name);
  // A field of another layout of the kind (the 25-field object's
  // collidable in a 17-field one, the 19-field one's fixed ...): absent,
  // with that layout's default.
  for (const Layout& other : kind_->layouts)
    for (const FieldDef& f : other.fields)
      if (!loc.def && &other != layout_ && f.name == name) loc.def = &f;
  return loc;
}


bool RecordReader::has(std::string_view name) const {
  Located l = locate(name);
  return l.firstToken >= 0 || l.key;
}

int RecordReader::positionalToken(std::string_view name) const { return locate(name).firstToken; }

std::optional<std::string> RecordReader::text(std::string_view name) const {
  Located l = locate(name);
  if (l.firstToken >= 0) {
    std::string out;
    for (int c = 0; c < l.def->width; ++c) {
      if (c) out += ',';
      out += percentDecode(doc_.positionalText(*rec_, static_cast<std::uint32_t>(l.firstToken + c)));
    }
    return out;
  }
  if (l.key) return percentDecode(doc_.text(l.key->value));
  if (l.def && l.def->defaultValue) return *l.def->defaultValue;
  return std::nullopt;
}

std::string RecordReader::str(std::string_view name, std::string fallback) const {
  std::optional<std::string> t = text(name);
  return t ? *t : fallback;
}

std::uint32_t RecordReader::columnOf(std::string_view name) const {
  Located l = locate(name);
  if (l.firstToken >= 0) {
    const Field* f = doc_.positional(*rec_, static_cast<std::uint32_t>(l.firstToken));
    return f ? doc_.column(*rec_, f->value) : 0;
  }
  if (l.key) return doc_.column(*rec_, l.key->value);  // where the validator points too
  return 0;
}

void RecordReader::error(std::string_view name, const char* code, const std::string& message, std::string hint,
                         Severity severity) const {
  if (!rec_) return;  // defaults parse (tests/core/schema_test.cpp): nothing to report
  Diagnostic d;
  d.severity = severity;
  d.code = code;
  d.line = rec_->line;
  d.column = name.empty() ? 1 : columnOf(name);
  if (!d.column && rec_->line) d.column = 1;
  d.message = message;
  d.hint = std::move(hint);
  d.tag = kind_ ? kind_->tag : std::string(doc_.tag(*rec_));
  d.field = std::string(name);
  diags_.push_back(std::move(d));
}

void reportAt(const Document* doc, int recordIndex, std::string_view field, const char* code,
              const std::string& message, Diagnostics& diagnostics, Severity severity, std::string hint) {
  if (doc && recordIndex >= 0 && static_cast<std::size_t>(recordIndex) < doc->records.size()) {
    RecordReader(*doc, static_cast<std::size_t>(recordIndex), diagnostics)
        .error(field, code, message, std::move(hint), severity);
    return;
  }
  Diagnostic d;
  d.severity = severity;
  d.code = code;
  d.message = message;
  d.hint = std::move(hint);
  diagnostics.push_back(std::move(d));
}

void RecordReader::bad(std::string_view name, std::string_view value, std::string_view expected, const char* code) const {
  std::string shown(value.substr(0, 60));
  error(name, code,
        "invalid " + std::string(expected) + " '" + shown + "' for " + std::string(name) +
            (name == kind_->tag ? std::string() : " of " + kind_->tag));
}

// The validator's code for text that is not a number (check_types.cpp):
// RS2002 when it is a number but not a finite one, RS2009 for a list with an
// empty entry, else RS2001.
const char* RecordReader::numberCode(std::string_view s) {
  double v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (!s.empty() && p == s.data() + s.size() && (ec == std::errc::result_out_of_range || !std::isfinite(v)))
    return rs::RS2002;
  return rs::RS2001;
}

double RecordReader::number(std::string_view name, double fallback) const {
  std::optional<std::string> t = text(name);
  if (!t || t->empty()) return fallback;
  if (std::optional<double> v = parseNumber(*t)) return *v;
  bad(name, *t, "number", numberCode(*t));
  return fallback;
}

std::int64_t RecordReader::integer(std::string_view name, std::int64_t fallback) const {
  std::optional<std::string> t = text(name);
  if (!t || t->empty()) return fallback;
  std::optional<std::int64_t> v = parseInteger(*t);
  // An `int` field holds 32 bits, as lib/core's validator checks: a value
  // past that range is the same error here, never a wrap (-2147483649
  // solver iterations must not become 2147483647).
  Located l = locate(name);
  bool int32 = l.def && l.def->type == ValueType::Integer;
  if (v && (!int32 || (*v >= INT32_MIN && *v <= INT32_MAX))) return *v;
  bad(name, *t, int32 ? "32-bit integer" : "integer", rs::RS2003);
  return fallback;
}

bool RecordReader::flag(std::string_view name, bool fallback) const {
  std::optional<std::string> t = text(name);
  if (!t || t->empty()) return fallback;
  if (std::optional<bool> v = parseFlag(*t)) return *v;
  bad(name, *t, "flag", rs::RS2005);
  return fallback;
}

std::uint64_t RecordReader::group(std::string_view name, std::uint64_t fallback) const {
  std::optional<std::string> t = text(name);
  if (!t || t->empty()) return fallback;
  if (std::optional<std::uint64_t> v = parseGroup(*t)) return *v;
  bad(name, *t, "collision group", rs::RS2004);
  return fallback;
}

std::string RecordReader::name(std::string_view field, std::string fallback) const {
  std::optional<std::string> t = text(field);
  if (!t || t->empty()) return fallback;
  Located l = locate(field);
  if (!l.def || !l.def->enumDef) return *t;
  if (std::optional<std::string_view> c = l.def->enumDef->canonical(*t)) return std::string(*c);
  if (l.def->enumDef->open) {
    std::string lower = *t;
    for (char& ch : lower) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return lower;
  }
  bad(field, *t, l.def->enumDef->name + " name", rs::RS2006);
  return fallback;
}

bool RecordReader::components(std::string_view name, std::vector<double>& out) const {
  out.clear();
  Located l = locate(name);
  if (l.firstToken >= 0 && l.def->width > 1) {  // point at the bad component itself
    for (int c = 0; c < l.def->width; ++c) {
      const Field* f = doc_.positional(*rec_, static_cast<std::uint32_t>(l.firstToken + c));
      std::string v = f ? percentDecode(doc_.text(f->value)) : std::string();
      std::optional<double> x = parseNumber(v);
      if (!x) {
        bad(name, v, "number", numberCode(v));
        if (f) diags_.back().column = doc_.column(*rec_, f->value);
        out.clear();
        return false;
      }
      out.push_back(*x);
    }
    return true;
  }
  std::optional<std::string> t = text(name);
  if (!t || t->empty()) return true;
  if (parseNumberList(*t, out)) return true;
  out.clear();
  // The first item that is no number decides the code, as in the
  // validator; else an empty item is RS2009 in a list, RS2008 in a vector.
  const char* code = nullptr;
  std::string_view rest = *t;
  for (std::size_t at; !code; rest.remove_prefix(at + 1)) {
    at = std::min(rest.find(','), rest.find(';'));
    std::string_view item = rest.substr(0, at);
    if (!item.empty() && !parseNumber(item)) code = numberCode(item);
    if (at == std::string_view::npos) break;
  }
  if (!code) code = l.def && componentCount(l.def->type) > 0 ? rs::RS2008 : rs::RS2009;
  bad(name, *t, "numbers", code);
  return false;
}

Eigen::Vector3d RecordReader::vec3(std::string_view name, const Eigen::Vector3d& fallback) const {
  std::vector<double> v;
  if (!components(name, v) || v.empty()) return fallback;
  if (v.size() != 3) {
    bad(name, *text(name), "vector of 3 numbers", rs::RS2008);
    return fallback;
  }
  return {v[0], v[1], v[2]};
}

Eigen::Vector4d RecordReader::color(std::string_view name, const Eigen::Vector4d& fallback) const {
  std::vector<double> v;
  if (!components(name, v) || v.empty()) return fallback;
  if (v.size() != 3 && v.size() != 4) {
    bad(name, *text(name), "color of 3 or 4 numbers", rs::RS2008);
    return fallback;
  }
  return {v[0], v[1], v[2], v.size() == 4 ? v[3] : 1.0};
}

Eigen::Vector4d RecordReader::quat(std::string_view name) const {
  std::vector<double> v;
  Eigen::Vector4d identity(1, 0, 0, 0);
  if (!components(name, v) || v.empty()) return identity;
  if (v.size() != 4) {
    bad(name, *text(name), "quaternion of 4 numbers", rs::RS2008);
    return identity;
  }
  Eigen::Vector4d q(v[0], v[1], v[2], v[3]);
  if (q.norm() < 1e-12) {
    error(name, rs::RS4009, "zero quaternion for " + std::string(name) + " of " + kind_->tag);
    return identity;
  }
  return q.normalized();
}

bool RecordReader::numbers(std::string_view name, std::vector<double>& out) const { return components(name, out); }

// The forms without a fallback.  The schema default when the field is
// absent or empty; its text is checked by tests/core/schema_test.cpp, so
// parsing it cannot fail.  A required field written empty (`-`) that has
// no default is reported like any value that does not parse, with the
// validator's code, and reads as zero.
std::optional<std::string> RecordReader::defaultText(std::string_view name, std::string_view expected,
                                                     const char* code) const {
  Located l = locate(name);
  if (l.def && l.def->defaultValue) return *l.def->defaultValue;
  if (l.firstToken < 0 && !l.key)
    throw std::logic_error("the scene model reads " + (kind_ ? kind_->tag : std::string("?")) + "." +
                           std::string(name) + ", which has no default in the schema table");
  std::optional<std::string> t = text(name);
  if (!t || t->empty()) {
    bad(name, "", expected, code);
    return std::string();
  }
  return std::nullopt;  // written: the value decides
}

double RecordReader::number(std::string_view name) const {
  std::optional<std::string> d = defaultText(name, "number", rs::RS2001);
  return number(name, d ? parseNumber(*d).value_or(0) : 0);
}
std::int64_t RecordReader::integer(std::string_view name) const {
  std::optional<std::string> d = defaultText(name, "integer", rs::RS2003);
  return integer(name, d ? parseInteger(*d).value_or(0) : 0);
}
bool RecordReader::flag(std::string_view name) const {
  std::optional<std::string> d = defaultText(name, "flag", rs::RS2005);
  return flag(name, d ? parseFlag(*d).value_or(false) : false);
}
std::uint64_t RecordReader::group(std::string_view name) const {
  std::optional<std::string> d = defaultText(name, "collision group", rs::RS2004);
  return group(name, d ? parseGroup(*d).value_or(0) : 0);
}
std::string RecordReader::name(std::string_view field) const {
  std::optional<std::string> d = defaultText(field, "name", rs::RS2006);
  if (!d) return name(field, std::string());
  Located l = locate(field);
  std::optional<std::string_view> c = l.def && l.def->enumDef ? l.def->enumDef->canonical(*d) : std::nullopt;
  return name(field, c ? std::string(*c) : *d);
}
Eigen::Vector3d RecordReader::vec3(std::string_view name) const {
  std::optional<std::string> d = defaultText(name, "vector of 3 numbers", rs::RS2008);
  std::vector<double> v;
  if (d) parseNumberList(*d, v);
  return vec3(name, v.size() == 3 ? Eigen::Vector3d(v[0], v[1], v[2]) : Eigen::Vector3d::Zero());
}
Eigen::Vector4d RecordReader::color(std::string_view name) const {
  std::optional<std::string> d = defaultText(name, "color of 3 or 4 numbers", rs::RS2008);
  std::vector<double> v;
  if (d) parseNumberList(*d, v);
  Eigen::Vector4d c(0, 0, 0, 1);
  for (std::size_t i = 0; i < v.size() && i < 4; ++i) c[static_cast<Eigen::Index>(i)] = v[i];
  return color(name, c);
}

}  // namespace rscene
