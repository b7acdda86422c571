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

SourceLines::SourceLines(std::string_view text, std::vector<std::uint32_t> lines) : lines_(std::move(lines)) {
  std::sort(lines_.begin(), lines_.end());
  lines_.erase(std::unique(lines_.begin(), lines_.end()), lines_.end());
  if (!lines_.empty() && lines_.front() == 0) lines_.erase(lines_.begin());  // 0: the whole file, no line
  text_.reserve(lines_.size());
  std::uint32_t line = 1;
  std::size_t pos = 0;
  for (std::uint32_t want : lines_) {
    // Skip to the start of line `want`, one newline at a time (memchr-fast).
    while (line < want && pos != std::string_view::npos) {
      pos = text.find('\n', pos);
      if (pos != std::string_view::npos) ++pos;
      ++line;
    }
    if (pos == std::string_view::npos || pos > text.size()) {
      text_.emplace_back();
      continue;
    }
    std::size_t end = text.find('\n', pos);
    text_.push_back(chopCr(text.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos)));
  }
}

std::string_view SourceLines::operator()(std::uint32_t line) const {
  auto it = std::lower_bound(lines_.begin(), lines_.end(), line);
  if (it == lines_.end() || *it != line) return {};
  return text_[static_cast<std::size_t>(it - lines_.begin())];
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
