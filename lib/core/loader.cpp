#include "core/loader.hpp"

#include <algorithm>
#include <cstring>

#include "core/codes.hpp"
#include "core/text.hpp"

namespace rscene {
namespace {

constexpr std::size_t kMaxErrors = 50;

std::string hexByte(unsigned char c) {
  static const char* hex = "0123456789ABCDEF";
  return std::string{hex[c >> 4], hex[c & 15]};
}

std::string expectedCounts(const KindDef& k) {
  std::string s;
  for (std::size_t i = 0; i < k.layouts.size(); ++i) {
    if (i) s += i + 1 == k.layouts.size() ? " or " : ", ";
    s += std::to_string(k.layouts[i].tokenCount());
  }
  return s;
}

// Byte classes for the tokenizer.  kSpecial bytes (`%`, control bytes,
// non-ASCII) send a token through checkToken.
enum : std::uint8_t { kPlain, kSeparator, kEquals, kSpecial };
struct ByteClasses {
  std::uint8_t cls[256] = {};
  bool special[256] = {};
  ByteClasses() {
    for (int c = 0; c < 256; ++c) {
      special[c] = c == '%' || c < 0x20 || c >= 0x7f;
      cls[c] = special[c] ? kSpecial : kPlain;
    }
    cls[static_cast<unsigned char>(' ')] = cls[static_cast<unsigned char>('\t')] = kSeparator;
    cls[static_cast<unsigned char>('=')] = kEquals;
  }
};
const ByteClasses kBytes;

class Loader {
 public:
  explicit Loader(LoadResult& out) : out_(out), doc_(out.document) {}

  void run() {
    const std::string& text = doc_.buffer();
    if (text.size() > kMaxInputBytes) {
      error(0, 0, rs::RS1010, "input too large (" + std::to_string(text.size()) + " bytes; the limit is 4 GiB)");
      return;
    }
    if (byteOrderMark(text)) return;
    reserve(text);
    const char* data = text.data();
    std::size_t n = text.size();
    std::size_t pos = 0;
    std::uint32_t line = 0;
    pendingComment_ = 0;
    while (pos < n && !stop_) {
      const char* nl = static_cast<const char*>(std::memchr(data + pos, '\n', n - pos));
      std::size_t end = nl ? static_cast<std::size_t>(nl - data) : n;
      ++line;
      parseLine(pos, end, line);
      pos = end + 1;
    }
    hintContinuations(out_.continuedLines, out_.diagnostics);
    if (stop_) return;
    if (doc_.records.empty()) {
      error(line ? line : 1, 1, rs::RS1001, "missing raisim_engine_scene header", "the first record must be `raisim_engine_scene 1` or `raisim_engine_scene 2`");
      return;
    }
    doc_.trailingFirstComment = static_cast<std::uint32_t>(doc_.comments.size()) - pendingComment_;
    doc_.trailingCommentCount = pendingComment_;
  }

 private:
  // The format has no byte order mark and compat-notes.md names no reader
  // that skips one: Engine 2 would read it as part of the header's tag.  It
  // is invisible under a caret, so the message names it.
  bool byteOrderMark(std::string_view text) {
    const char* what = text.rfind("\xEF\xBB\xBF", 0) == 0 ? "a UTF-8 byte order mark (EF BB BF); remove it"
                       : text.rfind("\xFF\xFE", 0) == 0    ? "a UTF-16 byte order mark (FF FE); save it as UTF-8"
                       : text.rfind("\xFE\xFF", 0) == 0    ? "a UTF-16 byte order mark (FE FF); save it as UTF-8"
                                                            : nullptr;
    if (!what) return false;
    error(1, 1, rs::RS1001, std::string("file starts with ") + what,
          "the first bytes must be the header `raisim_engine_scene 1` or `raisim_engine_scene 2`");
    stop_ = true;
    return true;
  }

  void reserve(const std::string& text) {
    std::size_t lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
    std::size_t spaces = static_cast<std::size_t>(std::count(text.begin(), text.end(), ' '));
    doc_.records.reserve(lines);
    doc_.fields.reserve(spaces + lines);
  }

