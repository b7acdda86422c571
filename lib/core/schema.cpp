#include "core/schema.hpp"

#include <stdexcept>

#include "core/text.hpp"

namespace rscene {
namespace {

struct TypeSpec {
  std::string_view word;
  ValueType type;
  int width;  // tokens as a positional
};

constexpr TypeSpec kTypes[] = {
    {"num", ValueType::Number, 1},     {"int", ValueType::Integer, 1},
    {"u64", ValueType::Group, 1},      {"flag", ValueType::Flag, 1},
    {"text", ValueType::Text, 1},      {"path", ValueType::Path, 1},
    {"id", ValueType::Id, 1},          {"ref", ValueType::Ref, 1},
    {"name", ValueType::Name, 1},      {"vec2", ValueType::Vec2, 2},
    {"vec3", ValueType::Vec3, 3},      {"quat", ValueType::Quat, 4},
    {"color", ValueType::Color, 1},    {"rgb", ValueType::Color, 3},
    {"rgba", ValueType::Color, 4},     {"csv3", ValueType::Vec3, 1},
    {"nums", ValueType::NumberList, 1},
    {"ints", ValueType::IntegerList, 1}, {"vec3s", ValueType::Vec3List, 1},
    {"colors", ValueType::ColorList, 1}, {"xforms", ValueType::TransformList, 1},
    {"strs", ValueType::StringList, 1},
};

// The table is compiled in; a malformed row is a programming error caught
// by the first unit test, so it throws rather than returning diagnostics.
[[noreturn]] void tableError(const std::string& what) {
  throw std::logic_error("rscene schema table: " + what);
}

FieldDef parseField(std::string_view spec, bool positional) {
  FieldDef f;
  std::size_t colon = spec.find(':');
  if (colon == std::string_view::npos) tableError("field without type: " + std::string(spec));
  f.name = spec.substr(0, colon);
  std::string_view rest = spec.substr(colon + 1);
  if (std::size_t eq = rest.find('='); eq != std::string_view::npos) {
    f.defaultValue = std::string(rest.substr(eq + 1));
    rest = rest.substr(0, eq);
  }
  if (std::size_t at = rest.find('@'); at != std::string_view::npos) {
    f.arg = rest.substr(at + 1);
    rest = rest.substr(0, at);
  }
  for (const TypeSpec& t : kTypes) {
    if (t.word == rest) {
      f.type = t.type;
      f.width = positional ? t.width : 1;
      return f;
    }
  }
  tableError("unknown type '" + std::string(rest) + "' in " + std::string(spec));
}

Layout parseLayout(std::string_view spec) {
  Layout layout;
  for (std::string_view word : splitWords(spec)) {
    layout.fields.push_back(parseField(word, true));
    int idx = static_cast<int>(layout.fields.size()) - 1;
    for (int c = 0; c < layout.fields.back().width; ++c) layout.tokens.emplace_back(idx, c);
  }
  return layout;
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

}  // namespace

std::string_view typeName(ValueType t) {
  switch (t) {
    case ValueType::Number: return "number";
    case ValueType::Integer: return "integer";
    case ValueType::Group: return "uint64";
    case ValueType::Flag: return "flag";
    case ValueType::Text: return "text";
    case ValueType::Path: return "path";
    case ValueType::Id: return "id";
    case ValueType::Ref: return "reference";
    case ValueType::Name: return "name";
    case ValueType::Vec2: return "vec2";
    case ValueType::Vec3: return "vec3";
    case ValueType::Quat: return "quaternion";
    case ValueType::Color: return "color";
    case ValueType::NumberList: return "number list";
    case ValueType::IntegerList: return "integer list";
    case ValueType::Vec3List: return "vec3 list";
    case ValueType::ColorList: return "color list";
    case ValueType::TransformList: return "transform list";
    case ValueType::StringList: return "string list";
  }
  return "?";
}

bool isNumericList(ValueType t) {
  switch (t) {
    case ValueType::Vec2:
    case ValueType::Vec3:
    case ValueType::Quat:
    case ValueType::Color:
    case ValueType::NumberList:
    case ValueType::IntegerList:
    case ValueType::Vec3List:
    case ValueType::ColorList:
    case ValueType::TransformList:
      return true;
    default:
      return false;
  }
}

int componentCount(ValueType t) {
  switch (t) {
    case ValueType::Vec2: return 2;
    case ValueType::Vec3: return 3;
    case ValueType::Quat: return 4;
    case ValueType::Color: return 3;
    default: return 0;
  }
}

std::optional<std::string_view> EnumDef::canonical(std::string_view text) const {
  for (const Value& v : values) {
    if (iequals(v.name, text)) return v.name;
    for (const std::string& a : v.aliases)
      if (iequals(a, text)) return v.name;
  }
  return std::nullopt;
}

const FieldDef* KindDef::key(std::string_view name) const {
  int i = keyIndex(name);
  return i < 0 ? nullptr : &keys[static_cast<std::size_t>(i)];
}

int KindDef::keyIndex(std::string_view name) const {
  auto it = keyIndex_.find(name);
  return it == keyIndex_.end() ? -1 : it->second;
}

const Layout* KindDef::layoutFor(std::size_t tokens) const {
  for (const Layout& l : layouts)
    if (l.tokenCount() == tokens) return &l;
  return nullptr;
}

const FieldDef* KindDef::positionalToken(std::size_t total, std::size_t i) const {
  const Layout* l = layoutFor(total);
  if (!l || i >= l->tokens.size()) return nullptr;
  return &l->fields[static_cast<std::size_t>(l->tokens[i].first)];
}

const Schema& Schema::get() {
  static const Schema schema;
  return schema;
}

Schema::Schema() {
  enums_.reserve(table::kEnumCount);
  for (std::size_t i = 0; i < table::kEnumCount; ++i) {
    EnumDef e;
    e.name = table::kEnums[i].name;
    for (std::string_view word : splitWords(table::kEnums[i].values)) {
      if (word == "...") {
        e.open = true;
        continue;
      }
      EnumDef::Value v;
      std::size_t eq = word.find('=');
      v.name = word.substr(0, eq);
      if (eq != std::string_view::npos) {
        std::string_view aliases = word.substr(eq + 1);
        while (!aliases.empty()) {
          std::size_t comma = aliases.find(',');
          v.aliases.emplace_back(aliases.substr(0, comma));
          aliases = comma == std::string_view::npos ? std::string_view() : aliases.substr(comma + 1);
        }
      }
      e.values.push_back(std::move(v));
    }
    enums_.push_back(std::move(e));
  }

  kinds_.reserve(table::kKindCount);
  for (std::size_t i = 0; i < table::kKindCount; ++i) {
    const table::KindRow& row = table::kKinds[i];
    KindDef k;
    k.tag = row.tag;
    k.rank = row.rank;
    k.role = row.role;
    k.idPrefix = row.idPrefix;
    k.parentTag = row.parentTag;
    k.layouts.push_back(parseLayout(row.positional));
    for (std::size_t j = 0; j < table::kAltLayoutCount; ++j)
      if (k.tag == table::kAltLayouts[j].tag) k.layouts.push_back(parseLayout(table::kAltLayouts[j].positional));
    for (std::string_view word : splitWords(row.keys)) k.keys.push_back(parseField(word, false));
    if (k.rank > maxRank_) maxRank_ = k.rank;
    kinds_.push_back(std::move(k));
  }
  // Pointers into the vectors are taken only now that they no longer grow.
  for (KindDef& k : kinds_) {
    auto resolve = [&](FieldDef& f) {
      if (f.type == ValueType::Name && !f.arg.empty()) {
        f.enumDef = enumDef(f.arg);
        if (!f.enumDef) tableError("unknown enum " + f.arg);
      }
    };
    for (Layout& l : k.layouts)
      for (FieldDef& f : l.fields) resolve(f);
    for (std::size_t j = 0; j < k.keys.size(); ++j) {
      resolve(k.keys[j]);
      if (!k.keyIndex_.emplace(k.keys[j].name, static_cast<int>(j)).second)
        tableError("duplicate key " + k.tag + "." + k.keys[j].name);
    }
    if (!kindIndex_.emplace(k.tag, static_cast<int>(&k - kinds_.data())).second)
      tableError("duplicate kind " + k.tag);
  }
}

const KindDef* Schema::kind(std::string_view tag) const {
  auto it = kindIndex_.find(tag);
  return it == kindIndex_.end() ? nullptr : &kinds_[static_cast<std::size_t>(it->second)];
}

const EnumDef* Schema::enumDef(std::string_view name) const {
  for (const EnumDef& e : enums_)
    if (e.name == name) return &e;
  return nullptr;
}

}  // namespace rscene
