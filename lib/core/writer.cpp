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

void appendCanonicalRecord(const Document& doc, const Record& r, std::string& out) {
  for (std::uint32_t c = 0; c < r.commentCount; ++c) {
    out.append(doc.commentText(r.firstComment + c));
    out.push_back('\n');
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
    const FieldDef* def = r.kind ? r.kind->key(key) : nullptr;
    if (def)
      appendCanonical(out, raw, def->type, doc.version);
    else if (!raw.empty())  // unknown key: keep `key=` and `key=-` apart
      appendCanonical(out, raw, ValueType::Text, doc.version);
  }
  out.push_back('\n');
}

void writeCanonical(const Document& doc, Sink& sink) {
  std::string buf;
  buf.reserve(kChunk * 2);
  for (std::uint32_t i : canonicalOrder(doc)) {
    appendCanonicalRecord(doc, doc.records[i], buf);
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
