#include "xml/expression.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include "core/text.hpp"

namespace rscene::xml {
namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isNameStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool isNameChar(char c) { return isNameStart(c) || isDigit(c); }

class Parser {
 public:
  Parser(std::string_view text, const ExpressionLimits& limits) : s_(text), limits_(limits) {}

  std::optional<double> run(std::string* error) {
    skipSpace();
    if (pos_ == s_.size()) fail("empty expression");
    double v = failed_ ? 0 : expr();
    if (!failed_) {
      skipSpace();
      if (pos_ < s_.size()) fail(std::string("unexpected '") + s_[pos_] + "'");
    }
    if (failed_) {
      if (error) *error = error_;
      return std::nullopt;
    }
    return v;
  }

 private:
  // Every failure stops the parse: later steps see failed_ and return at once,
  // so the first message is the one reported.
  double fail(std::string message) {
    if (!failed_) {
      failed_ = true;
      error_ = std::move(message);
      if (error_.find("column") == std::string::npos && pos_ <= s_.size())
        error_ += " at column " + std::to_string(pos_ + 1);
    }
    return 0;
  }
  // An arithmetic failure names what went wrong, not where the parser is.
  double failValue(std::string message) {
    if (!failed_) {
      failed_ = true;
      error_ = std::move(message);
    }
    return 0;
  }
  double finite(double v) { return std::isfinite(v) ? v : failValue("result is not finite"); }

