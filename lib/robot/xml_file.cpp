#include "robot/xml_file.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>

#include "core/assets.hpp"
#include "core/filesystem.hpp"
#include "robot/load.hpp"

namespace rscene::robot {

Diagnostic robotDiagnostic(Severity severity, const char* code, const std::string& file, int line,
                           std::string message) {
  Diagnostic d;
  d.severity = severity;
  d.code = code;
  d.file = file;
  d.line = line > 0 ? static_cast<std::uint32_t>(line) : 0;
  d.message = std::move(message);
  return d;
}

std::vector<int> blankMisplacedDeclarations(std::string& text) {
  std::vector<int> lines;
  bool other = false;  // a comment, a processing instruction or a DOCTYPE came first
  std::size_t i = 0;
  auto lineAt = [&](std::size_t at) { return 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n')); };
  auto past = [&](std::size_t from, std::string_view end) {
    std::size_t j = text.find(end, from);
    return j == std::string::npos ? std::string::npos : j + end.size();
  };
  if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) i = 3;  // a byte-order mark
  while (i < text.size()) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (std::isspace(c)) {
      ++i;
      continue;
    }
    if (c != '<') break;
    std::size_t next;
    const bool declaration =
        text.compare(i, 5, "<?xml") == 0 && i + 5 < text.size() && std::isspace(static_cast<unsigned char>(text[i + 5]));
    if (declaration) {
      next = past(i, "?>");
      if (next == std::string::npos) break;
      if (other) {
        lines.push_back(lineAt(i));
        for (std::size_t k = i; k < next; ++k)
          if (text[k] != '\n') text[k] = ' ';
      }
    } else if (text.compare(i, 4, "<!--") == 0) {
      next = past(i + 4, "-->");
    } else if (text.compare(i, 2, "<?") == 0) {
      next = past(i + 2, "?>");
    } else if (text.compare(i, 2, "<!") == 0) {
      next = past(i + 2, ">");  // a DOCTYPE without an internal subset
    } else {
      break;  // the root element
    }
    if (next == std::string::npos) break;
    if (!declaration) other = true;
    i = next;
  }
  return lines;
}

namespace {

// tinyxml2 reports a mismatched end tag at the line of the element it
// closes, without naming either: find the first end tag that does not
// match its start tag, and say both.  Empty when none is found.
std::string mismatchedEndTag(std::string_view text, int& line) {
  struct Open {
    std::string_view name;
    int line;
  };
  std::vector<Open> open;
  int at = 1;
  std::size_t i = 0;
  auto advance = [&](std::size_t to) {
    to = std::min(to, text.size());
    at += static_cast<int>(std::count(text.begin() + i, text.begin() + to, '\n'));
    i = to;
  };
  auto past = [&](std::size_t from, std::string_view end) {
    std::size_t j = text.find(end, from);
    return j == std::string_view::npos ? text.size() : j + end.size();
  };
  auto nameEnd = [&](std::size_t from) {
    std::size_t j = from;
    while (j < text.size() && !std::isspace(static_cast<unsigned char>(text[j])) && text[j] != '>' && text[j] != '/')
      ++j;
    return j;
  };
  while (i < text.size()) {
    std::size_t lt = text.find('<', i);
    if (lt == std::string_view::npos) break;
    advance(lt);
    if (text.substr(i, 4) == "<!--") {
      advance(past(i + 4, "-->"));
    } else if (text.substr(i, 9) == "<![CDATA[") {
      advance(past(i + 9, "]]>"));
    } else if (text.substr(i, 2) == "<?") {
      advance(past(i + 2, "?>"));
    } else if (text.substr(i, 2) == "<!") {
      advance(past(i + 2, ">"));
    } else if (text.substr(i, 2) == "</") {
      std::string_view name = text.substr(i + 2, nameEnd(i + 2) - (i + 2));
      if (open.empty()) {
        line = at;
        return "</" + std::string(name) + "> closes no element";
      }
      if (name != open.back().name) {
        line = at;
        return "</" + std::string(name) + "> does not close <" + std::string(open.back().name) + "> (opened at line " +
               std::to_string(open.back().line) + ")";
      }
      open.pop_back();
      advance(past(i, ">"));
    } else {
      std::string_view name = text.substr(i + 1, nameEnd(i + 1) - (i + 1));
      const int startLine = at;
      std::size_t j = i + 1;
      char quote = 0;
      for (; j < text.size(); ++j) {
        if (quote) {
          if (text[j] == quote) quote = 0;
        } else if (text[j] == '"' || text[j] == '\'') {
          quote = text[j];
        } else if (text[j] == '>') {
          break;
        }
      }
      if (j >= text.size()) break;
      if (text[j - 1] != '/') open.push_back({name, startLine});
      advance(j + 1);
    }
  }
  return {};
}

}  // namespace

