// JSON -> Document.  nlohmann's SAX parser feeds a small tree builder that
// keeps one record at a time: each record is checked against the schema,
// turned into raw tokens in the Document and dropped, so a large scene
// never exists as one JSON tree.  Errors name the JSON pointer and the
// line and column of the nearest member key in the JSON text.
#include <charconv>
#include <cmath>
#include <iterator>
#include <nlohmann/json.hpp>
#include <unordered_map>

#include "core/json.hpp"
#include "core/json_value.hpp"
#include "core/text.hpp"

namespace rscene {
namespace {

using Json = nlohmann::ordered_json;
using json::Shape;

// An iterator over the input that tells the reader how far the parser got,
// so errors can name a line and column.
struct CountingIterator {
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;
  const char* p = nullptr;
  const char** position = nullptr;
  const char& operator*() const { return *p; }
  CountingIterator& operator++() {
    *position = ++p;
    return *this;
  }
  CountingIterator operator++(int) {
    CountingIterator old = *this;
    ++*this;
    return old;
  }
  bool operator==(const CountingIterator& o) const { return p == o.p; }
  bool operator!=(const CountingIterator& o) const { return p != o.p; }
};

std::string escapePointer(std::string_view name) {
  std::string out;
  for (char c : name) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out.push_back(c);
  }
  return out;
}

std::string describe(const Json& v) {
  switch (v.type()) {
    case Json::value_t::null: return "null";
    case Json::value_t::boolean: return "a boolean";
    case Json::value_t::string: return "a string";
    case Json::value_t::array: return "an array";
    case Json::value_t::object: return "an object";
    default: return "a number";
  }
}

// Why `t` cannot be a token of scene text, or empty.
std::string tokenProblem(std::string_view t, bool allowEmpty) {
  if (t.empty() && !allowEmpty) return "empty token";
  for (char ch : t) {
    auto c = static_cast<unsigned char>(ch);
    if (c == ' ' || c == '\t') return "white space in token (encode it as %20 or %09)";
    if (c < 0x20 || c == 0x7f) return "control character in token";
  }
  if (findBadEscape(t) != std::string_view::npos) return "invalid percent escape in token";
  return {};
}

struct Failure {
  std::string pointer;
  std::string message;
};

class RecordBuilder {
 public:
  explicit RecordBuilder(Document& doc) : doc_(doc) {}

  // Adds record `index` from `j`; on failure returns false and fills `f`.
  bool add(const Json& j, std::size_t index, Failure& f) {
    base_ = "/records/" + std::to_string(index);
    fail_ = &f;
    std::size_t fieldsBefore = doc_.fields.size(), commentsBefore = doc_.comments.size();
    bool ok = build(j, index);
    if (!ok) {
      doc_.fields.resize(fieldsBefore);
      doc_.comments.resize(commentsBefore);
    }
    return ok;
  }

 private:
  bool fail(const std::string& where, std::string message) {
    fail_->pointer = base_ + where;
    fail_->message = std::move(message);
    return false;
  }

