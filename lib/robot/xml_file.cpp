#include "robot/xml_file.hpp"

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
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    error = doc.ErrorName() ? doc.ErrorName() : "error";
    // tinyxml2's names are XML_ERROR_MISMATCHED_ELEMENT ...: lower-case words read better.
    for (const char* prefix : {"XML_ERROR_", "XML_"})
      if (error.rfind(prefix, 0) == 0) {
        error = error.substr(std::strlen(prefix));
        break;
      }
    for (char& c : error) c = c == '_' ? ' ' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    diagnostics.push_back(robotDiagnostic(Severity::Error, bad, path, doc.ErrorLineNum(),
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
