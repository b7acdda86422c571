// Reading a world XML and everything it includes, then expanding it
// (expand.hpp).  Reading comes first and is done once per file: each file's
// <params> are read before its includes are followed (so an including
// file's parameters are visible in the files it includes, and the first
// definition wins), includes are spliced in place, and the object classes of
// every file are gathered; then the whole tree is expanded with every
// parameter known.
//
// <include> (RaiSim's templatedWorld examples): the file is named by `file`,
// `path` or `file_name` (the first one written), relative to the including
// file's directory, after [THIS_DIR] and @@ parameters (not loop variables:
// a file is read once, not per iteration); `exist` works on it as on any
// element.  Directly under <raisim>, the included file's top-level children
// are spliced in place.  Under <objects> (or an array in it), its <objects>
// children are spliced in place and its other top-level elements (material,
// gravity, object_class ...) join the top <raisim>.  Anywhere else an
// include is an error.  After expansion, several top-level <objects> (or
// <material>) elements are merged into the first, in document order.
#include <filesystem>

#include "core/filesystem.hpp"
#include "xml/expand.hpp"
#include "xml/xml_source.hpp"
#include "xml/xml_tree.hpp"

namespace rscene::xml {
namespace {

namespace fs = std::filesystem;

enum class Place { Raisim, Objects, Other };

struct SourceFile {
  std::string name;       // as messages show it
  std::string dir;        // where its relative includes resolve ("" = the working directory)
  std::string thisDir;    // [THIS_DIR]: its directory, absolute
  std::string identity;   // canonical path, for cycles ("" for standard input)
};

std::string absoluteDir(const std::string& dir) {
  std::error_code ec;
  fs::path p = fs::absolute(dir.empty() ? fs::path(".") : fs::path(dir), ec);
  if (ec) return dir;
  std::string s = p.lexically_normal().string();
  while (s.size() > 1 && s.back() == '/') s.pop_back();
  return s;
}

std::string identityOf(const std::string& path) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(path, ec);
  return ec ? fs::absolute(path, ec).lexically_normal().string() : p.string();
}

std::size_t countElements(const Element& e) {
  std::size_t n = 1;
  for (const Element& c : e.children) n += countElements(c);
  return n;
}

Diagnostic fileError(const char* code, const std::string& file, std::string message) {
  Diagnostic d;
  d.code = code;
  d.file = file;
  d.message = std::move(message);
  return d;
}

class WorldReader {
 public:
  WorldReader(const LoadOptions& options, LoadResult& result, Parameters& params)
      : options_(options), result_(result), params_(params) {}

  // Reads `text` (the file `file`) and what it includes into `root`.
  bool read(std::string_view text, const SourceFile& file, Element& root) {
    result_.files.push_back(file.name);
    // A file included many times (not a cycle: a diamond of includes) is
    // read each time; what all reads hold together is bounded too.
    bytesRead_ += text.size();
    if (stop_) return false;
    if (bytesRead_ > options_.limits.maxExpandedBytes) {
      stop_ = true;
      error(fileError(code::kXmlLimit, file.name,
                      "the files read make more than " + std::to_string(options_.limits.maxExpandedBytes) +
                          " bytes together, the limit"));
      return false;
    }
    if (!parseWorldSource(text, file.name, file.thisDir, options_.limits.maxDepth, root, result_.diagnostics))
      return false;
    elementsRead_ += countElements(root);
    if (elementsRead_ > options_.limits.maxElements) {
      stop_ = true;
      error(fileError(code::kXmlLimit, file.name,
                      "the files read hold more than " + std::to_string(options_.limits.maxElements) +
                          " elements together, the limit"));
      return false;
    }
    chain_.push_back(file);
    readParams(root);
    resolve(root, Place::Raisim);
    chain_.pop_back();
    return !hasErrors(result_.diagnostics);
  }

  // Top-level elements of files included under <objects> that are not
  // objects: they join the top <raisim>.
  std::vector<Element> hoisted;

 private:
  void error(Diagnostic d) { result_.diagnostics.push_back(std::move(d)); }

  void readParams(Element& root) {
    for (const Element& params : root.children) {
      if (params.name != "params") continue;
      for (const Element& p : params.children) {
        const Attribute* value = p.attribute("value");
        if (!isParameterName(p.name)) {
          error(elementDiagnostic(Severity::Error, code::kXmlParam, p,
                                  "a parameter name is letters, digits and '_' (what @@ can delimit)"));
        } else if (!value) {
          error(elementDiagnostic(Severity::Error, code::kXmlParam, p, "no value (write <" + p.name + " value=\"...\"/>)"));
        } else {
          params_.define(p.name, value->value);  // false: set already (--param or an including file)
        }
      }
    }
  }

