#include "core/diff_identity.hpp"

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

#include "core/text.hpp"

namespace rscene {
namespace {

constexpr char kSep = '\x1f';  // never in a decoded name people write

// Integers are keyed by value, so `slot=01` and `slot=1` match.
std::string normalized(std::string text) {
  if (auto v = parseInteger(text)) return std::to_string(*v);
  return text;
}

// The alternatives of a rule's `a|b` word that count: all but `id` when
// ids are ignored (and `id` is not the only one).
std::vector<std::string_view> alternatives(std::string_view word, bool ignoreId) {
  std::vector<std::string_view> out;
  for (std::string_view rest = word;;) {
    std::size_t bar = rest.find('|');
    std::string_view a = rest.substr(0, bar);
    if (!(ignoreId && a == "id")) out.push_back(a);
    if (bar == std::string_view::npos) break;
    rest = rest.substr(bar + 1);
  }
  if (out.empty()) out.push_back(word);
  return out;
}

std::string ruleKey(const Document& doc, const Record& r, const IdentityRule& rule, bool ignoreId) {
  std::vector<std::string> parts;
  for (std::string_view word : splitWords(rule.fields)) {
    std::string value;
    for (std::string_view a : alternatives(word, ignoreId)) {
      value = fieldText(doc, r, a);
      if (!value.empty()) break;
    }
    parts.push_back(normalized(std::move(value)));
  }
  if (rule.unordered) std::sort(parts.begin(), parts.end());
  std::string key;
  for (const std::string& p : parts) {
    if (!key.empty()) key.push_back(kSep);
    key += p;
  }
  return key;
}

const IdentityRule* ruleFor(std::string_view tag) {
  for (const IdentityRule& rule : identityRules())
    if (tag == rule.tag) return &rule;
  return nullptr;
}

}  // namespace

const std::vector<IdentityRule>& identityRules() {
  static const std::vector<IdentityRule> rules = {
      {"material", "id|name"},
      {"contact_material", "materialA materialB", true},
      {"terrain_texture", "slot"},
      {"asset", "id|label"},
      {"articulated_resource", "id|name"},
      {"prefab_override", "path property"},
      {"terrain_splat_layer", "slot"},
      {"terrain_foliage_layer", "id|name"},
      {"articulated_ik", "frame"},
      {"compound_child", ""},  // position among its siblings
  };
  return rules;
}

std::string fieldText(const Document& doc, const Record& r, std::string_view name) {
  if (r.kind) {
    if (const Layout* layout = r.kind->layoutFor(r.positionalCount)) {
      for (std::size_t t = 0; t < layout->tokens.size(); ++t) {
        const FieldDef& f = layout->fields[static_cast<std::size_t>(layout->tokens[t].first)];
        if (f.name == name && f.width == 1) return percentDecode(doc.positionalText(r, static_cast<std::uint32_t>(t)));
      }
    }
  }
  const Field* f = doc.find(r, name);
  return f ? percentDecode(doc.text(f->value)) : std::string();
}

bool IdentityOptions::ignoresId(std::string_view tag) const {
  return std::any_of(ignoreIdTags.begin(), ignoreIdTags.end(),
                     [&](const std::string& t) { return t == "*" || t == tag; });
}

std::string childPath(const Document& doc, const Record& r, std::string_view key, const IdentityOptions& options) {
  std::string out = percentDecode(doc.positionalText(r, 0));
  out.push_back('[');
  if (const IdentityRule* rule = ruleFor(doc.tag(r)); rule && *rule->fields) {
    // The field that gave the key: the first alternative of `id|name` that is set.
    std::vector<std::string_view> names =
        alternatives(splitWords(rule->fields).front(), options.ignoresId(doc.tag(r)));
    std::string_view name = names.front();
    for (std::string_view alternative : names)
      if (!fieldText(doc, r, alternative).empty()) {
        name = alternative;
        break;
      }
    out.append(name).push_back('=');
  }
  out.append(key.substr(key.rfind(kSep) + 1));
  out.push_back(']');
  return out;
}

namespace {

// Keys before repeats are numbered; `overrides` replaces the key of a
// record (by index) before its children are keyed under it.
std::vector<std::string> baseKeys(const Document& doc, const IdentityOptions& options,
                                  const std::unordered_map<std::size_t, std::string>& overrides) {
  static const std::vector<std::string> parentTags = [] {
    std::vector<std::string> v;
    for (const KindDef& k : Schema::get().kinds())
      if (!k.parentTag.empty()) v.push_back(k.parentTag);
    return v;
  }();
  std::vector<std::string> keys(doc.records.size());
  // Latest parent record per (tag, path), and how many children each has.
  std::unordered_map<std::string, std::string> parents;
  std::unordered_map<std::string, int> siblings;
  for (std::size_t i = 0; i < doc.records.size(); ++i) {
    const Record& r = doc.records[i];
    std::string& key = keys[i];
    std::string_view tag = doc.tag(r);
    key.assign(tag);
    key.push_back(kSep);
    if (!r.kind) {
      for (std::uint32_t j = 0; j < r.fieldCount; ++j) {
        const Field& f = doc.field(r, j);
        // Decoded, so that re-encoding (what rscene-fmt does) keeps the key.
        if (f.isKey()) key.append(percentDecode(doc.text(f.key))).push_back('=');
        key.append(percentDecode(doc.text(f.value))).push_back(' ');
      }
      continue;
    }
    const KindDef& k = *r.kind;
    if (k.role == Role::Singleton) {
      key.pop_back();
    } else if (k.role == Role::Child) {
      std::string parentPath = percentDecode(doc.positionalText(r, 0));
      auto it = parents.find(k.parentTag + kSep + parentPath);
      std::string parent = it != parents.end() ? it->second : k.parentTag + kSep + parentPath;
      key = parent + kSep + key;
      const IdentityRule* rule = ruleFor(tag);
      if (rule && *rule->fields) key += ruleKey(doc, r, *rule, options.ignoresId(tag));
      else key += std::to_string(siblings[parent + kSep + std::string(tag)]++);
    } else if (k.role == Role::Node) {
      std::string id = options.ignoresId(tag) ? std::string() : nodeId(doc, r);
      if (!id.empty()) {
        key += "id";
        key.push_back(kSep);
        key += id;
      } else {
        key += nodePath(doc, r);
      }
      if (auto o = overrides.find(i); o != overrides.end()) key = o->second;  // before its children
      if (std::find(parentTags.begin(), parentTags.end(), k.tag) != parentTags.end()) {
        parents[k.tag + kSep + nodePath(doc, r)] = key;
        // A child may name its parent by id (`compound_child compound_table`)
        // where the other side names it by path: the same parent either way.
        if (std::string ref = nodeId(doc, r); !ref.empty() && ref != nodePath(doc, r)) parents[k.tag + kSep + ref] = key;
      }
    } else if (const IdentityRule* rule = ruleFor(tag)) {
      key += ruleKey(doc, r, *rule, options.ignoresId(tag));
    } else {
      key += percentDecode(doc.positionalText(r, 0));
    }
    if (auto o = overrides.find(i); o != overrides.end()) key = o->second;
  }
  return keys;
}

std::vector<std::string> numberRepeats(std::vector<std::string> keys) {
  // Repeats: the second record with a key is `key#2`, and so on.
  std::unordered_map<std::string_view, int> seen;
  seen.reserve(keys.size());
  std::vector<std::pair<std::size_t, int>> repeats;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    int n = ++seen[keys[i]];
    if (n > 1) repeats.emplace_back(i, n);
  }
  for (auto [i, n] : repeats) keys[i] += "#" + std::to_string(n);
  return keys;
}

bool hasExplicitId(const Document& doc, const Record& r) { return r.kind && !fieldText(doc, r, "id").empty(); }

}  // namespace

