// INTERIM (foundation): parses a plain world XML into the Element tree
// without template expansion; the XML front end replaces this file.
#include <tinyxml2.h>

#include <filesystem>

#include "core/filesystem.hpp"
#include "xml/xml_tree.hpp"

namespace rscene::xml {
namespace {

Element convert(const tinyxml2::XMLElement& e, const std::string& file) {
  Element out;
  out.name = e.Name();
  out.where = {file, static_cast<std::uint32_t>(e.GetLineNum()), 0};
  for (const tinyxml2::XMLAttribute* a = e.FirstAttribute(); a; a = a->Next())
    out.attributes.push_back({a->Name(), a->Value(), out.where});
  for (const tinyxml2::XMLElement* c = e.FirstChildElement(); c; c = c->NextSiblingElement())
    out.children.push_back(convert(*c, file));
  return out;
}

}  // namespace

LoadResult loadWorldText(std::string_view text, const std::string& displayName, const std::string&,
                         const LoadOptions&) {
  LoadResult result;
  result.files.push_back(displayName);
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    Diagnostic d;
    d.code = "RS8101";
    d.file = displayName;
    d.line = static_cast<std::uint32_t>(doc.ErrorLineNum());
    d.message = "not well-formed XML";
    result.diagnostics.push_back(d);
    return result;
  }
  const tinyxml2::XMLElement* root = doc.RootElement();
  if (!root || std::string_view(root->Name()) != "raisim") {
    Diagnostic d;
    d.code = "RS8101";
    d.file = displayName;
    d.message = "the top element is not <raisim>";
    result.diagnostics.push_back(d);
    return result;
  }
  result.root = convert(*root, displayName);
  return result;
}

LoadResult loadWorld(const std::string& path, const LoadOptions& options) {
  std::string text, error;
  if (!diskFileSystem().read(path, text, &error, options.limits.maxFileBytes)) {
    LoadResult result;
    Diagnostic d;
    d.code = "RS8101";
    d.file = path;
    d.message = "cannot read: " + error;
    result.diagnostics.push_back(d);
    return result;
  }
  return loadWorldText(text, path, std::filesystem::path(path).parent_path().string(), options);
}

}  // namespace rscene::xml
