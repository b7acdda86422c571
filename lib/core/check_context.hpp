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
#include "core/text.hpp"

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

// Whether parseNumber accepts `s`, without computing it when it is a plain
// decimal (no exponent, at most 100 characters: finite and in range).
inline bool isNumber(std::string_view s) {
  const char* p = s.data();
  const char* e = p + s.size();
  p += p != e && *p == '-';
  const char* d = p;
  while (p != e && static_cast<unsigned>(*p - '0') < 10) ++p;
  std::size_t digits = static_cast<std::size_t>(p - d);
  if (p != e && *p == '.') {
    const char* f = ++p;
    while (p != e && static_cast<unsigned>(*p - '0') < 10) ++p;
    digits += static_cast<std::size_t>(p - f);
  }
  if (p == e && digits > 0 && s.size() <= 100) return true;
  return parseNumber(s).has_value();
}

// A map from text to a record index for the node maps: open addressing in
// one array of 8-byte slots (a 32-bit hash and the index); the key of index
// i is keys[i], a view that outlives the map.  std::unordered_map costs a
// bucket, a node, an allocation and a cache miss for each of them.
class TextIndex {
 public:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  explicit TextIndex(const std::vector<std::string_view>& keys) : keys_(keys) {}
  void reserve(std::size_t n) {
    std::size_t size = 16;
    while (size < 2 * n) size *= 2;
    if (size > slots_.size()) rehash(size);
  }
  // Maps keys[value] to value unless that key is there; returns the value
  // the key has.
  std::uint32_t emplace(std::uint32_t value) {
    if (2 * (used_ + 1) > slots_.size()) rehash(slots_.empty() ? 16 : 2 * slots_.size());
    std::string_view key = keys_[value];
    auto h = static_cast<std::uint32_t>(std::hash<std::string_view>{}(key));
    for (std::size_t i = h & mask_;; i = (i + 1) & mask_) {
      Slot& s = slots_[i];
      if (s.value == kNone) {
        s = Slot{h, value};
        ++used_;
        return value;
      }
      if (s.hash == h && keys_[s.value] == key) return s.value;
    }
  }
  // The value of key, or kNone.
  std::uint32_t find(std::string_view key) const {
    if (slots_.empty()) return kNone;
    auto h = static_cast<std::uint32_t>(std::hash<std::string_view>{}(key));
    for (std::size_t i = h & mask_;; i = (i + 1) & mask_) {
      const Slot& s = slots_[i];
      if (s.value == kNone) return kNone;
      if (s.hash == h && keys_[s.value] == key) return s.value;
    }
  }

 private:
  struct Slot {
    std::uint32_t hash = 0;
    std::uint32_t value = kNone;
  };
  void rehash(std::size_t size) {
    std::vector<Slot> old(size);
    old.swap(slots_);
    mask_ = size - 1;
    for (const Slot& s : old) {
      if (s.value == kNone) continue;
      std::size_t i = s.hash & mask_;
      while (slots_[i].value != kNone) i = (i + 1) & mask_;
      slots_[i] = s;
    }
  }
  const std::vector<std::string_view>& keys_;
  std::vector<Slot> slots_;
  std::size_t used_ = 0, mask_ = 0;
};

class Context {
 public:
  Context(const Document& d, const CheckOptions& o, Diagnostics& out);

  const Document& doc;
  const CheckOptions& opt;
  bool raisim() const { return opt.profile == Profile::RaiSim; }

  // Reports `code` (severity from the code table) at span `at` of record r.
  void report(std::string_view code, const Record& r, Span at, std::string_view field, std::string message,
              std::string hint = {});
  // Where a field's value starts (its key for a key=value when keyColumn).
  Span spanOf(const Record& r, const FieldRef& f) const;

  // Makes `r` (a record of a known kind) the current record: each of its
  // fields is resolved to its FieldDef once, for every pass.
  void resolve(const Record& r);
  // Of the current record: field j's FieldDef (nullptr: an unknown key),
  // whether key j was written before in the record, the layout.
  const FieldDef* defOf(std::uint32_t j) const { return cur_.defs[j]; }
  bool repeatedKey(std::uint32_t j) const { return cur_.repeated[j] != 0; }
  const Layout* layout() const { return cur_.layout; }
  bool isCurrent(const Record& r) const { return cur_.record == &r; }

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

  // Decoded text of a raw token: a view of `raw` itself unless it has
  // escapes or is `-` (then of `scratch`).
  static std::string_view decode(std::string_view raw, std::string& scratch);

