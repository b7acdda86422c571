// rscene -> JSON, streamed in chunks: no JSON tree is built, so a 128 MB
// scene costs its output buffer and nothing per value.
#include <unordered_set>

#include "core/json.hpp"
#include "core/json_value.hpp"
#include "core/text.hpp"

namespace rscene {
namespace {

using json::Shape;

constexpr std::size_t kChunk = 1 << 16;

bool needsDecode(std::string_view raw) { return raw == "-" || raw.find('%') != std::string_view::npos; }

class Writer {
 public:
  Writer(const Document& doc, Sink& sink, JsonStyle style) : doc_(doc), sink_(sink), pretty_(style.pretty) {
    out_.reserve(kChunk * 2);
  }

  void run() {
    out_.push_back('{');
    open_ = 1;
    member("format");
    out_.append("\"rscene\"");
    member("version");
    appendInteger(out_, doc_.version);
    member("records");
    out_.push_back('[');
    ++depth_;
    for (std::size_t i = 0; i < doc_.records.size(); ++i) {
      if (i) out_.push_back(',');
      newline();
      record(doc_.records[i]);
      flushIfFull();
    }
    --depth_;
    if (!doc_.records.empty()) newline();
    out_.push_back(']');
    member("trailingComments");
    comments(doc_.trailingFirstComment, doc_.trailingCommentCount);
    depth_ = 0;
    newline();
    out_.push_back('}');
    out_.push_back('\n');
    sink_.write(out_);
  }

 private:
  void newline() {
    if (!pretty_) return;
    out_.push_back('\n');
    out_.append(static_cast<std::size_t>(depth_) * 2, ' ');
  }
  void flushIfFull() {
    if (out_.size() < kChunk) return;
    sink_.write(out_);
    out_.clear();
  }
  // `"name": ` inside the object being written (first member opens it).
  void member(std::string_view name) {
    if (open_ == 1) {
      ++depth_;
      open_ = 2;
    } else {
      out_.push_back(',');
    }
    newline();
    json::appendString(out_, name);
    out_.append(pretty_ ? ": " : ":");
  }
  void beginObject() {
    out_.push_back('{');
    open_ = 1;
  }
  void endObject() {
    if (open_ == 2) {
      --depth_;
      newline();
    }
    open_ = 2;  // the enclosing object already has members
    out_.push_back('}');
  }
  void separator() { out_.append(pretty_ ? ", " : ","); }

  void comments(std::uint32_t first, std::uint32_t count) {
    out_.push_back('[');
    for (std::uint32_t c = 0; c < count; ++c) {
      if (c) separator();
      json::appendString(out_, doc_.commentText(first + c));
    }
    out_.push_back(']');
  }

  void rawObject(std::string_view raw) {
    out_.append(pretty_ ? "{\"raw\": " : "{\"raw\":");
    json::appendString(out_, raw);
    out_.push_back('}');
  }

  void item(std::string_view s, bool integer) {
    if (!json::appendNumberItem(out_, s, integer)) json::appendString(out_, s);
  }

  // Items of a `,`-separated list (the caller checked the separators).
  void flat(std::string_view s, bool integer) {
    out_.push_back('[');
    if (!s.empty()) {
      std::size_t start = 0;
      for (std::size_t i = 0; i <= s.size(); ++i) {
        if (i == s.size() || s[i] == ',') {
          if (start) separator();
          item(s.substr(start, i - start), integer);
          start = i + 1;
        }
      }
    }
    out_.push_back(']');
  }

  void nested(std::string_view s) {
    out_.push_back('[');
    if (!s.empty()) {
      std::size_t start = 0;
      for (std::size_t i = 0; i <= s.size(); ++i) {
        if (i == s.size() || s[i] == ';') {
          if (start) separator();
          flat(s.substr(start, i - start), false);
          start = i + 1;
        }
      }
    }
    out_.push_back(']');
  }

  void value(std::string_view raw, ValueType type) {
    std::string_view v = raw;
    if (needsDecode(raw)) {
      scratch_.clear();
      percentDecode(raw, scratch_);
      v = scratch_;
      if (!json::validUtf8(v)) return rawObject(raw);
    }
    switch (json::shapeOf(type)) {
      case Shape::Flat:
        if (v.find(';') != std::string_view::npos) return json::appendString(out_, v);
        return flat(v, type == ValueType::IntegerList);
      case Shape::Nested:
        return nested(v);
      case Shape::Strings: {
        out_.push_back('[');
        bool first = true;
        for (const std::string& s : parseStringList(raw)) {
          if (!first) separator();
          first = false;
          json::appendString(out_, s);
        }
        out_.push_back(']');
        return;
      }
      case Shape::Scalar:
        break;
    }
    switch (type) {
      case ValueType::Number:
      case ValueType::Integer:
        return item(v, type == ValueType::Integer);
      case ValueType::Flag:
        if (auto f = parseFlag(v)) {
          out_.append(*f ? "true" : "false");
          return;
        }
        break;
      default:
        break;
    }
    json::appendString(out_, v);
  }

