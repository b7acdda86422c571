// Template expansion of a world XML whose includes are already spliced in
// and whose <params> are already read (load_world.cpp): `array` loops,
// `@@` substitution and `{...}` expressions in every attribute value,
// `exist`, and `object_class` instances.  The result holds only plain
// elements with literal values.
//
// Bounds (LoadLimits) are checked before the work: before an outermost
// array runs, its whole expansion is measured without building anything
// (iteration counts are computed, not counted out; a body without nested
// arrays is measured once and multiplied), so a loop of 10^9 or nested
// loops of 10^4 x 10^4 are refused at once with an error naming the limit.
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "core/diagnostic.hpp"
#include "xml/expand_params.hpp"
#include "xml/xml_tree.hpp"

namespace rscene::xml {

// An attribute's final text: `@@` parameters substituted, then `{...}`
// expressions evaluated.  False with a diagnostic (RS8104 or RS8105) whose
// message ends with `context` (the loop variables, when in a loop).
bool resolveValue(Parameters& params, const LoadLimits& limits, const Element& element, const Attribute& attribute,
                  std::string& out, Diagnostics& diagnostics, const std::string& context = {});

// object_class definitions by class name, as written (not yet expanded).
using ClassTable = std::map<std::string, Element, std::less<>>;

class Expander {
 public:
  Expander(Parameters& params, const ClassTable& classes, const LoadLimits& limits, Diagnostics& diagnostics)
      : params_(params), classes_(classes), limits_(limits), diagnostics_(diagnostics) {}

  // `raw` is the <raisim> element; false when an error was reported.
  bool expandWorld(const Element& raw, Element& out);

 private:
  bool reportUnsetParameters(const Element& raw);
  enum class Context { Raisim, Objects, Other };
  struct Cost;

  void expandChildren(const Element& raw, Element& out, Context context, int depth);
  void expandArray(const Element& array, Element& out, Context context, int depth);
  // False when the element is removed (exist false) or on error.
  bool expandElement(const Element& raw, Element& out, Context context, int depth);
  // An attribute's final text: parameters, then expressions.
  bool finalValue(const Element& element, const Attribute& attribute, std::string& out);
  // exist="...": true keeps, false removes; nullopt on error.
  std::optional<bool> exists(const Element& element);

  struct Loop {
    std::string idx;
    std::int64_t start = 0, increment = 1;
    std::uint64_t count = 0;
    std::int64_t value(std::uint64_t k) const;  // the variable in iteration k
  };
  bool readLoop(const Element& array, Loop& loop, bool report);

  void measureChildren(const Element& raw, Context context, Cost& cost);
  void measureArray(const Element& array, Context context, Cost& cost);

  void fail(Diagnostic d);
  std::string loopContext() const;

  Parameters& params_;
  const ClassTable& classes_;
  const LoadLimits& limits_;
  Diagnostics& diagnostics_;
  std::uint64_t elements_ = 0, iterations_ = 0, bytes_ = 0;
  bool measured_ = false;  // inside an array whose whole expansion was measured
  bool stop_ = false;      // a limit was passed, or too many errors
  int errors_ = 0;
};

// Turns the instance `instance` (expanded) of the class `cls` (expanded
// with the instance's parameters) into a plain element: the class's
// `type` becomes the tag; the class's attributes, then the instance's (which
// win); the class's children converted (dimension -> dim, file/scale ->
// file_name/scale attributes, a compound class's children -> standard
// children with <dim> and <state>), each replaced by an instance child of
// the same name, then the instance's other children.  False with a
// diagnostic (RS8109) when the class cannot be applied.
bool applyClass(const Element& cls, Element& instance, Diagnostics& diagnostics);

// Whether `name` is an element the world format defines itself: a class
// may not take such a name (it would hide the element).
bool isBuiltInElement(std::string_view name);

}  // namespace rscene::xml
