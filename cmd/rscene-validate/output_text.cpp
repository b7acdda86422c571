#include <cstdio>
#include <iostream>
#include <vector>

#include "core/report.hpp"
#include "rscene-validate/output.hpp"

namespace rscene::validate {
namespace {

std::string plural(std::size_t n, const char* word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

class TextReporter : public Reporter {
 public:
  explicit TextReporter(bool color) : color_(color) {}
  void file(const std::string& name, std::string_view text, const Diagnostics& shown, const FileCounts&) override {
    std::vector<std::uint32_t> lines;
    lines.reserve(shown.size());
    for (const Diagnostic& d : shown) lines.push_back(d.line);
    SourceLines source(text, std::move(lines));  // one pass over the text for all of them
    for (const Diagnostic& d : shown) std::cout << formatDiagnostic(d, name, source(d.line), color_);
  }
  bool finish(const Totals& totals) override {
    std::cout.flush();
    std::cerr << summaryLine(totals) << '\n';
    return static_cast<bool>(std::cout);
  }

 private:
  bool color_;
};

}  // namespace

std::string summaryLine(const Totals& t) {
  std::string s;
  if (t.errors == 0 && t.warnings == 0) s = "no issues";
  else if (t.warnings == 0) s = plural(t.errors, "error");
  else if (t.errors == 0) s = plural(t.warnings, "warning");
  else s = plural(t.errors, "error") + ", " + plural(t.warnings, "warning");
  s += " in " + plural(t.files, "file");
  if (t.truncated()) s += " (" + std::to_string(t.errors + t.warnings - t.shown) + " not shown)";
  return s;
}

std::unique_ptr<Reporter> textReporter(bool color) { return std::make_unique<TextReporter>(color); }

}  // namespace rscene::validate
