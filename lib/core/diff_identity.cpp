#include "core/diff_identity.hpp"

#include <algorithm>
#include <unordered_map>

#include "core/text.hpp"

namespace rscene {
namespace {

constexpr char kSep = '\x1f';  // never in a decoded name people write

// Integers are keyed by value, so `slot=01` and `slot=1` match.
std::string normalized(std::string text) {
  if (auto v = parseInteger(text)) return std::to_string(*v);
  return text;
}

std::string ruleKey(const Document& doc, const Record& r, const IdentityRule& rule) {
  std::vector<std::string> parts;
  for (std::string_view word : splitWords(rule.fields)) {
    std::string value;
    while (!word.empty()) {
      std::size_t bar = word.find('|');
      value = fieldText(doc, r, word.substr(0, bar));
      if (!value.empty() || bar == std::string_view::npos) break;
      word = word.substr(bar + 1);
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
      {"articulated_resource", "id"},
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

std::string childPath(const Document& doc, const Record& r, std::string_view key) {
  std::string out = percentDecode(doc.positionalText(r, 0));
  out.push_back('[');
  if (const IdentityRule* rule = ruleFor(doc.tag(r)); rule && *rule->fields) {
    // The field that gave the key: the first alternative of `id|name` that is set.
    std::string_view word = splitWords(rule->fields).front();
    std::string_view name = word.substr(0, word.find('|'));
    for (std::string_view rest = word; !rest.empty();) {
      std::size_t bar = rest.find('|');
      std::string_view alternative = rest.substr(0, bar);
      if (!fieldText(doc, r, alternative).empty()) {
        name = alternative;
        break;
      }
      rest = bar == std::string_view::npos ? std::string_view() : rest.substr(bar + 1);
    }
    out.append(name).push_back('=');
  }
  out.append(key.substr(key.rfind(kSep) + 1));
  out.push_back(']');
  return out;
}

std::vector<std::string> identityKeys(const Document& doc) {
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
      if (rule && *rule->fields) key += ruleKey(doc, r, *rule);
      else key += std::to_string(siblings[parent + kSep + std::string(tag)]++);
    } else if (k.role == Role::Node) {
      std::string id = nodeId(doc, r);
      if (!id.empty()) {
        key += "id";
        key.push_back(kSep);
        key += id;
      } else {
        key += nodePath(doc, r);
      }
      if (std::find(parentTags.begin(), parentTags.end(), k.tag) != parentTags.end())
        parents[k.tag + kSep + nodePath(doc, r)] = key;
    } else if (const IdentityRule* rule = ruleFor(tag)) {
      key += ruleKey(doc, r, *rule);
    } else {
      key += percentDecode(doc.positionalText(r, 0));
    }
  }
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

}  // namespace rscene
