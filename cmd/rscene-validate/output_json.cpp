// --format json, written as findings come: memory does not grow with the
// number of findings (10 million repeated records print in constant
// space).  Within a file object the counts follow the findings; JSON
// readers do not depend on key order.
#include <iostream>
#include <nlohmann/json.hpp>

#include "rscene-validate/output.hpp"

namespace rscene::validate {
namespace {

// Messages quote user text; a cut multi-byte character must not throw.
std::string dump(const nlohmann::json& j) { return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace); }

class JsonReporter : public Reporter {
 public:
  bool streams() const override { return true; }
  void finding(const std::string& name, std::string_view, const Diagnostic& d) override {
    if (!open_ || name != file_) openFile(name);
    nlohmann::json f = {{"code", d.code},           {"severity", severityName(d.severity)},
                        {"line", d.line},           {"column", d.column},
                        {"tag", d.tag},             {"field", d.field},
                        {"message", d.message},     {"hint", d.hint}};
    if (!d.file.empty()) f["file"] = d.file;  // a finding inside a robot file
    std::cout << (firstFinding_ ? "\n" : ",\n") << "        " << dump(f);
    firstFinding_ = false;
  }
  void file(const std::string& name, std::string_view, const Diagnostics&, const FileCounts& counts) override {
    if (!open_ || name != file_) openFile(name);
    std::cout << (firstFinding_ ? "" : "\n      ") << "],\n      \"errors\": " << counts.errors
              << ",\n      \"warnings\": " << counts.warnings << "\n    }";
    open_ = false;
  }
  bool finish(const Totals& t) override {
    start();
    std::cout << (firstFile_ ? "]" : "\n  ]") << ",\n  \"counts\": "
              << dump({{"files", t.files}, {"errors", t.errors}, {"warnings", t.warnings}})
              << ",\n  \"truncated\": " << (t.truncated() ? "true" : "false") << "\n}\n";
    std::cout.flush();
    return static_cast<bool>(std::cout);
  }

 private:
  void start() {
    if (!started_) std::cout << "{\n  \"files\": [";
    started_ = true;
  }
  void openFile(const std::string& name) {
    start();
    std::cout << (firstFile_ ? "\n" : ",\n") << "    {\n      \"file\": " << dump(name) << ",\n      \"findings\": [";
    firstFile_ = false;
    firstFinding_ = true;
    open_ = true;
    file_ = name;
  }

  bool started_ = false, firstFile_ = true, firstFinding_ = true, open_ = false;
  std::string file_;
};

}  // namespace

std::unique_ptr<Reporter> jsonReporter() { return std::make_unique<JsonReporter>(); }

}  // namespace rscene::validate
