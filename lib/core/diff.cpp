#include "core/diff.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "core/diff_identity.hpp"
#include "core/text.hpp"

namespace rscene {
namespace {

// One named value of a record: a positional field (one or more tokens) or
// a key.  `tokens` point into the document's buffer.
struct Value {
  std::string_view name;
  ValueType type = ValueType::Text;
  std::vector<std::string_view> tokens;
  const FieldDef* def = nullptr;
};

bool editorTag(std::string_view tag) { return tag == "snapping" || tag == "editor_ux" || tag == "render_bake"; }
bool editorField(std::string_view name) {
  return name == "locked" || name == "expanded" || name.substr(0, 9) == "selection";
}

class Differ {
 public:
  Differ(const Document& a, const Document& b, const DiffOptions& opt) : a_(a), b_(b), opt_(opt) {}

  DiffResult run() {
    DiffResult result;
    result.oldRecords = a_.records.size();
    result.newRecords = b_.records.size();
    std::vector<std::string> keysA = identityKeys(a_), keysB = identityKeys(b_);
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
        out.push_back({{rank(rb), j}, header(Change::Added, b_, rb, keysB[j])});
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

  static RecordDiff header(Change c, const Document& doc, const Record& r, const std::string& key) {
    RecordDiff d;
    d.change = c;
    d.tag = doc.tag(r);
    d.path = nodePath(doc, r);
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

  static std::vector<Value> values(const Document& doc, const Record& r) {
    std::vector<Value> vs;
    const Layout* layout = r.kind ? r.kind->layoutFor(r.positionalCount) : nullptr;
    if (layout) {
      std::uint32_t t = 0;
      for (const FieldDef& f : layout->fields) {
        Value v;
        v.name = f.name;
        v.type = f.width > 1 ? ValueType::Number : f.type;
        v.def = &f;
        for (int c = 0; c < f.width; ++c) v.tokens.push_back(doc.positionalText(r, t++));
        vs.push_back(std::move(v));
      }
    } else {
      Value v;  // an unknown record's positional text, as one value
      v.name = "tokens";
      for (std::uint32_t j = 0; j < r.fieldCount; ++j)
        if (!doc.field(r, j).isKey()) v.tokens.push_back(doc.text(doc.field(r, j).value));
      vs.push_back(std::move(v));
    }
    for (std::uint32_t j = 0; j < r.fieldCount; ++j) {
      const Field& f = doc.field(r, j);
      if (!f.isKey()) continue;
      Value v;
      v.name = doc.text(f.key);
      const FieldDef* def = r.kind ? r.kind->key(v.name) : nullptr;
      v.type = def ? def->type : ValueType::Text;
      v.tokens.push_back(doc.text(f.value));
      auto same = std::find_if(vs.begin(), vs.end(), [&](const Value& o) { return o.name == v.name && !o.def; });
      if (same != vs.end()) *same = std::move(v);  // a repeated key: the last one wins
      else vs.push_back(std::move(v));
    }
    return vs;
  }

  bool closeEnough(double x, double y) const {
    if (x == y) return true;
    double d = std::fabs(x - y);
    return d <= opt_.tolerance || d <= opt_.relTolerance * std::max(std::fabs(x), std::fabs(y));
  }

  // Items of a list value after decoding (`,` and `;` both separate).
  static std::vector<std::string> items(std::string_view raw) {
    std::string v = percentDecode(raw);
    std::vector<std::string> out;
    if (v.empty()) return out;
    std::size_t start = 0;
    for (std::size_t i = 0; i <= v.size(); ++i)
      if (i == v.size() || v[i] == ',' || v[i] == ';') {
        out.push_back(v.substr(start, i - start));
        start = i + 1;
      }
    return out;
  }

  bool sameItem(const std::string& x, const std::string& y, double& delta) const {
    auto px = parseNumber(x), py = parseNumber(y);
    if (px && py) {
      delta = std::max(delta, std::fabs(*px - *py));
      return closeEnough(*px, *py);
    }
    return x == y;
  }

  bool sameScalar(std::string_view x, std::string_view y, ValueType type, const FieldDef* def) const {
    std::string dx = percentDecode(x), dy = percentDecode(y);
    switch (type) {
      case ValueType::Number: {
        auto px = parseNumber(dx), py = parseNumber(dy);
        if (px && py) return closeEnough(*px, *py);
        break;
      }
      case ValueType::Integer: {
        auto px = parseInteger(dx), py = parseInteger(dy);
        if (px && py) return *px == *py;
        break;
      }
      case ValueType::Group: {
        auto px = parseGroup(dx), py = parseGroup(dy);
        if (px && py) return *px == *py;
        break;
      }
      case ValueType::Flag: {
        auto px = parseFlag(dx), py = parseFlag(dy);
        if (px && py) return *px == *py;
        break;
      }
      case ValueType::Name:
        if (def && def->enumDef) {
          auto cx = def->enumDef->canonical(dx), cy = def->enumDef->canonical(dy);
          if (cx && cy) return *cx == *cy;
        }
        break;
      case ValueType::StringList:
        return parseStringList(x) == parseStringList(y);
      default:
        break;
    }
    return dx == dy;
  }

  std::string display(const Document& doc, const Value& v) const {
    std::string out;
    for (std::size_t i = 0; i < v.tokens.size(); ++i) {
      if (i) out.push_back(v.def ? ',' : ' ');
      appendCanonical(out, v.tokens[i], v.type, doc.version);
    }
    return out;
  }

  std::string defaultText(const FieldDef* def) const {
    return def && def->defaultValue ? *def->defaultValue + " (default)" : std::string();
  }

  // Compares one value present on both sides; adds a FieldDiff if it differs.
  void compareValue(const Value& va, const Value& vb, const FieldDef* def, RecordDiff& d) {
    ValueType type = vb.type;
    bool list = isNumericList(type) && componentCount(type) == 0 && vb.tokens.size() == 1;
    if (list || type == ValueType::StringList) {
      std::vector<std::string> ia, ib;
      if (type == ValueType::StringList) {
        ia = parseStringList(va.tokens[0]);
        ib = parseStringList(vb.tokens[0]);
      } else {
        ia = items(va.tokens[0]);
        ib = items(vb.tokens[0]);
      }
      double delta = 0;
      std::size_t changed = 0;
      std::size_t common = std::min(ia.size(), ib.size());
      for (std::size_t i = 0; i < common; ++i)
        if (type == ValueType::StringList ? ia[i] != ib[i] : !sameItem(ia[i], ib[i], delta)) ++changed;
      if (!changed && ia.size() == ib.size()) return;
      FieldDiff f;
      f.name = vb.name;
      if (std::max(ia.size(), ib.size()) > opt_.summarizeAbove) {
        f.summarized = true;
        f.oldCount = ia.size();
        f.newCount = ib.size();
        f.changedCount = changed;
        f.maxDelta = delta;
      } else {
        f.oldValue = display(a_, va);
        f.newValue = display(b_, vb);
      }
      d.fields.push_back(std::move(f));
      return;
    }
    if (va.tokens.size() == vb.tokens.size()) {
      bool same = true;
      for (std::size_t i = 0; i < vb.tokens.size() && same; ++i)
        same = sameScalar(va.tokens[i], vb.tokens[i], vb.tokens.size() > 1 ? ValueType::Number : type, def);
      if (same) return;
    }
    FieldDiff f;
    f.name = vb.name;
    f.oldValue = display(a_, va);
    f.newValue = display(b_, vb);
    d.fields.push_back(std::move(f));
  }

  void compare(const Record& ra, const Record& rb, RecordDiff& d) {
    std::string tag(b_.tag(rb));
    std::vector<Value> va = values(a_, ra), vb = values(b_, rb);
    const KindDef* kind = rb.kind;
    auto lookup = [](std::vector<Value>& vs, std::string_view name) -> Value* {
      for (Value& v : vs)
        if (v.name == name) return &v;
      return nullptr;
    };
    auto schemaDef = [&](std::string_view name) -> const FieldDef* {
      if (!kind) return nullptr;
      if (const FieldDef* k = kind->key(name)) return k;
      for (const Layout& l : kind->layouts)
        for (const FieldDef& f : l.fields)
          if (f.name == name) return &f;
      return nullptr;
    };
    if (kind && kind->role == Role::Node) {
      std::string pa = nodePath(a_, ra), pb = nodePath(b_, rb);
      if (pa != pb) d.oldPath = pa;
    }
    // A set-like identity (the contact pair) matched already, in any order.
    std::vector<std::string_view> identity;
    for (const IdentityRule& rule : identityRules())
      if (rule.unordered && tag == rule.tag) identity = splitWords(rule.fields);
    auto isIdentity = [&](std::string_view name) {
      return std::find(identity.begin(), identity.end(), name) != identity.end();
    };
    for (Value& b : vb) {
      if (ignored(tag, b.name) || isIdentity(b.name)) continue;
      if (d.renamed() && b.name == "path" && b.def) continue;
      const FieldDef* def = schemaDef(b.name);
      Value* a = lookup(va, b.name);
      if (a) {
        compareValue(*a, b, def, d);
        continue;
      }
      FieldDiff f;
      f.name = b.name;
      f.newValue = display(b_, b);
      if (def && def->defaultValue) {
        Value dv = b;
        dv.tokens.assign(1, *def->defaultValue);
        std::size_t before = d.fields.size();
        compareValue(dv, b, def, d);
        if (d.fields.size() == before) continue;  // written out, but the default
        d.fields.back().oldValue = defaultText(def);
        continue;
      }
      f.change = Change::Added;
      d.fields.push_back(std::move(f));
    }
    for (Value& a : va) {
      if (ignored(tag, a.name) || isIdentity(a.name) || lookup(vb, a.name)) continue;
      if (d.renamed() && a.name == "path" && a.def) continue;
      const FieldDef* def = schemaDef(a.name);
      if (def && def->defaultValue) {
        Value dv = a;
        dv.tokens.assign(1, *def->defaultValue);
        std::size_t before = d.fields.size();
        compareValue(a, dv, def, d);
        if (d.fields.size() == before) continue;
        d.fields.back().newValue = defaultText(def);
        continue;
      }
      FieldDiff f;
      f.name = a.name;
      f.change = Change::Removed;
      f.oldValue = display(a_, a);
      d.fields.push_back(std::move(f));
    }
  }

  const Document& a_;
  const Document& b_;
  const DiffOptions& opt_;
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

DiffResult diff(const Document& oldDoc, const Document& newDoc, const DiffOptions& options) {
  return Differ(oldDoc, newDoc, options).run();
}

}  // namespace rscene
