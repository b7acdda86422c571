// A RaiSim world configuration XML (WorldConfigurationFile.rst) after
// template expansion: `params` and `@@NAME` parameters, `include`
// (with [THIS_DIR]), `array` loops, `{...}` expressions, `exist` and
// `object_class` instances are all resolved by loadWorld(), so the mapping
// to records (from_xml.hpp) sees plain elements with literal attribute
// values.  Every element and attribute keeps where it was written (the
// file an include brought it from, line and column), so an error names
// the XML file, line and element.
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostic.hpp"
#include "core/filesystem.hpp"

namespace rscene::xml {

// The name of a file read, shared by every element and attribute that came
// from it: one allocation per file, not one per attribute (a world of
// 100,000 bodies holds about a million Wheres).
class FileName {
 public:
  FileName() = default;
  FileName(std::string name) : name_(std::make_shared<const std::string>(std::move(name))) {}
  FileName(const char* name) : FileName(std::string(name)) {}
  const std::string& str() const {
    static const std::string empty;
    return name_ ? *name_ : empty;
  }
  operator const std::string&() const { return str(); }
  std::size_t size() const { return str().size(); }
  friend bool operator==(const FileName& a, std::string_view b) { return a.str() == b; }

 private:
  std::shared_ptr<const std::string> name_;
};

// Where something was written: a file (the top file or an included one),
// 1-based line and column (0: unknown).
struct Where {
  FileName file;
  std::uint32_t line = 0;
  std::uint32_t column = 0;
};

struct Attribute {
  std::string name;   // as written (snake_case or a camelCase alias)
  std::string value;  // final: parameters substituted, expressions evaluated
  Where where;
};

struct Element {
  std::string name;  // tag as written
  std::vector<Attribute> attributes;  // document order
  std::vector<Element> children;      // document order, expanded
  Where where;

  // The first attribute named `name` or, when absent, `alias`; nullptr
  // when neither is written.
  const Attribute* attribute(std::string_view name, std::string_view alias = {}) const;
  // The first child element named `name` (or `alias`), nullptr when none.
  const Element* child(std::string_view name, std::string_view alias = {}) const;
};

// Bounds on what a hostile file can make the loader do; every one is
// refused with an error naming it, before the work or allocation.
struct LoadLimits {
  std::size_t maxFileBytes = 64u << 20;       // one XML file (top or included)
  std::size_t maxElements = 1'000'000;        // elements after expansion, in all
  std::uint64_t maxLoopIterations = 1'000'000;  // array iterations, in all
  int maxDepth = 64;                          // element nesting after expansion
  int maxIncludeDepth = 16;                   // include chains (cycles are refused outright)
  std::size_t maxExpressionLength = 4096;     // characters inside one {...}
  int maxExpressionDepth = 64;                // nested parentheses and operators
  std::size_t maxExpandedBytes = 256u << 20;  // attributes after expansion (names, values, bookkeeping),
                                              // in all; also the bytes of all files read together
};

struct LoadOptions {
  // --param NAME=VALUE: set or override a `params` entry (name without @@).
  std::map<std::string, std::string> params;
  LoadLimits limits;
  // Where the world file and its includes are read from (nullptr: the disk).
  const FileSystem* files = nullptr;
  const FileSystem& fileSystem() const { return files ? *files : diskFileSystem(); }
};

struct LoadResult {
  std::optional<Element> root;  // the <raisim> element, expanded; empty on error
  Diagnostics diagnostics;      // Diagnostic::file names the XML file of each
  std::vector<std::string> files;  // every file read (the top one first, then includes)
  bool ok() const { return root.has_value() && !hasErrors(diagnostics); }
};

// Reads and expands the world XML at `path`.  [THIS_DIR] in a value
// becomes the absolute directory of the file the value is written in.
// The template conventions (include attributes, array end exclusive, the
// expression grammar) are described in load_world.cpp, expand.hpp and
// expression.hpp.
LoadResult loadWorld(const std::string& path, const LoadOptions& options);
// The same for text already read (standard input): `displayName` names it
// in messages, `baseDir` is its [THIS_DIR] and where relative includes
// resolve.
LoadResult loadWorldText(std::string_view text, const std::string& displayName, const std::string& baseDir,
                         const LoadOptions& options);

// An error or warning about an element: `file:line:col: error: <tag>: message`.
Diagnostic elementDiagnostic(Severity severity, const char* code, const Element& element, std::string message);
Diagnostic attributeDiagnostic(Severity severity, const char* code, const Element& element,
                               const Attribute& attribute, std::string message);

}  // namespace rscene::xml
