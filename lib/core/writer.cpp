#include "core/writer.hpp"

#include <algorithm>
#include <map>

#include "core/text.hpp"

namespace rscene {
namespace {

constexpr std::size_t kChunk = 1 << 16;

ValueType positionalType(const Record& r, std::uint32_t i) {
  if (!r.kind) return ValueType::Text;
  const Layout* layout = r.kind->layoutFor(r.positionalCount);
  if (!layout || i >= layout->tokens.size()) return ValueType::Text;
  const FieldDef& f = layout->fields[static_cast<std::size_t>(layout->tokens[i].first)];
  return f.width > 1 ? ValueType::Number : f.type;
}

bool isParentKind(const KindDef& k) {
  static const std::vector<const KindDef*> parents = [] {
    std::vector<const KindDef*> v;
    const Schema& s = Schema::get();
    for (const KindDef& c : s.kinds())
      if (!c.parentTag.empty()) v.push_back(s.kind(c.parentTag));
    return v;
  }();
  return std::find(parents.begin(), parents.end(), &k) != parents.end();
}

}  // namespace

std::vector<std::uint32_t> canonicalOrder(const Document& doc) {
  const std::size_t n = doc.records.size();
  std::vector<std::uint32_t> group(n), groupRank;
  groupRank.reserve(n);
  // Most recent parent record per (parent tag, path), for children.
  std::map<std::pair<std::string, std::string>, std::uint32_t> parents;
  for (std::size_t i = 0; i < n; ++i) {
    const Record& r = doc.records[i];
    const KindDef* k = r.kind;
    auto joinPrevious = [&] { group[i] = i ? group[i - 1] : 0; };
    if (i == 0 || (k && k->role != Role::Child)) {
      group[i] = static_cast<std::uint32_t>(groupRank.size());
      groupRank.push_back(i == 0 ? -1 : k->rank);
      if (k && !k->tag.empty()) {
        if (isParentKind(*k)) parents[{k->tag, percentDecode(doc.positionalText(r, 0))}] = group[i];
      }
    } else if (k) {
      auto it = parents.find({k->parentTag, percentDecode(doc.positionalText(r, 0))});
      if (it != parents.end()) {
        group[i] = it->second;
      } else {
        // An orphan (no parent before it; validate reports it) sorts as a
        // group of its own with its parent's rank.  It then keeps its place
        // relative to a parent that comes later, so fmt stays idempotent.
        group[i] = static_cast<std::uint32_t>(groupRank.size());
        groupRank.push_back(k->rank);
      }
    } else {
      joinPrevious();
    }
  }
  std::vector<std::uint32_t> order(n);
  for (std::uint32_t i = 0; i < n; ++i) order[i] = i;
  auto before = [&](std::uint32_t a, std::uint32_t b) {
    int ra = groupRank[group[a]], rb = groupRank[group[b]];
    if (ra != rb) return ra < rb;
    if (group[a] != group[b]) return group[a] < group[b];
    return a < b;
  };
  if (!std::is_sorted(order.begin(), order.end(), before)) std::sort(order.begin(), order.end(), before);
  return order;
}

namespace {

// The schema entry of each key of a record, remembered per kind from the
// record before: records of a kind repeat their keys in the same order, and
// comparing a short string is cheaper than hashing it.
class KeyDefs {
 public:
  // nullptr for an unknown key (or a record of an unknown kind).
  const FieldDef* get(const Record& r, std::uint32_t j, std::string_view key) {
    if (!r.kind) return nullptr;
    const Schema& schema = Schema::get();
    auto k = static_cast<std::size_t>(r.kind - schema.kinds().data());
    if (last_.empty()) last_.resize(schema.kinds().size());
    std::vector<std::pair<std::string_view, const FieldDef*>>& seen = last_[k];
    if (j < seen.size() && seen[j].first == key) return seen[j].second;
    const FieldDef* def = r.kind->key(key);
    if (j >= seen.size()) seen.resize(j + 1);
    seen[j] = {key, def};
    return def;
  }