  // Replaces the includes under `parent` by what they bring and refuses
  // params and classes out of place.
  void resolve(Element& parent, Place place) {
    std::vector<Element> children;
    children.reserve(parent.children.size());
    for (Element& child : parent.children) {
      if (child.name == "include") {
        include(child, place, children);
      } else if (child.name == "params" || child.name == "object_class") {
        if (place == Place::Raisim) {
          if (child.name == "object_class") children.push_back(std::move(child));
        } else {
          error(elementDiagnostic(Severity::Error, child.name == "params" ? code::kXmlParam : code::kXmlClass, child,
                                  "belongs directly under <raisim>"));
        }
      } else {
        Place inner = child.name == "objects" ? Place::Objects
                      : child.name == "array" ? place == Place::Raisim ? Place::Other : place
                                              : Place::Other;
        resolve(child, inner);
        children.push_back(std::move(child));
      }
    }
    parent.children = std::move(children);
  }

  void include(const Element& inc, Place place, std::vector<Element>& out) {
    if (stop_) return;
    if (place == Place::Other) {
      error(elementDiagnostic(Severity::Error, code::kXmlInclude, inc,
                              "belongs directly under <raisim> or <objects>"));
      return;
    }
    if (const Attribute* exist = inc.attribute("exist")) {
      std::string v;
      if (!resolveValue(params_, options_.limits, inc, *exist, v, result_.diagnostics)) return;
      if (v == "false" || v == "0") return;
      if (v != "true" && v != "1") {
        error(attributeDiagnostic(Severity::Error, code::kXmlExist, inc, *exist,
                                  "'" + v.substr(0, 64) + "' is not true, false, 1 or 0"));
        return;
      }
    }
    // RaiSim's own templatedWorld.xml writes <include value="..."/>; file,
    // path and file_name are read too.
    const Attribute* named = inc.attribute("value");
    if (!named) named = inc.attribute("file");
    if (!named) named = inc.attribute("path");
    if (!named) named = inc.attribute("file_name");
    if (!named) {
      error(elementDiagnostic(Severity::Error, code::kXmlInclude, inc, "no file (write <include value=\"...\"/>)"));
      return;
    }
    std::string target, why;
    if (!params_.substitute(named->value, target, &why, options_.limits.maxFileBytes)) {
      error(attributeDiagnostic(Severity::Error, code::kXmlParam, inc, *named, why));
      return;
    }
    const SourceFile& from = chain_.back();
    fs::path path(target);
    if (path.is_relative() && !from.dir.empty()) path = fs::path(from.dir) / path;
    SourceFile file;
    file.name = path.lexically_normal().string();
    file.dir = path.parent_path().string();
    file.thisDir = absoluteDir(file.dir);
    file.identity = identityOf(file.name);
    for (std::size_t i = 0; i < chain_.size(); ++i)
      if (chain_[i].identity == file.identity) {
        // The whole chain from the top file: which include led into the
        // cycle matters as much as the cycle itself.
        std::string cycle;
        for (const SourceFile& f : chain_) cycle += f.name + " -> ";
        error(attributeDiagnostic(Severity::Error, code::kXmlInclude, inc, *named,
                                  "include cycle: " + cycle + file.name));
        return;
      }
    if (static_cast<int>(chain_.size()) > options_.limits.maxIncludeDepth) {
      error(attributeDiagnostic(Severity::Error, code::kXmlInclude, inc, *named,
                                "includes nested deeper than " + std::to_string(options_.limits.maxIncludeDepth)));
      return;
    }
    std::string text, readError;
    if (!options_.fileSystem().read(file.name, text, &readError, options_.limits.maxFileBytes)) {
      error(attributeDiagnostic(Severity::Error, code::kXmlInclude, inc, *named,
                                "cannot read '" + file.name + "': " + readError));
      return;
    }
    Element root;
    if (!read(text, file, root)) return;
    for (Element& child : root.children) {
      if (place == Place::Raisim) {
        out.push_back(std::move(child));
      } else if (child.name == "objects") {
        for (Element& object : child.children) out.push_back(std::move(object));
      } else {
        hoisted.push_back(std::move(child));
      }
    }
  }