  // The closest known name to an unknown key of `kind` (nullptr: to an
  // unknown record tag), or empty; remembered, since an unknown key tends
  // to be on every record a newer writer saved.
  const std::string& suggestion(const KindDef* kind, std::string_view name);

  // Identity of the nodes and resources, built once (check_refs.cpp).
  struct Index {
    // Views into the document's text, or into `owned` for decoded text.
    std::vector<std::string_view> pathOf, idOf;  // per record; nodes only (idOf: the id= written)
    TextIndex nodeByPath{pathOf}, nodeById{idOf};  // ids written as id=
    // Per record: the first node with the same path / the same id= (the
    // record itself when it is the first), kNoRecord when none.
    std::vector<std::uint32_t> firstWithPath, firstWithId;
    std::deque<std::string> owned;
    std::unordered_map<std::string_view, std::uint32_t> materials, resources;
    std::unordered_map<std::string_view, bool> contacts;
    std::vector<std::int64_t> textureSlots;
    bool inheritedTransforms = true;
    std::string assetRoot = ".";  // decoded, of the last asset_root
    // "Did you mean" for references (check_refs.cpp): the names of each
    // kind of target, gathered on the first miss; the answer per name; and
    // how many more candidates may be compared, so a file full of broken
    // references among a million nodes stays linear.
    std::unordered_map<std::string, std::vector<std::string_view>> refCandidates;
    std::unordered_map<std::string, std::string> refSuggestions;
    std::size_t refBudget = std::size_t{1} << 20;
    // Filled while records are visited in order.
    std::vector<std::uint32_t> lastOfKind;  // per kind (index in the schema): record index, kNoRecord when none
    std::vector<std::uint32_t> parentOf;    // kNoRecord when none
  } index;
  static constexpr std::uint32_t kNoRecord = 0xffffffffu;
  // Index of a kind in Schema::get().kinds().
  static std::size_t kindIndex(const KindDef& k) {
    return static_cast<std::size_t>(&k - Schema::get().kinds().data());
  }
  // The node a reference names (by id, default id or path), or nullptr.
  // Only once the index is built.
  const Record* node(std::string_view ref) const;
  // The terrain_region a reference names, or nullptr.
  const Record* terrain(std::string_view ref) const;
  // Whether a node has an id= of its own (and so no default id).
  bool hasExplicitId(const Record& r) const;

 private:
  FieldRef getSlow(const Record& r, std::string_view name) const;
  const Record* findNode(std::string_view ref) const;
  // The last node() answer: references repeat (siblings name one parent).
  mutable std::string memoRef_;
  mutable const Record* memoNode_ = nullptr;
  mutable bool memoValid_ = false;
  // A name the passes ask for, resolved for one kind and layout.
  struct NameSlot {
    std::string name;
    const Layout* layout;
    int keyIndex;  // -1: not a key of the kind
    int token;     // first positional token of the field, -1: none
  };
  struct Current {
    const Record* record = nullptr;
    const Layout* layout = nullptr;
    std::size_t kind = 0;
    std::vector<const FieldDef*> defs;     // per field
    std::vector<std::uint8_t> repeated;    // per field
    std::vector<std::uint32_t> lastKey;    // per key index: field index of its last occurrence
    std::vector<std::uint32_t> stamp;      // per key index: generation lastKey is valid for
    std::uint32_t generation = 0;
  } cur_;
  // Per kind: the names asked for (searched from the last hit, since the
  // passes ask in the same order for every record), and the key names of
  // the last record of the kind with their key indexes (records of a kind
  // mostly repeat their keys in the same order).
  mutable std::vector<std::vector<NameSlot>> slots_;
  mutable std::vector<std::size_t> slotCursor_;
  std::vector<std::vector<std::pair<std::string_view, int>>> lastKeys_;
  const NameSlot& slot(std::string_view name) const;
  std::unordered_map<std::string, std::string> suggestions_;
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

// Visits every single-token field of the current record (positional
// fields of one token, then keys the schema knows) as f(def, field).
template <class F>
void forEachValue(const Context& ctx, const Record& r, F&& f) {
  const Document& doc = ctx.doc;
  if (const Layout* layout = ctx.layout()) {
    for (std::size_t t = 0; t < layout->tokens.size(); ++t) {
      const FieldDef& def = layout->fields[static_cast<std::size_t>(layout->tokens[t].first)];
      if (def.width == 1) f(def, *doc.positional(r, static_cast<std::uint32_t>(t)));
    }
  }
  for (std::uint32_t j = r.positionalCount; j < r.fieldCount; ++j) {
    const Field& field = doc.field(r, j);
    if (!field.isKey()) continue;
    if (const FieldDef* def = ctx.defOf(j)) f(*def, field);
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
