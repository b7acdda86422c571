#include "core/diff_value.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/text.hpp"

namespace rscene {
namespace {

// The decoded text of a raw token; `storage` holds it when decoding
// changes anything (most tokens need none, and cost no copy).
std::string_view decoded(std::string_view raw, std::string& storage) {
  if (raw != "-" && raw.find('%') == std::string_view::npos) return raw;
  if (findBadEscape(raw) != std::string_view::npos) return raw;  // the loader refuses these
  storage.clear();
  percentDecode(raw, storage);
  return storage;
}

// Calls f(item) for each item of a `,`/`;` list (none for empty text).
template <class F>
void forEachItem(std::string_view s, F&& f) {
  if (s.empty()) return;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= s.size(); ++i)
    if (i == s.size() || s[i] == ',' || s[i] == ';') {
      f(s.substr(start, i - start), i == s.size() ? '\0' : s[i]);
      start = i + 1;
    }
}

// A list split into items, grouped into entries: a fixed number of items
// per entry (3 for vec3 lists, 10 for transforms, 1 for number lists), or
// the `;` groups of a color list (rgb and rgba entries may mix).
struct Entries {
  std::vector<std::string_view> items;
  std::vector<std::uint32_t> start;  // first item of each entry, then items.size()
  std::size_t size() const { return start.size() - 1; }
  std::size_t width(std::size_t e) const { return start[e + 1] - start[e]; }
  std::string_view item(std::size_t e, std::size_t k) const { return items[start[e] + k]; }
};

std::size_t entryWidth(ValueType t) {
  switch (t) {
    case ValueType::Vec3List: return 3;
    case ValueType::TransformList: return 10;
    case ValueType::ColorList: return 0;  // `;` groups
    default: return 1;
  }
}

void split(std::string_view text, ValueType type, Entries& out) {
  std::size_t width = entryWidth(type);
  const bool groups = width == 0 && text.find(';') != std::string_view::npos;
  if (width == 0 && !groups) width = 4;
  char previous = ';';
  forEachItem(text, [&](std::string_view item, char sep) {
    if (groups ? previous == ';' : out.items.size() % width == 0)
      out.start.push_back(static_cast<std::uint32_t>(out.items.size()));
    out.items.push_back(item);
    previous = sep;
  });
  out.start.push_back(static_cast<std::uint32_t>(out.items.size()));
}

ValueType entryType(ValueType list) {
  switch (list) {
    case ValueType::NumberList: return ValueType::Number;
    case ValueType::IntegerList: return ValueType::Integer;
    case ValueType::Vec3List: return ValueType::Vec3;
    case ValueType::ColorList: return ValueType::Color;
    default: return ValueType::NumberList;
  }
}

// The parts of a transform list's entry, by their names in the spec.
struct Part {
  const char* name;
  std::size_t begin, end;
  ValueType type;
};
constexpr Part kTransformParts[] = {
    {"position", 0, 3, ValueType::Vec3}, {"orientation", 3, 7, ValueType::Quat}, {"scale", 7, 10, ValueType::Vec3}};

void appendItem(std::string& out, std::string_view item, bool integer, int version) {
  if (integer) {
    if (auto v = parseInteger(item)) return appendInteger(out, *v);
  } else if (auto v = parseNumber(item)) {
    return appendNumber(out, *v);
  }
  percentEncode(item, version, out);  // not a number: as written (validate reports it)
}

std::string joinItems(const Entries& l, std::size_t e, std::size_t begin, std::size_t end, bool integer,
                      int version) {
  std::string out;
  for (std::size_t k = begin; k < end; ++k) {
    if (k > begin) out.push_back(',');
    appendItem(out, l.item(e, k), integer, version);
  }
  return out;
}

bool isList(const DiffValue& v) {
  return isNumericList(v.type) && componentCount(v.type) == 0 && v.tokens.size() == 1;
}

// The one line that stands for a long list's change ("19 values, 3
// changed, max |delta| ...") above the entries listed under it.
FieldDiff listSummary(const DiffValue& b, const Entries& la, const Entries& lb, std::size_t changed, double maxDelta) {
  FieldDiff summary;
  summary.name = b.name;
  summary.type = b.type;
  summary.summarized = true;
  summary.oldCount = la.size();
  summary.newCount = lb.size();
  summary.changedCount = changed;
  summary.maxDelta = maxDelta;
  return summary;
}

}  // namespace

