// Private to the check*.cpp files: the state one validation run shares and
// typed access to a record's fields by their schema name.
#pragma once
#include <deque>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/check.hpp"
#include "core/document.hpp"

namespace rscene::checks {

// A field of a record as written: one key=value, or the tokens of one
// positional field (vec3 positionals span three tokens).
struct FieldRef {
  const FieldDef* def = nullptr;
  const Field* first = nullptr;  // first token; nullptr = absent
  std::uint32_t tokens = 0;
  bool isKey = false;
  explicit operator bool() const { return first != nullptr; }
};

class Context {
 public:
  Context(const Document& d, const CheckOptions& o, Diagnostics& out) : doc(d), opt(o), out_(out) {}

  const Document& doc;
  const CheckOptions& opt;
  bool raisim() const { return opt.profile == Profile::RaiSim; }

  // Reports `code` (severity from the code table) at span `at` of record r.
  void report(std::string_view code, const Record& r, Span at, std::string_view field, std::string message,
              std::string hint = {});
  // Where a field's value starts (its key for a key=value when keyColumn).
  Span spanOf(const Record& r, const FieldRef& f) const;

  // The key `name` if written, else the positional field `name`.
  FieldRef get(const Record& r, std::string_view name) const;
  // Raw text of a single-token field ("" when absent).
  std::string_view raw(const Record& r, std::string_view name) const;
  // Decoded text of a single-token field.
  std::string text(const Record& r, std::string_view name) const;
  // Typed values; nullopt when absent or malformed (the type checks report
  // malformed values, so later checks stay quiet about them).
  std::optional<double> number(const Record& r, std::string_view name) const;
  std::optional<std::int64_t> integer(const Record& r, std::string_view name) const;
  std::optional<bool> flag(const Record& r, std::string_view name) const;
  // Up to `n` components of a vector field (positional tokens or CSV key).
  bool vector(const Record& r, const FieldRef& f, double* out, int n) const;

  // Identity of the nodes and resources, built once (check_refs.cpp).
  struct Index {
    // Views into the document's text, or into `owned` for decoded text.
    std::unordered_map<std::string_view, std::uint32_t> nodeByPath, nodeById;  // ids written as id=
    std::vector<std::string_view> pathOf;                                      // per record; nodes only
    std::deque<std::string> owned;
    std::unordered_map<std::string, std::uint32_t> materials, resources;
    std::unordered_map<std::string, bool> contacts;
    std::vector<std::int64_t> textureSlots;
    bool inheritedTransforms = true;
    std::string assetRoot = ".";  // decoded, of the last asset_root
    // Filled while records are visited in order.
    std::unordered_map<const KindDef*, std::uint32_t> lastOfKind;  // record index
    std::vector<std::uint32_t> parentOf;                          // kNoRecord when none
  } index;
  static constexpr std::uint32_t kNoRecord = 0xffffffffu;
  // The node a reference names (by id, default id or path), or nullptr.
  const Record* node(std::string_view ref) const;
  // The terrain_region a reference names, or nullptr.
  const Record* terrain(std::string_view ref) const;
  // Whether a node has an id= of its own (and so no default id).
  bool hasExplicitId(const Record& r) const;

 private:
  Diagnostics& out_;
};

// Passes, one per area; each walks the records it needs.
void checkTypes(Context& ctx, const Record& r);      // check_types.cpp
void buildIndex(Context& ctx);                         // check_refs.cpp
void checkRefs(Context& ctx, std::size_t recordIndex); // check_refs.cpp
void checkParentCycles(Context& ctx);                  // check_refs.cpp
void checkSizes(Context& ctx, const Record& r);        // check_sizes.cpp
void checkQuaternion(Context& ctx, const Record& r, Span at, std::string_view field, const double q[4]);
void checkFiles(Context& ctx, const Record& r);        // check_files.cpp
void checkRaisim(Context& ctx, std::size_t recordIndex); // check_raisim.cpp

// Visits every single-token field of a known record (positional fields of
// one token, then keys the schema knows) as f(def, field).
template <class F>
void forEachValue(const Document& doc, const Record& r, F&& f) {
  if (const Layout* layout = r.kind->layoutFor(r.positionalCount)) {
    for (std::size_t t = 0; t < layout->tokens.size(); ++t) {
      const FieldDef& def = layout->fields[static_cast<std::size_t>(layout->tokens[t].first)];
      if (def.width == 1) f(def, *doc.positional(r, static_cast<std::uint32_t>(t)));
    }
  }
  for (std::uint32_t j = r.positionalCount; j < r.fieldCount; ++j) {
    const Field& field = doc.field(r, j);
    if (!field.isKey()) continue;
    if (const FieldDef* def = r.kind->key(doc.text(field.key))) f(*def, field);
  }
}

// Visits the items of a number list (`,` and `;` both separate) without
// allocating; returns false at the first empty item.
template <class F>
bool forEachNumber(std::string_view s, F&& f) {
  if (s.empty()) return true;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= s.size(); ++i) {
    if (i == s.size() || s[i] == ',' || s[i] == ';') {
      if (i == start) return false;
      f(s.substr(start, i - start), i == s.size() ? '\0' : s[i]);
      start = i + 1;
    }
  }
  return true;
}

}  // namespace rscene::checks
