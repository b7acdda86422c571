#include "rscene-diff/render.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <map>

namespace rscene::diffout {
namespace {

const char* kGreen = "\033[32m";
const char* kRed = "\033[31m";
const char* kYellow = "\033[33m";
const char* kReset = "\033[0m";

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// `heights: 25 values, 2 changed, max |delta| 0.03`; structured lists
// count entries (a transform, a vec3), number lists values.
std::string summary(const FieldDiff& f) {
  const char* unit =
      f.type == ValueType::NumberList || f.type == ValueType::IntegerList ? " values" : " entries";
  std::string s;
  if (f.change != Change::Changed)  // a whole list one side has
    return std::to_string(f.change == Change::Added ? f.newCount : f.oldCount) + unit;
  if (f.oldCount != f.newCount) {
    s = std::to_string(f.oldCount) + " -> " + std::to_string(f.newCount) + unit;
    if (f.changedCount) s += ", " + std::to_string(f.changedCount) + " of the common ones changed";
  } else {
    s = std::to_string(f.newCount) + unit + ", " + std::to_string(f.changedCount) + " changed";
  }
  if (f.maxDelta > 0) s += ", max |delta| " + number(f.maxDelta);
  std::size_t differing = f.changedCount + (f.oldCount > f.newCount ? f.oldCount - f.newCount : f.newCount - f.oldCount);
  if (f.listedCount < differing) s += " (the first " + std::to_string(f.listedCount) + " below)";
  return s;
}

std::string value(const std::string& text, bool isDefault) { return isDefault ? text + " (default)" : text; }

std::string label(const RecordDiff& r) {
  std::string s = r.tag;
  if (!r.path.empty()) s += " " + r.path;
  else if (!r.key.empty() && r.key != r.tag) s += " " + r.key;
  if (r.renamed()) {
    std::string_view from = r.oldPath, to = r.path;
    std::string_view fromDir = from.substr(0, from.rfind('/') + 1), toDir = to.substr(0, to.rfind('/') + 1);
    s += std::string(fromDir == toDir ? " (renamed from " : " (moved from ") + r.oldPath + ")";
  }
  return s;
}

}  // namespace

std::string blocks(const DiffResult& result, bool color) {
  std::string out;
  for (const RecordDiff& r : result.records) {
    const char* sign = r.change == Change::Added ? "+" : r.change == Change::Removed ? "-" : "~";
    const char* paint = r.change == Change::Added ? kGreen : r.change == Change::Removed ? kRed : kYellow;
    if (color) out += paint;
    out += std::string(sign) + " " + label(r);
    if (color) out += kReset;
    out.push_back('\n');
    // An added or removed record's fields are all added or removed: no sign.
    const bool whole = r.change != Change::Changed;
    for (const FieldDiff& f : r.fields) {
      out += "    ";
      if (!whole && f.change == Change::Added) out += color ? std::string(kGreen) + "+ " + kReset : "+ ";
      if (!whole && f.change == Change::Removed) out += color ? std::string(kRed) + "- " + kReset : "- ";
      // A key named like a positional field of its kind is another field.
      out += f.name + (f.keyForm ? " (key): " : ": ");
      if (f.summarized) out += summary(f);
      else if (f.change == Change::Added) out += f.newValue;
      else if (f.change == Change::Removed) out += f.oldValue;
      else out += value(f.oldValue, f.oldDefault) + " -> " + value(f.newValue, f.newDefault);
      out.push_back('\n');
    }
  }
  return out;
}

std::string stat(const DiffResult& result) {
  std::map<std::string, std::array<std::size_t, 3>> perTag;
  std::size_t width = 0;
  for (const RecordDiff& r : result.records) {
    perTag[r.tag][static_cast<int>(r.change)]++;
    width = std::max(width, r.tag.size());
  }
  auto counts = [](std::size_t added, std::size_t removed, std::size_t changed) {
    std::string s;
    auto add = [&](std::size_t n, const char* what) {
      if (!n) return;
      if (!s.empty()) s += ", ";
      s += std::to_string(n) + " " + what;
    };
    add(changed, "changed");
    add(added, "added");
    add(removed, "removed");
    return s;
  };
  std::string out;
  for (const auto& [tag, c] : perTag)
    out += " " + tag + std::string(width - tag.size(), ' ') + "  " +
           counts(c[static_cast<int>(Change::Added)], c[static_cast<int>(Change::Removed)],
                  c[static_cast<int>(Change::Changed)]) +
           "\n";
  std::size_t n = result.records.size();
  out += " " + std::to_string(n) + (n == 1 ? " record: " : " records: ") +
         counts(result.count(Change::Added), result.count(Change::Removed), result.count(Change::Changed)) + "\n";
  return out;
}

}  // namespace rscene::diffout