bool ValueComparer::closeEnough(double x, double y) const {
  if (x == y) return true;
  double d = std::fabs(x - y);
  return d <= opt_.tolerance || d <= opt_.relTolerance * std::max(std::fabs(x), std::fabs(y));
}

// Decoded numbers item by item (vectors, colors, quaternions in one token).
// Values that mean the same are the same: a color without alpha and the
// same color with alpha 1 (alpha defaults to 1), and a quaternion and its
// negation (the same rotation).
bool ValueComparer::sameNumbers(std::string_view x, std::string_view y, ValueType type) const {
  std::vector<std::string_view> ix, iy;
  forEachItem(x, [&](std::string_view s, char) { ix.push_back(s); });
  forEachItem(y, [&](std::string_view s, char) { iy.push_back(s); });
  return sameItems(ix, iy, type);
}

bool ValueComparer::sameItems(std::vector<std::string_view> ix, std::vector<std::string_view> iy,
                              ValueType type) const {
  if (type == ValueType::Color && ix.size() + iy.size() == 7) {
    std::vector<std::string_view>& longer = ix.size() == 4 ? ix : iy;
    auto alpha = parseNumber(longer[3]);
    if (!alpha || !closeEnough(*alpha, 1)) return false;
    longer.pop_back();
  }
  if (ix.size() != iy.size()) return false;
  std::vector<double> nx(ix.size()), ny(iy.size());
  bool same = true;
  for (std::size_t i = 0; i < ix.size(); ++i) {
    auto px = parseNumber(ix[i]), py = parseNumber(iy[i]);
    if (!px || !py) {
      if (ix[i] != iy[i]) return false;
      continue;
    }
    nx[i] = *px, ny[i] = *py;
    same = same && (ix[i] == iy[i] || closeEnough(*px, *py));
  }
  if (same || type != ValueType::Quat || nx.size() != 4) return same;
  for (std::size_t i = 0; i < 4; ++i)
    if (!closeEnough(nx[i], -ny[i])) return false;
  return true;
}

bool ValueComparer::sameToken(std::string_view x, std::string_view y, ValueType type, const FieldDef* def) const {
  if (x == y) return true;
  std::string sx, sy;
  std::string_view dx = decoded(x, sx), dy = decoded(y, sy);
  switch (type) {
    case ValueType::Number: {
      auto px = parseNumber(dx), py = parseNumber(dy);
      if (px && py) return closeEnough(*px, *py);
      break;
    }
    case ValueType::Integer: {
      auto px = parseInteger(dx), py = parseInteger(dy);
      if (px && py) return *px == *py;
      // `2.0` is not integer syntax (validate says so) but is still the number 2.
      auto nx = parseNumber(dx), ny = parseNumber(dy);
      if (nx && ny) return *nx == *ny;
      break;
    }
    case ValueType::Group: {
      auto px = parseGroup(dx), py = parseGroup(dy);
      if (px && py) return *px == *py;
      break;
    }
    case ValueType::Flag: {
      auto px = parseFlag(dx), py = parseFlag(dy);
      if (px && py) return *px == *py;
      break;
    }
    case ValueType::Name:
      if (def && def->enumDef) {
        auto cx = def->enumDef->canonical(dx), cy = def->enumDef->canonical(dy);
        if (cx && cy) return *cx == *cy;
      }
      break;
    case ValueType::StringList:
      return parseStringList(x) == parseStringList(y);
    default:
      if (componentCount(type) > 0) return sameNumbers(dx, dy, type);
      break;
  }
  return dx == dy;
}

void ValueComparer::compare(const DiffValue& a, const DiffValue& b, std::vector<FieldDiff>& out) const {
  if (isList(a) && isList(b)) return compareList(a, b, out);
  if (a.tokens.size() == b.tokens.size()) {
    // A vector written over several positional tokens: one number each.
    const ValueType type = b.tokens.size() > 1 && !b.unknownTokens ? ValueType::Number : b.type;
    bool same = true;
    for (std::size_t i = 0; i < b.tokens.size() && same; ++i) same = sameToken(a.tokens[i], b.tokens[i], type, b.def);
    if (same) return;
    if (b.type == ValueType::Quat && b.tokens.size() == 4 && !b.unknownTokens) {  // q and -q
      std::vector<std::string_view> qa(a.tokens.begin(), a.tokens.end()), qb(b.tokens.begin(), b.tokens.end());
      if (sameItems(qa, qb, ValueType::Quat)) return;
    }
  }
  out.push_back(wholeChange(a, b));
}

