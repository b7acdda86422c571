#include "core/report.hpp"

#include <algorithm>

namespace rscene {
namespace {

constexpr std::size_t kMaxShownLine = 200;

const char* severityColor(Severity s) {
  switch (s) {
    case Severity::Error: return "\033[1;31m";
    case Severity::Warning: return "\033[1;35m";
    case Severity::Note: return "\033[1;36m";
  }
  return "";
}

}  // namespace

std::string_view lineOf(std::string_view text, std::uint32_t line) {
  if (line == 0) return {};
  std::size_t pos = 0;
  for (std::uint32_t l = 1; l < line; ++l) {
    pos = text.find('\n', pos);
    if (pos == std::string_view::npos) return {};
    ++pos;
  }
  std::size_t end = text.find('\n', pos);
  std::string_view s = text.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos);
  if (!s.empty() && s.back() == '\r') s.remove_suffix(1);
  return s;
}

namespace {

// `s` without a final '\r'.
std::string_view chopCr(std::string_view s) {
  if (!s.empty() && s.back() == '\r') s.remove_suffix(1);
  return s;
}

}  // namespace

std::string_view LineCursor::operator()(std::uint32_t line) {
  if (line == 0) return {};
  while (line_ < line) {
    std::size_t nl = text_.find('\n', pos_);
    if (nl == std::string_view::npos) return {};  // past the end; the cursor stays on the last line
    pos_ = nl + 1;
    ++line_;
  }
  while (line_ > line) {
    // pos_ - 1 is the newline ending the line before; its start follows the newline before that.
    std::size_t nl = pos_ >= 2 ? text_.rfind('\n', pos_ - 2) : std::string_view::npos;
    pos_ = nl == std::string_view::npos ? 0 : nl + 1;
    --line_;
  }
  std::size_t end = text_.find('\n', pos_);
  return chopCr(text_.substr(pos_, end == std::string_view::npos ? std::string_view::npos : end - pos_));
}

std::string formatDiagnostic(const Diagnostic& d, std::string_view file, std::string_view sourceLine, bool color) {
  std::string out;
  const char* bold = color ? "\033[1m" : "";
  const char* reset = color ? "\033[0m" : "";
  out += bold;
  out += file;
  if (d.line) {
    out += ':' + std::to_string(d.line);
    if (d.column) out += ':' + std::to_string(d.column);
  }
  out += ": ";
  out += reset;
  if (color) out += severityColor(d.severity);
  out += severityName(d.severity);
  out += ": ";
  out += reset;
  out += bold;
  out += d.message;
  out += reset;
  if (!d.code.empty()) out += " [" + d.code + "]";
  out += '\n';
  if (!sourceLine.empty() && d.column) {
    // Long lines (a terrain's heights) are shown as a window around the column.
    std::size_t col = d.column - 1;
    std::size_t start = col > kMaxShownLine / 2 ? col - kMaxShownLine / 2 : 0;
    std::string_view shown = sourceLine.substr(std::min(start, sourceLine.size()), kMaxShownLine);
    std::string prefix = start ? "..." : "";
    out += "  " + prefix;
    for (char c : shown) out += (static_cast<unsigned char>(c) < 0x20 && c != '\t') ? '?' : c;
    if (start + kMaxShownLine < sourceLine.size()) out += "...";
    out += "\n  " + std::string(prefix.size(), ' ');
    for (std::size_t i = start; i < col && i < sourceLine.size(); ++i) out += sourceLine[i] == '\t' ? '\t' : ' ';
    out += color ? "\033[1;32m^\033[0m\n" : "^\n";
  }
  if (!d.hint.empty()) out += "  hint: " + d.hint + "\n";
  return out;
}

}  // namespace rscene