  // Tokens as written, for records a JSON object cannot hold.
  void tokens(const Record& r) {
    member("tokens");
    out_.push_back('[');
    for (std::uint32_t j = 0; j < r.fieldCount; ++j) {
      if (j) separator();
      const Field& f = doc_.field(r, j);
      if (!f.isKey()) {
        json::appendString(out_, doc_.text(f.value));
      } else {
        std::string_view all = doc_.buffer();
        json::appendString(out_, all.substr(f.key.offset, f.value.offset + f.value.length - f.key.offset));
      }
    }
    out_.push_back(']');
  }

  // Whether the record's names are unique (no repeated key, no key named
  // like one of its positional fields).
  bool namesUnique(const Record& r, const Layout& layout) {
    names_.clear();
    for (const FieldDef& f : layout.fields) names_.insert(f.name);
    for (std::uint32_t j = r.positionalCount; j < r.fieldCount; ++j)
      if (!names_.insert(doc_.text(doc_.field(r, j).key)).second) return false;
    return true;
  }

  void fields(const Record& r, const Layout& layout) {
    member("fields");
    beginObject();
    std::uint32_t token = 0;
    for (const FieldDef& f : layout.fields) {
      member(f.name);
      if (f.width == 1) {
        value(doc_.text(doc_.field(r, token++).value), f.type);
        continue;
      }
      out_.push_back('[');
      for (int c = 0; c < f.width; ++c) {
        if (c) separator();
        std::string_view raw = doc_.text(doc_.field(r, token++).value);
        if (!needsDecode(raw)) {
          item(raw, false);
          continue;
        }
        std::string decoded = percentDecode(raw);
        if (!json::validUtf8(decoded)) rawObject(raw);
        else item(decoded, false);
      }
      out_.push_back(']');
    }
    bool unknown = false;
    for (std::uint32_t j = r.positionalCount; j < r.fieldCount; ++j) {
      const Field& f = doc_.field(r, j);
      std::string_view key = doc_.text(f.key);
      member(key);
      const FieldDef* def = r.kind->key(key);
      if (def) {
        value(doc_.text(f.value), def->type);
      } else {
        unknown = true;
        std::string_view raw = doc_.text(f.value);
        if (raw.empty()) out_.append("null");  // `key=`, apart from `key=-`
        else value(raw, ValueType::Text);
      }
    }
    endObject();
    if (!unknown) return;
    member("unknownKeys");
    out_.push_back('[');
    bool first = true;
    for (std::uint32_t j = r.positionalCount; j < r.fieldCount; ++j) {
      std::string_view key = doc_.text(doc_.field(r, j).key);
      if (r.kind->key(key)) continue;
      if (!first) separator();
      first = false;
      json::appendString(out_, key);
    }
    out_.push_back(']');
  }

  void record(const Record& r) {
    beginObject();
    member("tag");
    json::appendString(out_, doc_.tag(r));
    if (r.line) {
      member("line");
      appendInteger(out_, r.line);
    }
    if (r.commentCount) {
      member("comments");
      comments(r.firstComment, r.commentCount);
    }
    const Layout* layout = r.kind ? r.kind->layoutFor(r.positionalCount) : nullptr;
    if (!layout) {
      member("unknownTag");
      out_.append("true");
      tokens(r);
    } else {
      if (layout != &r.kind->layouts[0]) {
        member("positionalCount");
        appendInteger(out_, r.positionalCount);
      }
      if (r.interleaved || !namesUnique(r, *layout))
        tokens(r);
      else
        fields(r, *layout);
    }
    endObject();
  }

  const Document& doc_;
  Sink& sink_;
  bool pretty_;
  std::string out_;
  std::string scratch_;
  std::unordered_set<std::string_view> names_;
  int depth_ = 0;
  int open_ = 0;  // 1: object just opened, 2: it has members
};

}  // namespace

void writeJson(const Document& doc, Sink& sink, JsonStyle style) { Writer(doc, sink, style).run(); }

std::string toJson(const Document& doc, JsonStyle style) {
  std::string out;
  StringSink sink(out);
  writeJson(doc, sink, style);
  return out;
}

}  // namespace rscene