 private:
  std::vector<std::vector<std::pair<std::string_view, const FieldDef*>>> last_;  // per kind, per field index
};

// The record's line as written when it is canonical already: the tag and
// the tokens separated by single spaces, nothing before, after or between
// them, and every token canonical.  Most records of a file a writer saved
// are, and copying those lines whole is what keeps rscene-fmt as fast as
// reading.  Empty when the record needs formatting.
std::string_view canonicalLine(const Document& doc, const Record& r, KeyDefs& keys) {
  const std::string& text = doc.buffer();
  if (r.line == 0 || r.tag.offset != r.lineOffset) return {};
  std::uint32_t end = r.tag.offset + r.tag.length;
  std::uint32_t p = 0;
  for (std::uint32_t j = 0; j < r.fieldCount; ++j) {
    const Field& f = doc.field(r, j);
    std::uint32_t start = f.isKey() ? f.key.offset : f.value.offset;
    if (start != end + 1 || text[end] != ' ') return {};
    // key=value as one token (an edited document may keep them apart)
    if (f.isKey() && (f.value.offset != f.key.offset + f.key.length + 1 || text[f.value.offset - 1] != '='))
      return {};
    std::string_view raw = doc.text(f.value);
    if (!f.isKey()) {
      if (!isCanonicalToken(raw, positionalType(r, p++), doc.version)) return {};
    } else {
      const FieldDef* def = keys.get(r, j, doc.text(f.key));
      // An unknown key keeps `key=` as it is.
      if (!(def ? isCanonicalToken(raw, def->type, doc.version)
                : raw.empty() || isCanonicalToken(raw, ValueType::Text, doc.version)))
        return {};
    }
    end = f.value.offset + f.value.length;
  }
  if (end >= text.size() || text[end] != '\n') return {};
  return std::string_view(text).substr(r.lineOffset, end - r.lineOffset);
}

// Appends the record to `out`; a long canonical line goes to `direct`
// (when given) after what `out` holds, so that a 40 MB height field is not
// copied into a buffer of its size first.
void appendRecord(const Document& doc, const Record& r, std::string& out, KeyDefs& keys, Sink* direct = nullptr) {
  for (std::uint32_t c = 0; c < r.commentCount; ++c) {
    out.append(doc.commentText(r.firstComment + c));
    out.push_back('\n');
  }
  if (std::string_view line = canonicalLine(doc, r, keys); !line.empty()) {
    if (direct && line.size() >= kChunk) {
      if (!out.empty()) direct->write(out);
      out.clear();
      direct->write(std::string_view(line.data(), line.size() + 1));  // the line's own '\n'
      return;
    }
    out.append(line);
    out.push_back('\n');
    return;
  }
  out.append(doc.tag(r));
  std::uint32_t p = 0;
  for (std::uint32_t j = 0; j < r.fieldCount; ++j) {
    const Field& f = doc.field(r, j);
    out.push_back(' ');
    std::string_view raw = doc.text(f.value);
    if (!f.isKey()) {
      appendCanonical(out, raw, positionalType(r, p++), doc.version);
      continue;
    }
    std::string_view key = doc.text(f.key);
    out.append(key);
    out.push_back('=');
    const FieldDef* def = keys.get(r, j, key);
    if (def)
      appendCanonical(out, raw, def->type, doc.version);
    else if (!raw.empty())  // unknown key: keep `key=` and `key=-` apart
      appendCanonical(out, raw, ValueType::Text, doc.version);
  }
  out.push_back('\n');
}

}  // namespace

void appendCanonicalRecord(const Document& doc, const Record& r, std::string& out) {
  KeyDefs keys;
  appendRecord(doc, r, out, keys);
}

void writeCanonical(const Document& doc, Sink& sink) {
  std::string buf;
  buf.reserve(kChunk * 2);
  KeyDefs keys;
  for (std::uint32_t i : canonicalOrder(doc)) {
    appendRecord(doc, doc.records[i], buf, keys, &sink);
    if (buf.size() >= kChunk) {
      sink.write(buf);
      buf.clear();
    }
  }
  for (std::uint32_t c = 0; c < doc.trailingCommentCount; ++c) {
    buf.append(doc.commentText(doc.trailingFirstComment + c));
    buf.push_back('\n');
  }
  if (!buf.empty()) sink.write(buf);
}

std::string canonicalText(const Document& doc) {
  std::string out;
  StringSink sink(out);
  writeCanonical(doc, sink);
  return out;
}

}  // namespace rscene
