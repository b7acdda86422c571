// The JSON form of a scene (rscene-to-json / rscene-from-json): lossless,
// typed from the schema table, and stable through `jq .`.
//
//   {"format": "rscene", "version": 2,
//    "records": [{"tag": "object", "line": 12, "comments": ["# ..."],
//                 "positionalCount": 19,          // only for an older layout
//                 "fields": {"path": "/World/Box", "position": [0, 0, 1], ...},
//                 "unknownKeys": ["futureKey"]},  // fields the schema lacks
//                {"tag": "future_kind", "unknownTag": true, "tokens": ["a", "k=v"]}],
//    "trailingComments": []}
//
// Values: numbers, booleans, arrays (vectors, colors, lists; lists of
// structs as arrays of arrays), strings (names, paths, ids, uint64 groups
// as decimal strings, and any value that does not parse as its type).
// Negative zero and integers beyond 2^53 are strings because jq 1.6 would
// change them.  A value whose decoded text is not UTF-8 is {"raw": TOKEN}
// with the percent-encoded token.  A record that a JSON object cannot hold
// (a repeated key, a key named like a positional field) keeps its
// canonical tokens in "tokens" instead of "fields".
#pragma once
#include <string>
#include <string_view>

#include "core/codes.hpp"
#include "core/diagnostic.hpp"
#include "core/document.hpp"
#include "core/writer.hpp"

namespace rscene {

// Diagnostic codes of the JSON passes.
inline constexpr const char* kJsonSyntax = rs::RS8001;  // not JSON
inline constexpr const char* kJsonSchema = rs::RS8002;  // JSON that is not a scene

struct JsonStyle {
  bool pretty = true;
};

// Streams the JSON form of `doc` to `sink` (no tree is built).
void writeJson(const Document& doc, Sink& sink, JsonStyle style = {});
std::string toJson(const Document& doc, JsonStyle style = {});

struct JsonLoadResult {
  Document document;
  Diagnostics diagnostics;  // message starts with the JSON pointer
  bool ok() const { return !hasErrors(diagnostics); }
};

// Rebuilds a Document from the JSON form; its canonicalText() is the
// canonical scene.  Diagnostics carry the line and column in the JSON text.
JsonLoadResult fromJson(std::string_view json);

// JSON Schema (2020-12) of the JSON form, generated from the schema table.
std::string jsonSchema();

}  // namespace rscene
