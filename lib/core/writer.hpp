// The canonical writer (DESIGN.md, "Canonical form").  Output goes to a
// Sink in chunks so that formatting a 128 MB scene never holds a second
// full copy of it.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/document.hpp"

namespace rscene {

class Sink {
 public:
  virtual ~Sink() = default;
  virtual void write(std::string_view chunk) = 0;
};

class StringSink : public Sink {
 public:
  explicit StringSink(std::string& out) : out_(out) {}
  void write(std::string_view chunk) override { out_.append(chunk); }

 private:
  std::string& out_;
};

// Record indices in the writer's order: by section, children after their
// parent, unknown tags after the record before them, stable otherwise.
std::vector<std::uint32_t> canonicalOrder(const Document& doc);

// Appends one record's canonical line (with its comments) to `out`.
void appendCanonicalRecord(const Document& doc, const Record& r, std::string& out);

void writeCanonical(const Document& doc, Sink& sink);
std::string canonicalText(const Document& doc);

}  // namespace rscene