std::vector<std::string> identityKeys(const Document& doc, const IdentityOptions& options) {
  return numberRepeats(baseKeys(doc, options, {}));
}

SideKeys matchedIdentityKeys(const Document& oldDoc, const Document& newDoc, const IdentityOptions& options) {
  std::vector<std::string> baseA = baseKeys(oldDoc, options, {}), baseB = baseKeys(newDoc, options, {});
  SideKeys out{numberRepeats(baseA), numberRepeats(baseB)};
  std::unordered_set<std::string_view> inA(out.oldKeys.begin(), out.oldKeys.end()),
      inB(out.newKeys.begin(), out.newKeys.end());
  // Most diffs leave nothing unmatched on one side or the other: done.
  auto unmatched = [](const std::vector<std::string>& keys, const std::unordered_set<std::string_view>& other) {
    return std::any_of(keys.begin() + (keys.empty() ? 0 : 1), keys.end(),
                       [&](const std::string& k) { return !other.count(k); });
  };
  if (!unmatched(out.oldKeys, inB) || !unmatched(out.newKeys, inA)) return out;
  // The keys records would have without ids: the same on both sides for a
  // node of the same tag and path, or a material of the same name.
  IdentityOptions noIds = options;
  noIds.ignoreIdTags.assign(1, "*");
  std::vector<std::string> plainA = numberRepeats(baseKeys(oldDoc, noIds, {}));
  std::vector<std::string> plainB = numberRepeats(baseKeys(newDoc, noIds, {}));
  // Unmatched records of the old side by their key without ids, in file order.
  std::unordered_map<std::string_view, std::vector<std::size_t>> waiting;
  for (std::size_t i = 1; i < oldDoc.records.size(); ++i)
    if (!inB.count(out.oldKeys[i]) && !options.ignoresId(oldDoc.tag(oldDoc.records[i])))
      waiting[plainA[i]].push_back(i);
  std::unordered_map<std::size_t, std::string> overridesA, overridesB;
  for (std::size_t j = 1; j < newDoc.records.size() && !waiting.empty(); ++j) {
    if (inA.count(out.newKeys[j])) continue;
    auto it = waiting.find(plainB[j]);
    if (it == waiting.end()) continue;
    const bool idB = hasExplicitId(newDoc, newDoc.records[j]);
    std::vector<std::size_t>& candidates = it->second;
    auto partner = std::find_if(candidates.begin(), candidates.end(),
                                [&](std::size_t i) { return hasExplicitId(oldDoc, oldDoc.records[i]) != idB; });
    if (partner == candidates.end()) continue;
    // The side without an id takes the key of the side with one.
    if (idB) overridesA[*partner] = baseB[j];
    else overridesB[j] = baseA[*partner];
    candidates.erase(partner);
  }
  if (!overridesA.empty()) out.oldKeys = numberRepeats(baseKeys(oldDoc, options, overridesA));
  if (!overridesB.empty()) out.newKeys = numberRepeats(baseKeys(newDoc, options, overridesB));
  return out;
}

}  // namespace rscene
