// The {...} evaluator: precedence, the four documented functions, the
// errors that name what went wrong, and its bounds.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "xml/expression.hpp"

namespace rscene::xml {
namespace {

double eval(const std::string& text) {
  std::string error;
  std::optional<double> v = evaluateExpression(text, ExpressionLimits{}, &error);
  EXPECT_TRUE(v.has_value()) << text << ": " << error;
  return v.value_or(NAN);
}

std::string failure(const std::string& text, ExpressionLimits limits = {}) {
  std::string error;
  std::optional<double> v = evaluateExpression(text, limits, &error);
  EXPECT_FALSE(v.has_value()) << text << " gave " << v.value_or(0);
  return error;
}

std::string expand(const std::string& value) {
  std::string out, error;
  EXPECT_TRUE(evaluateExpressions(value, ExpressionLimits{}, out, &error)) << value << ": " << error;
  return out;
}

TEST(Expression, PrecedenceAndAssociativity) {
  EXPECT_EQ(eval("1+2*3"), 7);
  EXPECT_EQ(eval("(1+2)*3"), 9);
  EXPECT_EQ(eval("2-3-4"), -5);
  EXPECT_EQ(eval("8/2/2"), 2);
  EXPECT_EQ(eval("-2*3"), -6);
  EXPECT_EQ(eval("2--3"), 5);
  EXPECT_EQ(eval("-(1+2)*-2"), 6);
  EXPECT_EQ(eval(" 10 / 4 "), 2.5);
  EXPECT_EQ(eval("+4"), 4);
}

TEST(Expression, Numbers) {
  EXPECT_EQ(eval("1e-3*1000"), 1);
  EXPECT_EQ(eval("2.5E2"), 250);
  EXPECT_EQ(eval(".5+.5"), 1);
  EXPECT_EQ(eval("7."), 7);
  EXPECT_EQ(eval("0.1*7"), 0.1 * 7);  // the double product, as C++ computes it
}

TEST(Expression, DocumentedFunctions) {
  EXPECT_EQ(eval("sin(0)"), 0);
  EXPECT_EQ(eval("cos(0)"), 1);
  EXPECT_EQ(eval("exp(0)"), 1);
  EXPECT_DOUBLE_EQ(eval("log(exp(2))"), 2);
  EXPECT_DOUBLE_EQ(eval("cos(0.1*7)*(7*0.2+0.1)"), std::cos(0.7) * 1.5);
  EXPECT_DOUBLE_EQ(eval("sin ( 1 ) * 2"), 2 * std::sin(1.0));
}

TEST(Expression, BracesGroupLikeParentheses) {
  // What a parameter holding "{1+2}" becomes inside "{@@p*2}".
  EXPECT_EQ(eval("{1+2}*2"), 6);
}

TEST(Expression, ArithmeticErrorsNameTheProblem) {
  EXPECT_EQ(failure("1/0"), "division by zero");
  EXPECT_EQ(failure("1/(2-2)"), "division by zero");
  EXPECT_EQ(failure("log(0)"), "log of a number that is not positive (0)");
  EXPECT_EQ(failure("log(-1)"), "log of a number that is not positive (-1)");
  EXPECT_EQ(failure("exp(1000)"), "result is not finite");
  EXPECT_EQ(failure("1e308*10"), "result is not finite");
  EXPECT_EQ(failure("1e999"), "number 1e999 is out of range");
}

TEST(Expression, OnlyTheDocumentedNames) {
  EXPECT_EQ(failure("tan(1)"), "unknown name 'tan' (the functions are sin, cos, exp and log)");
  EXPECT_EQ(failure("pi*2"), "unknown name 'pi' (the functions are sin, cos, exp and log)");
  EXPECT_EQ(failure("system(1)"), "unknown name 'system' (the functions are sin, cos, exp and log)");
  EXPECT_EQ(failure("2^3"), "unexpected '^' at column 2");
  EXPECT_EQ(failure("sin 1"), "'sin' needs '(' at column 5");
}

TEST(Expression, SyntaxErrors) {
  EXPECT_EQ(failure(""), "empty expression at column 1");
  EXPECT_EQ(failure("1+"), "missing a number at column 3");
  EXPECT_EQ(failure("(1"), "missing ')' at column 3");
  EXPECT_EQ(failure("1 2"), "unexpected '2' at column 3");
  EXPECT_EQ(failure("2x"), "'2x' is not a number at column 2");
  EXPECT_EQ(failure("@@n+1"), "parameter @@n left in an expression at column 1");
}

TEST(Expression, BoundedLengthAndDepth) {
  ExpressionLimits limits;
  limits.maxLength = 10;
  EXPECT_EQ(failure("1+1+1+1+1+1", limits), "expression longer than 10 characters");
  // 100000 opening parentheses or signs: refused at the depth limit, not
  // by the stack.
  ExpressionLimits long_;
  long_.maxLength = 1 << 20;
  std::string deep(100000, '(');
  EXPECT_EQ(failure(deep + "1", long_), "expression nested deeper than 64 at column 65");
  std::string signs(100000, '-');
  EXPECT_EQ(failure(signs + "1", long_), "expression nested deeper than 64 at column 65");
  std::string ok = std::string(60, '(') + "1" + std::string(60, ')');
  EXPECT_EQ(eval(ok), 1);
}

TEST(Expression, SeveralPerValueShortestText) {
  EXPECT_EQ(expand("{1} {2+3} x{0.5*3}"), "1 5 x1.5");
  EXPECT_EQ(expand("{0.1*3}"), "0.30000000000000004");
  EXPECT_EQ(expand("{1e-7}"), "1e-07");
  EXPECT_EQ(expand("{-0}"), "0");
  EXPECT_EQ(expand("{ {1+2}*2 }"), "6");
  EXPECT_EQ(expand("no braces"), "no braces");
}

TEST(Expression, UnbalancedBracesAndNamedExpression) {
  std::string out, error;
  EXPECT_FALSE(evaluateExpressions("1 2}", ExpressionLimits{}, out, &error));
  EXPECT_EQ(error, "'}' without '{' at column 4");
  EXPECT_FALSE(evaluateExpressions("{1+2", ExpressionLimits{}, out, &error));
  EXPECT_EQ(error, "'{' without '}' at column 1");
  EXPECT_FALSE(evaluateExpressions("0 {1/(3-3)} 0", ExpressionLimits{}, out, &error));
  EXPECT_EQ(error, "{1/(3-3)}: division by zero");
  // An unclosed brace in a long value is refused at the length limit.
  ExpressionLimits limits;
  limits.maxLength = 100;
  EXPECT_FALSE(evaluateExpressions("{" + std::string(1000000, '1'), limits, out, &error));
  EXPECT_EQ(error, "expression longer than 100 characters");
}

}  // namespace
}  // namespace rscene::xml
