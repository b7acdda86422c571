#include "xml/xml_source.hpp"

#include <tinyxml2.h>

#include <cctype>
#include <cstring>
#include <unordered_set>

namespace rscene::xml {
namespace {

struct AttributePosition {
  std::string_view name;
  std::uint32_t line = 0, column = 0;
};
struct TagPosition {
  std::uint32_t line = 0, column = 0;
  std::vector<AttributePosition> attributes;
};

Diagnostic error(const char* code, const std::string& file, std::uint32_t line, std::uint32_t column,
                 std::string message) {
  Diagnostic d;
  d.code = code;
  d.file = file;
  d.line = line;
  d.column = column;
  d.message = std::move(message);
  return d;
}

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// Line and column of increasing offsets, counted once: the scan as a whole
// stays linear in the file.
class Cursor {
 public:
  explicit Cursor(std::string_view text) : text_(text) {}
  std::pair<std::uint32_t, std::uint32_t> at(std::size_t offset) {
    for (; pos_ < offset && pos_ < text_.size(); ++pos_)
      if (text_[pos_] == '\n') {
        ++line_;
        lineStart_ = pos_ + 1;
      }
    return {line_, static_cast<std::uint32_t>(offset - lineStart_ + 1)};
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0, lineStart_ = 0;
  std::uint32_t line_ = 1;
};

// Finds the element start tags and attribute names in document order (the
// order tinyxml2 builds them in) and checks entity and character
// references, nesting depth, end tags against start tags and repeated
// attributes, where tinyxml2 gives only a line (and not always the right
// one).  On other text it cannot follow it stops, and tinyxml2 reports.
class Scanner {
 public:
  Scanner(std::string_view text, const std::string& file, int maxDepth, Diagnostics& diagnostics)
      : s_(text), cursor_(text), file_(file), maxDepth_(maxDepth), diagnostics_(diagnostics) {}

  bool run() {
    std::size_t i = 0;
    while (i < s_.size() && !stop_) {
      char c = s_[i];
      if (c == '&') {
        checkReference(i);
        ++i;
      } else if (c != '<') {
        ++i;
      } else if (startsWith(i, "<!--")) {
        i = skipPast(i + 4, "-->");
      } else if (startsWith(i, "<![CDATA[")) {
        i = skipPast(i + 9, "]]>");
      } else if (startsWith(i, "<?")) {
        i = skipPast(i + 2, "?>");
      } else if (startsWith(i, "<!")) {
        i = declaration(i);
      } else if (startsWith(i, "</")) {
        i = endTag(i);
      } else {
        i = startTag(i);
      }
    }
    // tinyxml2 names no element here: say which one is left open.
    if (!stop_ && !open_.empty())
      report(code::kXmlRead, open_.back().line, open_.back().column,
             "not well-formed XML: <" + std::string(open_.back().name) + "> is never closed");
    return ok_;
  }

  std::vector<TagPosition> tags;

 private:
  bool startsWith(std::size_t i, std::string_view prefix) const { return s_.substr(i, prefix.size()) == prefix; }
  std::size_t skipPast(std::size_t from, std::string_view end) {
    std::size_t j = s_.find(end, from);
    if (j == std::string_view::npos) {
      stop_ = true;  // unterminated: tinyxml2 says where
      return s_.size();
    }
    return j + end.size();
  }
  void report(const char* code, std::size_t offset, std::string message) {
    auto [line, column] = cursor_.at(offset);
    report(code, line, column, std::move(message));
  }
  // At a place found earlier (the cursor only moves forward).
  void report(const char* code, std::uint32_t line, std::uint32_t column, std::string message) {
    diagnostics_.push_back(error(code, file_, line, column, std::move(message)));
    ok_ = false;
    if (++errors_ >= 10) stop_ = true;
  }

