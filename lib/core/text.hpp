// Text codec of the format: percent-encoding, numbers, flags, lists, and
// the canonical spelling of one value of a given type.  Pure functions over
// string_views; nothing here allocates unless it appends to `out`.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/schema.hpp"

namespace rscene {

// Words of `s` separated by spaces (used for the schema table only).
std::vector<std::string_view> splitWords(std::string_view s);

// Offset of the first malformed `%` escape in `token`, or npos.
std::size_t findBadEscape(std::string_view token);
// Decodes `%XX` (either case) and a bare `-` to the empty string.
// `token` must have no bad escape.
void percentDecode(std::string_view token, std::string& out);
std::string percentDecode(std::string_view token);
// Encodes `value` as one token for the file `version` (1 or 2): control
// bytes, space, `%`, `=` always; `;` and a lone `-` in version 2; the empty
// string as `-`.
void percentEncode(std::string_view value, int version, std::string& out);

// Length of the valid UTF-8 sequence that starts at s[i], or 0.
std::size_t utf8SequenceLength(std::string_view s, std::size_t i);

// Typed parses of decoded text.  Numbers must be finite and use the whole
// text (C locale, std::from_chars); flags are true/1/yes/on, false/0/no/off.
std::optional<double> parseNumber(std::string_view s);
std::optional<std::int64_t> parseInteger(std::string_view s);
std::optional<std::uint64_t> parseGroup(std::string_view s);
std::optional<bool> parseFlag(std::string_view s);
// Numbers of a list type; `,` and `;` both separate.  False on an item that
// is not a finite number (an empty text is an empty list).
bool parseNumberList(std::string_view s, std::vector<double>& out);
// Elements of a string list, decoded.
std::vector<std::string> parseStringList(std::string_view raw);

// Shortest text that reads back as `v` (std::to_chars).
void appendNumber(std::string& out, double v);
std::string numberText(double v);  // the same, as a string (for messages)
// `v` to `digits` significant digits (printf's %g): a figure in a message
// where the full round-trip spelling would only be noise.
std::string roundedNumber(double v, int digits);
void appendInteger(std::string& out, std::int64_t v);

// n times `step` as a person would write it: the exact product of n and
// step's shortest decimal, rounded once to a double.  14 steps of 0.1 are
// 1.4, where 14 * 0.1 is 1.4000000000000001.
double decimalMultiple(std::uint64_t n, double step);

// Appends the canonical spelling of the raw token `raw` of type `type`
// (see DESIGN.md, canonical form).  Text that does not parse as its type is
// kept, only re-encoded, so formatting never loses what a user wrote.
void appendCanonical(std::string& out, std::string_view raw, ValueType type, int version);

// Whether appendCanonical(raw, type, version) would append `raw` itself,
// decided without building anything.  It may say false for a token that is
// canonical after all (escapes, unusual spellings); callers then format it.
bool isCanonicalToken(std::string_view raw, ValueType type, int version);

// Whether two raw tokens hold the same value of `type`: numbers compare by
// their bits after parsing, text after decoding.
bool sameValue(std::string_view a, std::string_view b, ValueType type);

}  // namespace rscene
