#include "xml/expand.hpp"

#include <algorithm>
#include <charconv>
#include <functional>
#include <limits>

#include "xml/expression.hpp"
#include "xml/xml_source.hpp"

namespace rscene::xml {
namespace {

constexpr int kMaxErrors = 20;

std::optional<std::int64_t> parseInt(std::string_view s) {
  std::int64_t v = 0;
  auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || ptr != s.data() + s.size() || s.empty()) return std::nullopt;
  return v;
}

std::uint64_t saturatingAdd(std::uint64_t a, std::uint64_t b) {
  return a > std::numeric_limits<std::uint64_t>::max() - b ? std::numeric_limits<std::uint64_t>::max() : a + b;
}
std::uint64_t saturatingMul(std::uint64_t a, std::uint64_t b) {
  if (a == 0 || b == 0) return 0;
  return a > std::numeric_limits<std::uint64_t>::max() / b ? std::numeric_limits<std::uint64_t>::max() : a * b;
}

}  // namespace

// start + k * increment in two's complement: every value the loop reaches
// lies between start and end, but k * increment alone may not fit.
std::int64_t Expander::Loop::value(std::uint64_t k) const {
  return static_cast<std::int64_t>(static_cast<std::uint64_t>(start) + k * static_cast<std::uint64_t>(increment));
}

namespace {

bool hasArray(const Element& e) {
  for (const Element& c : e.children)
    if (c.name == "array" || hasArray(c)) return true;
  return false;
}

std::uint64_t descendants(const Element& e) {
  std::uint64_t n = 0;
  for (const Element& c : e.children) n += 1 + descendants(c);
  return n;
}

}  // namespace

// What the expansion of a subtree would make, counted against what is left
// of the limits; counting stops as soon as either is passed.
struct Expander::Cost {
  std::uint64_t elements = 0, iterations = 0;
  std::uint64_t maxElements = 0, maxIterations = 0;
  bool over() const { return elements > maxElements || iterations > maxIterations; }
};

void Expander::fail(Diagnostic d) {
  diagnostics_.push_back(std::move(d));
  if (++errors_ >= kMaxErrors) stop_ = true;
}

std::string Expander::loopContext() const {
  if (params_.loops().empty()) return {};
  std::string s = " (in array iteration ";
  bool first = true;
  for (const auto& [name, value] : params_.loops()) {
    s += (first ? "" : ", ") + name + "=" + value;
    first = false;
  }
  return s + ")";
}

bool resolveValue(Parameters& params, const LoadLimits& limits, const Element& element, const Attribute& attribute,
                  std::string& out, Diagnostics& diagnostics, const std::string& context) {
  std::string substituted, why;
  if (!params.substitute(attribute.value, substituted, &why, limits.maxFileBytes)) {
    diagnostics.push_back(attributeDiagnostic(Severity::Error, code::kXmlParam, element, attribute, why + context));
    return false;
  }
  if (substituted.find_first_of("{}") == std::string::npos) {
    out = std::move(substituted);
    return true;
  }
  ExpressionLimits expressionLimits{limits.maxExpressionLength, limits.maxExpressionDepth};
  if (!evaluateExpressions(substituted, expressionLimits, out, &why)) {
    diagnostics.push_back(attributeDiagnostic(Severity::Error, code::kXmlExpr, element, attribute, why + context));
    return false;
  }
  return true;
}

bool Expander::finalValue(const Element& element, const Attribute& attribute, std::string& out) {
  if (resolveValue(params_, limits_, element, attribute, out, diagnostics_, loopContext())) return true;
  if (++errors_ >= kMaxErrors) stop_ = true;
  return false;
}

std::optional<bool> Expander::exists(const Element& element) {
  const Attribute* a = element.attribute("exist");
  if (!a) return true;
  std::string v;
  if (!finalValue(element, *a, v)) return std::nullopt;
  if (v == "true" || v == "1") return true;
  if (v == "false" || v == "0") return false;
  fail(attributeDiagnostic(Severity::Error, code::kXmlExist, element, *a,
                           "'" + v.substr(0, 64) + "' is not true, false, 1 or 0" + loopContext()));
  return std::nullopt;
}