// The field as a whole, old value to new.
FieldDiff ValueComparer::wholeChange(const DiffValue& a, const DiffValue& b) const {
  FieldDiff f;
  f.name = b.name;
  f.type = b.type;
  f.oldValue = display(a, oldVersion_);
  f.newValue = display(b, newVersion_);
  return f;
}

void ValueComparer::compareList(const DiffValue& a, const DiffValue& b, std::vector<FieldDiff>& out) const {
  if (a.tokens[0] == b.tokens[0]) return;
  std::string sa, sb;
  Entries la, lb;
  split(decoded(a.tokens[0], sa), b.type, la);
  split(decoded(b.tokens[0], sb), b.type, lb);
  const bool integer = b.type == ValueType::IntegerList;

  double maxDelta = 0;
  auto sameRange = [&](std::size_t e, std::size_t begin, std::size_t end) {
    bool same = true;
    for (std::size_t k = begin; k < end; ++k) {
      std::string_view x = la.item(e, k), y = lb.item(e, k);
      if (x == y) continue;
      if (integer) {
        auto px = parseInteger(x), py = parseInteger(y);
        if (px && py) {  // exact: ids and indices, no tolerance
          maxDelta = std::max(maxDelta, std::fabs(static_cast<double>(*px) - static_cast<double>(*py)));
          same = same && *px == *py;
          continue;
        }
      }
      // Numbers; also integers written as `2.0`, which are still the number 2.
      if (auto px = parseNumber(x), py = parseNumber(y); px && py) {
        maxDelta = std::max(maxDelta, std::fabs(*px - *py));
        if (closeEnough(*px, *py)) continue;
      }
      same = false;
    }
    return same;
  };
  const std::size_t common = std::min(la.size(), lb.size());
  std::size_t changed = 0;
  std::vector<std::size_t> named;  // changed entries to name, the first listEntries
  for (std::size_t e = 0; e < common; ++e) {
    if (la.width(e) == lb.width(e) && sameRange(e, 0, la.width(e))) continue;
    if (changed++ < opt_.listEntries) named.push_back(e);
  }
  if (!changed && la.size() == lb.size()) return;

  if (std::max(la.items.size(), lb.items.size()) <= opt_.summarizeAbove) {
    out.push_back(wholeChange(a, b));
    return;
  }
  const std::size_t at = out.size();
  out.push_back(listSummary(b, la, lb, changed, maxDelta));

  const ValueType itemType = entryType(b.type);
  auto entryName = [&](std::size_t e) { return std::string(b.name) + "[" + std::to_string(e) + "]"; };
  std::size_t listed = 0;
  for (std::size_t e : named) {
    ++listed;
    if (b.type == ValueType::TransformList && la.width(e) == 10 && lb.width(e) == 10) {
      for (const Part& p : kTransformParts) {
        if (sameRange(e, p.begin, p.end)) continue;
        FieldDiff f;
        f.name = entryName(e) + "." + p.name;
        f.entry = true;
        f.type = p.type;
        f.oldValue = joinItems(la, e, p.begin, p.end, false, oldVersion_);
        f.newValue = joinItems(lb, e, p.begin, p.end, false, newVersion_);
        out.push_back(std::move(f));
      }
      continue;
    }
    FieldDiff f;
    f.name = entryName(e);
    f.entry = true;
    f.type = itemType;
    f.oldValue = joinItems(la, e, 0, la.width(e), integer, oldVersion_);
    f.newValue = joinItems(lb, e, 0, lb.width(e), integer, newVersion_);
    out.push_back(std::move(f));
  }
  // Entries only one side has: appended or cut off at the end.
  const Entries& longer = la.size() > lb.size() ? la : lb;
  for (std::size_t e = common; e < longer.size() && listed < opt_.listEntries; ++e, ++listed) {
    FieldDiff f;
    f.name = entryName(e);
    f.entry = true;
    f.type = itemType;
    f.change = &longer == &lb ? Change::Added : Change::Removed;
    std::string text = joinItems(longer, e, 0, longer.width(e), integer, &longer == &lb ? newVersion_ : oldVersion_);
    (f.change == Change::Added ? f.newValue : f.oldValue) = std::move(text);
    out.push_back(std::move(f));
  }
  out[at].listedCount = listed;
}

