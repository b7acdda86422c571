// RS1101, RS2xxx, RS3001/RS3002: every token against its type in the
// schema, repeated and unknown keys, unknown tags.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>

#include "core/codes.hpp"
#include "core/check_context.hpp"
#include "core/suggest.hpp"
#include "core/text.hpp"

namespace rscene::checks {
namespace {

std::string quoted(std::string_view s) {
  constexpr std::size_t kMax = 40;
  std::string q(1, '\'');
  q.append(s.substr(0, kMax));
  q.append(s.size() > kMax ? "...'" : "'");
  return q;
}

// Why a token that should be a number is not one.
void badNumber(Context& ctx, const Record& r, Span at, std::string_view field, std::string_view s) {
  double v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  bool parsed = p == s.data() + s.size() && !s.empty();
  if (parsed && (ec == std::errc::result_out_of_range || !std::isfinite(v)))
    ctx.report(rs::RS2002, r, at, field, "number " + quoted(s) + " is not finite", "numbers must be finite decimals");
  else if (s.empty())
    ctx.report(rs::RS2001, r, at, field, "expected a number, found nothing");
  else
    ctx.report(rs::RS2001, r, at, field, "expected a number, found " + quoted(s),
               s.find(',') != std::string_view::npos ? "decimals use `.`; `,` separates list items" : "");
}

class TypeChecker {
 public:
  TypeChecker(Context& ctx, const Record& r) : ctx_(ctx), r_(r), doc_(ctx.doc) {}

  void run() {
    const KindDef& kind = *r_.kind;
    if (const Layout* layout = kind.layoutFor(r_.positionalCount)) positionals(*layout);
    keys(kind);
  }

 private:
  void positionals(const Layout& layout) {
    for (std::size_t t = 0; t < layout.tokens.size();) {
      const FieldDef& def = layout.fields[static_cast<std::size_t>(layout.tokens[t].first)];
      const Field* f = r_.interleaved ? doc_.positional(r_, static_cast<std::uint32_t>(t)) : &doc_.field(r_, static_cast<std::uint32_t>(t));
      if (def.width == 1 && componentCount(def.type) > 0) {
        vectorKey(def, f->value, doc_.text(f->value));  // csv3: a vector in one token (articulated_ik target)
      } else if (def.width == 1) {
        scalar(def, f->value, doc_.text(f->value));
      } else {
        double q[4] = {0, 0, 0, 0};
        bool all = true;
        for (int c = 0; c < def.width; ++c) {
          Span s = (f + c)->value;
          auto v = number(s, def.name, doc_.text(s));
          if (v && c < 4) q[c] = *v;
          all = all && v;
        }
        if (all && def.type == ValueType::Quat) checkQuaternion(ctx_, r_, f->value, def.name, q);
      }
      t += static_cast<std::size_t>(def.width);
    }
  }

  void keys(const KindDef& kind) {
    for (std::uint32_t j = r_.positionalCount; j < r_.fieldCount; ++j) {
      const Field& f = doc_.field(r_, j);
      if (!f.isKey()) continue;
      std::string_view name = doc_.text(f.key);
      if (ctx_.repeatedKey(j)) {
        if (ctx_.raisim())
          ctx_.report(rs::RS6002, r_, f.key, name, "key '" + std::string(name) + "' repeated; RaiSim refuses the record");
        else
          ctx_.report(rs::RS1101, r_, f.key, name, "key '" + std::string(name) + "' repeated; the last value wins",
                      "remove the earlier one");
      }
      const FieldDef* def = ctx_.defOf(j);
      if (!def) {
        unknownKey(kind, f.key, name);
        continue;
      }
      if (def->type == ValueType::Name || def->type == ValueType::Text || def->type == ValueType::Path ||
          def->type == ValueType::Id || def->type == ValueType::Ref || def->type == ValueType::StringList ||
          componentCount(def->type) == 0)
        scalar(*def, f.value, doc_.text(f.value));
      else
        vectorKey(*def, f.value, doc_.text(f.value));
    }
  }

  void unknownKey(const KindDef& kind, Span at, std::string_view name) {
    const std::string& best = ctx_.suggestion(&kind, name);
    ctx_.report(rs::RS3002, r_, at, name, "unknown key '" + std::string(name) + "' for " + kind.tag,
                best.empty() ? std::string() : "did you mean `" + best + "`?");
  }

  // Decoded text of a raw token (a scratch copy only when it has escapes).
  std::string_view decode(std::string_view raw) { return Context::decode(raw, scratch_); }

  std::optional<double> number(Span at, std::string_view field, std::string_view raw) {
    if (auto v = parseNumber(raw)) return v;  // most values have no escapes to decode
    std::string_view s = decode(raw);
    if (auto v = parseNumber(s)) return v;
    badNumber(ctx_, r_, at, field, s);
    return std::nullopt;
  }

