// object_class instances (WorldConfigurationFile.rst, "object_class"): a
// class is written in its own vocabulary (<dimension>, <file name>,
// <scale x y z>, compound children with object_param/pos/quat) and becomes
// the element the mapping reads (<dim>, file_name/scale attributes,
// children with <dim> and <state>).
#include <algorithm>
#include <array>
#include <cctype>

#include "xml/expand.hpp"
#include "xml/xml_source.hpp"

namespace rscene::xml {
namespace {

std::vector<std::string> words(std::string_view s) {
  std::vector<std::string> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    std::size_t j = i;
    while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j]))) ++j;
    if (j > i) out.emplace_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

// Sets `name` unless already there (the instance's own value wins).
void setAttribute(std::vector<Attribute>& attributes, Attribute a) {
  for (Attribute& existing : attributes)
    if (existing.name == a.name) {
      existing = std::move(a);
      return;
    }
  attributes.push_back(std::move(a));
}

// The dim attributes object_param gives each primitive, in order.
const std::vector<const char*>* dimNames(std::string_view shape) {
  static const std::vector<const char*> sphere{"radius"}, box{"x", "y", "z"}, round{"radius", "height"};
  if (shape == "sphere") return &sphere;
  if (shape == "box") return &box;
  if (shape == "capsule" || shape == "cylinder") return &round;
  return nullptr;
}

// <sphere object_param="r" pos="..." quat="..." material=".."/> ->
// <sphere material=".."><dim radius="r"/><state pos="..." quat="..."/></sphere>
bool convertCompoundChild(const Element& in, Element& out, Diagnostics& diagnostics) {
  const std::vector<const char*>* names = dimNames(in.name);
  if (!names) {
    diagnostics.push_back(elementDiagnostic(Severity::Error, code::kXmlClass, in,
                                            "a compound class's child is a sphere, box, capsule or cylinder"));
    return false;
  }
  const Attribute* param = in.attribute("object_param");
  const Attribute* pos = in.attribute("pos");
  if (!param || !pos) {
    diagnostics.push_back(elementDiagnostic(Severity::Error, code::kXmlClass, in,
                                            std::string("no ") + (param ? "pos" : "object_param") +
                                                " (a compound class's child needs object_param and pos)"));
    return false;
  }
  std::vector<std::string> values = words(param->value);
  if (values.size() != names->size()) {
    std::string expected;
    for (const char* n : *names) expected += (expected.empty() ? "" : " ") + std::string(n);
    diagnostics.push_back(attributeDiagnostic(Severity::Error, code::kXmlClass, in, *param,
                                              "a " + in.name + " takes " + std::to_string(names->size()) +
                                                  " number" + (names->size() > 1 ? "s" : "") + " (" + expected +
                                                  "), found " + std::to_string(values.size())));
    return false;
  }
  out.name = in.name;
  out.where = in.where;
  Element dim{"dim", {}, {}, param->where};
  for (std::size_t i = 0; i < values.size(); ++i) dim.attributes.push_back({(*names)[i], values[i], param->where});
  Element state{"state", {}, {}, pos->where};
  state.attributes.push_back({"pos", pos->value, pos->where});
  for (const Attribute& a : in.attributes) {
    if (a.name == "quat") state.attributes.push_back(a);
    else if (a.name != "object_param" && a.name != "pos") out.attributes.push_back(a);
  }
  out.children.push_back(std::move(dim));
  out.children.push_back(std::move(state));
  return true;
}

// The class's children in the mapping's vocabulary; `derived` receives the
// attributes that <file> and <scale> stand for.
bool convertClassChildren(const Element& cls, std::vector<Element>& children, std::vector<Attribute>& derived,
                          Diagnostics& diagnostics) {
  bool ok = true;
  for (const Element& c : cls.children) {
    if (c.name == "dimension") {
      Element dim = c;
      dim.name = "dim";
      children.push_back(std::move(dim));
    } else if (c.name == "file") {
      const Attribute* name = c.attribute("name");
      if (!name) {
        diagnostics.push_back(elementDiagnostic(Severity::Error, code::kXmlClass, c, "no name (the mesh file)"));
        ok = false;
        continue;
      }
      derived.push_back({"file_name", name->value, name->where});
    } else if (c.name == "scale") {
      std::string value;
      for (const char* axis : {"x", "y", "z"}) {
        const Attribute* a = c.attribute(axis);
        if (!a) {
          diagnostics.push_back(elementDiagnostic(Severity::Error, code::kXmlClass, c,
                                                  std::string("no ") + axis + " (a scale has x, y and z)"));
          ok = false;
          break;
        }
        value += (value.empty() ? "" : " ") + a->value;
      }
      derived.push_back({"scale", value, c.where});
    } else if (c.name == "children") {
      Element list{"children", c.attributes, {}, c.where};
      for (const Element& child : c.children) {
        Element converted;
        if (convertCompoundChild(child, converted, diagnostics)) list.children.push_back(std::move(converted));
        else ok = false;
      }
      children.push_back(std::move(list));
    } else {
      children.push_back(c);  // <inertia> and what the mapping knows
    }
  }
  return ok;
}

}  // namespace

bool isBuiltInElement(std::string_view name) {
  static constexpr std::array<std::string_view, 17> kBuiltIn = {
      "sphere", "box",  "capsule", "cylinder", "mesh",  "compound", "ground",       "heightmap",         "wire",
      "array",  "include", "params", "object_class", "objects", "material", "articulatedSystem", "articulated_system"};
  return std::find(kBuiltIn.begin(), kBuiltIn.end(), name) != kBuiltIn.end();
}

bool applyClass(const Element& cls, Element& instance, Diagnostics& diagnostics) {
  const Attribute* type = cls.attribute("type");
  if (!type || type->value.empty()) {
    diagnostics.push_back(elementDiagnostic(Severity::Error, code::kXmlClass, cls,
                                            "no type (the element a class stands for: sphere, box, mesh ...)"));
    return false;
  }
  Element merged;
  merged.name = type->value;
  merged.where = instance.where;
  for (const Attribute& a : cls.attributes)
    if (a.name != "type") merged.attributes.push_back(a);
  std::vector<Attribute> derived;
  if (!convertClassChildren(cls, merged.children, derived, diagnostics)) return false;
  for (Attribute& a : derived) setAttribute(merged.attributes, std::move(a));
  for (Attribute& a : instance.attributes) setAttribute(merged.attributes, std::move(a));
  // An instance child replaces the class's child of the same name (its own
  // <dim>, <inertia>); the others (<state>) follow the class's.
  const std::ptrdiff_t fromClass = static_cast<std::ptrdiff_t>(merged.children.size());
  for (Element& child : instance.children) {
    auto classEnd = merged.children.begin() + fromClass;
    auto same = std::find_if(merged.children.begin(), classEnd,
                             [&](const Element& c) { return c.name == child.name; });
    if (same != classEnd) *same = std::move(child);
    else merged.children.push_back(std::move(child));
  }
  instance = std::move(merged);
  return true;
}

}  // namespace rscene::xml
