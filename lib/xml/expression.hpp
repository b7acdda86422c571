// The `{...}` expressions of RaiSim's world configuration templates
// (WorldConfigurationFile.rst, "Configuration Template"): a small
// recursive-descent evaluator over numbers only.  It runs after `@@`
// parameters were substituted, so an expression holds no names except
// the documented functions; nothing is executed, nothing is looked up.
//
// Grammar (whitespace anywhere between tokens):
//   expr    := term (('+' | '-') term)*
//   term    := unary (('*' | '/') unary)*
//   unary   := ('+' | '-') unary | primary
//   primary := number | func '(' expr ')' | '(' expr ')' | '{' expr '}'
//   func    := sin | cos | exp | log        (radians; log is the natural log)
//   number  := digits ['.' digits] [('e' | 'E') ['+' | '-'] digits], or '.' digits
// Only RaiSim's documented operations, so that a template that works here
// works in RaiSim: no '^', no other functions, no constants.  Braces inside
// an expression group like parentheses, so a parameter whose value is an
// expression ("{1+2}") can be used inside another one ("{@@p*2}").
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace rscene::xml {

struct ExpressionLimits {
  std::size_t maxLength = 4096;  // characters between the outer braces
  int maxDepth = 64;             // nested parentheses, braces and unary signs
};

// The value of `expression` (the text between the braces), or nullopt with
// `error` set: "division by zero", "log of a number that is not positive",
// "result is not finite", "unknown name 'tan' (the functions are sin, cos,
// exp and log)", a syntax error naming the column, or a limit.
std::optional<double> evaluateExpression(std::string_view expression, const ExpressionLimits& limits,
                                         std::string* error);

// `value` with every `{...}` replaced by its result written as the shortest
// text that reads back as the same double ("0.5", "1e-07", never "-0").
// False with `error` naming the expression ("{1/0}: division by zero") or
// the unbalanced brace.  A value without braces is copied unchanged.
bool evaluateExpressions(std::string_view value, const ExpressionLimits& limits, std::string& out,
                         std::string* error);

}  // namespace rscene::xml
