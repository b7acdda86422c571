// SARIF 2.1.0, the format GitHub code scanning reads.  Rules come from the
// code table, so every code a run can report has a description.
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "core/check.hpp"
#include "rscene-validate/output.hpp"

namespace rscene::validate {
namespace {

const char* level(Severity s) {
  switch (s) {
    case Severity::Error: return "error";
    case Severity::Warning: return "warning";
    case Severity::Note: return "note";
  }
  return "error";
}

class SarifReporter : public Reporter {
 public:
  void file(const std::string& name, std::string_view, const Diagnostics& shown, const FileCounts&) override {
    for (const Diagnostic& d : shown) {
      nlohmann::json location = {{"artifactLocation", {{"uri", name}}}};
      if (d.line) {
        location["region"] = {{"startLine", d.line}};
        if (d.column) location["region"]["startColumn"] = d.column;
      }
      std::string text = d.message + (d.hint.empty() ? "" : " (hint: " + d.hint + ")");
      nlohmann::json result = {{"ruleId", d.code},
                               {"level", level(d.severity)},
                               {"message", {{"text", text}}},
                               {"locations", {{{"physicalLocation", location}}}}};
      if (auto it = ruleIndex_.find(d.code); it != ruleIndex_.end()) result["ruleIndex"] = it->second;
      results_.push_back(std::move(result));
    }
  }
  bool finish(const Totals&) override {
    nlohmann::json rules = nlohmann::json::array();
    for (const CheckInfo& c : checkTable())
      rules.push_back({{"id", c.code},
                       {"shortDescription", {{"text", c.summary}}},
                       {"defaultConfiguration", {{"level", level(c.severity)}}}});
    nlohmann::json doc = {
        {"$schema", "https://json.schemastore.org/sarif-2.1.0.json"},
        {"version", "2.1.0"},
        {"runs",
         {{{"tool", {{"driver", {{"name", "rscene-validate"}, {"version", RSCENE_VERSION}, {"rules", rules}}}}},
           {"results", std::move(results_)}}}}};
    std::cout << doc.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
    std::cout.flush();
    return static_cast<bool>(std::cout);
  }

  SarifReporter() {
    std::size_t i = 0;
    for (const CheckInfo& c : checkTable()) ruleIndex_.emplace(std::string(c.code), i++);
  }

 private:
  std::map<std::string, std::size_t> ruleIndex_;
  nlohmann::json results_ = nlohmann::json::array();
};

}  // namespace

std::unique_ptr<Reporter> sarifReporter() { return std::make_unique<SarifReporter>(); }

}  // namespace rscene::validate
