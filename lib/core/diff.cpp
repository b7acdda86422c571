#include "core/diff.hpp"

#include <algorithm>
#include <unordered_map>

#include "core/diff_identity.hpp"
#include "core/diff_value.hpp"
#include "core/suggest.hpp"
#include "core/text.hpp"

namespace rscene {
namespace {

bool editorTag(std::string_view tag) { return tag == "snapping" || tag == "editor_ux" || tag == "render_bake"; }
bool editorField(std::string_view name) {
  return name == "locked" || name == "expanded" || name.substr(0, 9) == "selection";
}

class Differ {
 public:
  Differ(const Document& a, const Document& b, const DiffOptions& opt) : a_(a), b_(b), opt_(opt) {
    // `--ignore id` (or TAG.id): ids take no part in matching either.
    for (const std::string& i : opt_.ignore) {
      if (i == "id") identity_.ignoreIdTags.push_back("*");
      else if (i.size() > 3 && i.compare(i.size() - 3, 3, ".id") == 0) identity_.ignoreIdTags.push_back(i.substr(0, i.size() - 3));
    }
  }

  DiffResult run() {
    DiffResult result;
    result.oldRecords = a_.records.size();
    result.newRecords = b_.records.size();
    SideKeys keys = matchedIdentityKeys(a_, b_, identity_);
    const std::vector<std::string>&keysA = keys.oldKeys, &keysB = keys.newKeys;
    std::unordered_map<std::string_view, std::uint32_t> inA;
    inA.reserve(keysA.size());
    for (std::uint32_t i = 0; i < keysA.size(); ++i) inA.emplace(keysA[i], i);
    std::vector<char> matched(keysA.size(), 0);
    // Sort key: the kind's writer rank, then the position in its file.
    std::vector<std::pair<std::pair<int, std::uint32_t>, RecordDiff>> out;

    for (std::uint32_t j = 0; j < keysB.size(); ++j) {
      const Record& rb = b_.records[j];
      if (skipped(b_, rb)) continue;
      auto it = inA.find(keysB[j]);
      if (it == inA.end()) {
        RecordDiff d = header(Change::Added, b_, rb, keysB[j]);
        describe(b_, rb, false, d);
        out.push_back({{rank(rb), j}, std::move(d)});
        continue;
      }
      matched[it->second] = 1;
      const Record& ra = a_.records[it->second];
      if (a_.version == b_.version && a_.sourceLine(ra) == b_.sourceLine(rb) && ra.line && rb.line) continue;
      RecordDiff d = header(Change::Changed, b_, rb, keysB[j]);
      d.oldLine = ra.line;
      compare(ra, rb, d);
      if (!d.fields.empty() || d.renamed()) out.push_back({{rank(rb), j}, std::move(d)});
    }
    for (std::uint32_t i = 0; i < keysA.size(); ++i) {
      const Record& ra = a_.records[i];
      if (matched[i] || skipped(a_, ra)) continue;
      RecordDiff d = header(Change::Removed, a_, ra, keysA[i]);
      d.oldLine = ra.line;
      d.newLine = 0;
      describe(a_, ra, true, d);
      out.push_back({{rank(ra), i}, std::move(d)});
    }
    std::stable_sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.first.first < y.first.first; });
    result.records.reserve(out.size());
    for (auto& [_, d] : out) result.records.push_back(std::move(d));
    return result;
  }

 private:
  static int rank(const Record& r) { return r.kind ? r.kind->rank : 1000; }

  bool skipped(const Document& doc, const Record& r) const {
    return opt_.ignoreEditorState && editorTag(doc.tag(r));
  }

  bool ignored(std::string_view tag, std::string_view name) const {
    if (opt_.ignoreEditorState && editorField(name)) return true;
    for (const std::string& i : opt_.ignore) {
      if (i == name) return true;
      if (i.size() == tag.size() + 1 + name.size() && i.compare(0, tag.size(), tag) == 0 && i[tag.size()] == '.' &&
          i.compare(tag.size() + 1, name.size(), name) == 0)
        return true;
    }
    return false;
  }

