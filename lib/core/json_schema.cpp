// The JSON Schema (2020-12) of the JSON form, generated from the schema
// table so that it names every record kind and field the tools know.
#include <nlohmann/json.hpp>

#include "core/json.hpp"
#include "core/json_value.hpp"

namespace rscene {
namespace {

using Json = nlohmann::ordered_json;

Json defRef(std::string_view def) { return Json{{"$ref", "#/$defs/" + std::string(def)}}; }

// The $defs entry a field of `type` (as a key, or a positional of width 1) uses.
std::string_view typeDef(ValueType t) {
  switch (t) {
    case ValueType::Number: return "number";
    case ValueType::Integer: return "integer";
    case ValueType::Group: return "uint64";
    case ValueType::Flag: return "flag";
    case ValueType::IntegerList: return "integerList";
    case ValueType::StringList: return "stringList";
    default:
      switch (json::shapeOf(t)) {
        case json::Shape::Flat: return "numberList";
        case json::Shape::Nested: return "nestedList";
        default: return "text";
      }
  }
}

Json fieldSchema(const FieldDef& f, bool positional) {
  Json s;
  if (positional && f.width > 1) {
    s = {{"type", "array"},
         {"items", {{"anyOf", Json::array({defRef("numberItem"), defRef("raw")})}}},
         {"minItems", f.width},
         {"maxItems", f.width}};
  } else {
    s = defRef(typeDef(f.type));
  }
  std::string about(typeName(f.type));
  if (f.type == ValueType::Name && f.enumDef) {
    about += ": ";
    for (std::size_t i = 0; i < f.enumDef->values.size(); ++i) about += (i ? ", " : "") + f.enumDef->values[i].name;
    if (f.enumDef->open) about += ", ...";
  } else if (!f.arg.empty()) {
    about += " (" + f.arg + ")";
  }
  if (f.defaultValue) about += "; default " + *f.defaultValue;
  s["description"] = about;
  return s;
}

Json kindSchema(const KindDef& k) {
  Json props = Json::object();
  std::vector<std::string> required;
  for (const Layout& l : k.layouts)
    for (const FieldDef& f : l.fields)
      if (!props.contains(f.name)) props[f.name] = fieldSchema(f, true);
  // Positional names every layout shares are required.
  for (const FieldDef& f : k.layouts[0].fields) {
    bool everywhere = true;
    for (const Layout& l : k.layouts) {
      bool found = false;
      for (const FieldDef& g : l.fields) found = found || g.name == f.name;
      everywhere = everywhere && found;
    }
    if (everywhere) required.push_back(f.name);
  }
  for (const FieldDef& f : k.keys)
    if (!props.contains(f.name)) props[f.name] = fieldSchema(f, false);
  Json s = {{"type", "object"}, {"properties", props}};
  if (!required.empty()) s["required"] = required;
  return s;
}

Json defs() {
  Json d = Json::object();
  d["raw"] = {{"description", "a token exactly as written (percent-encoded), for text that is not UTF-8"},
              {"type", "object"},
              {"properties", {{"raw", {{"type", "string"}}}}},
              {"required", {"raw"}},
              {"additionalProperties", false}};
  d["text"] = {{"anyOf", Json::array({Json{{"type", "string"}}, defRef("raw")})}};
  d["number"] = {{"description", "a number; a string keeps text that is not one (and -0)"},
                 {"anyOf", Json::array({Json{{"type", "number"}}, Json{{"type", "string"}}, defRef("raw")})}};
  d["integer"] = {{"description", "an integer; beyond 2^53 a decimal string"},
                  {"anyOf", Json::array({Json{{"type", "integer"}}, Json{{"type", "string"}}, defRef("raw")})}};
  d["uint64"] = {{"description", "an unsigned 64-bit collision group or mask as a decimal string"},
                 {"anyOf", Json::array({Json{{"type", "string"}}, Json{{"type", "integer"}, {"minimum", 0}}, defRef("raw")})}};
  d["flag"] = {{"anyOf", Json::array({Json{{"type", "boolean"}}, Json{{"type", "string"}}, defRef("raw")})}};
  d["numberItem"] = {{"anyOf", Json::array({Json{{"type", "number"}}, Json{{"type", "string"}}})}};
  d["numberList"] = {{"description", "comma-separated numbers; a string keeps other separators"},
                     {"anyOf", Json::array({Json{{"type", "array"}, {"items", defRef("numberItem")}},
                                            Json{{"type", "string"}}, defRef("raw")})}};
  d["integerList"] = d["numberList"];
  d["nestedList"] = {{"description", "a list of structs: one array of numbers per entry"},
                     {"anyOf", Json::array({Json{{"type", "array"},
                                                 {"items", {{"type", "array"}, {"items", defRef("numberItem")}}}},
                                            Json{{"type", "string"}}, defRef("raw")})}};
  d["stringList"] = {{"anyOf", Json::array({Json{{"type", "array"}, {"items", {{"type", "string"}}}},
                                            Json{{"type", "string"}}, defRef("raw")})}};
  d["comments"] = {{"type", "array"}, {"items", {{"type", "string"}, {"pattern", "^#"}}}};
  for (const KindDef& k : Schema::get().kinds()) d["fields_" + k.tag] = kindSchema(k);
  return d;
}

Json recordSchema() {
  Json tags = Json::array();
  for (const KindDef& k : Schema::get().kinds()) tags.push_back(k.tag);
  Json s = {
      {"type", "object"},
      {"required", {"tag"}},
      {"properties",
       {{"tag", {{"type", "string"}, {"minLength", 1}}},
        {"line", {{"type", "integer"}, {"minimum", 0}}},
        {"comments", defRef("comments")},
        {"positionalCount", {{"type", "integer"}, {"minimum", 0}}},
        {"fields", {{"type", "object"}}},
        {"unknownKeys", {{"type", "array"}, {"items", {{"type", "string"}}}}},
        {"unknownTag", {{"type", "boolean"}}},
        {"tokens", {{"type", "array"}, {"items", {{"type", "string"}, {"minLength", 1}}}}}}},
      {"additionalProperties", false},
      {"oneOf", Json::array({Json{{"required", {"fields"}}}, Json{{"required", {"tokens"}}}})}};
  Json all = Json::array();
  for (const KindDef& k : Schema::get().kinds()) {
    all.push_back({{"if", {{"properties", {{"tag", {{"const", k.tag}}}}}}},
                   {"then", {{"properties", {{"fields", defRef("fields_" + k.tag)}}}}}});
  }
  all.push_back({{"if", {{"properties", {{"tag", {{"not", {{"enum", tags}}}}}}}}},
                 {"then", {{"required", {"tokens", "unknownTag"}}}}});
  s["allOf"] = all;
  return s;
}

}  // namespace

std::string jsonSchema() {
  Json s;
  s["$schema"] = "https://json-schema.org/draft/2020-12/schema";
  s["$id"] = "https://raisim.com/schemas/rscene.schema.json";
  s["title"] = "rscene scene (JSON form written by rscene-to-json)";
  s["description"] =
      "Lossless JSON form of a RaiSim Engine 2 .rscene scene; rscene-from-json turns it back into the canonical text.";
  s["type"] = "object";
  s["required"] = {"format", "version", "records"};
  s["properties"] = {{"$schema", {{"type", "string"}}},
                     {"format", {{"const", "rscene"}}},
                     {"version", {{"enum", {1, 2}}}},
                     {"records", {{"type", "array"}, {"minItems", 1}, {"items", defRef("record")}}},
                     {"trailingComments", defRef("comments")}};
  s["additionalProperties"] = false;
  Json d = defs();
  d["record"] = recordSchema();
  s["$defs"] = d;
  return s.dump(2) + "\n";
}

}  // namespace rscene
