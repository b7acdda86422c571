// The validation driver: runs the passes of check_*.cpp over a document and
// the shared field accessors they use.
#include <algorithm>
#include <cstdint>

#include "core/check_context.hpp"
#include "core/loader.hpp"
#include "core/suggest.hpp"
#include "core/text.hpp"

namespace rscene {
namespace checks {

void Context::report(std::string_view code, const Record& r, Span at, std::string_view field, std::string message,
                     std::string hint) {
  Diagnostic d;
  const CheckInfo* info = checkInfo(code);
  d.severity = info ? info->severity : Severity::Error;
  d.code = std::string(code);
  d.line = r.line;
  d.column = doc.column(r, at);
  d.message = std::move(message);
  d.hint = std::move(hint);
  d.tag = r.kind ? r.kind->tag : std::string(doc.tag(r));
  d.field = std::string(field);
  out_.push_back(std::move(d));
}

Context::Context(const Document& d, const CheckOptions& o, Diagnostics& out) : doc(d), opt(o), out_(out) {
  const auto& kinds = Schema::get().kinds();
  std::size_t maxKeys = 0;
  for (const KindDef& k : kinds) maxKeys = std::max(maxKeys, k.keys.size());
  cur_.lastKey.assign(maxKeys, 0);
  cur_.stamp.assign(maxKeys, 0);
  slots_.resize(kinds.size());
  slotCursor_.assign(kinds.size(), 0);
  lastKeys_.resize(kinds.size());
}

Span Context::spanOf(const Record& r, const FieldRef& f) const {
  if (!f.first) return r.tag;
  return f.first->value;
}

std::string_view Context::decode(std::string_view raw, std::string& scratch) {
  if (raw.find('%') == std::string_view::npos && raw != "-") return raw;
  scratch.clear();
  percentDecode(raw, scratch);
  return scratch;
}

void Context::resolve(const Record& r) {
  const KindDef& kind = *r.kind;
  cur_.record = &r;
  cur_.layout = kind.layoutFor(r.positionalCount);
  cur_.kind = kindIndex(kind);
  if (++cur_.generation == 0) {  // wrapped: forget every stamp
    std::fill(cur_.stamp.begin(), cur_.stamp.end(), 0);
    cur_.generation = 1;
  }
  const std::uint32_t gen = cur_.generation;
  cur_.defs.assign(r.fieldCount, nullptr);
  cur_.repeated.assign(r.fieldCount, 0);
  if (const Layout* layout = cur_.layout) {
    for (std::uint32_t t = 0; t < r.positionalCount && t < layout->tokens.size(); ++t) {
      const Field* f = r.interleaved ? doc.positional(r, t) : &doc.field(r, t);
      if (f)
        cur_.defs[static_cast<std::size_t>(f - &doc.field(r, 0))] =
            &layout->fields[static_cast<std::size_t>(layout->tokens[t].first)];
    }
  }
  auto& last = lastKeys_[cur_.kind];
  std::size_t k = 0;  // keys seen so far
  for (std::uint32_t j = 0; j < r.fieldCount; ++j) {
    const Field& f = doc.field(r, j);
    if (!f.isKey()) continue;
    std::string_view name = doc.text(f.key);
    int ki;
    if (k < last.size() && last[k].first == name) {
      ki = last[k].second;
    } else {
      ki = kind.keyIndex(name);
      if (k >= last.size()) last.resize(k + 1);
      last[k] = {name, ki};
    }
    ++k;
    if (ki >= 0) {
      auto i = static_cast<std::size_t>(ki);
      cur_.defs[j] = &kind.keys[i];
      cur_.repeated[j] = cur_.stamp[i] == gen;
      cur_.stamp[i] = gen;
      cur_.lastKey[i] = j;
    } else {
      // An unknown key repeats only another unknown key.
      for (std::uint32_t g = 0; g < j; ++g) {
        const Field& h = doc.field(r, g);
        if (h.isKey() && !cur_.defs[g] && doc.text(h.key) == name) {
          cur_.repeated[j] = 1;
          break;
        }
      }
    }
  }
}

const Context::NameSlot& Context::slot(std::string_view name) const {
  auto& slots = slots_[cur_.kind];
  std::size_t& cursor = slotCursor_[cur_.kind];
  for (std::size_t n = 0, i = cursor; n < slots.size(); ++n, i = i + 1 == slots.size() ? 0 : i + 1) {
    const NameSlot& s = slots[i];
    if (s.layout == cur_.layout && s.name == name) {
      cursor = i + 1 == slots.size() ? 0 : i + 1;
      return s;
    }
  }
  NameSlot s{std::string(name), cur_.layout, -1, -1};
  const KindDef& kind = Schema::get().kinds()[cur_.kind];
  s.keyIndex = kind.keyIndex(name);
  if (const Layout* layout = cur_.layout) {
    for (std::size_t t = 0; t < layout->tokens.size(); ++t) {
      const FieldDef& def = layout->fields[static_cast<std::size_t>(layout->tokens[t].first)];
      if (layout->tokens[t].second == 0 && def.name == name) {
        s.token = static_cast<int>(t);
        break;
      }
    }
  }
  slots.push_back(std::move(s));
  cursor = 0;
  return slots.back();
}

FieldRef Context::get(const Record& r, std::string_view name) const {
  if (cur_.record != &r) return getSlow(r, name);
  const NameSlot& s = slot(name);
  const KindDef& kind = *r.kind;
  if (s.keyIndex >= 0) {
    auto i = static_cast<std::size_t>(s.keyIndex);
    if (cur_.stamp[i] == cur_.generation) return FieldRef{&kind.keys[i], &doc.field(r, cur_.lastKey[i]), 1, true};
  }
  if (s.token >= 0) {
    const Layout& layout = *cur_.layout;
    auto t = static_cast<std::size_t>(s.token);
    const FieldDef& def = layout.fields[static_cast<std::size_t>(layout.tokens[t].first)];
    return FieldRef{&def, doc.positional(r, static_cast<std::uint32_t>(t)), static_cast<std::uint32_t>(def.width),
                    false};
  }
  return FieldRef{};
}

FieldRef Context::getSlow(const Record& r, std::string_view name) const {
  FieldRef ref;
  if (!r.kind) return ref;
  if (const FieldDef* k = r.kind->key(name)) {
    if (const Field* f = doc.find(r, name)) return FieldRef{k, f, 1, true};
  }
  const Layout* layout = r.kind->layoutFor(r.positionalCount);
  if (!layout) return ref;
  for (std::size_t t = 0; t < layout->tokens.size(); ++t) {
    const FieldDef& def = layout->fields[static_cast<std::size_t>(layout->tokens[t].first)];
    if (layout->tokens[t].second == 0 && def.name == name)
      return FieldRef{&def, doc.positional(r, static_cast<std::uint32_t>(t)), static_cast<std::uint32_t>(def.width),
                      false};
  }
  return ref;
}

std::string_view Context::raw(const Record& r, std::string_view name) const {
  FieldRef f = get(r, name);
  return f ? doc.text(f.first->value) : std::string_view();
}

std::string Context::text(const Record& r, std::string_view name) const { return percentDecode(raw(r, name)); }

std::optional<double> Context::number(const Record& r, std::string_view name) const {
  FieldRef f = get(r, name);
  return f ? parseNumber(doc.text(f.first->value)) : std::nullopt;
}

std::optional<std::int64_t> Context::integer(const Record& r, std::string_view name) const {
  FieldRef f = get(r, name);
  auto v = f ? parseInteger(doc.text(f.first->value)) : std::nullopt;
  // Integers beyond 32 bits are RS2003 already; later checks stay quiet.
  return v && *v >= INT32_MIN && *v <= INT32_MAX ? v : std::nullopt;
}

std::optional<bool> Context::flag(const Record& r, std::string_view name) const {
  FieldRef f = get(r, name);
  return f ? parseFlag(doc.text(f.first->value)) : std::nullopt;
}

bool Context::vector(const Record& r, const FieldRef& f, double* out, int n) const {
  (void)r;
  if (!f) return false;
  if (!f.isKey) {
    if (static_cast<int>(f.tokens) < n) return false;
    for (int i = 0; i < n; ++i) {
      auto v = parseNumber(doc.text((f.first + i)->value));
      if (!v) return false;
      out[i] = *v;
    }
    return true;
  }
  int i = 0;
  bool ok = forEachNumber(doc.text(f.first->value), [&](std::string_view item, char) {
    auto v = parseNumber(item);
    if (!v) ok = false;
    if (i < n && v) out[i] = *v;
    ++i;
  });
  return ok && i >= n;
}

const std::string& Context::suggestion(const KindDef* kind, std::string_view name) {
  static const std::string kNone;
  if (name.empty() || name.size() > 64) return kNone;  // closestName suggests nothing for these
  std::string key = kind ? std::to_string(kindIndex(*kind)) + ":" : std::string("tag:");
  key.append(name);
  auto [it, added] = suggestions_.try_emplace(std::move(key));
  if (added) {
    std::vector<std::string_view> names;
    if (kind) {
      names.reserve(kind->keys.size());
      for (const FieldDef& k : kind->keys) names.push_back(k.name);
    } else {
      for (const KindDef& k : Schema::get().kinds()) names.push_back(k.tag);
    }
    it->second = closestName(name, names);
  }
  return it->second;
}

bool Context::hasExplicitId(const Record& r) const {
  // Decoding yields "" only for `-` and the empty token.
  FieldRef ref = get(r, "id");
  const Field* f = ref && ref.isKey ? ref.first : doc.find(r, "id");
  if (!f) return false;
  std::string_view v = doc.text(f->value);
  return !v.empty() && v != "-";
}

const Record* Context::node(std::string_view ref) const {
  if (memoValid_ && memoRef_ == ref) return memoNode_;
  memoNode_ = findNode(ref);
  memoRef_.assign(ref);
  memoValid_ = true;
  return memoNode_;
}

const Record* Context::findNode(std::string_view ref) const {
  if (std::uint32_t i = index.nodeById.find(ref); i != TextIndex::kNone) return &doc.records[i];
  if (std::uint32_t i = index.nodeByPath.find(ref); i != TextIndex::kNone) return &doc.records[i];
  // Default ids are a kind's prefix and the path (compat-notes.md); they
  // are resolved through the path map instead of being stored.
  for (const KindDef& k : Schema::get().kinds()) {
    if (k.idPrefix.empty() || ref.substr(0, k.idPrefix.size()) != k.idPrefix) continue;
    std::uint32_t i = index.nodeByPath.find(ref.substr(k.idPrefix.size()));
    if (i == TextIndex::kNone) continue;
    const Record& r = doc.records[i];
    if (r.kind == &k && !hasExplicitId(r)) return &r;
  }
  return nullptr;
}

const Record* Context::terrain(std::string_view ref) const {
  const Record* r = node(ref);
  return r && r->kind->tag == "terrain_region" ? r : nullptr;
}

}  // namespace checks

void check(const Document& doc, const CheckOptions& options, DiagnosticSink& sink) {
  // The passes report into `out`, which is handed on and emptied after each
  // record: a file of ten million bad lines never holds its findings at once.
  Diagnostics out;
  auto flush = [&] {
    for (Diagnostic& d : out) sink.add(std::move(d));
    out.clear();
  };
  checks::Context ctx(doc, options, out);
  checks::buildIndex(ctx);
  flush();
  for (std::size_t i = 0; i < doc.records.size(); ++i) {
    const Record& r = doc.records[i];
    if (r.kind) ctx.resolve(r);
    checks::checkTypes(ctx, r);
    if (r.kind) {
      checks::checkRefs(ctx, i);
      checks::checkSizes(ctx, r);
      if (options.checkFiles) checks::checkFiles(ctx, r);
      if (options.profile == Profile::RaiSim) checks::checkRaisim(ctx, i);
      // Findings of one record in column order, so they read left to right.
      std::stable_sort(out.begin(), out.end(),
                       [](const Diagnostic& a, const Diagnostic& b) { return a.column < b.column; });
    }
    flush();
  }
  checks::checkParentCycles(ctx);
  flush();
}

Diagnostics check(const Document& doc, const CheckOptions& options) {
  CollectDiagnostics all;
  check(doc, options, all);
  return std::move(all.all);
}

Diagnostics validateText(std::string text, const CheckOptions& options, Document& doc) {
  LoadResult loaded = parse(std::move(text));
  doc = std::move(loaded.document);
  if (!loaded.ok()) return std::move(loaded.diagnostics);
  Diagnostics found = check(doc, options);
  hintContinuations(loaded.continuedLines, found);
  loaded.diagnostics.insert(loaded.diagnostics.end(), std::make_move_iterator(found.begin()),
                            std::make_move_iterator(found.end()));
  return std::move(loaded.diagnostics);
}

}  // namespace rscene