  void scalar(const FieldDef& def, Span at, std::string_view raw) {
    std::string_view s;
    switch (def.type) {
      case ValueType::Number:
        number(at, def.name, raw);
        return;
      case ValueType::Integer:
        // Text that parses has no escapes: decode only the rest.
        if (auto v = parseInteger(raw); v && *v >= INT32_MIN && *v <= INT32_MAX) return;
        s = decode(raw);
        if (auto v = parseInteger(s); !v || *v < INT32_MIN || *v > INT32_MAX)
          ctx_.report(rs::RS2003, r_, at, def.name, "expected a 32-bit integer, found " + quoted(s));
        return;
      case ValueType::Group:
        if (parseGroup(raw)) return;
        s = decode(raw);
        if (!parseGroup(s))
          ctx_.report(rs::RS2004, r_, at, def.name, "expected an unsigned 64-bit integer, found " + quoted(s),
                      "all bits is 18446744073709551615");
        return;
      case ValueType::Flag:
        if (parseFlag(raw)) return;
        s = decode(raw);
        if (!parseFlag(s))
          ctx_.report(rs::RS2005, r_, at, def.name, "expected a flag, found " + quoted(s),
                      "write true or false");
        return;
      case ValueType::Name:
        if (def.enumDef) name(*def.enumDef, def.name, at, decode(raw));
        return;
      case ValueType::NumberList:
      case ValueType::IntegerList:
      case ValueType::Vec3List:
      case ValueType::TransformList:
        list(def, at, decode(raw));
        return;
      case ValueType::ColorList:
        colorList(def, at, decode(raw));
        return;
      default:
        return;  // text, paths, ids, references, string lists: any text
    }
  }

  void name(const EnumDef& e, std::string_view field, Span at, std::string_view s) {
    if (e.canonical(s)) return;
    std::vector<std::string_view> names;
    std::string all;
    for (const EnumDef::Value& v : e.values) {
      names.push_back(v.name);
      all += (all.empty() ? "" : ", ") + v.name;
    }
    std::string best = closestName(s, names);
    std::string hint = best.empty() ? "known names: " + all : "did you mean `" + best + "`?";
    if (!e.open)
      ctx_.report(rs::RS2006, r_, at, field, "unknown " + e.name + " " + quoted(s), hint);
    else if (ctx_.raisim())
      ctx_.report(rs::RS6009, r_, at, field, "RaiSim does not know " + e.name + " " + quoted(s), hint);
    else
      ctx_.report(rs::RS2007, r_, at, field, "unknown " + e.name + " " + quoted(s), hint);
  }

  // The span of item [offset, offset+len) of a value, for the caret.
  Span item(Span value, std::string_view s, std::string_view part) const {
    if (s.data() < doc_.buffer().data() || s.data() >= doc_.buffer().data() + doc_.buffer().size()) return value;
    return Span{static_cast<std::uint32_t>(part.data() - doc_.buffer().data()), static_cast<std::uint32_t>(part.size())};
  }

  // Checks numbers of a list; returns their count or -1 after a report.
  // Items are separated by `,` or `;`; the scan stops at the first empty
  // item (RS2009) and reports only the first item that is no number.
  long long numbers(const FieldDef& def, Span at, std::string_view s, bool integers) {
    if (s.empty()) return 0;
    long long count = 0;
    bool bad = false;
    const char* p = s.data();
    const char* e = p + s.size();
    for (;;) {
      const char* q = p;
      // A plain decimal is scanned in place; anything else up to the next
      // separator goes to the full parser.
      q += q != e && *q == '-';
      const char* d = q;
      while (q != e && static_cast<unsigned>(*q - '0') < 10) ++q;
      std::size_t digits = static_cast<std::size_t>(q - d);
      bool plain = true;
      if (q != e && *q == '.') {
        plain = !integers;
        const char* fr = ++q;
        while (q != e && static_cast<unsigned>(*q - '0') < 10) ++q;
        digits += static_cast<std::size_t>(q - fr);
      }
      plain = plain && digits > 0 && (q == e || *q == ',' || *q == ';');
      if (!plain)
        while (q != e && *q != ',' && *q != ';') ++q;
      std::string_view part(p, static_cast<std::size_t>(q - p));
      if (part.empty()) {
        ctx_.report(rs::RS2009, r_, at, def.name, def.name + " has an empty entry",
                    "separate numbers with single `,` or `;` and end without one");
        return -1;
      }
      ++count;
      if (!bad && !(plain && part.size() <= (integers ? 18u : 100u))) {
        if (integers) {
          if (!parseInteger(part)) {
            ctx_.report(rs::RS2003, r_, item(at, s, part), def.name, "expected an integer, found " + quoted(part));
            bad = true;
          }
        } else if (!parseNumber(part)) {
          badNumber(ctx_, r_, item(at, s, part), def.name, part);
          bad = true;
        }
      }
      if (q == e) break;
      p = q + 1;
    }
    return bad ? -1 : count;
  }