  void error(std::uint32_t line, std::uint32_t col, const char* code, std::string msg, std::string hint = {},
             std::string tag = {}) {
    Diagnostic d;
    d.severity = Severity::Error;
    d.code = code;
    d.line = line;
    d.column = col;
    d.message = std::move(msg);
    d.hint = std::move(hint);
    d.tag = std::move(tag);
    out_.diagnostics.push_back(std::move(d));
    if (++errors_ >= kMaxErrors) stop_ = true;
  }

  // Checks the bytes of one token; returns false after reporting an error.
  bool checkToken(std::size_t start, std::size_t end, std::uint32_t line, std::size_t lineStart,
                  bool comment = false) {
    const auto* s = reinterpret_cast<const unsigned char*>(doc_.buffer().data());
    for (std::size_t i = start; i < end; ++i) {
      unsigned char c = s[i];
      if (!kBytes.special[c]) continue;
      auto col = static_cast<std::uint32_t>(i - lineStart + 1);
      if (c == '%' && !comment) {
        if (i + 2 >= end || !std::isxdigit(s[i + 1]) || !std::isxdigit(s[i + 2])) {
          std::string seq(reinterpret_cast<const char*>(s) + i, std::min<std::size_t>(3, end - i));
          error(line, col, rs::RS1003, "invalid percent escape '" + seq + "'",
                "write a literal % as %25; escapes are % and two hex digits");
          return false;
        }
        i += 2;
      } else if (c == 0) {
        error(line, col, rs::RS1004, "NUL byte in scene text", "the file may be binary or corrupted");
        return false;
      } else if ((c < 0x20 && !(comment && c == '\t')) || c == 0x7f) {
        error(line, col, rs::RS1006, "control character 0x" + hexByte(c) + " in token",
              "write it as %" + hexByte(c));
        return false;
      } else if (c >= 0x80) {
        std::size_t len = utf8SequenceLength(std::string_view(reinterpret_cast<const char*>(s), end), i);
        if (!len) {
          error(line, col, rs::RS1005, "invalid UTF-8 byte 0x" + hexByte(c), "save the file as UTF-8");
          return false;
        }
        i += len - 1;
      }
    }
    return true;
  }

  void parseLine(std::size_t start, std::size_t end, std::uint32_t line) {
    const std::string& text = doc_.buffer();
    std::size_t lineStart = start;
    while (end > start && (text[end - 1] == '\r' || text[end - 1] == ' ' || text[end - 1] == '\t')) --end;
    while (start < end && (text[start] == ' ' || text[start] == '\t')) ++start;
    if (start == end) return;  // blank line
    if (text[end - 1] == '\\' && text[start] != '#' &&
        (end - 1 == start || text[end - 2] == ' ' || text[end - 2] == '\t'))
      out_.continuedLines.push_back(line);
    if (text[start] == '#') {
      if (!checkToken(start, end, line, lineStart, true)) return;
      doc_.comments.push_back(Span{static_cast<std::uint32_t>(start), static_cast<std::uint32_t>(end - start)});
      ++pendingComment_;
      return;
    }

    Record r;
    r.line = line;
    r.lineOffset = static_cast<std::uint32_t>(lineStart);
    r.firstField = static_cast<std::uint32_t>(doc_.fields.size());
    r.firstComment = static_cast<std::uint32_t>(doc_.comments.size()) - pendingComment_;
    r.commentCount = pendingComment_;

    bool first = true, sawKey = false;
    std::size_t misplaced = 0;
    std::size_t pos = start;
    const char* data = text.data();
    while (pos < end) {
      // One pass per token: split, find the first `=`, and note whether any
      // byte needs the closer look of checkToken (most tokens need none).
      while (pos < end && kBytes.cls[static_cast<unsigned char>(data[pos])] == kSeparator) ++pos;
      if (pos >= end) break;
      std::size_t tokStart = pos, eqPos = std::string::npos;
      bool special = false;
      for (; pos < end; ++pos) {
        std::uint8_t cls = kBytes.cls[static_cast<unsigned char>(data[pos])];
        if (cls == kPlain) continue;
        if (cls == kSeparator) break;
        if (cls == kEquals) {
          if (eqPos == std::string::npos) eqPos = pos;
        } else {
          special = true;
        }
      }
      if (special && !checkToken(tokStart, pos, line, lineStart)) return;
      Span whole{static_cast<std::uint32_t>(tokStart), static_cast<std::uint32_t>(pos - tokStart)};
      if (first) {
        r.tag = whole;
        first = false;
        continue;
      }
      Field f;
      if (eqPos != std::string::npos) {
        if (eqPos == tokStart) {
          error(line, static_cast<std::uint32_t>(tokStart - lineStart + 1), rs::RS1009, "key=value token without a key",
                "write the key before `=`, or escape `=` as %3D");
          return;
        }
        f.key = Span{whole.offset, static_cast<std::uint32_t>(eqPos - tokStart)};
        f.value = Span{static_cast<std::uint32_t>(eqPos + 1), static_cast<std::uint32_t>(pos - eqPos - 1)};
        sawKey = true;
      } else {
        f.value = whole;
        if (sawKey && !misplaced) misplaced = tokStart;
        ++r.positionalCount;
      }
      doc_.fields.push_back(f);
    }
    r.fieldCount = static_cast<std::uint32_t>(doc_.fields.size()) - r.firstField;
    std::string_view tag = doc_.text(r.tag);
    r.kind = Schema::get().kind(tag);

    if (doc_.records.empty()) {
      if (!checkHeader(r, tag, lineStart)) return;
    }
    if (r.kind) {
      if (misplaced) {
        doc_.fields.resize(r.firstField);
        error(line, static_cast<std::uint32_t>(misplaced - lineStart + 1), rs::RS1008,
              "positional field after key=value fields", "move positional fields before the first key=value",
              std::string(tag));
        return;
      }
      if (!r.kind->layoutFor(r.positionalCount)) {
        const Field* lastPos = r.positionalCount ? &doc_.fields[r.firstField + r.positionalCount - 1] : nullptr;
        std::uint32_t col = lastPos ? lastPos->value.offset + lastPos->value.length - r.lineOffset + 1
                                    : r.tag.offset + r.tag.length - r.lineOffset + 1;
        std::string msg = std::string(tag) + " has " + std::to_string(r.positionalCount) +
                          " positional field" + (r.positionalCount == 1 ? "" : "s") + ", expected " +
                          expectedCounts(*r.kind);
        doc_.fields.resize(r.firstField);
        error(line, col, rs::RS1007, msg,
              r.positionalCount < r.kind->layouts[0].tokenCount() ? "the line may be truncated" : "",
              std::string(tag));
        return;
      }
    } else {
      r.interleaved = misplaced != 0;
    }
    pendingComment_ = 0;
    doc_.records.push_back(r);
  }