bool ValueComparer::compareNamed(const DiffValue& a, const DiffValue& b, const std::vector<std::string>& namesA,
                                 const std::vector<std::string>& namesB, std::vector<FieldDiff>& out) const {
  if (!isList(a) || !isList(b) || b.type != ValueType::NumberList) return false;
  std::string sa, sb;
  Entries la, lb;
  split(decoded(a.tokens[0], sa), b.type, la);
  split(decoded(b.tokens[0], sb), b.type, lb);
  if (la.size() != namesA.size() || lb.size() != namesB.size()) return false;
  std::unordered_map<std::string_view, std::size_t> inA;
  for (std::size_t i = 0; i < namesA.size(); ++i)
    if (!inA.emplace(namesA[i], i).second) return false;  // names that do not identify entries
  std::unordered_map<std::string_view, std::size_t> inB;
  for (std::size_t j = 0; j < namesB.size(); ++j)
    if (!inB.emplace(namesB[j], j).second) return false;

  std::vector<FieldDiff> entries;
  std::size_t changed = 0;
  double maxDelta = 0;
  auto entry = [&](const std::string& name, Change c, std::string oldText, std::string newText) {
    FieldDiff f;
    f.name = std::string(b.name) + "[" + name + "]";
    f.type = ValueType::Number;
    f.change = c;
    f.oldValue = std::move(oldText);
    f.newValue = std::move(newText);
    entries.push_back(std::move(f));
  };
  std::vector<char> matched(namesA.size(), 0);
  for (std::size_t j = 0; j < namesB.size(); ++j) {
    auto it = inA.find(namesB[j]);
    if (it == inA.end()) {
      entry(namesB[j], Change::Added, {}, joinItems(lb, j, 0, 1, false, newVersion_));
      continue;
    }
    matched[it->second] = 1;
    std::string_view x = la.item(it->second, 0), y = lb.item(j, 0);
    if (x == y) continue;
    auto px = parseNumber(x), py = parseNumber(y);
    if (px && py) {
      maxDelta = std::max(maxDelta, std::fabs(*px - *py));
      if (closeEnough(*px, *py)) continue;
    }
    ++changed;
    entry(namesB[j], Change::Changed, joinItems(la, it->second, 0, 1, false, oldVersion_),
          joinItems(lb, j, 0, 1, false, newVersion_));
  }
  for (std::size_t i = 0; i < namesA.size(); ++i)
    if (!matched[i]) entry(namesA[i], Change::Removed, joinItems(la, i, 0, 1, false, oldVersion_), {});
  if (entries.empty()) return true;

  // A long list keeps its summary line, with the first listEntries below it.
  if (std::max(la.items.size(), lb.items.size()) > opt_.summarizeAbove) {
    FieldDiff summary = listSummary(b, la, lb, changed, maxDelta);
    if (entries.size() > opt_.listEntries) entries.resize(opt_.listEntries);
    summary.listedCount = entries.size();
    for (FieldDiff& f : entries) f.entry = true;
    out.push_back(std::move(summary));
  }
  for (FieldDiff& f : entries) out.push_back(std::move(f));
  return true;
}

void ValueComparer::whole(const DiffValue& v, bool isOld, std::vector<FieldDiff>& out) const {
  FieldDiff f;
  f.name = v.name;
  f.type = v.type;
  f.change = isOld ? Change::Removed : Change::Added;
  if (isList(v)) {
    std::string storage;
    Entries l;
    split(decoded(v.tokens[0], storage), v.type, l);
    if (l.items.size() > opt_.summarizeAbove) {
      f.summarized = true;
      (isOld ? f.oldCount : f.newCount) = l.size();
      out.push_back(std::move(f));
      return;
    }
  }
  (isOld ? f.oldValue : f.newValue) = display(v, isOld ? oldVersion_ : newVersion_);
  out.push_back(std::move(f));
}

std::string ValueComparer::display(const DiffValue& v, int version) {
  std::string out;
  const ValueType type = v.tokens.size() > 1 && !v.unknownTokens ? ValueType::Number : v.type;
  for (std::size_t i = 0; i < v.tokens.size(); ++i) {
    if (i) out.push_back(v.unknownTokens ? ' ' : ',');
    appendCanonical(out, v.tokens[i], type, version);
  }
  return out;
}

}  // namespace rscene
