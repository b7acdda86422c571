#include "robot/xml_file.hpp"

#include <cstring>

#include "core/assets.hpp"
#include "core/filesystem.hpp"

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

bool readXmlFile(const std::string& path, std::size_t maxBytes, tinyxml2::XMLDocument& doc,
                 Diagnostics& diagnostics) {
  const FileSystem& disk = diskFileSystem();
  FileStatus status = disk.stat(path);
  if (status.kind != FileKind::Regular) {
    diagnostics.push_back(
        robotDiagnostic(Severity::Error, "RS5001", path, 0, "robot file '" + path + "' " + whyNotAFile(path)));
    return false;
  }
  std::string text, error;
  if (!disk.read(path, text, &error, maxBytes)) {
    diagnostics.push_back(
        robotDiagnostic(Severity::Error, "RS7030", path, 0, "cannot read robot file '" + path + "': " + error));
    return false;
  }
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    std::string what = doc.ErrorName() ? doc.ErrorName() : "error";
    // tinyxml2's names are XML_ERROR_PARSING_ELEMENT ...: lower-case words read better.
    if (what.rfind("XML_", 0) == 0) what = what.substr(4);
    for (char& c : what) c = c == '_' ? ' ' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    diagnostics.push_back(robotDiagnostic(Severity::Error, "RS7030", path, doc.ErrorLineNum(),
                                          "robot file is not well-formed XML (" + what + ")"));
    return false;
  }
  return true;
}

bool looksLikeTemplate(const char* text) {
  return text && (std::strstr(text, "${") || std::strstr(text, "$(") || std::strstr(text, "@@"));
}

}  // namespace rscene::robot