// Every parameter set nowhere, each at its first use, before anything is
// expanded: an unset loop bound or `exist` would otherwise hide the
// parameters used inside it until it is given (RS8104).
bool Expander::reportUnsetParameters(const Element& raw) {
  std::vector<std::string> loopNames;
  std::vector<const Element*> roots{&raw};
  for (const auto& [name, cls] : classes_) roots.push_back(&cls);
  std::function<void(const Element&)> loops = [&](const Element& e) {
    if (e.name == "array")
      if (const Attribute* idx = e.attribute("idx"))
        loopNames.push_back(idx->value.rfind("@@", 0) == 0 ? idx->value.substr(2) : idx->value);
    for (const Element& c : e.children) loops(c);
  };
  for (const Element* r : roots) loops(*r);
  loopNames.erase(std::remove(loopNames.begin(), loopNames.end(), std::string()), loopNames.end());
  std::vector<std::string> reported;
  std::function<void(const Element&)> visit = [&](const Element& e) {
    // An element that exist removes needs none of its values (its exist
    // known now: no loop variable in it).
    if (const Attribute* exist = e.attribute("exist")) {
      std::string substituted, value, why;
      ExpressionLimits limits{limits_.maxExpressionLength, limits_.maxExpressionDepth};
      if (params_.substitute(exist->value, substituted, &why, limits_.maxFileBytes) &&
          evaluateExpressions(substituted, limits, value, &why) && (value == "false" || value == "0"))
        return;
    }
    for (const Attribute& a : e.attributes) {
      if (e.name == "array" && a.name == "idx") continue;
      for (const std::string& name : params_.unsetNames(a.value, loopNames)) {
        if (std::find(reported.begin(), reported.end(), name) != reported.end()) continue;
        reported.push_back(name);
        fail(attributeDiagnostic(Severity::Error, code::kXmlParam, e, a,
                                 "@@" + name + " is not set: define it in <params> or give --param " + name + "=VALUE"));
      }
    }
    for (const Element& c : e.children) visit(c);
  };
  for (const Element* r : roots) visit(*r);
  return reported.empty();
}

bool Expander::expandWorld(const Element& raw, Element& out) {
  if (!reportUnsetParameters(raw)) return false;
  if (!expandElement(raw, out, Context::Raisim, 1) && !hasErrors(diagnostics_))
    fail(elementDiagnostic(Severity::Error, code::kXmlExist, raw, "exist removes the whole world"));
  return !hasErrors(diagnostics_);
}

bool Expander::expandElement(const Element& raw, Element& out, Context context, int depth) {
  if (stop_) return false;
  if (depth > limits_.maxDepth) {
    fail(elementDiagnostic(Severity::Error, code::kXmlLimit, raw,
                           "elements nested deeper than " + std::to_string(limits_.maxDepth) + " after expansion"));
    stop_ = true;
    return false;
  }
  std::optional<bool> keep = exists(raw);
  if (!keep || !*keep) return false;
  if (++elements_ > limits_.maxElements) {
    fail(elementDiagnostic(Severity::Error, code::kXmlLimit, raw,
                           "the expansion makes more than " + std::to_string(limits_.maxElements) +
                               " elements, the limit"));
    stop_ = true;
    return false;
  }
  out.name = raw.name;
  out.where = raw.where;
  bool ok = true;
  for (const Attribute& a : raw.attributes) {
    if (a.name == "exist") continue;
    Attribute value{a.name, {}, a.where};
    if (!finalValue(raw, a, value.value)) {
      ok = false;
      continue;
    }
    // What the attribute holds in memory, so that many empty attributes
    // count as well as a few long values.
    bytes_ += sizeof(Attribute) + value.name.size() + value.value.size() + value.where.file.size();
    if (bytes_ > limits_.maxExpandedBytes) {
      fail(attributeDiagnostic(Severity::Error, code::kXmlLimit, raw, a,
                               "the expansion makes more than " + std::to_string(limits_.maxExpandedBytes) +
                                   " bytes of attributes, the limit"));
      stop_ = true;
      return false;
    }
    out.attributes.push_back(std::move(value));
  }
  expandChildren(raw, out, raw.name == "objects" ? Context::Objects : Context::Other, depth + 1);
  if (!ok || stop_) return false;
  if (context != Context::Objects) return true;
  auto cls = classes_.find(raw.name);
  if (cls == classes_.end()) return true;  // not a class: the mapping says what it is
  // The class is expanded where it is used, so its values can use the
  // instance's loop variables and parameters.
  Element literal;
  if (!expandElement(cls->second, literal, Context::Other, depth)) return false;
  std::size_t before = diagnostics_.size();
  if (!applyClass(literal, out, diagnostics_)) {
    errors_ += static_cast<int>(diagnostics_.size() - before);
    return false;
  }
  return true;
}