  void skipSpace() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool accept(char c) {
    skipSpace();
    if (pos_ < s_.size() && s_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  // Depth counts every recursion that the input can repeat without bound:
  // "((((...", "{{{{...", "----...1".
  bool enter() {
    if (++depth_ > limits_.maxDepth) {
      fail("expression nested deeper than " + std::to_string(limits_.maxDepth));
      return false;
    }
    return true;
  }

  double expr() {
    double v = term();
    while (!failed_) {
      if (accept('+')) v = finite(v + term());
      else if (accept('-')) v = finite(v - term());
      else break;
    }
    return v;
  }

  double term() {
    double v = unary();
    while (!failed_) {
      if (accept('*')) {
        v = finite(v * unary());
      } else if (accept('/')) {
        double d = unary();
        if (failed_) break;
        if (d == 0) return failValue("division by zero");
        v = finite(v / d);
      } else {
        break;
      }
    }
    return v;
  }

  double unary() {
    if (!enter()) return 0;
    double v;
    if (accept('-')) v = -unary();
    else if (accept('+')) v = unary();
    else v = primary();
    --depth_;
    return v;
  }

  // Nesting is counted in unary(), which every parenthesis passes through.
  double group(char close) {
    double v = expr();
    if (!failed_ && !accept(close)) return fail(std::string("missing '") + close + "'");
    return v;
  }

  double primary() {
    skipSpace();
    if (pos_ == s_.size()) return fail("missing a number");
    char c = s_[pos_];
    if (c == '(') {
      ++pos_;
      return group(')');
    }
    if (c == '{') {
      ++pos_;
      return group('}');
    }
    if (isDigit(c) || c == '.') return number();
    if (isNameStart(c)) return call();
    if (c == '@') return fail("parameter " + nameAt(pos_) + " left in an expression");
    return fail(std::string("unexpected '") + c + "'");
  }

  std::string nameAt(std::size_t from) const {
    std::size_t end = from;
    while (end < s_.size() && (isNameChar(s_[end]) || s_[end] == '@') && end - from < 64) ++end;
    return std::string(s_.substr(from, end - from));
  }

  double number() {
    std::size_t start = pos_;
    while (pos_ < s_.size() && isDigit(s_[pos_])) ++pos_;
    if (pos_ < s_.size() && s_[pos_] == '.') {
      ++pos_;
      while (pos_ < s_.size() && isDigit(s_[pos_])) ++pos_;
    }
    // An exponent only when digits follow, so "2e" stays an error below.
    if (pos_ < s_.size() && (s_[pos_] == 'e' || s_[pos_] == 'E')) {
      std::size_t e = pos_ + 1;
      if (e < s_.size() && (s_[e] == '+' || s_[e] == '-')) ++e;
      if (e < s_.size() && isDigit(s_[e])) {
        pos_ = e;
        while (pos_ < s_.size() && isDigit(s_[pos_])) ++pos_;
      }
    }
    std::string_view token = s_.substr(start, pos_ - start);
    double v = 0;
    auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
    if (ec == std::errc::result_out_of_range) return failValue("number " + std::string(token) + " is out of range");
    if (ec != std::errc{} || ptr != token.data() + token.size()) {
      pos_ = start;
      return fail("'" + std::string(token) + "' is not a number");
    }
    if (pos_ < s_.size() && isNameChar(s_[pos_])) return fail("'" + std::string(token) + s_[pos_] + "' is not a number");
    return v;
  }

  double call() {
    std::size_t start = pos_;
    while (pos_ < s_.size() && isNameChar(s_[pos_])) ++pos_;
    std::string name(s_.substr(start, pos_ - start));
    bool known = name == "sin" || name == "cos" || name == "exp" || name == "log";
    if (!known) {
      pos_ = start;
      return failValue("unknown name '" + name.substr(0, 64) + "' (the functions are sin, cos, exp and log)");
    }
    if (!accept('(')) return fail("'" + name + "' needs '('");
    double x = group(')');
    if (failed_) return 0;
    if (name == "sin") return finite(std::sin(x));
    if (name == "cos") return finite(std::cos(x));
    if (name == "exp") return finite(std::exp(x));
    if (x <= 0) return failValue("log of a number that is not positive (" + numberText(x) + ")");
    return finite(std::log(x));
  }

  std::string_view s_;
  const ExpressionLimits& limits_;
  std::size_t pos_ = 0;
  int depth_ = 0;
  bool failed_ = false;
  std::string error_;
};

}  // namespace

std::optional<double> evaluateExpression(std::string_view expression, const ExpressionLimits& limits,
                                         std::string* error) {
  if (expression.size() > limits.maxLength) {
    if (error)
      *error = "expression longer than " + std::to_string(limits.maxLength) + " characters";
    return std::nullopt;
  }
  return Parser(expression, limits).run(error);
}

bool evaluateExpressions(std::string_view value, const ExpressionLimits& limits, std::string& out,
                         std::string* error) {
  out.clear();
  std::size_t i = 0;
  while (i < value.size()) {
    std::size_t open = value.find_first_of("{}", i);
    if (open == std::string_view::npos) {
      out.append(value.substr(i));
      break;
    }
    out.append(value.substr(i, open - i));
    if (value[open] == '}') {
      if (error) *error = "'}' without '{' at column " + std::to_string(open + 1);
      return false;
    }
    // The matching brace: inner braces group, so count them.  The scan
    // stops at the length limit, so an unclosed brace in a long value costs
    // no more than the limit.
    int nesting = 0;
    std::size_t close = open;
    for (; close < value.size(); ++close) {
      if (value[close] == '{') ++nesting;
      else if (value[close] == '}' && --nesting == 0) break;
      if (close - open > limits.maxLength + 1) break;
    }
    std::string_view inner = value.substr(open + 1, std::min(close, value.size()) - open - 1);
    if (close - open > limits.maxLength + 1) {
      if (error) *error = "expression longer than " + std::to_string(limits.maxLength) + " characters";
      return false;
    }
    if (close >= value.size()) {
      if (error) *error = "'{' without '}' at column " + std::to_string(open + 1);
      return false;
    }
    std::string why;
    std::optional<double> v = evaluateExpression(inner, limits, &why);
    if (!v) {
      if (error) *error = "{" + std::string(inner) + "}: " + why;
      return false;
    }
    appendNumber(out, *v == 0 ? 0.0 : *v);  // never "-0"
    i = close + 1;
  }
  return true;
}

}  // namespace rscene::xml