  // <!DOCTYPE ...>: tinyxml2 keeps it as an unknown node and expands no
  // entity, so a declared entity would silently stay "&lol;" in values.
  // Refuse any internal subset: entity declarations are what it is for.
  std::size_t declaration(std::size_t i) {
    std::size_t k = i + 2;
    char quote = 0;
    int brackets = 0;
    bool subset = false;
    for (; k < s_.size(); ++k) {
      char c = s_[k];
      if (quote) {
        if (c == quote) quote = 0;
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (c == '[') {
        ++brackets;
        subset = true;
      } else if (c == ']') {
        --brackets;
      } else if (c == '>' && brackets <= 0) {
        break;
      }
    }
    std::string_view decl = s_.substr(i, k - i);
    if (decl.find("<!ENTITY") != std::string_view::npos)
      report(code::kXmlEntity, i, "DOCTYPE declares entities: entity declarations are refused (they can expand without bound)");
    else if (subset)
      report(code::kXmlEntity, i, "DOCTYPE with an internal subset ([...]): it is not read");
    if (k >= s_.size()) stop_ = true;
    return k + 1;
  }

  // "&name;": only XML's five entities and numeric references exist here.
  // A '&' that starts no "&name;" is left to tinyxml2, which keeps it as text.
  void checkReference(std::size_t i) {
    std::size_t k = i + 1;
    if (k < s_.size() && s_[k] == '#') return characterReference(i);
    while (k < s_.size() && k - i <= 64 &&
           (std::isalnum(static_cast<unsigned char>(s_[k])) || s_[k] == '_' || s_[k] == '-' || s_[k] == '.' ||
            s_[k] == ':'))
      ++k;
    if (k == i + 1 || k >= s_.size() || s_[k] != ';') return;
    std::string_view name = s_.substr(i + 1, k - i - 1);
    if (name == "amp" || name == "lt" || name == "gt" || name == "quot" || name == "apos") return;
    report(code::kXmlEntity, i,
           "&" + std::string(name) + "; is no XML entity: only &amp; &lt; &gt; &quot; &apos; and &#...; are read "
           "(DOCTYPE entities are not expanded)");
  }

  // "&#N;" / "&#xH;": XML 1.0 allows tab, LF, CR, 0x20-0xD7FF,
  // 0xE000-0xFFFD and 0x10000-0x10FFFF only.  tinyxml2 decodes the rest
  // silently (&#0; cut a name short, &#x1; made one rscene-to-xml refuses).
  void characterReference(std::size_t i) {
    std::size_t k = i + 2;
    bool hex = k < s_.size() && s_[k] == 'x';
    if (hex) ++k;
    std::size_t digits = k;
    std::uint64_t value = 0;
    for (; k < s_.size(); ++k) {
      int d = hexDigit(s_[k]);
      if (d < 0 || (!hex && d > 9)) break;
      value = std::min<std::uint64_t>(value * (hex ? 16 : 10) + static_cast<std::uint64_t>(d), 0x110000);
    }
    std::string_view shown = s_.substr(i, std::min<std::size_t>(k + 1 - i, 32));
    if (k == digits || k >= s_.size() || s_[k] != ';') {
      report(code::kXmlEntity, i, std::string(shown) + ": not a character reference (&#digits; or &#xhex;)");
      return;
    }
    bool allowed = value == 0x9 || value == 0xA || value == 0xD || (value >= 0x20 && value <= 0xD7FF) ||
                   (value >= 0xE000 && value <= 0xFFFD) || (value >= 0x10000 && value <= 0x10FFFF);
    if (!allowed)
      report(code::kXmlEntity, i,
             std::string(shown) + " is a character XML 1.0 forbids (controls other than tab, LF and CR, "
             "surrogates, U+FFFE, U+FFFF and values past U+10FFFF)");
  }
  static int hexDigit(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  }

  // "</name>": it must close the innermost open element.  tinyxml2 says
  // only "mismatched element" at the line of the opening tag.
  std::size_t endTag(std::size_t i) {
    std::size_t k = i + 2;
    while (k < s_.size() && !isSpace(s_[k]) && s_[k] != '>') ++k;
    std::string_view name = s_.substr(i + 2, k - i - 2);
    std::size_t end = skipPast(k, ">");
    if (stop_) return end;
    if (open_.empty()) {
      report(code::kXmlRead, i, "not well-formed XML: </" + std::string(name) + "> closes no open element");
      stop_ = true;
    } else if (open_.back().name != name) {
      const OpenElement& top = open_.back();
      report(code::kXmlRead, i,
             "not well-formed XML: </" + std::string(name) + "> closes <" + std::string(top.name) + "> opened at " +
                 std::to_string(top.line) + ":" + std::to_string(top.column));
      stop_ = true;  // the rest of the nesting no longer says anything
    } else {
      open_.pop_back();
    }
    return end;
  }

  // Two attributes of one name: tinyxml2 reports the line of the tag only.
  void checkDuplicate(const std::vector<AttributePosition>& attributes) {
    const AttributePosition& last = attributes.back();
    for (std::size_t j = 0; j + 1 < attributes.size(); ++j)
      if (attributes[j].name == last.name) {
        report(code::kXmlRead, last.line, last.column,
               "not well-formed XML: attribute '" + std::string(last.name) + "' written twice (first at " +
                   std::to_string(attributes[j].line) + ":" + std::to_string(attributes[j].column) + ")");
        return;
      }
  }

  std::size_t startTag(std::size_t i) {
    TagPosition tag;
    std::tie(tag.line, tag.column) = cursor_.at(i);
    if (static_cast<int>(open_.size()) + 1 > maxDepth_) {
      report(code::kXmlLimit, i, "elements nested deeper than " + std::to_string(maxDepth_));
      stop_ = true;
      return s_.size();
    }
    std::size_t k = i + 1;
    while (k < s_.size() && !isSpace(s_[k]) && s_[k] != '/' && s_[k] != '>') ++k;
    open_.push_back({s_.substr(i + 1, k - i - 1), tag.line, tag.column});
    // Attributes seen in this tag, by name: a tag with very many attributes
    // is checked through a set so the scan stays linear.
    std::unordered_set<std::string_view> names;
    while (k < s_.size()) {
      while (k < s_.size() && isSpace(s_[k])) ++k;
      if (k >= s_.size()) break;
      if (s_[k] == '>') {
        ++k;
        break;
      }
      if (s_[k] == '/') {
        open_.pop_back();  // <x/>: no end tag will close it
        k = skipPast(k, ">");
        break;
      }
      std::size_t nameStart = k;
      while (k < s_.size() && !isSpace(s_[k]) && s_[k] != '=' && s_[k] != '/' && s_[k] != '>') ++k;
      AttributePosition a;
      a.name = s_.substr(nameStart, k - nameStart);
      std::tie(a.line, a.column) = cursor_.at(nameStart);
      while (k < s_.size() && isSpace(s_[k])) ++k;
      if (k >= s_.size() || s_[k] != '=') {  // malformed: tinyxml2 reports it
        stop_ = true;
        break;
      }
      ++k;
      while (k < s_.size() && isSpace(s_[k])) ++k;
      if (k >= s_.size() || (s_[k] != '"' && s_[k] != '\'')) {
        stop_ = true;
        break;
      }
      char quote = s_[k];
      std::size_t end = s_.find(quote, k + 1);
      if (end == std::string_view::npos) {
        stop_ = true;
        break;
      }
      // Search the value only: a find over the rest of the file per
      // attribute made a 100,000-body world take minutes.
      for (std::size_t j = k + 1; j < end; ++j)
        if (s_[j] == '&') checkReference(j);
      tag.attributes.push_back(a);
      if (tag.attributes.size() <= 16) {
        checkDuplicate(tag.attributes);
      } else {
        if (names.empty())
          for (std::size_t j = 0; j + 1 < tag.attributes.size(); ++j) names.insert(tag.attributes[j].name);
        if (!names.insert(a.name).second) checkDuplicate(tag.attributes);
      }
      k = end + 1;
    }
    tags.push_back(std::move(tag));
    return k;
  }

  std::string_view s_;
  Cursor cursor_;
  const std::string& file_;
  int maxDepth_;
  Diagnostics& diagnostics_;
  struct OpenElement {
    std::string_view name;
    std::uint32_t line, column;
  };
  std::vector<OpenElement> open_;  // at most maxDepth_ long
  int errors_ = 0;
  bool ok_ = true;
  bool stop_ = false;
};

std::size_t countElements(const tinyxml2::XMLElement& e) {
  std::size_t n = 1;
  for (const tinyxml2::XMLElement* c = e.FirstChildElement(); c; c = c->NextSiblingElement()) n += countElements(*c);
  return n;
}

class Converter {
 public:
  Converter(const std::string& file, const std::string& thisDir, const std::vector<TagPosition>* tags)
      : file_(file), thisDir_(thisDir), tags_(tags) {}  // file_: the one shared copy of the name

