// The parsed schema: record kinds, their fields and value types, enums.
// Built once from schema_table.cpp; immutable and shared afterwards.
#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/schema_table.hpp"

namespace rscene {

enum class ValueType {
  Number,         // finite double
  Integer,        // int64 text without fraction
  Group,          // uint64 collision group/mask, never through a double
  Flag,           // true/1/yes/on, false/0/no/off
  Text,           // any percent-encoded string, `-` = empty
  Path,           // asset path (resolved by the asset rule)
  Id,             // this record's id
  Ref,            // reference to another record (FieldDef::arg says what)
  Name,           // enumeration (FieldDef::arg names it)
  Vec2,
  Vec3,
  Quat,           // w,x,y,z
  Color,          // r,g,b or r,g,b,a
  NumberList,     // dense CSV
  IntegerList,
  Vec3List,       // x,y,z;x,y,z
  ColorList,      // r,g,b,a;...
  TransformList,  // 10 numbers per entry
  StringList,     // ;-separated encoded tokens
};

std::string_view typeName(ValueType t);
// True for every type whose text is numbers separated by `,`/`;`.
bool isNumericList(ValueType t);
// Components a fixed-size vector type has (0 for other types; color 3..4).
int componentCount(ValueType t);

struct EnumDef {
  struct Value {
    std::string name;
    std::vector<std::string> aliases;
  };
  std::string name;
  std::vector<Value> values;
  bool open = false;  // other names are allowed (future kinds)
  // Canonical name for `text` (case-insensitive, aliases resolved).
  std::optional<std::string_view> canonical(std::string_view text) const;
};

struct FieldDef {
  std::string name;
  ValueType type = ValueType::Text;
  int width = 1;             // tokens taken as a positional field
  std::string arg;           // enum name (Name) or reference target (Ref)
  std::optional<std::string> defaultValue;
  const EnumDef* enumDef = nullptr;
};

struct Layout {
  std::vector<FieldDef> fields;
  // For each positional token: the field it belongs to and its component.
  std::vector<std::pair<int, int>> tokens;
  std::size_t tokenCount() const { return tokens.size(); }
};

struct KindDef {
  std::string tag;
  int rank = 0;
  Role role = Role::Plain;
  std::string idPrefix;
  std::string parentTag;
  std::vector<Layout> layouts;  // [0] is the one writers use
  std::vector<FieldDef> keys;

  const FieldDef* key(std::string_view name) const;
  int keyIndex(std::string_view name) const;  // -1 when unknown
  // Layout with exactly `tokens` positional tokens, or nullptr.
  const Layout* layoutFor(std::size_t tokens) const;
  // Type of positional token `i` in the layout with `total` tokens.
  const FieldDef* positionalToken(std::size_t total, std::size_t i) const;
  bool isNode() const { return role == Role::Node; }

  std::unordered_map<std::string_view, int> keyIndex_;
};

class Schema {
 public:
  static const Schema& get();
  const KindDef* kind(std::string_view tag) const;
  const EnumDef* enumDef(std::string_view name) const;
  const std::vector<KindDef>& kinds() const { return kinds_; }
  const std::vector<EnumDef>& enums() const { return enums_; }
  // Highest writer rank, for callers that bucket records by rank.
  int maxRank() const { return maxRank_; }

 private:
  Schema();
  std::vector<KindDef> kinds_;
  std::vector<EnumDef> enums_;
  std::unordered_map<std::string_view, int> kindIndex_;
  int maxRank_ = 0;
};

}  // namespace rscene