bool readXmlFile(const FileSystem& disk, const std::string& path, std::size_t maxBytes, tinyxml2::XMLDocument& doc,
                 Diagnostics& diagnostics, const char* what, const char* badFileCode) {
  const char* bad = badFileCode ? badFileCode : code::kBadFile;
  FileStatus status = disk.stat(path);
  if (status.kind != FileKind::Regular) {
    diagnostics.push_back(robotDiagnostic(Severity::Error, code::kMissingFile, path, 0,
                                          std::string(what) + " '" + path + "' " + whyNotAFile(path)));
    return false;
  }
  std::string text, error;
  if (!disk.read(path, text, &error, maxBytes)) {
    diagnostics.push_back(
        robotDiagnostic(Severity::Error, bad, path, 0, "cannot read " + std::string(what) + " '" + path + "': " + error));
    return false;
  }
  for (int line : blankMisplacedDeclarations(text))
    diagnostics.push_back(robotDiagnostic(Severity::Warning, rs::RS7054, path, line,
                                          "the <?xml ...?> declaration comes after a comment: XML wants it first; "
                                          "it is skipped, as RaiSim reads such files"));
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    error = doc.ErrorName() ? doc.ErrorName() : "error";
    // tinyxml2's names are XML_ERROR_MISMATCHED_ELEMENT ...: lower-case words read better.
    for (const char* prefix : {"XML_ERROR_", "XML_"})
      if (error.rfind(prefix, 0) == 0) {
        error = error.substr(std::strlen(prefix));
        break;
      }
    for (char& c : error) c = c == '_' ? ' ' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    int line = doc.ErrorLineNum();
    if (doc.ErrorID() == tinyxml2::XML_ERROR_MISMATCHED_ELEMENT)
      if (std::string which = mismatchedEndTag(text, line); !which.empty()) error += ": " + which;
    diagnostics.push_back(robotDiagnostic(Severity::Error, bad, path, line,
                                          std::string(what) + " is not well-formed XML (" + error + ")"));
    return false;
  }
  return true;
}

bool looksLikeTemplate(const char* text) {
  return text && (std::strstr(text, "${") || std::strstr(text, "$(") || std::strstr(text, "@@"));
}

bool parseXmlNumber(std::string_view token, double& out) {
  const char* first = token.data();
  const char* last = first + token.size();
  if (first != last && *first == '+') ++first;  // from_chars refuses a leading '+', XML writers use it
  auto [ptr, ec] = std::from_chars(first, last, out);
  return ec == std::errc{} && ptr == last && std::isfinite(out);
}

bool parseXmlNumbers(const char* text, std::vector<double>& out) {
  out.clear();
  std::string_view s(text);
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    if (i == s.size()) break;
    std::size_t j = i;
    while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j]))) ++j;
    double v = 0;
    if (!parseXmlNumber(s.substr(i, j - i), v)) return false;
    out.push_back(v);
    i = j;
  }
  return true;
}

Eigen::Quaterniond rpyToQuaternion(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .normalized();
}

}  // namespace rscene::robot