  Element convert(const tinyxml2::XMLElement& e) {
    Element out;
    out.name = e.Name();
    const TagPosition* tag = tags_ ? &(*tags_)[next_++] : nullptr;
    auto line = static_cast<std::uint32_t>(e.GetLineNum());
    out.where = {file_, line, tag ? tag->column : 0};
    std::size_t index = 0;
    for (const tinyxml2::XMLAttribute* a = e.FirstAttribute(); a; a = a->Next(), ++index) {
      Where where{file_, line, 0};
      if (tag && index < tag->attributes.size() && tag->attributes[index].name == a->Name())
        where = {file_, tag->attributes[index].line, tag->attributes[index].column};
      out.attributes.push_back({a->Name(), replaceThisDir(a->Value(), thisDir_), where});
    }
    for (const tinyxml2::XMLElement* c = e.FirstChildElement(); c; c = c->NextSiblingElement())
      out.children.push_back(convert(*c));
    return out;
  }

 private:
  FileName file_;
  const std::string& thisDir_;
  const std::vector<TagPosition>* tags_;
  std::size_t next_ = 0;
};

// tinyxml2's names are XML_ERROR_MISMATCHED_ELEMENT ...: lower-case words read better.
std::string tinyxmlError(const tinyxml2::XMLDocument& doc) {
  std::string name = doc.ErrorName() ? doc.ErrorName() : "error";
  for (const char* prefix : {"XML_ERROR_", "XML_"})
    if (name.rfind(prefix, 0) == 0) {
      name = name.substr(std::strlen(prefix));
      break;
    }
  for (char& c : name) c = c == '_' ? ' ' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name;
}

}  // namespace

std::string replaceThisDir(std::string_view value, const std::string& thisDir) {
  std::string out(value);
  static constexpr std::string_view kThisDir = "[THIS_DIR]";
  for (std::size_t at = out.find(kThisDir); at != std::string::npos; at = out.find(kThisDir, at + thisDir.size()))
    out.replace(at, kThisDir.size(), thisDir);
  return out;
}

bool parseWorldSource(std::string_view text, const std::string& file, const std::string& thisDir, int maxDepth,
                      Element& root, Diagnostics& diagnostics) {
  Scanner scanner(text, file, maxDepth, diagnostics);
  if (!scanner.run()) return false;
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    diagnostics.push_back(error(code::kXmlRead, file, static_cast<std::uint32_t>(std::max(doc.ErrorLineNum(), 0)),
                                0, "not well-formed XML (" + tinyxmlError(doc) + ")"));
    return false;
  }
  const tinyxml2::XMLElement* top = doc.RootElement();
  if (!top) {
    diagnostics.push_back(error(code::kXmlRead, file, 0, 0, "no element: a world XML is a <raisim> element"));
    return false;
  }
  // The scan and tinyxml2 read the same text, so they find the same start
  // tags; should they ever not, columns are left unknown rather than wrong.
  if (const tinyxml2::XMLElement* second = top->NextSiblingElement()) {
    diagnostics.push_back(error(code::kXmlRead, file, static_cast<std::uint32_t>(second->GetLineNum()), 0,
                                "a second top element <" + std::string(second->Name()) + ">: a world XML is one <raisim> element"));
    return false;
  }
  const std::vector<TagPosition>* tags = countElements(*top) == scanner.tags.size() ? &scanner.tags : nullptr;
  root = Converter(file, thisDir, tags).convert(*top);
  if (root.name != "raisim") {
    diagnostics.push_back(error(code::kXmlRead, file, root.where.line, root.where.column,
                                "the top element is <" + root.name + ">, not <raisim>"));
    return false;
  }
  return true;
}

}  // namespace rscene::xml
