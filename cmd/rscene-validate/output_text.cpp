#include <cstdio>
#include <iostream>
#include <optional>

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
  bool streams() const override { return true; }
  void finding(const std::string& name, std::string_view text, const Diagnostic& d) override {
    // A new file's text: a new cursor (the text lives until file() is called).
    if (!cursor_ || text.data() != text_.data() || text.size() != text_.size()) {
      text_ = text;
      cursor_.emplace(text);
    }
    // A finding inside another file (a robot's URDF) names that file.
    std::cout << (d.file.empty() ? formatDiagnostic(d, name, (*cursor_)(d.line), color_)
                                 : formatDiagnostic(d, d.file, {}, color_));
  }
  void file(const std::string&, std::string_view, const Diagnostics& shown, const FileCounts&) override {
    (void)shown;  // empty: findings were printed as they came
    cursor_.reset();
  }
  bool finish(const Totals& totals) override {
    std::cout.flush();
    std::cerr << summaryLine(totals) << '\n';
    return static_cast<bool>(std::cout);
  }

 private:
  bool color_;
  std::string_view text_;
  std::optional<LineCursor> cursor_;
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