void Expander::expandChildren(const Element& raw, Element& out, Context context, int depth) {
  for (const Element& child : raw.children) {
    if (stop_) return;
    if (child.name == "array") {
      expandArray(child, out, context, depth);
      continue;
    }
    Element e;
    if (expandElement(child, e, context, depth)) out.children.push_back(std::move(e));
  }
}

bool Expander::readLoop(const Element& array, Loop& loop, bool report) {
  std::string values[4];
  const char* names[4] = {"idx", "start", "end", "increment"};
  for (int i = 0; i < 4; ++i) {
    const Attribute* a = array.attribute(names[i]);
    if (!a) {
      if (report)
        fail(elementDiagnostic(Severity::Error, code::kXmlArray, array,
                               std::string("no ") + names[i] + " (an array needs idx, start, end and increment)"));
      return false;
    }
    // idx names the variable: "@@i" or "i", never substituted itself.
    if (i == 0) {
      values[0] = a->value.rfind("@@", 0) == 0 ? a->value.substr(2) : a->value;
      if (!isParameterName(values[0])) {
        if (report)
          fail(attributeDiagnostic(Severity::Error, code::kXmlArray, array, *a,
                                   "'" + a->value.substr(0, 64) + "' is not a variable name (write idx=\"@@i\")"));
        return false;
      }
      continue;
    }
    if (report) {
      if (!finalValue(array, *a, values[i])) return false;
    } else {
      // Measuring: stay quiet; the expansion reports the same error.
      std::string substituted, why;
      if (!params_.substitute(a->value, substituted, &why, limits_.maxFileBytes)) return false;
      ExpressionLimits limits{limits_.maxExpressionLength, limits_.maxExpressionDepth};
      if (!evaluateExpressions(substituted, limits, values[i], &why)) return false;
    }
  }
  std::optional<std::int64_t> bounds[4];
  for (int i = 1; i < 4; ++i)
    if (!(bounds[i] = parseInt(values[i]))) {
      if (report)
        fail(attributeDiagnostic(Severity::Error, code::kXmlArray, array, *array.attribute(names[i]),
                                 "'" + values[i].substr(0, 64) + "' is not an integer" + loopContext()));
      return false;
    }
  const std::int64_t start = *bounds[1], end = *bounds[2], inc = *bounds[3];
  if (inc == 0 || (end > start && inc < 0) || (end < start && inc > 0)) {
    if (report)
      fail(attributeDiagnostic(Severity::Error, code::kXmlArray, array, *array.attribute("increment"),
                               "increment " + values[3] + " never reaches end " + values[2] + " from start " +
                                   values[1] + " (end is exclusive)" + loopContext()));
    return false;
  }
  // end is exclusive: start, start+inc, ... while before end.  The span is
  // taken in unsigned arithmetic, where end - start cannot overflow.
  std::uint64_t span = end >= start ? static_cast<std::uint64_t>(end) - static_cast<std::uint64_t>(start)
                                      : static_cast<std::uint64_t>(start) - static_cast<std::uint64_t>(end);
  std::uint64_t step = inc > 0 ? static_cast<std::uint64_t>(inc) : 0 - static_cast<std::uint64_t>(inc);
  loop.idx = values[0];
  loop.start = start;
  loop.increment = inc;
  loop.count = span / step + (span % step != 0);
  return true;
}

