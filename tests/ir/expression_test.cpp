// ir::Expression: postfix trees evaluated against the same formulas written in
// C++, the faults found where a value stops being finite, and trees far deeper
// than the parser allows walked, copied and destroyed without recursion.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "ir/expression.h"

namespace mbfe::ir {
namespace {

using Kind = ExpressionNode::Kind;

ExpressionNode num(double v) {
  ExpressionNode n;
  n.kind = Kind::kNumber;
  n.value = v;
  return n;
}
ExpressionNode op(Kind kind, int column = 0) {
  ExpressionNode n;
  n.kind = kind;
  n.loc = {1, column};
  return n;
}
ExpressionNode call(Function f, int column = 0) {
  ExpressionNode n = op(Kind::kCall, column);
  n.function = f;
  return n;
}
const ExpressionNode kT = op(Kind::kTime);

TEST(Expression, EvaluatesLikeTheFormulaInCpp) {
  // max(0, 3 - t)*step(t - 1) + abs(t - 4)^2 + exp(-t)*sqrt(t + 1)/log(t + 2) + min(t, 1)/tan(t + 1)*cos(t)
  const Expression e({num(0),  num(3), kT, op(Kind::kSubtract), call(Function::kMax), kT, num(1),
                      op(Kind::kSubtract), call(Function::kStep), op(Kind::kMultiply), kT, num(4),
                      op(Kind::kSubtract), call(Function::kAbs), num(2), op(Kind::kPower), op(Kind::kAdd), kT,
                      op(Kind::kNegate), call(Function::kExp), kT, num(1), op(Kind::kAdd), call(Function::kSqrt),
                      op(Kind::kMultiply), kT, num(2), op(Kind::kAdd), call(Function::kLog), op(Kind::kDivide),
                      op(Kind::kAdd), kT, num(1), call(Function::kMin), kT, num(1), op(Kind::kAdd),
                      call(Function::kTan), op(Kind::kDivide), kT, call(Function::kCos), op(Kind::kMultiply),
                      op(Kind::kAdd)});
  for (double t : {0.0, 0.5, 1.0, 2.5, 4.0, 7.25}) {
    const double expected = std::max(0.0, 3 - t) * (t >= 1 ? 1.0 : 0.0) + std::pow(std::fabs(t - 4), 2) +
                            std::exp(-t) * std::sqrt(t + 1) / std::log(t + 2) +
                            std::min(t, 1.0) / std::tan(t + 1) * std::cos(t);
    EXPECT_EQ(e.evaluate(t), expected) << "t = " << t;  // the same operations in the same order
  }
  EXPECT_FALSE(e.is_constant());
  EXPECT_TRUE(Expression::number(2.5).is_constant());
  EXPECT_EQ(Expression().evaluate(3.0), 0.0);
}

// t + t + ... + t, as the parser builds it: ((t + t) + t) + ..., one level per term.
Expression flat_sum(int terms) {
  std::vector<ExpressionNode> nodes{kT};
  for (int i = 1; i < terms; ++i) {
    nodes.push_back(kT);
    nodes.push_back(op(Kind::kAdd));
  }
  return Expression(std::move(nodes));
}

// A tree 200,000 levels deep (the parser stops at 1000; 60,000 crashed the
// recursive walks of a nested tree): a recursive walk, copy or destructor
// would need tens of megabytes of stack.
TEST(Expression, VeryDeepTreeIsWalkedCopiedAndDestroyedWithoutRecursion) {
  constexpr int kTerms = 200000;
  const Expression e = flat_sum(kTerms);
  EXPECT_EQ(e.depth(), kTerms);
  EXPECT_EQ(e.evaluate(0.5), 0.5 * kTerms);  // exact: halves and integers below 2^53
  EXPECT_FALSE(e.is_constant());
  EXPECT_FALSE(e.fault_at(0.5));
  EXPECT_FALSE(e.constant_fault());
  const Expression copy = e;  // NOLINT: the copy is the point
  EXPECT_EQ(copy.evaluate(2.0), 2.0 * kTerms);
}

// Right-nested: t - (t - (t - ...)) holds every value until the end, past the
// 32 evaluate() keeps on the stack.
TEST(Expression, DeepRightNestingNeedsMoreThanTheInlineStack) {
  constexpr int kTerms = 100;
  std::vector<ExpressionNode> nodes;
  for (int i = 0; i < kTerms; ++i) nodes.push_back(kT);
  for (int i = 1; i < kTerms; ++i) nodes.push_back(op(Kind::kSubtract));
  const Expression e(std::move(nodes));
  // 100 terms alternate: t - t + t - ... - t = 0 for an even count.
  EXPECT_EQ(e.evaluate(3.0), 0.0);
  EXPECT_EQ(e.depth(), kTerms);
}

TEST(Expression, RefusesWhatIsNotOneTreeInPostfixOrder) {
  EXPECT_THROW(Expression({op(Kind::kAdd)}), std::logic_error);
  EXPECT_THROW(Expression({kT, kT}), std::logic_error);
  EXPECT_THROW(Expression(std::vector<ExpressionNode>{}), std::logic_error);
  EXPECT_THROW(Expression({kT, call(Function::kMin)}), std::logic_error);  // min takes two
}

TEST(Expression, FaultAtNamesTheFirstNodeWhereTheValueStopsBeingFinite) {
  // 1/(t - 0.5): the division, at t = 0.5 only.
  const Expression e({num(1), kT, num(0.5), op(Kind::kSubtract, 3), op(Kind::kDivide, 2)});
  EXPECT_FALSE(e.fault_at(0.4));
  const auto fault = e.fault_at(0.5);
  ASSERT_TRUE(fault);
  EXPECT_EQ(fault->node, 4);
  EXPECT_EQ(fault->value, std::numeric_limits<double>::infinity());
  EXPECT_EQ(fault->reason, "division by zero");

  // exp(1/(t - 0.5)) * 0: the NaN at the end comes from the inf of the division.
  const Expression outer({num(1), kT, num(0.5), op(Kind::kSubtract), op(Kind::kDivide, 2), call(Function::kExp),
                          num(0), op(Kind::kMultiply)});
  EXPECT_TRUE(std::isnan(outer.evaluate(0.5)));
  ASSERT_TRUE(outer.fault_at(0.5));
  EXPECT_EQ(outer.fault_at(0.5)->node, 4);

  const Expression log_t({kT, call(Function::kLog, 1)});
  EXPECT_EQ(log_t.fault_at(0.0)->reason, "log of 0");
  EXPECT_EQ(log_t.fault_at(-2.0)->reason, "log of a negative number (-2)");
  const Expression root({kT, call(Function::kSqrt)});
  EXPECT_EQ(root.fault_at(-0.25)->reason, "sqrt of a negative number (-0.25)");
  const Expression grow({kT, call(Function::kExp)});
  EXPECT_FALSE(grow.fault_at(709.0));
  EXPECT_EQ(grow.fault_at(710.0)->reason, "overflows a double (exp gives inf, beyond 1.8e308)");
  // t^t is 1 at t = 0 in C++ (and in the generated code): not a fault of a run.
  EXPECT_FALSE(Expression({kT, kT, op(Kind::kPower)}).fault_at(0.0));
}

TEST(Expression, ConstantFaultLooksOnlyAtPartsWithoutT) {
  // t + 1/0: the division, whatever t.
  const auto division = Expression({kT, num(1), num(0), op(Kind::kDivide, 7), op(Kind::kAdd)}).constant_fault();
  ASSERT_TRUE(division);
  EXPECT_EQ(division->node, 3);
  EXPECT_EQ(division->reason, "division by zero");
  EXPECT_EQ(Expression({num(0), num(0), op(Kind::kPower)}).constant_fault()->reason, "0^0 is undefined");
  EXPECT_EQ(Expression({num(0), num(-2), op(Kind::kPower)}).constant_fault()->reason,
            "0 to the negative power -2 (a division by zero)");
  EXPECT_EQ(Expression({num(-8), num(1), num(3), op(Kind::kDivide), op(Kind::kPower)}).constant_fault()->reason,
            "a negative number to a non-integer power ((-8)^0.3333333333333333 is not real)");
  EXPECT_EQ(Expression({num(1e200), num(1e200), op(Kind::kMultiply)}).constant_fault()->reason,
            "overflows a double (* gives inf, beyond 1.8e308)");
  // Parts with t are left to the run: 1/t, t^0, log(t - 1).
  EXPECT_FALSE(Expression({num(1), kT, op(Kind::kDivide)}).constant_fault());
  EXPECT_FALSE(Expression({kT, num(0), op(Kind::kPower)}).constant_fault());
  EXPECT_FALSE(Expression({kT, num(1), op(Kind::kSubtract), call(Function::kLog)}).constant_fault());
}

TEST(Expression, DescribesAFaultWithItsSourceAndPosition) {
  const Expression e({num(100), kT, op(Kind::kDivide, 12)},
                     ExpressionSource{"m.yaml", "load #1: value", "100/t", {9, 9}});
  const auto fault = e.fault_at(0.0);
  ASSERT_TRUE(fault);
  EXPECT_EQ(describe_fault(e, *fault, 0.0), "load #1: value \"100/t\" is inf at t = 0 s: division by zero");
  EXPECT_EQ(node_location(e, fault->node), "m.yaml:1:12");
}

}  // namespace
}  // namespace mbfe::ir
