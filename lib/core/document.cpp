#include "core/document.hpp"

#include "core/diagnostic.hpp"
#include "core/text.hpp"

namespace rscene {

const char* severityName(Severity s) {
  switch (s) {
    case Severity::Note: return "note";
    case Severity::Warning: return "warning";
    case Severity::Error: return "error";
  }
  return "error";
}

const Field* Document::positional(const Record& r, std::uint32_t i) const {
  if (i >= r.positionalCount) return nullptr;
  if (!r.interleaved) return &fields[r.firstField + i];
  for (std::uint32_t j = 0; j < r.fieldCount; ++j) {
    const Field& f = fields[r.firstField + j];
    if (!f.isKey() && i-- == 0) return &f;
  }
  return nullptr;
}

std::string_view Document::positionalText(const Record& r, std::uint32_t i) const {
  const Field* f = positional(r, i);
  return f ? text(f->value) : std::string_view();
}

const Field* Document::find(const Record& r, std::string_view key) const {
  for (std::uint32_t j = r.fieldCount; j-- > 0;) {
    const Field& f = fields[r.firstField + j];
    if (f.isKey() && text(f.key) == key) return &f;
  }
  return nullptr;
}

std::string_view Document::value(const Record& r, std::string_view key, std::string_view fallback) const {
  const Field* f = find(r, key);
  return f ? text(f->value) : fallback;
}

std::string_view Document::sourceLine(const Record& r) const {
  if (!r.line) return {};
  std::string_view all(text_);
  std::size_t end = all.find('\n', r.lineOffset);
  std::string_view line = all.substr(r.lineOffset, end == std::string_view::npos ? std::string_view::npos : end - r.lineOffset);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

Span Document::append(std::string_view raw) {
  Span s{static_cast<std::uint32_t>(text_.size()), static_cast<std::uint32_t>(raw.size())};
  text_.append(raw);
  return s;
}

void Document::setKey(std::size_t recordIndex, std::string_view key, std::string_view raw) {
  Record& r = records[recordIndex];
  for (std::uint32_t j = r.fieldCount; j-- > 0;) {
    Field& f = fields[r.firstField + j];
    if (f.isKey() && text(f.key) == key) {
      f.value = append(raw);
      return;
    }
  }
  // A new key: move the record's fields to the end so they stay contiguous.
  if (r.firstField + r.fieldCount != fields.size()) {
    std::uint32_t first = static_cast<std::uint32_t>(fields.size());
    for (std::uint32_t j = 0; j < r.fieldCount; ++j) fields.push_back(fields[r.firstField + j]);
    r.firstField = first;
  }
  Field f;
  f.key = append(key);
  f.value = append(raw);
  fields.push_back(f);
  ++r.fieldCount;
}

std::string nodePath(const Document& doc, const Record& r) {
  if (!r.kind || r.kind->role != Role::Node || r.positionalCount == 0) return {};
  return percentDecode(doc.positionalText(r, 0));
}

std::string nodeId(const Document& doc, const Record& r) {
  if (!r.kind) return {};
  if (const Field* f = doc.find(r, "id")) {
    std::string id = percentDecode(doc.text(f->value));
    if (!id.empty()) return id;
  }
  if (r.kind->tag == "material") return percentDecode(doc.positionalText(r, 0));
  if (r.kind->idPrefix.empty()) return {};
  return r.kind->idPrefix + nodePath(doc, r);
}

}  // namespace rscene