  const LoadOptions& options_;
  LoadResult& result_;
  Parameters& params_;
  std::vector<SourceFile> chain_;  // the files being read, the top one first
  std::size_t bytesRead_ = 0, elementsRead_ = 0;
  bool stop_ = false;  // a limit was passed: read nothing more
};

ClassTable gatherClasses(Element& root, Diagnostics& diagnostics) {
  ClassTable classes;
  std::vector<Element> kept;
  for (Element& child : root.children) {
    if (child.name != "object_class") {
      kept.push_back(std::move(child));
      continue;
    }
    for (Element& cls : child.children) {
      if (isBuiltInElement(cls.name)) {
        diagnostics.push_back(elementDiagnostic(Severity::Error, code::kXmlClass, cls,
                                                "a class may not take the name of an element of the format"));
      } else if (!cls.attribute("type")) {
        diagnostics.push_back(elementDiagnostic(Severity::Error, code::kXmlClass, cls,
                                                "no type (the element the class stands for: sphere, box, mesh ...)"));
      } else if (auto first = classes.find(cls.name); first != classes.end()) {
        diagnostics.push_back(elementDiagnostic(Severity::Error, code::kXmlClass, cls,
                                                "class defined twice (first at " + first->second.where.file.str() + ":" +
                                                    std::to_string(first->second.where.line) + ")"));
      } else {
        std::string name = cls.name;
        classes.emplace(std::move(name), std::move(cls));
      }
    }
  }
  root.children = std::move(kept);
  return classes;
}

// Several <objects> (from includes) become one, and so do several <material>.
void mergeContainers(Element& root) {
  for (const char* name : {"objects", "material"}) {
    Element* first = nullptr;
    std::vector<Element> kept;
    kept.reserve(root.children.size());
    for (Element& child : root.children) {
      if (child.name != name) {
        kept.push_back(std::move(child));
      } else if (!first) {
        kept.push_back(std::move(child));
        first = &kept.back();  // kept was reserved below: the address stays
      } else {
        for (Element& c : child.children) first->children.push_back(std::move(c));
      }
    }
    root.children = std::move(kept);
  }
}

LoadResult load(std::string_view text, const SourceFile& file, const LoadOptions& options) {
  LoadResult result;
  Parameters params;
  for (const auto& [name, value] : options.params) {
    if (!isParameterName(name)) {
      result.diagnostics.push_back(fileError(code::kXmlParam, file.name,
                                             "--param '" + name.substr(0, 64) +
                                                 "': a parameter name is letters, digits and '_'"));
      return result;
    }
    // A --param is written in no file: [THIS_DIR] in it is the top file's.
    params.setFromCommandLine(name, replaceThisDir(value, file.thisDir));
  }
  WorldReader reader(options, result, params);
  Element raw;
  if (!reader.read(text, file, raw)) return result;
  for (Element& e : reader.hoisted) raw.children.push_back(std::move(e));
  ClassTable classes = gatherClasses(raw, result.diagnostics);
  if (hasErrors(result.diagnostics)) return result;
  Element expanded;
  if (!Expander(params, classes, options.limits, result.diagnostics).expandWorld(raw, expanded)) return result;
  mergeContainers(expanded);
  result.root = std::move(expanded);
  return result;
}

}  // namespace

LoadResult loadWorldText(std::string_view text, const std::string& displayName, const std::string& baseDir,
                         const LoadOptions& options) {
  SourceFile file{displayName, baseDir, absoluteDir(baseDir), ""};
  // The same per-file limit as a file read from disk or included (a caller
  // that read standard input passes what it read).
  if (text.size() > options.limits.maxFileBytes) {
    LoadResult result;
    result.diagnostics.push_back(fileError(code::kXmlRead, displayName,
                                           "cannot read: file larger than " +
                                               std::to_string(options.limits.maxFileBytes) + " bytes"));
    return result;
  }
  return load(text, file, options);
}

LoadResult loadWorld(const std::string& path, const LoadOptions& options) {
  std::string text, error;
  if (!options.fileSystem().read(path, text, &error, options.limits.maxFileBytes)) {
    LoadResult result;
    result.diagnostics.push_back(fileError(code::kXmlRead, path, "cannot read: " + error));
    return result;
  }
  std::string dir = fs::path(path).parent_path().string();
  SourceFile file{path, dir, absoluteDir(dir), identityOf(path)};
  return load(text, file, options);
}

}  // namespace rscene::xml