void Expander::expandArray(const Element& array, Element& out, Context context, int depth) {
  std::optional<bool> keep = exists(array);
  if (!keep || !*keep) return;
  Loop loop;
  if (!readLoop(array, loop, true)) return;
  bool outermost = !measured_;
  if (outermost) {
    // Measure the whole expansion first, building nothing.
    Cost cost;
    cost.maxElements = limits_.maxElements - std::min(elements_, limits_.maxElements);
    cost.maxIterations = limits_.maxLoopIterations - std::min(iterations_, limits_.maxLoopIterations);
    measureArray(array, context, cost);
    if (cost.over()) {
      bool elements = cost.elements > cost.maxElements;
      fail(elementDiagnostic(Severity::Error, code::kXmlLimit, array,
                             elements ? "the loops here make more than " + std::to_string(limits_.maxElements) +
                                            " elements, the limit"
                                      : "the loops here run more than " + std::to_string(limits_.maxLoopIterations) +
                                            " iterations, the limit"));
      stop_ = true;
      return;
    }
    measured_ = true;
  }
  if (iterations_ + loop.count > limits_.maxLoopIterations) {  // measured arrays never get here
    fail(elementDiagnostic(Severity::Error, code::kXmlLimit, array,
                           "the loops here run more than " + std::to_string(limits_.maxLoopIterations) +
                               " iterations, the limit"));
    stop_ = true;
  }
  for (std::uint64_t k = 0; k < loop.count && !stop_; ++k) {
    params_.pushLoop(loop.idx, std::to_string(loop.value(k)));
    ++iterations_;
    int errorsBefore = errors_;
    expandChildren(array, out, context, depth);
    params_.popLoop();
    if (errors_ != errorsBefore) break;  // the next iteration would say the same
  }
  if (outermost) measured_ = false;
}

void Expander::measureChildren(const Element& raw, Context context, Cost& cost) {
  for (const Element& child : raw.children) {
    if (cost.over()) return;
    if (child.name == "array") {
      measureArray(child, context, cost);
      continue;
    }
    cost.elements = saturatingAdd(cost.elements, 1);
    if (context == Context::Objects)
      if (auto cls = classes_.find(child.name); cls != classes_.end())
        // A class's children can become up to three elements each (a
        // compound class child -> the child, <dim> and <state>).
        cost.elements = saturatingAdd(cost.elements, 1 + 3 * descendants(cls->second));
    measureChildren(child, child.name == "objects" ? Context::Objects : Context::Other, cost);
  }
}

void Expander::measureArray(const Element& array, Context context, Cost& cost) {
  Loop loop;
  if (!readLoop(array, loop, false)) return;  // the expansion reports it
  // An array that runs no iteration still counts one, so that measuring
  // many empty loops inside a long one is bounded too.
  cost.iterations = saturatingAdd(cost.iterations, std::max<std::uint64_t>(loop.count, 1));
  if (cost.over() || loop.count == 0) return;
  params_.pushLoop(loop.idx, std::to_string(loop.start));
  if (!hasArray(array)) {
    // Without nested loops every iteration makes as many elements.
    Cost once;
    once.maxElements = once.maxIterations = std::numeric_limits<std::uint64_t>::max();
    measureChildren(array, context, once);
    cost.elements = saturatingAdd(cost.elements, saturatingMul(once.elements, loop.count));
  } else {
    // Nested loops may depend on this one's variable: count them out.
    // Each step adds to the iterations counted, so this stops within the limit.
    for (std::uint64_t k = 0; k < loop.count && !cost.over(); ++k) {
      params_.popLoop();
      params_.pushLoop(loop.idx, std::to_string(loop.value(k)));
      measureChildren(array, context, cost);
    }
  }
  params_.popLoop();
}

}  // namespace rscene::xml