  bool build(const Json& j, std::size_t index) {
    if (!j.is_object()) return fail("", "expected a record object, got " + describe(j));
    static const char* kMembers[] = {"tag", "line", "comments", "positionalCount", "fields", "unknownKeys",
                                     "unknownTag", "tokens"};
    for (auto it = j.begin(); it != j.end(); ++it) {
      bool known = false;
      for (const char* m : kMembers) known = known || it.key() == m;
      if (!known) return fail("/" + escapePointer(it.key()), "unexpected member '" + it.key() + "'");
    }
    auto tagIt = j.find("tag");
    if (tagIt == j.end()) return fail("", "missing member 'tag'");
    if (!tagIt->is_string()) return fail("/tag", "expected a string, got " + describe(*tagIt));
    const std::string& tag = tagIt->get_ref<const std::string&>();
    if (std::string why = tokenProblem(tag, false); !why.empty()) return fail("/tag", why);
    if (tag[0] == '#') return fail("/tag", "a tag cannot start with '#'");
    if (index == 0 && tag != "raisim_engine_scene")
      return fail("/tag", "the first record must be the raisim_engine_scene header");

    Record r;
    if (auto it = j.find("line"); it != j.end()) {
      if (!it->is_number_unsigned() || it->get<std::uint64_t>() > 0xffffffffu)
        return fail("/line", "expected a line number, got " + describe(*it));
      r.line = static_cast<std::uint32_t>(it->get<std::uint64_t>());
    }
    r.firstComment = static_cast<std::uint32_t>(doc_.comments.size());
    if (auto it = j.find("comments"); it != j.end()) {
      if (!addComments(*it, "/comments")) return false;
      r.commentCount = static_cast<std::uint32_t>(doc_.comments.size()) - r.firstComment;
    }
    r.tag = doc_.append(tag);
    r.kind = Schema::get().kind(tag);
    r.firstField = static_cast<std::uint32_t>(doc_.fields.size());

    auto unknownTag = j.find("unknownTag");
    if (unknownTag != j.end() && !unknownTag->is_boolean())
      return fail("/unknownTag", "expected a boolean, got " + describe(*unknownTag));
    bool markedUnknown = unknownTag != j.end() && unknownTag->get<bool>();
    if (markedUnknown && r.kind) return fail("/unknownTag", "'" + tag + "' is a known record kind");

    auto tokens = j.find("tokens");
    auto fields = j.find("fields");
    if (tokens != j.end() && fields != j.end()) return fail("", "a record has either 'fields' or 'tokens', not both");
    if (tokens != j.end()) {
      if (!fromTokens(*tokens, r)) return false;
    } else if (!r.kind) {
      return fail("/tag", "unknown record kind '" + tag + "'; unknown records keep their text in 'tokens'");
    } else if (!fromFields(j, fields, r)) {
      return false;
    }
    r.fieldCount = static_cast<std::uint32_t>(doc_.fields.size()) - r.firstField;
    if (r.kind) {
      const Layout* layout = r.kind->layoutFor(r.positionalCount);
      if (!layout) return fail("", tag + " has " + std::to_string(r.positionalCount) + " positional fields");
      if (auto it = j.find("positionalCount"); it != j.end()) {
        if (!it->is_number_unsigned() || it->get<std::uint64_t>() != r.positionalCount)
          return fail("/positionalCount", "does not match the record's positional fields");
      }
    }
    if (index == 0) {
      std::string_view v = r.positionalCount ? doc_.text(doc_.fields[r.firstField].value) : std::string_view();
      if (v != "1" && v != "2") return fail("/fields/version", "unsupported rscene version");
      doc_.version = v[0] - '0';
    }
    doc_.records.push_back(r);
    return true;
  }

 public:
  bool addComments(const Json& list, const std::string& where) {
    if (!list.is_array()) return fail(where, "expected an array of comment lines, got " + describe(list));
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Json& c = list[i];
      std::string at = where + "/" + std::to_string(i);
      if (!c.is_string()) return fail(at, "expected a string, got " + describe(c));
      const std::string& s = c.get_ref<const std::string&>();
      if (s.empty() || s[0] != '#') return fail(at, "a comment line starts with '#'");
      if (s.back() == ' ' || s.back() == '\t') return fail(at, "a comment line cannot end in white space");
      for (char ch : s) {
        auto b = static_cast<unsigned char>(ch);
        if ((b < 0x20 && b != '\t') || b == 0x7f) return fail(at, "control character in comment");
      }
      doc_.comments.push_back(doc_.append(s));
    }
    return true;
  }
  void setBase(std::string base) { base_ = std::move(base); }
  void setFailure(Failure& f) { fail_ = &f; }

