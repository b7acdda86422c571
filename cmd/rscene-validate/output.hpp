// How rscene-validate reports findings: text for people, JSON and SARIF
// for machines.  A reporter sees each file once, then the totals.
#pragma once
#include <memory>
#include <string>
#include <string_view>

#include "core/diagnostic.hpp"

namespace rscene::validate {

struct FileCounts {
  std::size_t errors = 0;
  std::size_t warnings = 0;
};

struct Totals {
  std::size_t files = 0;
  std::size_t errors = 0;
  std::size_t warnings = 0;
  std::size_t shown = 0;  // findings printed (--max-issues may hide some)
  bool truncated() const { return shown < errors + warnings; }
};

class Reporter {
 public:
  virtual ~Reporter() = default;
  // `shown` are the findings to print; `counts` count all of the file's.
  // `text` is the file's source, for the lines under messages.
  virtual void file(const std::string& name, std::string_view text, const Diagnostics& shown,
                    const FileCounts& counts) = 0;
  // A reporter that streams is handed each finding to show as it is found,
  // instead of in file()'s `shown` (then empty): it needs no memory per
  // finding.  All three formats stream (JSON writes a file's counts after
  // its findings).
  virtual bool streams() const { return false; }
  virtual void finding(const std::string& /*name*/, std::string_view /*text*/, const Diagnostic& /*d*/) {}
  // Writes what is left; false when standard output failed.
  virtual bool finish(const Totals& totals) = 0;
};

std::unique_ptr<Reporter> textReporter(bool color);
std::unique_ptr<Reporter> jsonReporter();
std::unique_ptr<Reporter> sarifReporter();

// `2 errors, 1 warning in 3 files`, `no issues in 1 file`.
std::string summaryLine(const Totals& totals);

}  // namespace rscene::validate
