// The lossless parse of a scene: every record with its tag, source line,
// tokens as written and the comment lines above it.  Tokens are spans into
// one text buffer the document owns, which keeps a 128 MB scene at well
// under one extra copy of its size.  Values stay text until a typed
// accessor (text.hpp) parses them.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/schema.hpp"

namespace rscene {

struct Span {
  std::uint32_t offset = 0;
  std::uint32_t length = 0;
};

inline constexpr std::uint32_t kNoKey = 0xffffffffu;

// One token: a positional value, or key=value (split at the first `=`).
struct Field {
  Span key{kNoKey, 0};
  Span value;
  bool isKey() const { return key.offset != kNoKey; }
};

struct Record {
  Span tag;
  std::uint32_t line = 0;        // 1-based source line (0 = made in memory)
  std::uint32_t lineOffset = 0;  // offset of the line start, for columns
  std::uint32_t firstField = 0;  // into Document::fields
  std::uint32_t fieldCount = 0;
  std::uint32_t positionalCount = 0;
  std::uint32_t firstComment = 0;  // into Document::comments
  std::uint32_t commentCount = 0;
  // Positionals come first unless the record's kind is unknown and the
  // file interleaved them (known kinds refuse that at load time).
  bool interleaved = false;
  const KindDef* kind = nullptr;  // nullptr: unknown tag, kept verbatim
};

class Document {
 public:
  int version = 1;
  std::vector<Record> records;   // records[0] is the header
  std::vector<Field> fields;
  std::vector<Span> comments;    // whole comment lines, `#` included
  std::uint32_t trailingFirstComment = 0;  // comments after the last record
  std::uint32_t trailingCommentCount = 0;

  std::string_view text(Span s) const { return std::string_view(text_).substr(s.offset, s.length); }
  std::string_view tag(const Record& r) const { return text(r.tag); }
  const Field& field(const Record& r, std::uint32_t i) const { return fields[r.firstField + i]; }
  // Positional token `i` (0-based), or nullptr.
  const Field* positional(const Record& r, std::uint32_t i) const;
  std::string_view positionalText(const Record& r, std::uint32_t i) const;
  // Last key=value named `key` (a repeated key: the last one wins, as in
  // Engine 2), or nullptr.
  const Field* find(const Record& r, std::string_view key) const;
  // Raw value of `key`, or `fallback` when absent.
  std::string_view value(const Record& r, std::string_view key, std::string_view fallback = {}) const;
  std::string_view commentText(std::uint32_t i) const { return text(comments[i]); }

  // 1-based byte column of a span on the record's line.
  std::uint32_t column(const Record& r, Span s) const {
    return s.offset >= r.lineOffset && r.line ? s.offset - r.lineOffset + 1 : 0;
  }
  // The source line of a record, for carets under messages.
  std::string_view sourceLine(const Record& r) const;

  // --- building and editing (loader, from_json, sim) ---
  // Appends raw (already encoded) text to the buffer and returns its span.
  Span append(std::string_view raw);
  // Replaces the raw text of a value (stays in place in the field list).
  void setValue(std::uint32_t fieldIndex, std::string_view raw) { fields[fieldIndex].value = append(raw); }
  // Sets key=raw on record `r` (replacing the last occurrence, or adding it
  // at the end).  The record must be the last one if the key is new.
  void setKey(std::size_t recordIndex, std::string_view key, std::string_view raw);
  std::string& buffer() { return text_; }
  const std::string& buffer() const { return text_; }

 private:
  std::string text_;
};

// Identity helpers shared by validate, diff and the scene view.
// The node's path (first positional) decoded, or empty.
std::string nodePath(const Document& doc, const Record& r);
// The explicit id, or the default id of compat-notes.md (prefix + path; a
// material's name), or empty when the kind has none.
std::string nodeId(const Document& doc, const Record& r);

}  // namespace rscene