 private:
  bool fromTokens(const Json& list, Record& r) {
    if (!list.is_array()) return fail("/tokens", "expected an array of strings, got " + describe(list));
    bool sawKey = false;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Json& t = list[i];
      std::string at = "/tokens/" + std::to_string(i);
      if (!t.is_string()) return fail(at, "expected a string, got " + describe(t));
      const std::string& s = t.get_ref<const std::string&>();
      if (std::string why = tokenProblem(s, false); !why.empty()) return fail(at, why);
      Field f;
      std::size_t eq = s.find('=');
      if (eq == 0) return fail(at, "key=value token without a key");
      if (eq != std::string::npos) {
        Span whole = doc_.append(s);
        f.key = Span{whole.offset, static_cast<std::uint32_t>(eq)};
        f.value = Span{static_cast<std::uint32_t>(whole.offset + eq + 1), static_cast<std::uint32_t>(s.size() - eq - 1)};
        sawKey = true;
      } else {
        if (sawKey) {
          if (r.kind) return fail(at, "positional field after key=value fields");
          r.interleaved = true;
        }
        f.value = doc_.append(s);
        ++r.positionalCount;
      }
      doc_.fields.push_back(f);
    }
    return true;
  }

  bool fromFields(const Json& j, Json::const_iterator fieldsIt, Record& r) {
    if (fieldsIt == j.end()) return fail("", "missing member 'fields'");
    const Json& fields = *fieldsIt;
    if (!fields.is_object()) return fail("/fields", "expected an object, got " + describe(fields));
    const KindDef& kind = *r.kind;
    const Layout* layout = &kind.layouts[0];
    if (auto it = j.find("positionalCount"); it != j.end()) {
      layout = it->is_number_unsigned() ? kind.layoutFor(it->get<std::uint64_t>()) : nullptr;
      if (!layout) return fail("/positionalCount", "no " + kind.tag + " layout has " + it->dump() + " positional fields");
    }
    std::vector<std::string_view> unknown;
    if (auto it = j.find("unknownKeys"); it != j.end()) {
      if (!it->is_array()) return fail("/unknownKeys", "expected an array of key names, got " + describe(*it));
      for (std::size_t i = 0; i < it->size(); ++i) {
        if (!(*it)[i].is_string()) return fail("/unknownKeys/" + std::to_string(i), "expected a string");
        unknown.push_back((*it)[i].get_ref<const std::string&>());
      }
    }
    for (const FieldDef& f : layout->fields) {
      auto v = fields.find(f.name);
      if (v == fields.end()) return fail("/fields", "missing positional field '" + f.name + "'");
      if (!positional(*v, f, "/fields/" + escapePointer(f.name), r)) return false;
    }
    for (auto it = fields.begin(); it != fields.end(); ++it) {
      const std::string& name = it.key();
      bool isPositional = false;
      for (const FieldDef& f : layout->fields) isPositional = isPositional || f.name == name;
      if (isPositional) continue;
      std::string at = "/fields/" + escapePointer(name);
      if (std::string why = tokenProblem(name, false); !why.empty() || name.find('=') != std::string::npos)
        return fail(at, "'" + name + "' cannot be a key name");
      const FieldDef* def = kind.key(name);
      bool listed = std::find(unknown.begin(), unknown.end(), name) != unknown.end();
      std::string raw;
      if (def && !listed) {
        if (!value(it.value(), def->type, at, raw)) return false;
      } else if (def || listed) {
        if (!unknownValue(it.value(), at, raw)) return false;
      } else {
        return fail(at, "unknown field '" + name + "' for " + kind.tag + " (list it in 'unknownKeys' to keep it)");
      }
      Field f;
      f.key = doc_.append(name);
      f.value = doc_.append(raw);
      doc_.fields.push_back(f);
    }
    return true;
  }

  bool rawObject(const Json& v, const std::string& at, bool allowEmpty, std::string& raw) {
    auto it = v.find("raw");
    if (v.size() != 1 || it == v.end() || !it->is_string())
      return fail(at, "expected {\"raw\": TOKEN}, got another object");
    const std::string& s = it->get_ref<const std::string&>();
    if (std::string why = tokenProblem(s, allowEmpty); !why.empty()) return fail(at + "/raw", why);
    raw = s;
    return true;
  }

  bool unknownValue(const Json& v, const std::string& at, std::string& raw) {
    if (v.is_null()) return true;  // `key=`
    if (v.is_object()) return rawObject(v, at, true, raw);
    if (!v.is_string()) return fail(at, "expected a string (an unknown key's text), got " + describe(v));
    percentEncode(v.get_ref<const std::string&>(), doc_.version, raw);
    return true;
  }

  bool positional(const Json& v, const FieldDef& f, const std::string& at, Record& r) {
    std::vector<std::string> tokens;
    if (f.width == 1) {
      tokens.emplace_back();
      if (v.is_null()) return fail(at, "expected " + std::string(typeName(f.type)) + ", got null");
      if (!value(v, f.type, at, tokens.back())) return false;
      if (tokens.back().empty()) tokens.back() = "-";
    } else {
      if (!v.is_array() || v.size() != static_cast<std::size_t>(f.width))
        return fail(at, "expected an array of " + std::to_string(f.width) + " numbers, got " + describe(v));
      for (std::size_t i = 0; i < v.size(); ++i) {
        tokens.emplace_back();
        std::string itemAt = at + "/" + std::to_string(i);
        if (v[i].is_object()) {
          if (!rawObject(v[i], itemAt, false, tokens.back())) return false;
        } else if (!value(v[i], ValueType::Number, itemAt, tokens.back())) {
          return false;
        }
      }
    }
    for (const std::string& t : tokens) {
      Field field;
      field.value = doc_.append(t);
      doc_.fields.push_back(field);
      ++r.positionalCount;
    }
    return true;
  }

  // A number as text; false (with an error) when it is not one the type takes.
  bool number(const Json& v, bool integer, const std::string& at, std::string& out) {
    if (v.is_number_integer() && !v.is_number_unsigned()) {
      appendInteger(out, v.get<std::int64_t>());
    } else if (v.is_number_unsigned()) {
      char buf[24];
      auto [p, ec] = std::to_chars(buf, buf + sizeof buf, v.get<std::uint64_t>());
      out.append(buf, p);
    } else {
      double d = v.get<double>();
      if (integer) {
        if (d != std::floor(d) || std::fabs(d) > 9.2e18) return fail(at, "expected an integer");
        appendInteger(out, static_cast<std::int64_t>(d));
      } else {
        appendNumber(out, d);
      }
    }
    return true;
  }

  bool listItem(const Json& v, bool integer, const std::string& at, std::string& out) {
    if (v.is_number()) return number(v, integer, at, out);
    if (!v.is_string()) return fail(at, "expected a number, got " + describe(v));
    const std::string& s = v.get_ref<const std::string&>();
    if (s.find_first_of(",;") != std::string::npos) return fail(at, "a list item cannot contain ',' or ';'");
    std::string encoded;
    percentEncode(s, doc_.version, encoded);
    out.append(s.empty() ? std::string_view() : std::string_view(encoded));
    return true;
  }

  bool flat(const Json& v, bool integer, const std::string& at, std::string& out) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (i) out.push_back(',');
      if (!listItem(v[i], integer, at + "/" + std::to_string(i), out)) return false;
    }
    return true;
  }

  bool value(const Json& v, ValueType type, const std::string& at, std::string& raw) {
    const std::string_view want = typeName(type);
    if (v.is_object()) return rawObject(v, at, true, raw);
    if (v.is_null()) return true;
    if (v.is_string()) {
      percentEncode(v.get_ref<const std::string&>(), doc_.version, raw);
      return true;
    }
    Shape shape = json::shapeOf(type);
    if (shape != Shape::Scalar) {
      if (!v.is_array()) return fail(at, "expected " + std::string(want) + " as an array, got " + describe(v));
      if (shape == Shape::Flat) {
        if (!flat(v, type == ValueType::IntegerList, at, raw)) return false;
      } else if (shape == Shape::Nested) {
        for (std::size_t i = 0; i < v.size(); ++i) {
          std::string itemAt = at + "/" + std::to_string(i);
          if (!v[i].is_array()) return fail(itemAt, "expected an array, got " + describe(v[i]));
          if (i) raw.push_back(';');
          if (!flat(v[i], false, itemAt, raw)) return false;
        }
      } else {
        for (std::size_t i = 0; i < v.size(); ++i) {
          if (!v[i].is_string()) return fail(at + "/" + std::to_string(i), "expected a string, got " + describe(v[i]));
          if (i) raw.push_back(';');
          const std::string& s = v[i].get_ref<const std::string&>();
          for (char ch : s) {
            auto c = static_cast<unsigned char>(ch);
            if (c < 0x20 || c == 0x7f || c == ' ' || c == '%' || c == '=' || (doc_.version >= 2 && c == ';')) {
              static const char* hex = "0123456789ABCDEF";
              raw.push_back('%');
              raw.push_back(hex[c >> 4]);
              raw.push_back(hex[c & 15]);
            } else {
              raw.push_back(ch);
            }
          }
        }
      }
      // A lone `-` would read back as the empty list.
      if (raw == "-") raw = "%2D";
      return true;
    }
    switch (type) {
      case ValueType::Number:
      case ValueType::Integer:
        if (!v.is_number()) return fail(at, "expected " + std::string(want) + ", got " + describe(v));
        return number(v, type == ValueType::Integer, at, raw);
      case ValueType::Group:
        if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<std::int64_t>() >= 0))
          return fail(at, "expected an unsigned 64-bit integer as a decimal string, got " + describe(v));
        return number(v, true, at, raw);
      case ValueType::Flag:
        if (!v.is_boolean()) return fail(at, "expected a boolean, got " + describe(v));
        raw = v.get<bool>() ? "true" : "false";
        return true;
      default:
        return fail(at, "expected a string, got " + describe(v));
    }
  }

  Document& doc_;
  std::string base_;
  Failure* fail_ = nullptr;
};