  RecordDiff header(Change c, const Document& doc, const Record& r, const std::string& key) const {
    RecordDiff d;
    d.change = c;
    d.tag = doc.tag(r);
    d.path = r.kind && r.kind->role == Role::Child ? childPath(doc, r, key, identity_) : nodePath(doc, r);
    d.newLine = r.line;
    // People read the key without the separators used for matching.
    std::string_view k = key;
    bool first = true;
    while (true) {
      std::size_t sep = k.find('\x1f');
      std::string_view part = k.substr(0, sep);
      if (!(part == "id" || part.empty() || (first && part == d.tag))) {
        if (!d.key.empty()) d.key.push_back(' ');
        d.key.append(part);
      }
      first = false;
      if (sep == std::string_view::npos) break;
      k = k.substr(sep + 1);
    }
    if (d.key.empty()) d.key = d.tag;
    return d;
  }

  // The fields of a record only one side has, with their values: what an
  // added record holds, what a removed one held.
  void describe(const Document& doc, const Record& r, bool isOld, RecordDiff& d) const {
    const std::string_view tag = doc.tag(r);
    // A node's path, a child's parent path: the record's label says them.
    const bool pathInLabel = r.kind && (r.kind->role == Role::Node || r.kind->role == Role::Child);
    std::vector<DiffValue> vs = values(doc, r);
    for (std::size_t k = 0; k < vs.size(); ++k) {
      const DiffValue& v = vs[k];
      if (ignored(tag, v.name) || (pathInLabel && k == 0 && v.positional)) continue;
      std::size_t before = d.fields.size();
      values_.whole(v, isOld, d.fields);
      if (!v.positional && r.kind && hasPositional(*r.kind, v.name))
        for (std::size_t i = before; i < d.fields.size(); ++i) d.fields[i].keyForm = true;
    }
  }

  static bool hasPositional(const KindDef& kind, std::string_view name) {
    for (const Layout& l : kind.layouts)
      for (const FieldDef& f : l.fields)
        if (f.name == name) return true;
    return false;
  }

  static std::vector<DiffValue> values(const Document& doc, const Record& r) {
    std::vector<DiffValue> vs;
    const Layout* layout = r.kind ? r.kind->layoutFor(r.positionalCount) : nullptr;
    if (layout) {
      std::uint32_t t = 0;
      for (const FieldDef& f : layout->fields) {
        DiffValue v;
        v.name = f.name;
        v.type = f.type;
        v.def = &f;
        v.positional = true;
        for (int c = 0; c < f.width; ++c) v.tokens.push_back(doc.positionalText(r, t++));
        vs.push_back(std::move(v));
      }
    } else {
      DiffValue v;  // an unknown record's positional text, as one value
      v.name = "tokens";
      v.positional = true;
      v.unknownTokens = true;
      for (std::uint32_t j = 0; j < r.fieldCount; ++j)
        if (!doc.field(r, j).isKey()) v.tokens.push_back(doc.text(doc.field(r, j).value));
      vs.push_back(std::move(v));
    }
    for (std::uint32_t j = 0; j < r.fieldCount; ++j) {
      const Field& f = doc.field(r, j);
      if (!f.isKey()) continue;
      DiffValue v;
      v.name = doc.text(f.key);
      v.def = r.kind ? r.kind->key(v.name) : nullptr;
      v.type = v.def ? v.def->type : ValueType::Text;
      v.tokens.push_back(doc.text(f.value));
      // A positional field and a key of the same name are two fields.
      auto same = std::find_if(vs.begin(), vs.end(), [&](const DiffValue& o) { return o.name == v.name && !o.positional; });
      if (same != vs.end()) *same = std::move(v);  // a repeated key: the last one wins
      else vs.push_back(std::move(v));
    }
    return vs;
  }

