#include "xml/xml_tree.hpp"

namespace rscene::xml {

const Attribute* Element::attribute(std::string_view n, std::string_view alias) const {
  for (const Attribute& a : attributes)
    if (a.name == n) return &a;
  if (!alias.empty())
    for (const Attribute& a : attributes)
      if (a.name == alias) return &a;
  return nullptr;
}

const Element* Element::child(std::string_view n, std::string_view alias) const {
  for (const Element& c : children)
    if (c.name == n) return &c;
  if (!alias.empty())
    for (const Element& c : children)
      if (c.name == alias) return &c;
  return nullptr;
}

namespace {
Diagnostic at(Severity severity, const char* code, const Where& where, std::string message) {
  Diagnostic d;
  d.severity = severity;
  d.code = code;
  d.file = where.file;
  d.line = where.line;
  d.column = where.column;
  d.message = std::move(message);
  return d;
}
}  // namespace

Diagnostic elementDiagnostic(Severity severity, const char* code, const Element& element, std::string message) {
  Diagnostic d = at(severity, code, element.where, "<" + element.name + ">: " + std::move(message));
  d.tag = element.name;
  return d;
}

Diagnostic attributeDiagnostic(Severity severity, const char* code, const Element& element,
                               const Attribute& attribute, std::string message) {
  Diagnostic d = at(severity, code, attribute.where.line ? attribute.where : element.where,
                    "<" + element.name + "> " + attribute.name + ": " + std::move(message));
  d.tag = element.name;
  d.field = attribute.name;
  return d;
}

}  // namespace rscene::xml
