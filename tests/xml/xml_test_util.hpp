// Helpers of the XML front-end tests: load a world from text, print an
// expanded tree compactly, print a diagnostic as the tools would.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "xml/xml_tree.hpp"

namespace rscene::xml::test {

inline LoadResult loadText(const std::string& xml, const std::map<std::string, std::string>& params = {},
                           const LoadLimits& limits = {}) {
  LoadOptions options;
  options.params = params;
  options.limits = limits;
  return loadWorldText(xml, "w.xml", "/base", options);
}

// <tag a="1"><child/></tag>, attributes in order, no spaces between elements.
inline std::string show(const Element& e) {
  std::string s = "<" + e.name;
  for (const Attribute& a : e.attributes) s += " " + a.name + "=\"" + a.value + "\"";
  if (e.children.empty()) return s + "/>";
  s += ">";
  for (const Element& c : e.children) s += show(c);
  return s + "</" + e.name + ">";
}

// file:line:col: message [code], one line per diagnostic.
inline std::string errors(const LoadResult& r) {
  std::string s;
  for (const Diagnostic& d : r.diagnostics)
    s += d.file + ":" + std::to_string(d.line) + ":" + std::to_string(d.column) + ": " + d.message + " [" + d.code +
         "]\n";
  return s;
}

inline std::vector<const Element*> childrenNamed(const Element& e, const std::string& name) {
  std::vector<const Element*> out;
  for (const Element& c : e.children)
    if (c.name == name) out.push_back(&c);
  return out;
}

}  // namespace rscene::xml::test