  // The value standing in for a field that one side does not write: its
  // schema default (a key, or a width-1 positional of another layout).
  static bool defaultFor(const DiffValue& present, DiffValue& out) {
    if (!present.def || !present.def->defaultValue || present.unknownTokens) return false;
    out = present;
    std::string_view text = *present.def->defaultValue;
    out.tokens.assign(1, text);
    if (present.tokens.size() > 1) {  // a vector over several positional tokens
      out.tokens.clear();
      for (std::size_t start = 0, comma = 0; comma != std::string_view::npos; start = comma + 1) {
        comma = text.find(',', start);
        out.tokens.push_back(text.substr(start, comma == std::string_view::npos ? comma : comma - start));
      }
    }
    return true;
  }

  void compare(const Record& ra, const Record& rb, RecordDiff& d) {
    std::string_view tag = b_.tag(rb);
    std::vector<DiffValue> va = values(a_, ra), vb = values(b_, rb);
    const KindDef* kind = rb.kind;
    auto lookup = [](std::vector<DiffValue>& vs, const DiffValue& like) -> DiffValue* {
      for (DiffValue& v : vs)
        if (v.name == like.name && v.positional == like.positional) return &v;
      return nullptr;
    };
    // A key whose kind also has a positional field of its name.
    auto keyForm = [&](const DiffValue& v) { return !v.positional && kind && hasPositional(*kind, v.name); };
    if (kind && kind->role == Role::Node) {
      std::string pa = nodePath(a_, ra), pb = nodePath(b_, rb);
      if (pa != pb) d.oldPath = pa;
    }
    // A set-like identity (the contact pair) matched already, in any order.
    std::vector<std::string_view> identity;
    for (const IdentityRule& rule : identityRules())
      if (rule.unordered && tag == rule.tag) identity = splitWords(rule.fields);
    // A matched child has the same parent, named by path or by id: its
    // reference to it (the first positional field) is no change.
    std::string_view parentRef;
    if (kind && kind->role == Role::Child)
      if (const Layout* layout = kind->layoutFor(rb.positionalCount); layout && !layout->fields.empty())
        parentRef = layout->fields.front().name;
    auto skip = [&](const DiffValue& v) {
      if (ignored(tag, v.name)) return true;
      if (v.positional && std::find(identity.begin(), identity.end(), v.name) != identity.end()) return true;
      if (v.positional && !parentRef.empty() && v.name == parentRef) return true;
      return d.renamed() && v.positional && v.name == "path";
    };
    auto add = [&](const DiffValue& v, bool isOld) {
      std::size_t before = d.fields.size();
      DiffValue dv;
      if (defaultFor(v, dv)) {
        if (isOld) values_.compare(v, dv, d.fields);
        else values_.compare(dv, v, d.fields);
        if (d.fields.size() > before) (isOld ? d.fields[before].newDefault : d.fields[before].oldDefault) = true;
      } else {
        values_.whole(v, isOld, d.fields);
      }
      return before;
    };
    for (DiffValue& b : vb) {
      if (skip(b)) continue;
      std::size_t before = d.fields.size();
      if (DiffValue* a = lookup(va, b)) {
        if (!compareNamed(ra, rb, *a, b, d.fields)) values_.compare(*a, b, d.fields);
      } else {
        add(b, false);
      }
      if (keyForm(b))
        for (std::size_t i = before; i < d.fields.size(); ++i) d.fields[i].keyForm = true;
    }
    for (DiffValue& a : va) {
      if (skip(a) || lookup(vb, a)) continue;
      std::size_t before = add(a, true);
      if (keyForm(a))
        for (std::size_t i = before; i < d.fields.size(); ++i) d.fields[i].keyForm = true;
    }
  }

