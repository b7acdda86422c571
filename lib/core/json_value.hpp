// Value-level pieces the JSON writer, reader and schema share: how each
// schema type looks in JSON, and the text rules that keep numbers exact.
#pragma once
#include <string>
#include <string_view>

#include "core/schema.hpp"

namespace rscene::json {

// How a value of a type is spelled in JSON.
enum class Shape {
  Scalar,     // number, boolean or string
  Flat,       // array of items (vectors, colors, number lists)
  Nested,     // array of arrays (vec3 lists, color lists, transforms)
  Strings,    // array of strings (string lists)
};
Shape shapeOf(ValueType t);

// Largest integer jq 1.6 keeps exactly (it stores numbers as doubles).
inline constexpr long long kMaxExactInteger = 9007199254740992LL;

// Appends `item` as a JSON number when it reads back (also through jq) as
// the same value the canonical writer would write; false when it must stay
// a string (not a number, negative zero, an integer beyond 2^53).
bool appendNumberItem(std::string& out, std::string_view item, bool integer);

// Appends `s` as a JSON string literal (s must be UTF-8).
void appendString(std::string& out, std::string_view s);
bool validUtf8(std::string_view s);

}  // namespace rscene::json
