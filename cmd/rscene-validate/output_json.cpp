#include <iostream>
#include <nlohmann/json.hpp>

#include "rscene-validate/output.hpp"

namespace rscene::validate {
namespace {

class JsonReporter : public Reporter {
 public:
  void file(const std::string& name, std::string_view, const Diagnostics& shown, const FileCounts& counts) override {
    nlohmann::json findings = nlohmann::json::array();
    for (const Diagnostic& d : shown)
      findings.push_back({{"code", d.code},
                          {"severity", severityName(d.severity)},
                          {"line", d.line},
                          {"column", d.column},
                          {"tag", d.tag},
                          {"field", d.field},
                          {"message", d.message},
                          {"hint", d.hint}});
    files_.push_back({{"file", name},
                      {"errors", counts.errors},
                      {"warnings", counts.warnings},
                      {"findings", std::move(findings)}});
  }
  bool finish(const Totals& t) override {
    nlohmann::json doc = {{"files", std::move(files_)},
                          {"counts", {{"files", t.files}, {"errors", t.errors}, {"warnings", t.warnings}}},
                          {"truncated", t.truncated()}};
    // Messages quote user text; a cut multi-byte character must not throw.
    std::cout << doc.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
    std::cout.flush();
    return static_cast<bool>(std::cout);
  }

 private:
  nlohmann::json files_ = nlohmann::json::array();
};

}  // namespace

std::unique_ptr<Reporter> jsonReporter() { return std::make_unique<JsonReporter>(); }

}  // namespace rscene::validate