  // A number list whose entries the caller names (DiffOptions::entryNames).
  bool compareNamed(const Record& ra, const Record& rb, const DiffValue& a, const DiffValue& b,
                    std::vector<FieldDiff>& out) const {
    if (!opt_.entryNames || b.positional || b.type != ValueType::NumberList) return false;
    std::vector<std::string> na = opt_.entryNames(a_, static_cast<std::size_t>(&ra - a_.records.data()), b.name);
    if (na.empty()) return false;
    std::vector<std::string> nb = opt_.entryNames(b_, static_cast<std::size_t>(&rb - b_.records.data()), b.name);
    return !nb.empty() && values_.compareNamed(a, b, na, nb, out);
  }

  const Document& a_;
  const Document& b_;
  const DiffOptions& opt_;
  IdentityOptions identity_;
  ValueComparer values_{opt_, a_.version, b_.version};
};

}  // namespace

const char* changeName(Change c) {
  switch (c) {
    case Change::Added: return "added";
    case Change::Removed: return "removed";
    case Change::Changed: return "changed";
  }
  return "changed";
}

std::size_t DiffResult::count(Change c) const {
  return static_cast<std::size_t>(
      std::count_if(records.begin(), records.end(), [c](const RecordDiff& r) { return r.change == c; }));
}

namespace {

void fieldNames(const KindDef& k, std::vector<std::string_view>& out) {
  for (const Layout& l : k.layouts)
    for (const FieldDef& f : l.fields) out.push_back(f.name);
  for (const FieldDef& f : k.keys) out.push_back(f.name);
}

// Whether a record of `doc` (of kind `tag`, when given) is of an unknown
// kind named `name`, or writes a key `name` the schema does not know.
bool documentUses(const Document& doc, std::string_view tag, std::string_view name, bool asTag) {
  for (std::size_t i = 1; i < doc.records.size(); ++i) {
    const Record& r = doc.records[i];
    if (asTag) {
      if (doc.tag(r) == name) return true;
      continue;
    }
    if (!tag.empty() && doc.tag(r) != tag) continue;
    for (std::uint32_t j = r.positionalCount; j < r.fieldCount; ++j)
      if (doc.field(r, j).isKey() && doc.text(doc.field(r, j).key) == name) return true;
  }
  return false;
}

std::string suggestion(std::string_view word, const std::vector<std::string_view>& candidates) {
  std::string best = closestName(word, candidates);
  return best.empty() ? std::string() : "; did you mean '" + best + "'?";
}

}  // namespace

std::optional<std::string> checkIgnoreName(std::string_view entry, const Document& oldDoc, const Document& newDoc) {
  const Schema& schema = Schema::get();
  std::string_view tag, name = entry;
  if (std::size_t dot = entry.find('.'); dot != std::string_view::npos) {
    tag = entry.substr(0, dot);
    name = entry.substr(dot + 1);
  }
  std::vector<std::string_view> names{"tokens"};  // an unknown record's positional text
  const KindDef* kind = tag.empty() ? nullptr : schema.kind(tag);
  if (!tag.empty() && !kind) {
    if (documentUses(oldDoc, {}, tag, true) || documentUses(newDoc, {}, tag, true)) return std::nullopt;
    std::vector<std::string_view> tags;
    for (const KindDef& k : schema.kinds()) tags.push_back(k.tag);
    return "no record kind '" + std::string(tag) + "'" + suggestion(tag, tags);
  }
  if (kind) fieldNames(*kind, names);
  else
    for (const KindDef& k : schema.kinds()) fieldNames(k, names);
  if (std::find(names.begin(), names.end(), name) != names.end()) return std::nullopt;
  if (documentUses(oldDoc, tag, name, false) || documentUses(newDoc, tag, name, false)) return std::nullopt;
  std::string where = kind ? " in " + std::string(tag) + " records" : std::string();
  return "no field '" + std::string(name) + "'" + where + suggestion(name, names);
}

DiffResult diff(const Document& oldDoc, const Document& newDoc, const DiffOptions& options) {
  return Differ(oldDoc, newDoc, options).run();
}

}  // namespace rscene
