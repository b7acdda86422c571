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

// Written as findings come (results last in the run object), so memory
// does not grow with the number of findings.
class SarifReporter : public Reporter {
 public:
  bool streams() const override { return true; }
  void finding(const std::string& name, std::string_view, const Diagnostic& d) override {
    start();
    // A finding inside another file (a robot's URDF) is located there.
    nlohmann::json location = {{"artifactLocation", {{"uri", d.file.empty() ? name : d.file}}}};
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
    std::cout << (first_ ? "\n" : ",\n") << "        " << dump(result);
    first_ = false;
  }
  void file(const std::string&, std::string_view, const Diagnostics&, const FileCounts&) override {}
  bool finish(const Totals&) override {
    start();
    std::cout << (first_ ? "]" : "\n      ]") << "\n    }\n  ]\n}\n";
    std::cout.flush();
    return static_cast<bool>(std::cout);
  }

  SarifReporter() {
    std::size_t i = 0;
    for (const CheckInfo& c : checkTable()) ruleIndex_.emplace(std::string(c.code), i++);
  }

 private:
  static std::string dump(const nlohmann::json& j) {
    return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  }
  // The document up to the opening of the results array.
  void start() {
    if (started_) return;
    started_ = true;
    nlohmann::json rules = nlohmann::json::array();
    for (const CheckInfo& c : checkTable())
      rules.push_back({{"id", c.code},
                       {"shortDescription", {{"text", c.summary}}},
                       {"defaultConfiguration", {{"level", level(c.severity)}}}});
    nlohmann::json tool = {{"driver", {{"name", "rscene-validate"}, {"version", RSCENE_VERSION}, {"rules", rules}}}};
    std::cout << "{\n  \"$schema\": \"https://json.schemastore.org/sarif-2.1.0.json\",\n  \"version\": \"2.1.0\",\n"
              << "  \"runs\": [\n    {\n      \"tool\": " << dump(tool) << ",\n      \"results\": [";
  }

  std::map<std::string, std::size_t> ruleIndex_;
  bool started_ = false, first_ = true;
};

}  // namespace

std::unique_ptr<Reporter> sarifReporter() { return std::make_unique<SarifReporter>(); }

}  // namespace rscene::validate