// SAX handler: builds the top level and one record at a time.
class Reader {
 public:
  Reader(std::string_view text, JsonLoadResult& out) : text_(text), out_(out), builder_(out.document) {}

  void run() {
    const char* begin = text_.data();
    position_ = begin;
    CountingIterator first{begin, &position_}, last{begin + text_.size(), &position_};
    bool parsed = Json::sax_parse(first, last, this);
    if (!parsed || stopped_) return;
    finish();
  }

  // --- SAX interface ---
  bool null() { return scalar(Json(nullptr)); }
  bool boolean(bool v) { return scalar(Json(v)); }
  bool number_integer(Json::number_integer_t v) { return scalar(Json(v)); }
  bool number_unsigned(Json::number_unsigned_t v) { return scalar(Json(v)); }
  bool number_float(Json::number_float_t v, const std::string&) { return scalar(Json(v)); }
  bool string(std::string& v) {
    stringStart(v);
    return scalar(Json(std::move(v)));
  }
  bool binary(Json::binary_t&) { return false; }
  bool start_object(std::size_t) { return open(Json::object()); }
  bool start_array(std::size_t) { return open(Json::array()); }
  bool key(std::string& k) {
    Frame& f = stack_.back();
    std::size_t at = stringStart(k);
    std::string where = pointer() + "/" + escapePointer(k);
    if (inRecord()) offsets_[where] = at;
    if (f.value->contains(k)) return schemaError(where, "duplicate member '" + k + "'");
    f.key = k;
    return true;
  }
  bool end_object() { return close(); }
  bool end_array() { return close(); }
  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& ex) {
    std::string what = ex.what();
    std::size_t colon = what.find(": ", what.find("column"));
    std::string message = colon == std::string::npos ? what : what.substr(colon + 2);
    report(position ? position - 1 : 0, "invalid JSON: " + message, kJsonSyntax);
    return false;
  }

 private:
  struct Frame {
    Json* value;
    std::string key;   // current member of an object
    std::size_t index = 0;  // next element of an array
  };

  static constexpr std::size_t kMaxDepth = 32;

  std::size_t here() const { return static_cast<std::size_t>(position_ - text_.data()); }
  // Offset (1-based) of the opening quote of the string just read: found
  // by searching its quoted text between the previous string and the
  // parser's position (strings with escapes fall back to the position).
  std::size_t stringStart(std::string_view str) {
    std::size_t end = std::min(text_.size(), here() + 2);
    std::string quoted = "\"" + std::string(str) + "\"";
    std::size_t at = scan_ < end ? text_.substr(scan_, end - scan_).find(quoted) : std::string_view::npos;
    if (at == std::string_view::npos) return here();
    at += scan_;
    scan_ = at + quoted.size();
    return at + 1;
  }
  // Directly inside root.records: the frame depth of a record is 3.
  bool atRecords() const { return stack_.size() == 2 && stack_[0].key == "records" && stack_[1].value->is_array(); }
  bool inRecord() const { return stack_.size() >= 3 && stack_[0].key == "records"; }

  std::string pointer() const {
    std::string p;
    for (std::size_t i = 0; i < stack_.size(); ++i) {
      const Frame& f = stack_[i];
      if (f.value->is_array()) {
        if (i + 1 < stack_.size()) p += "/" + std::to_string(f.index);
      } else if (i + 1 < stack_.size()) {
        p += "/" + escapePointer(f.key);
      }
    }
    return p;
  }

  Json* place(Json&& v) {
    if (stack_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    Frame& f = stack_.back();
    if (f.value->is_array()) {
      if (atRecords()) {
        record_ = std::move(v);
        return &record_;
      }
      f.value->push_back(std::move(v));
      return &f.value->back();
    }
    Json& slot = (*f.value)[f.key];
    slot = std::move(v);
    return &slot;
  }

  bool open(Json&& v) {
    if (stack_.empty() && !v.is_object()) return schemaError("", "expected a JSON object at the top level");
    // A scene nests containers at most 6 deep (root, records, record,
    // fields, a list, its entries).  Refusing deeper nesting at once keeps
    // the per-key JSON pointer, and so the whole read, linear in the input.
    if (stack_.size() >= kMaxDepth)
      return schemaError(pointer(), "nesting deeper than " + std::to_string(kMaxDepth) +
                                        " levels (a scene nests at most 6)");
    if (atRecords()) {
      offsets_.clear();
      offsets_[pointer() + "/" + std::to_string(stack_.back().index)] = here();
    }
    Json* p = place(std::move(v));
    stack_.push_back(Frame{p, {}, 0});
    return true;
  }

  bool scalar(Json&& v) {
    if (stack_.empty()) return schemaError("", "expected a JSON object at the top level");
    if (atRecords()) {
      offsets_.clear();
      offsets_[pointer() + "/" + std::to_string(stack_.back().index)] = here();
    }
    bool recordDone = atRecords();
    place(std::move(v));
    if (recordDone) return closeRecord();
    if (stack_.back().value->is_array()) ++stack_.back().index;
    return true;
  }

  bool close() {
    stack_.pop_back();
    if (stack_.empty()) return true;
    if (atRecords()) return closeRecord();
    if (stack_.back().value->is_array()) ++stack_.back().index;
    return true;
  }

  bool closeRecord() {
    std::size_t index = stack_.back().index++;
    Failure f;
    if (index == 0 && !checkFormat()) return false;
    if (!builder_.add(record_, index, f)) return schemaError(f.pointer, f.message);
    record_ = Json();
    return true;
  }

  // Members before "records" that are already known are checked early, so
  // a file that is not a scene fails before its records are read.
  bool checkFormat() {
    if (auto it = root_.find("format"); it != root_.end() && *it != "rscene")
      return schemaError("/format", "expected \"rscene\"");
    return true;
  }

  void finish() {
    static const char* kMembers[] = {"$schema", "format", "version", "records", "trailingComments"};
    for (auto it = root_.begin(); it != root_.end(); ++it) {
      bool known = false;
      for (const char* m : kMembers) known = known || it.key() == m;
      if (!known) {
        schemaError("/" + escapePointer(it.key()), "unexpected member '" + it.key() + "'");
        return;
      }
    }
    auto format = root_.find("format");
    if (format == root_.end()) return (void)schemaError("", "missing member 'format' (\"rscene\")");
    if (*format != "rscene") return (void)schemaError("/format", "expected \"rscene\"");
    Document& doc = out_.document;
    if (doc.records.empty()) return (void)schemaError("/records", "expected an array starting with the raisim_engine_scene header");
    auto version = root_.find("version");
    if (version == root_.end()) return (void)schemaError("", "missing member 'version'");
    if (!version->is_number_unsigned() || version->get<std::uint64_t>() != static_cast<std::uint64_t>(doc.version))
      return (void)schemaError("/version", "expected " + std::to_string(doc.version) + ", the header's version");
    if (auto it = root_.find("trailingComments"); it != root_.end()) {
      Failure f;
      builder_.setFailure(f);
      builder_.setBase("");
      std::uint32_t first = static_cast<std::uint32_t>(doc.comments.size());
      if (!builder_.addComments(*it, "/trailingComments")) return (void)schemaError(f.pointer, f.message);
      doc.trailingFirstComment = first;
      doc.trailingCommentCount = static_cast<std::uint32_t>(doc.comments.size()) - first;
    }
  }

  bool schemaError(const std::string& pointer, const std::string& message) {
    std::size_t at = std::string::npos;
    for (std::string p = pointer;; p.resize(p.rfind('/'))) {
      if (auto it = offsets_.find(p); it != offsets_.end()) {
        at = it->second;
        break;
      }
      if (p.empty() || p.rfind('/') == std::string::npos) break;
    }
    if (at == std::string::npos) at = here();
    report(at ? at - 1 : 0, (pointer.empty() ? "/" : pointer) + ": " + message, kJsonSchema);
    stopped_ = true;
    return false;
  }

  void report(std::size_t offset, std::string message, const char* code) {
    offset = std::min(offset, text_.size());
    Diagnostic d;
    d.code = code;
    d.line = 1;
    std::size_t lineStart = 0;
    for (std::size_t i = 0; i < offset; ++i)
      if (text_[i] == '\n') {
        ++d.line;
        lineStart = i + 1;
      }
    d.column = static_cast<std::uint32_t>(offset - lineStart + 1);
    d.message = std::move(message);
    out_.diagnostics.push_back(std::move(d));
  }

  std::string_view text_;
  JsonLoadResult& out_;
  RecordBuilder builder_;
  const char* position_ = nullptr;
  std::size_t scan_ = 0;  // where the next string's text is searched from
  Json root_;
  Json record_;
  std::vector<Frame> stack_;
  std::unordered_map<std::string, std::size_t> offsets_;
  bool stopped_ = false;
};

}  // namespace

JsonLoadResult fromJson(std::string_view json) {
  JsonLoadResult result;
  result.document.buffer().reserve(json.size() / 2);
  Reader(json, result).run();
  if (!result.ok()) result.document = Document();
  return result;
}

}  // namespace rscene