  void list(const FieldDef& def, Span at, std::string_view s) {
    long long n = numbers(def, at, s, def.type == ValueType::IntegerList);
    if (n < 0) return;
    int per = def.type == ValueType::Vec3List ? 3 : def.type == ValueType::TransformList ? 10 : 1;
    if (n % per == 0) return;
    if (per == 10)
      ctx_.report(rs::RS4004, r_, at, def.name,
                  def.name + " has " + std::to_string(n) + " numbers, not a multiple of 10",
                  "each instance is position (3), quaternion w,x,y,z (4) and scale (3)");
    else
      ctx_.report(rs::RS2008, r_, at, def.name, def.name + " has " + std::to_string(n) + " numbers, not a multiple of 3");
  }

  // Colors of 3 or 4 numbers separated by `;` (numbers by `,`); reports
  // the first entry that is not one.  One scan, plain decimals in place.
  void colorList(const FieldDef& def, Span at, std::string_view s) {
    if (s.empty()) return;
    const char* p = s.data();
    const char* e = p + s.size();
    for (;;) {
      const char* start = p;
      int n = 0;
      bool good = true;
      for (;;) {  // the numbers of one color
        const char* q = p;
        q += q != e && *q == '-';
        const char* d = q;
        while (q != e && static_cast<unsigned>(*q - '0') < 10) ++q;
        std::size_t digits = static_cast<std::size_t>(q - d);
        if (q != e && *q == '.') {
          const char* fr = ++q;
          while (q != e && static_cast<unsigned>(*q - '0') < 10) ++q;
          digits += static_cast<std::size_t>(q - fr);
        }
        if (!(digits > 0 && (q == e || *q == ',' || *q == ';') && q - p <= 100)) {
          while (q != e && *q != ',' && *q != ';') ++q;
          if (q == p || !parseNumber(std::string_view(p, static_cast<std::size_t>(q - p)))) good = false;
        }
        ++n;
        p = q;
        if (p == e || *p == ';') break;
        ++p;  // past `,`
      }
      if (!good || n < 3 || n > 4) {
        std::string_view part(start, static_cast<std::size_t>(p - start));
        ctx_.report(rs::RS2008, r_, item(at, s, part), def.name,
                    def.name + " entry " + quoted(part) + " is not a color of 3 or 4 numbers",
                    "colors are r,g,b or r,g,b,a separated by `;`");
        return;
      }
      if (p == e) return;
      ++p;  // past `;`
    }
  }

  void vectorKey(const FieldDef& def, Span at, std::string_view raw) {
    std::string_view s = decode(raw);
    double q[4] = {0, 0, 0, 0};
    int n = 0;
    bool bad = false;
    bool ok = forEachNumber(s, [&](std::string_view part, char) {
      auto v = parseNumber(part);
      if (!v && !bad) {
        badNumber(ctx_, r_, item(at, s, part), def.name, part);
        bad = true;
      }
      if (v && n < 4) q[n] = *v;
      ++n;
    });
    if (bad) return;
    int want = componentCount(def.type);
    bool countOk = def.type == ValueType::Color ? (n == 3 || n == 4) : n == want;
    if (!ok || !countOk) {
      std::string expect = def.type == ValueType::Color ? "3 or 4" : std::to_string(want);
      ctx_.report(rs::RS2008, r_, at, def.name,
                  def.name + " has " + (ok ? std::to_string(n) : "an empty") + " component" + (n == 1 && ok ? "" : "s") +
                      ", expected " + expect,
                  "write " + expect + " numbers separated by `,`");
      return;
    }
    if (def.type == ValueType::Quat) checkQuaternion(ctx_, r_, at, def.name, q);
  }

  Context& ctx_;
  const Record& r_;
  const Document& doc_;
  std::string scratch_;
};

}  // namespace

void checkTypes(Context& ctx, const Record& r) {
  if (!r.kind) {
    std::string_view tag = ctx.doc.tag(r);
    const std::string& best = ctx.suggestion(nullptr, tag);
    ctx.report(rs::RS3001, r, r.tag, {}, "unknown record tag '" + std::string(tag.substr(0, 60)) + "'",
               best.empty() ? "newer writers may add kinds; this one is kept and ignored"
                            : "did you mean `" + best + "`?");
    return;
  }
  TypeChecker(ctx, r).run();
}

}  // namespace rscene::checks
