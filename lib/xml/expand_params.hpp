// `@@NAME` parameters of world templates: the values `<params>` defines,
// --param (LoadOptions::params) sets or overrides, and `array` loops bind
// to their `idx`, substituted textually into attribute values before any
// `{...}` expression is evaluated.
#pragma once
#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rscene::xml {

// How deep one parameter's value may refer to another (a -> b -> c ...):
// the recursion is bounded even when no name repeats.
inline constexpr int kMaxParameterNesting = 32;
// How many substitutions one attribute value may take, nested ones included.
inline constexpr std::size_t kMaxSubstitutions = std::size_t{1} << 20;

// Parameter names are what `@@` can delimit: letters, digits and '_'.
bool isParameterName(std::string_view name);

class Parameters {
 public:
  // --param NAME=VALUE: wins over every <params> entry.
  void setFromCommandLine(const std::string& name, const std::string& value);
  // A <params> entry.  The first definition wins (--param, then the
  // including file, then the files it includes in order), so an including
  // file sets the parameters of the files it includes.  False when the name
  // was already defined.
  bool define(const std::string& name, const std::string& value);

  // An `array` loop's variable; it shadows a parameter of the same name.
  void pushLoop(std::string name, std::string value);
  void popLoop() { loops_.pop_back(); }
  const std::vector<std::pair<std::string, std::string>>& loops() const { return loops_; }

  // `in` with every @@NAME replaced.  At each "@@" the longest name that is
  // set and that the following letters, digits and '_' start with is
  // replaced (@@idx2 is idx2 when idx2 is set, else idx then "2"); a
  // parameter's own value is substituted too, at most
  // kMaxParameterNesting deep and never from itself.  False with `error`
  // set when a name is set nowhere, on a cycle, or when the result would
  // pass `maxBytes`.
  bool substitute(std::string_view in, std::string& out, std::string* error, std::size_t maxBytes);

  // The parameter names `in` uses (after each "@@", the run of letters,
  // digits and '_') that neither a parameter nor a name in `loopNames`
  // starts, in order, each once: what substitute() would call unset,
  // found without expanding anything.
  std::vector<std::string> unsetNames(std::string_view in, const std::vector<std::string>& loopNames) const;

 private:
  bool expandInto(std::string_view in, std::string& out, std::vector<std::string>& chain, std::string* error,
                  std::size_t maxBytes);
  // The value bound to `name` (a loop variable first), nullptr when unset.
  const std::string* lookup(std::string_view name, bool* isLoop);

  std::map<std::string, std::string, std::less<>> globals_;
  std::vector<std::pair<std::string, std::string>> loops_;
  std::size_t longestName_ = 0;
  std::size_t steps_ = 0;
};

}  // namespace rscene::xml
