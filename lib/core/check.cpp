// The validation driver: runs the passes of check_*.cpp over a document and
// the shared field accessors they use.
#include <algorithm>
#include <cstdint>

#include "core/check_context.hpp"
#include "core/loader.hpp"
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

Span Context::spanOf(const Record& r, const FieldRef& f) const {
  if (!f.first) return r.tag;
  return f.first->value;
}

FieldRef Context::get(const Record& r, std::string_view name) const {
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

bool Context::hasExplicitId(const Record& r) const {
  const Field* f = doc.find(r, "id");
  return f && !percentDecode(doc.text(f->value)).empty();
}

const Record* Context::node(std::string_view ref) const {
  if (auto it = index.nodeById.find(ref); it != index.nodeById.end()) return &doc.records[it->second];
  if (auto it = index.nodeByPath.find(ref); it != index.nodeByPath.end()) return &doc.records[it->second];
  // Default ids are a kind's prefix and the path (compat-notes.md); they
  // are resolved through the path map instead of being stored.
  for (const KindDef& k : Schema::get().kinds()) {
    if (k.idPrefix.empty() || ref.substr(0, k.idPrefix.size()) != k.idPrefix) continue;
    auto it = index.nodeByPath.find(ref.substr(k.idPrefix.size()));
    if (it == index.nodeByPath.end()) continue;
    const Record& r = doc.records[it->second];
    if (r.kind == &k && !hasExplicitId(r)) return &r;
  }
  return nullptr;
}

const Record* Context::terrain(std::string_view ref) const {
  const Record* r = node(ref);
  return r && r->kind->tag == "terrain_region" ? r : nullptr;
}

}  // namespace checks

Diagnostics check(const Document& doc, const CheckOptions& options) {
  Diagnostics out;
  checks::Context ctx(doc, options, out);
  checks::buildIndex(ctx);
  for (std::size_t i = 0; i < doc.records.size(); ++i) {
    const Record& r = doc.records[i];
    std::size_t before = out.size();
    checks::checkTypes(ctx, r);
    if (!r.kind) continue;
    checks::checkRefs(ctx, i);
    checks::checkSizes(ctx, r);
    if (options.checkFiles) checks::checkFiles(ctx, r);
    if (options.profile == Profile::RaiSim) checks::checkRaisim(ctx, i);
    // Findings of one record in column order, so they read left to right.
    std::stable_sort(out.begin() + static_cast<std::ptrdiff_t>(before), out.end(),
                     [](const Diagnostic& a, const Diagnostic& b) { return a.column < b.column; });
  }
  checks::checkParentCycles(ctx);
  return out;
}

Diagnostics validateText(std::string text, const CheckOptions& options, Document& doc) {
  LoadResult loaded = parse(std::move(text));
  doc = std::move(loaded.document);
  if (!loaded.ok()) return std::move(loaded.diagnostics);
  Diagnostics found = check(doc, options);
  loaded.diagnostics.insert(loaded.diagnostics.end(), std::make_move_iterator(found.begin()),
                            std::make_move_iterator(found.end()));
  return std::move(loaded.diagnostics);
}

}  // namespace rscene
