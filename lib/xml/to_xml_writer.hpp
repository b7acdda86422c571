// rscene-to-xml's output: a small element tree printed as RaiSim's
// examples are (4-space indent, one element per line, `<tag a="v"/>` when
// empty), with attribute values escaped and numbers in their shortest
// round-trip spelling.  Printing is deterministic: attributes and children
// come out in the order they were added.
#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rscene::xml {

struct OutElement {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;
  std::vector<OutElement> children;
  // Whether a value could not be written (a non-finite number, a control
  // character XML 1.0 cannot hold): the exporter refuses the document.
  bool bad = false;
  std::string badWhat;  // the attribute that was refused, for the message

  explicit OutElement(std::string n) : name(std::move(n)) {}
  OutElement& text(std::string_view attribute, std::string_view value);
  OutElement& number(std::string_view attribute, double value);
  OutElement& integer(std::string_view attribute, std::int64_t value);
  // Numbers separated by single spaces (vectors, height lists, qpos).
  OutElement& numbers(std::string_view attribute, const double* values, std::size_t count);
  OutElement& vec3(std::string_view attribute, const Eigen::Vector3d& v) { return numbers(attribute, v.data(), 3); }
  OutElement& numbers(std::string_view attribute, const std::vector<double>& v) {
    return numbers(attribute, v.data(), v.size());
  }
  OutElement& add(OutElement child);  // appends; returns *this
  // First problem in this element or below ("<sphere> mass"), empty when none.
  std::string firstProblem() const;
};

// `v` as an attribute value: & < > " escaped, tab/LF/CR as character
// references (so a reader's whitespace normalisation keeps them).  False
// when `v` holds what XML 1.0 cannot represent (other C0 controls, bytes
// that are not UTF-8, U+FFFE, U+FFFF); those are written as '?'.
bool escapeAttribute(std::string_view v, std::string& out);

// The whole document: XML declaration, then `root` and a final newline.
std::string printDocument(const OutElement& root);

// A collision group or mask in RaiSim's notation: `collision[-1]` for all
// 64 bits, `collision[i|j|...]` when 1 to 8 bits are set, else the decimal.
std::string collisionBits(std::uint64_t bits);

}  // namespace rscene::xml
