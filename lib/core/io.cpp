#include "core/io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/filesystem.hpp"
#include "core/output_file.hpp"
#include "core/text.hpp"

namespace rscene {
namespace {

ValueType fieldType(const Record& r, const Document& doc, const Field& f, std::uint32_t positionalIndex) {
  if (!r.kind) return ValueType::Text;
  if (f.isKey()) {
    const FieldDef* def = r.kind->key(doc.text(f.key));
    return def ? def->type : ValueType::Text;
  }
  const Layout* layout = r.kind->layoutFor(r.positionalCount);
  if (!layout || positionalIndex >= layout->tokens.size()) return ValueType::Text;
  const FieldDef& def = layout->fields[static_cast<std::size_t>(layout->tokens[positionalIndex].first)];
  return def.width > 1 ? ValueType::Number : def.type;
}

}  // namespace

bool readFile(const std::string& path, std::string& out, std::string* error, std::size_t maxBytes) {
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    if (error) *error = std::strerror(errno);
    return false;
  }
  struct stat st {};
  if (::fstat(fd, &st) == 0 && S_ISDIR(st.st_mode)) {
    ::close(fd);
    if (error) *error = std::strerror(EISDIR);
    return false;
  }
  auto tooLarge = [&] {
    ::close(fd);
    if (error) *error = fileTooLarge(maxBytes);
    return false;
  };
  if (maxBytes > 0 && S_ISREG(st.st_mode) && static_cast<std::uint64_t>(st.st_size) > maxBytes) return tooLarge();
  // Regular files are read straight into the string; pipes grow it.
  out.clear();
  std::size_t used = 0;
  if (st.st_size > 0) out.resize(static_cast<std::size_t>(st.st_size));
  char probe[1 << 12];
  // A capped pipe gets its whole room at once: growing by doubling would
  // hold the old and the new buffer (three times the cap) near the end.
  if (maxBytes > 0 && !S_ISREG(st.st_mode)) out.reserve(maxBytes + sizeof probe);
  for (;;) {
    // When the string is full, a small read tells end of file from more
    // data, so a file of exactly st_size bytes is never over-allocated.
    bool full = used == out.size();
    ssize_t n = full ? ::read(fd, probe, sizeof probe) : ::read(fd, out.data() + used, out.size() - used);
    if (n < 0) {
      if (errno == EINTR) continue;
      if (error) *error = std::strerror(errno);
      ::close(fd);
      return false;
    }
    if (n == 0) break;
    if (full) {
      // Doubling, but never far past a cap: a pipe over it is refused
      // without first holding twice the cap.
      std::size_t grown = std::max<std::size_t>(out.size() * 2, 1 << 16);
      if (maxBytes > 0) grown = std::min(grown, maxBytes + 1);
      out.resize(std::max(grown, used + static_cast<std::size_t>(n)));
      std::memcpy(out.data() + used, probe, static_cast<std::size_t>(n));
    }
    used += static_cast<std::size_t>(n);
    if (maxBytes > 0 && used > maxBytes) return tooLarge();
    if (used > kMaxInputBytes + 1) break;  // the loader reports it
  }
  out.resize(used);
  ::close(fd);
  return true;
}

bool writeFileAtomic(const std::string& path, const std::function<bool(Sink&)>& produce, std::string* error) {
  return writeOutputFile(path, produce, error);
}

std::string firstError(const Diagnostics& diagnostics) {
  for (const Diagnostic& d : diagnostics)
    if (d.severity == Severity::Error) return "line " + std::to_string(d.line) + ": " + d.message;
  return {};
}

bool loadString(std::string text, Document& doc, std::string* error) {
  LoadResult r = parse(std::move(text));
  if (!r.ok()) {
    if (error) *error = firstError(r.diagnostics);
    return false;
  }
  doc = std::move(r.document);
  return true;
}

bool loadFile(const std::string& path, Document& doc, std::string* error) {
  std::string text, err;
  if (!readFile(path, text, &err)) {
    if (error) *error = path + ": " + err;
    return false;
  }
  return loadString(std::move(text), doc, error);
}

std::string saveString(const Document& doc) { return canonicalText(doc); }

bool saveFile(const Document& doc, const std::string& path, std::string* error) {
  return writeFileAtomic(path, [&](Sink& s) { writeCanonical(doc, s); return true; }, error);
}

bool sameDocument(const Document& a, const Document& b, std::string* why) {
  auto fail = [&](const Record& r, const std::string& what) {
    if (why) *why = "record at line " + std::to_string(r.line) + " (" + std::string(a.tag(r)) + "): " + what;
    return false;
  };
  if (a.version != b.version) {
    if (why) *why = "versions differ";
    return false;
  }
  std::vector<std::uint32_t> oa = canonicalOrder(a), ob = canonicalOrder(b);
  if (oa.size() != ob.size()) {
    if (why) *why = "record counts differ: " + std::to_string(oa.size()) + " vs " + std::to_string(ob.size());
    return false;
  }
  for (std::size_t i = 0; i < oa.size(); ++i) {
    const Record& ra = a.records[oa[i]];
    const Record& rb = b.records[ob[i]];
    if (a.tag(ra) != b.tag(rb)) return fail(ra, "tag differs from " + std::string(b.tag(rb)));
    if (ra.fieldCount != rb.fieldCount || ra.positionalCount != rb.positionalCount)
      return fail(ra, "field counts differ");
    if (ra.commentCount != rb.commentCount) return fail(ra, "comments differ");
    for (std::uint32_t c = 0; c < ra.commentCount; ++c)
      if (a.commentText(ra.firstComment + c) != b.commentText(rb.firstComment + c)) return fail(ra, "comment differs");
    // Positionals compare by index, keys in written order.
    std::uint32_t pa = 0;
    for (std::uint32_t j = 0, pb = 0; j < ra.fieldCount; ++j) {
      const Field& fa = a.field(ra, j);
      const Field& fb = b.field(rb, j);
      if (fa.isKey() != fb.isKey()) return fail(ra, "field " + std::to_string(j + 1) + " changed kind");
      if (fa.isKey() && a.text(fa.key) != b.text(fb.key))
        return fail(ra, "key " + std::string(a.text(fa.key)) + " became " + std::string(b.text(fb.key)));
      ValueType t = fieldType(ra, a, fa, pa);
      if (!fa.isKey()) ++pa, ++pb;
      if (!sameValue(a.text(fa.value), b.text(fb.value), t)) {
        // An unknown key keeps `key=` and `key=-` apart only in spelling.
        return fail(ra, "value of field " + std::to_string(j + 1) + " differs: '" +
                            std::string(a.text(fa.value).substr(0, 60)) + "' vs '" +
                            std::string(b.text(fb.value).substr(0, 60)) + "'");
      }
    }
  }
  if (a.trailingCommentCount != b.trailingCommentCount) {
    if (why) *why = "trailing comments differ";
    return false;
  }
  return true;
}

}  // namespace rscene
