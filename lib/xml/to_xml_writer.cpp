#include "xml/to_xml_writer.hpp"

#include <bit>
#include <cmath>

#include "core/text.hpp"

namespace rscene::xml {

OutElement& OutElement::text(std::string_view attribute, std::string_view value) {
  std::string escaped;
  if (!escapeAttribute(value, escaped) && !bad) {
    bad = true;
    badWhat = std::string(attribute);
  }
  attributes.emplace_back(std::string(attribute), std::move(escaped));
  return *this;
}

OutElement& OutElement::number(std::string_view attribute, double value) { return numbers(attribute, &value, 1); }

OutElement& OutElement::integer(std::string_view attribute, std::int64_t value) {
  std::string s;
  appendInteger(s, value);
  attributes.emplace_back(std::string(attribute), std::move(s));
  return *this;
}

OutElement& OutElement::numbers(std::string_view attribute, const double* values, std::size_t count) {
  std::string s;
  s.reserve(count * 4);
  for (std::size_t i = 0; i < count; ++i) {
    if (i) s += ' ';
    if (!std::isfinite(values[i]) && !bad) {
      bad = true;  // a non-finite number is never written (DESIGN.md, Resources)
      badWhat = std::string(attribute);
    }
    appendNumber(s, values[i] == 0 ? 0.0 : values[i]);  // one zero: "-0" is written "0" (as from-xml writes it)
  }
  attributes.emplace_back(std::string(attribute), std::move(s));
  return *this;
}

OutElement& OutElement::add(OutElement child) {
  children.push_back(std::move(child));
  return *this;
}

std::string OutElement::firstProblem() const {
  if (bad) return "<" + name + "> " + badWhat;
  for (const OutElement& c : children)
    if (std::string p = c.firstProblem(); !p.empty()) return p;
  return {};
}

bool escapeAttribute(std::string_view v, std::string& out) {
  bool ok = true;
  for (std::size_t i = 0; i < v.size(); ++i) {
    char c = v[i];
    switch (c) {
      case '&': out += "&amp;"; continue;
      case '<': out += "&lt;"; continue;
      case '>': out += "&gt;"; continue;
      case '"': out += "&quot;"; continue;
      case '\t': out += "&#9;"; continue;
      case '\n': out += "&#10;"; continue;
      case '\r': out += "&#13;"; continue;
      default: break;
    }
    auto u = static_cast<unsigned char>(c);
    if (u < 0x20) {  // other C0 controls: not even a character reference may name them
      ok = false;
      out += '?';
      continue;
    }
    if (u < 0x80) {
      out += c;
      continue;
    }
    // A document without an encoding declaration is UTF-8: a byte that
    // starts no valid sequence (a name percent-encoded from Latin-1), or
    // U+FFFE / U+FFFF, would make it not well-formed.
    std::size_t n = utf8SequenceLength(v, i);
    std::string_view seq = v.substr(i, n);
    if (n == 0 || seq == "\xEF\xBF\xBE" || seq == "\xEF\xBF\xBF") {
      ok = false;
      out += '?';
      continue;
    }
    out += seq;
    i += n - 1;
  }
  return ok;
}

namespace {

void print(const OutElement& e, int depth, std::string& out) {
  out.append(static_cast<std::size_t>(depth) * 4, ' ');
  out += '<';
  out += e.name;
  for (const auto& [name, value] : e.attributes) {
    out += ' ';
    out += name;
    out += "=\"";
    out += value;
    out += '"';
  }
  if (e.children.empty()) {
    out += "/>\n";
    return;
  }
  out += ">\n";
  for (const OutElement& c : e.children) print(c, depth + 1, out);
  out.append(static_cast<std::size_t>(depth) * 4, ' ');
  out += "</";
  out += e.name;
  out += ">\n";
}

}  // namespace

std::string printDocument(const OutElement& root) {
  std::string out = "<?xml version=\"1.0\" ?>\n";
  print(root, 0, out);
  return out;
}

std::string collisionBits(std::uint64_t bits) {
  if (bits == ~std::uint64_t{0}) return "collision[-1]";
  int count = std::popcount(bits);
  if (count < 1 || count > 8) return std::to_string(bits);
  std::string s = "collision[";
  bool first = true;
  for (int i = 0; i < 64; ++i) {
    if (!(bits >> i & 1)) continue;
    if (!first) s += '|';
    s += std::to_string(i);
    first = false;
  }
  return s + "]";
}

}  // namespace rscene::xml
