// A closed-form expression in time t: the value of a load that varies with
// time, or the motion of a driven joint.
//
// The front end parses the model file's text into it
// (frontend/expression_parser.h); the generator turns it into GiNaC and prints
// C++ from it, the runtime evaluates it directly. The text itself never
// reaches generated code.
//
// The tree is stored flat, in postfix order: every node comes after its
// arguments and the root is last (`2*t + 1` is `2 t * 1 +`). Evaluating,
// converting, copying and destroying an expression are loops over that array,
// never recursion, so the depth of the tree a file writes (a sum of 60,000
// terms is a tree 60,000 deep) cannot exhaust the stack. The parser bounds the
// depth and the size anyway (docs/model-format.md, "Expressions").
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "ir/source_loc.h"

namespace mbfe::ir {

/// The functions an expression may call, with their argument counts.
struct ExpressionFunction {
  const char* name;
  int arity;
};
inline constexpr ExpressionFunction kExpressionFunctions[] = {
    {"sin", 1}, {"cos", 1}, {"tan", 1}, {"exp", 1}, {"log", 1}, {"sqrt", 1},
    {"abs", 1}, {"min", 2}, {"max", 2}, {"step", 1}};

/// Index into kExpressionFunctions, in the same order.
enum class Function { kSin, kCos, kTan, kExp, kLog, kSqrt, kAbs, kMin, kMax, kStep };

/// One node of an expression.
struct ExpressionNode {
  enum class Kind {
    kNumber,  // `value`
    kTime,    // t
    kNegate,  // -a
    kAdd, kSubtract, kMultiply, kDivide, kPower,  // a op b
    kCall,    // function(a) or function(a, b)
  };
  Kind kind = Kind::kNumber;
  double value = 0.0;                // kNumber
  Function function = Function::kSin;  // kCall
  SourceLoc loc;  // its token: the number, t, the operator, the function's name

  /// How many arguments the node takes (0, 1 or 2).
  int arity() const;
  /// The operator's symbol or the function's name ("+", "sqrt"); "t"; the number.
  std::string symbol() const;
};

/// Where an expression was written, for messages; empty for one built in code.
struct ExpressionSource {
  std::string file;  // the model file, as it was opened
  std::string what;  // which value: "load #1: value", "body 'slider': joint.motion"
  std::string text;  // as written
  SourceLoc loc;     // of the text's first character
  /// The variable the text is written in: "t" (time, s) or, for a running
  /// surface's profile, "s" (the position along the beam, m). Messages only:
  /// the tree holds it as Kind::kTime either way.
  std::string variable = "t";
};

/// Where a value stops being finite: the first node (in postfix order) whose
/// arguments are finite but whose own value is not, or a power 0^0.
struct ExpressionFault {
  int node = -1;       // index into Expression::nodes()
  double value = 0.0;  // its value: inf, -inf or NaN (1 for 0^0)
  std::string reason;  // "division by zero", "log of a negative number (-2)", ...
};

/// step(x): 0 for x < 0, 1 for x >= 0 (so step(t - a) switches on at t = a).
double unit_step(double x);

class Expression {
 public:
  using Kind = ExpressionNode::Kind;

  /// The number 0.
  Expression();
  /// `postfix` must hold one complete tree in postfix order.
  /// @throws std::logic_error when it does not.
  explicit Expression(std::vector<ExpressionNode> postfix, ExpressionSource source = {});
  static Expression number(double v, SourceLoc loc = {});

  /// The nodes, each after its arguments, the root last; never empty.
  const std::vector<ExpressionNode>& nodes() const { return nodes_; }
  const ExpressionSource& source() const { return source_; }
  /// Depth of the tree: 1 for a number or t, 3 for `t + t + t`.
  int depth() const { return depth_; }

  /// The value at time t (IEEE arithmetic: may be inf or NaN). Allocates
  /// nothing unless the expression needs more than 32 intermediate values.
  double evaluate(double t) const;
  /// True when t does not occur.
  bool is_constant() const;
  /// Where the value at t stops being finite; empty when it is finite.
  std::optional<ExpressionFault> fault_at(double t) const;
  /// The first part that does not depend on t and is not finite (1/0,
  /// log(0), sqrt(-1), exp(1000)) or is 0^0; empty when there is none.
  std::optional<ExpressionFault> constant_fault() const;

 private:
  std::vector<ExpressionNode> nodes_;
  ExpressionSource source_;
  int depth_ = 1;
  int stack_size_ = 1;  // intermediate values a postfix evaluation holds at most
};

/// `fault` of `e` at time t in words, without a location:
/// `load #1: value "1/t" is inf at t = 0 s: division by zero`.
std::string describe_fault(const Expression& e, const ExpressionFault& fault, double t);

/// "file:line:col" of node `node` of `e` ("file" alone when it has no position).
std::string node_location(const Expression& e, int node);

/// When a load acts: start <= t < stop (seconds).
struct TimeWindow {
  double start = -std::numeric_limits<double>::infinity();
  double stop = std::numeric_limits<double>::infinity();
  bool contains(double t) const { return t >= start && t < stop; }
  bool always() const { return start == -std::numeric_limits<double>::infinity() &&
                               stop == std::numeric_limits<double>::infinity(); }
};

}  // namespace mbfe::ir
