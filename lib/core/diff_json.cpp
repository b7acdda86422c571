// DiffResult as JSON for machines (rscene-diff --format json).
#include <nlohmann/json.hpp>

#include "core/diff.hpp"

namespace rscene {

std::string diffToJson(const DiffResult& result) {
  using Json = nlohmann::ordered_json;
  Json out;
  out["same"] = result.same();
  std::size_t fields = 0;
  for (const RecordDiff& r : result.records) fields += r.fields.size();
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
    if (r.change == Change::Changed) {
      Json fs = Json::array();
      for (const FieldDiff& f : r.fields) {
        Json fj;
        fj["name"] = f.name;
        fj["change"] = changeName(f.change);
        if (f.summarized) {
          fj["oldCount"] = f.oldCount;
          fj["newCount"] = f.newCount;
          fj["changedCount"] = f.changedCount;
          fj["maxDelta"] = f.maxDelta;
        } else {
          if (f.change != Change::Added) fj["old"] = f.oldValue;
          if (f.change != Change::Removed) fj["new"] = f.newValue;
        }
        fs.push_back(std::move(fj));
      }
      j["fields"] = std::move(fs);
    }
    records.push_back(std::move(j));
  }
  out["records"] = std::move(records);
  // Text that is not UTF-8 (a `%FF` in a value) is replaced, not refused.
  return out.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace rscene
