// The expression parser's limits on the tree it builds (depth, nodes, and all
// expressions of a model together) and its refusal of constant parts that are
// not finite, each with the position of the operator; the oracle for the
// positions is the text itself (the column of the n-th operator).
#include <gtest/gtest.h>

#include <cmath>
#include <ctime>
#include <sstream>
#include <string>

#include "frontend/expression_parser.h"
#include "frontend/parse_model.h"
#include "ir/model_error.h"

namespace mbfe::frontend {
namespace {

// A sum of 60,000 terms, the size that crashed, parses in milliseconds; under
// the sanitizers and a loaded machine, a generous bound that still catches a
// quadratic parser (seconds at this size).
constexpr double kMaxParseSeconds = 2.0;

/// "t+t+...+t" with `terms` terms.
std::string flat_sum(int terms) {
  std::string text = "t";
  for (int i = 1; i < terms; ++i) text += "+t";
  return text;
}

/// The message of the ModelError that parsing `text` throws, or "(accepted)".
std::string refusal(const std::string& text) {
  try {
    parse_expression(text, "m.yaml", {3, 10}, "load #1: value");
  } catch (const ir::ModelError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(ExpressionParser, BuildsTheTreeInPostfixOrderWithPositions) {
  const ir::Expression e = parse_expression("2*t + sin(t)", "m.yaml", {3, 10}, "load #1: value");
  using Kind = ir::ExpressionNode::Kind;
  ASSERT_EQ(e.nodes().size(), 6u);
  EXPECT_EQ(e.nodes()[0].kind, Kind::kNumber);
  EXPECT_EQ(e.nodes()[1].kind, Kind::kTime);
  EXPECT_EQ(e.nodes()[2].kind, Kind::kMultiply);
  EXPECT_EQ(e.nodes()[2].loc.column, 11);  // "2*t": the '*' is the 2nd character
  EXPECT_EQ(e.nodes()[4].kind, Kind::kCall);
  EXPECT_EQ(e.nodes()[4].function, ir::Function::kSin);
  EXPECT_EQ(e.nodes()[5].kind, Kind::kAdd);
  EXPECT_EQ(e.nodes()[5].loc.column, 14);
  EXPECT_EQ(e.depth(), 3);
  EXPECT_EQ(e.evaluate(0.5), 1.0 + std::sin(0.5));
  EXPECT_EQ(e.source().file, "m.yaml");
  EXPECT_EQ(e.source().what, "load #1: value");
  EXPECT_EQ(e.source().text, "2*t + sin(t)");
}

TEST(ExpressionParser, FlatSumUpToTheDepthLimitIsAccepted) {
  const ir::Expression e = parse_expression(flat_sum(kMaxExpressionTreeDepth), "m.yaml", {3, 10}, "v");
  EXPECT_EQ(e.depth(), kMaxExpressionTreeDepth);
  EXPECT_EQ(e.evaluate(1.0), kMaxExpressionTreeDepth);
}

TEST(ExpressionParser, FlatSumDeeperThanTheLimitIsRefusedAtTheOperator) {
  // The '+' after term 1000 makes the tree 1001 deep; it is character
  // 2 * 1000 - 1 (1-based) of the text, which starts at column 10.
  const std::string expected_column = std::to_string(10 + 2 * kMaxExpressionTreeDepth - 1);
  const std::string what = refusal(flat_sum(kMaxExpressionTreeDepth + 1));
  EXPECT_EQ(what.rfind("m.yaml:3:" + expected_column + ": load #1: value: a tree deeper than 1000 (the limit, "
                       "kMaxExpressionTreeDepth; a sum or product of n terms is n deep)", 0),
            0u)
      << what;
}

// The reproducer: 60,000 terms (120 KB) overflowed the stack of `mbfe generate`
// and of Python's mbfe.load.
TEST(ExpressionParser, SixtyThousandTermSumIsRefusedQuickly) {
  const std::clock_t start = std::clock();
  const std::string what = refusal(flat_sum(60000));
  const double seconds = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  EXPECT_NE(what.find("a tree deeper than 1000"), std::string::npos) << what;
  EXPECT_NE(what.find("(119999 characters)"), std::string::npos) << what;  // the text is shortened
  EXPECT_LT(what.size(), 400u);
  EXPECT_LT(seconds, kMaxParseSeconds);
}

TEST(ExpressionParser, MoreNodesThanTheLimitAreRefused) {
  // Sums of 500 terms in parentheses, added up: 501 deep, 999 nodes each.
  const std::string group = "(" + flat_sum(500) + ")";
  std::string text = group;
  for (int i = 1; i < 11; ++i) text += "+" + group;
  const std::string what = refusal(text);
  EXPECT_NE(what.find("more than 10000 numbers, names and operators (the limit, kMaxExpressionNodes)"),
            std::string::npos)
      << what;
  // Ten groups hold 9,999 nodes: accepted.
  std::string ten = group;
  for (int i = 1; i < 10; ++i) ten += "+" + group;
  EXPECT_EQ(parse_expression(ten, "m.yaml", {3, 10}, "v").nodes().size(), 9999u);
}

TEST(ExpressionParser, ConstantPartsThatAreNotFiniteAreRefusedAtTheirOperator) {
  // Column: 10 + the 0-based offset of the operator in the text.
  EXPECT_EQ(refusal("100*sin(t) + 1/0"),
            "m.yaml:3:24: load #1: value: division by zero; expected a finite value in expression "
            "\"100*sin(t) + 1/0\"");
  EXPECT_EQ(refusal("0/0*t"),
            "m.yaml:3:11: load #1: value: division by zero; expected a finite value in expression \"0/0*t\"");
  EXPECT_EQ(refusal("log(0)"),
            "m.yaml:3:10: load #1: value: log of 0; expected a finite value in expression \"log(0)\"");
  EXPECT_EQ(refusal("t*sqrt(-1)"),
            "m.yaml:3:12: load #1: value: sqrt of a negative number (-1); expected a finite value in expression "
            "\"t*sqrt(-1)\"");
  EXPECT_EQ(refusal("0^0"),
            "m.yaml:3:11: load #1: value: 0^0 is undefined; expected a finite value in expression \"0^0\"");
  EXPECT_EQ(refusal("exp(1000)"),
            "m.yaml:3:10: load #1: value: overflows a double (exp gives inf, beyond 1.8e308); expected a finite "
            "value in expression \"exp(1000)\"");
  // With t they are the run's business: finite almost everywhere.
  EXPECT_EQ(refusal("1/t + log(t) + sqrt(t - 1) + t^0"), "(accepted)");
  // exp(1000)/exp(1000) is 1, but the parts are checked, not only the whole.
  EXPECT_NE(refusal("exp(1000)/exp(1000)").find("overflows a double"), std::string::npos);
}

/// A one-body model with `count` torque loads whose value is `value`.
std::string model_with_loads(int count, const std::string& value) {
  std::ostringstream out;
  out << "model: m\nbodies:\n  - name: a\n    parent: ground\n    joint: {type: revolute}\n"
      << "    mass: 1\n    inertia: 1\nloads:\n";
  for (int i = 0; i < count; ++i) out << "  - {type: torque, body: a, value: \"" << value << "\"}\n";
  return out.str();
}

TEST(ExpressionParser, AllExpressionsOfAModelShareOneBudget) {
  // One load of 9,999 nodes fits the 10,000 of ParseLimits::max_expression_nodes; two do not.
  const std::string group = "(" + flat_sum(500) + ")";
  std::string value = group;
  for (int i = 1; i < 10; ++i) value += "+" + group;
  EXPECT_EQ(parse_model_text(model_with_loads(1, value), "m.yaml").loads.size(), 1u);
  try {
    parse_model_text(model_with_loads(2, value), "m.yaml");
    FAIL() << "accepted";
  } catch (const ir::ModelError& e) {
    // Line 10 holds the second load; the text of its value starts at column 37, after the quote.
    EXPECT_EQ(std::string(e.what()),
              "m.yaml:10:37: load #2: value: the expressions in t hold 19998 numbers, names and operators up "
              "to here, more than the limit of 10000 for the whole model (ParseLimits::max_expression_nodes)");
  }
  ParseLimits more;
  more.max_expression_nodes = 19998;
  EXPECT_EQ(parse_model_text(model_with_loads(2, value), "m.yaml", more).loads.size(), 2u);
}

}  // namespace
}  // namespace mbfe::frontend