  bool checkHeader(const Record& r, std::string_view tag, std::size_t lineStart) {
    if (tag != "raisim_engine_scene") {
      error(r.line, static_cast<std::uint32_t>(r.tag.offset - lineStart + 1), rs::RS1001,
            "missing raisim_engine_scene header",
            "the first record must be `raisim_engine_scene 1` or `raisim_engine_scene 2`");
      stop_ = true;
      return false;
    }
    std::string_view v = r.positionalCount ? doc_.text(doc_.fields[r.firstField].value) : std::string_view();
    if (v == "1" || v == "2") {
      doc_.version = v[0] - '0';
      return true;
    }
    std::uint32_t col = r.positionalCount ? doc_.fields[r.firstField].value.offset - r.lineOffset + 1
                                          : r.tag.offset + r.tag.length - r.lineOffset + 1;
    error(r.line, col, rs::RS1002,
          v.empty() ? std::string("unsupported rscene version (none given)")
                    : "unsupported rscene version '" + std::string(v.substr(0, 40)) + "'",
          "this tool reads versions 1 and 2");
    stop_ = true;
    return false;
  }

  LoadResult& out_;
  Document& doc_;
  std::uint32_t pendingComment_ = 0;
  std::size_t errors_ = 0;
  bool stop_ = false;
};

}  // namespace

void hintContinuations(const std::vector<std::uint32_t>& continuedLines, Diagnostics& ds) {
  if (continuedLines.empty()) return;
  for (Diagnostic& d : ds) {
    auto it = std::lower_bound(continuedLines.begin(), continuedLines.end(), d.line ? d.line - 1 : 0);
    if (it == continuedLines.end() || *it > d.line || !d.line) continue;
    d.hint = "line " + std::to_string(*it) +
             " ends with `\\`, but the format has no continuation lines: write each record on one line";
  }
}

LoadResult parse(std::string text) {
  LoadResult result;
  result.document.buffer() = std::move(text);
  Loader(result).run();
  return result;
}

}  // namespace rscene
