// DiffResult as JSON for machines (rscene-diff --format json).  Values are
// typed the way rscene-to-json types them: numbers, booleans, arrays for
// vectors and lists (arrays of arrays for lists of structs), strings for
// names, paths and uint64 groups (beyond what a double holds).
#include <nlohmann/json.hpp>

#include "core/diff.hpp"
#include "core/json_value.hpp"
#include "core/text.hpp"

namespace rscene {
namespace {

using Json = nlohmann::ordered_json;

Json item(std::string_view s, bool integer) {
  if (integer) {
    if (auto v = parseInteger(s)) return *v;
  } else if (auto v = parseNumber(s)) {
    return *v;
  }
  return percentDecode(s);  // not a number: the text (validate reports it)
}

Json flat(std::string_view s, bool integer) {
  Json out = Json::array();
  if (s.empty()) return out;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= s.size(); ++i)
    if (i == s.size() || s[i] == ',' || s[i] == ';') {
      out.push_back(item(s.substr(start, i - start), integer));
      start = i + 1;
    }
  return out;
}

// `text` is the canonical text of a value of `type` (FieldDiff).
Json typed(const std::string& text, ValueType type) {
  std::string_view s = text;
  switch (json::shapeOf(type)) {
    case json::Shape::Flat:
      return flat(s, type == ValueType::IntegerList);
    case json::Shape::Nested: {
      Json out = Json::array();
      if (s.empty()) return out;
      std::size_t start = 0;
      for (std::size_t i = 0; i <= s.size(); ++i)
        if (i == s.size() || s[i] == ';') {
          out.push_back(flat(s.substr(start, i - start), false));
          start = i + 1;
        }
      return out;
    }
    case json::Shape::Strings: {
      Json out = Json::array();
      for (std::string& e : parseStringList(s)) out.push_back(std::move(e));
      return out;
    }
    case json::Shape::Scalar:
      break;
  }
  switch (type) {
    case ValueType::Number:
    case ValueType::Integer:
      return item(s, type == ValueType::Integer);
    case ValueType::Flag:
      if (auto f = parseFlag(s)) return *f;
      break;
    default:
      break;
  }
  return percentDecode(s);
}

Json fieldJson(const FieldDiff& f) {
  Json fj;
  fj["name"] = f.name;
  if (f.entry) fj["entry"] = true;
  if (f.keyForm) fj["form"] = "key";
  fj["change"] = changeName(f.change);
  fj["type"] = std::string(typeName(f.type));
  if (f.summarized) {
    fj["oldCount"] = f.oldCount;
    fj["newCount"] = f.newCount;
    fj["changedCount"] = f.changedCount;
    fj["listed"] = f.listedCount;
    fj["maxDelta"] = f.maxDelta;
    return fj;
  }
  if (f.change != Change::Added) {
    fj["old"] = typed(f.oldValue, f.type);
    if (f.oldDefault) fj["oldIsDefault"] = true;
  }
  if (f.change != Change::Removed) {
    fj["new"] = typed(f.newValue, f.type);
    if (f.newDefault) fj["newIsDefault"] = true;
  }
  return fj;
}

}  // namespace

std::string diffToJson(const DiffResult& result) {
  Json out;
  out["same"] = result.same();
  std::size_t fields = 0;
  for (const RecordDiff& r : result.records)
    if (r.change == Change::Changed)
      for (const FieldDiff& f : r.fields) fields += f.entry ? 0 : 1;
  out["stat"] = {{"added", result.count(Change::Added)},
                 {"removed", result.count(Change::Removed)},
                 {"changed", result.count(Change::Changed)},
                 {"fieldsChanged", fields}};
  Json records = Json::array();
  for (const RecordDiff& r : result.records) {
    Json j;
    j["change"] = changeName(r.change);
    j["tag"] = r.tag;
    j["key"] = r.key;
    if (!r.path.empty()) j["path"] = r.path;
    if (r.renamed()) j["oldPath"] = r.oldPath;
    if (r.oldLine) j["oldLine"] = r.oldLine;
    if (r.newLine) j["newLine"] = r.newLine;
    {  // an added record's fields are added, a removed one's removed
      Json fs = Json::array();
      for (const FieldDiff& f : r.fields) fs.push_back(fieldJson(f));
      j["fields"] = std::move(fs);
    }
    records.push_back(std::move(j));
  }
  out["records"] = std::move(records);
  // Text that is not UTF-8 (a `%FF` in a value) is replaced, not refused.
  return out.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace rscene
