#include "ir/expression.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "ir/shortest_decimal.h"

namespace mbfe::ir {

namespace {

using Kind = ExpressionNode::Kind;

// Intermediate values evaluate() keeps on the stack before it allocates.
constexpr int kInlineValues = 32;

std::string shown(double v) {
  if (!std::isfinite(v)) return std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf");
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", shortest_significant_digits(v), v);
  return text;
}

/// The value of node `n` from the values of its arguments `a`.
double apply(const ExpressionNode& n, const double* a) {
  switch (n.kind) {
    case Kind::kNumber: return n.value;
    case Kind::kTime: break;
    case Kind::kNegate: return -a[0];
    case Kind::kAdd: return a[0] + a[1];
    case Kind::kSubtract: return a[0] - a[1];
    case Kind::kMultiply: return a[0] * a[1];
    case Kind::kDivide: return a[0] / a[1];
    case Kind::kPower: return std::pow(a[0], a[1]);
    case Kind::kCall:
      switch (n.function) {
        case Function::kSin: return std::sin(a[0]);
        case Function::kCos: return std::cos(a[0]);
        case Function::kTan: return std::tan(a[0]);
        case Function::kExp: return std::exp(a[0]);
        case Function::kLog: return std::log(a[0]);
        case Function::kSqrt: return std::sqrt(a[0]);
        case Function::kAbs: return std::fabs(a[0]);
        case Function::kMin: return std::min(a[0], a[1]);
        case Function::kMax: return std::max(a[0], a[1]);
        case Function::kStep: return unit_step(a[0]);
      }
      break;
  }
  throw std::logic_error("Expression: a node without a value");
}

/// Why node `n`, of finite arguments `a`, has the value `v`, which is not finite.
std::string fault_reason(const ExpressionNode& n, const double* a, double v) {
  if (n.kind == Kind::kDivide && a[1] == 0.0) return "division by zero";
  if (n.kind == Kind::kPower && a[0] == 0.0 && a[1] < 0.0)
    return "0 to the negative power " + shown(a[1]) + " (a division by zero)";
  if (n.kind == Kind::kPower && a[0] < 0.0 && std::isnan(v))
    return "a negative number to a non-integer power ((" + shown(a[0]) + ")^" + shown(a[1]) + " is not real)";
  if (n.kind == Kind::kCall && n.function == Function::kLog)
    return a[0] == 0.0 ? "log of 0" : "log of a negative number (" + shown(a[0]) + ")";
  if (n.kind == Kind::kCall && n.function == Function::kSqrt)
    return "sqrt of a negative number (" + shown(a[0]) + ")";
  if (std::isnan(v)) return "not a number";
  return "overflows a double (" + n.symbol() + " gives " + shown(v) + ", beyond 1.8e308)";
}

/// A postfix walk that tracks, for every value on the stack, whether it is
/// finite and whether it depends on t; stops at the first fault.
/// `constants_only`: nodes that depend on t are not evaluated, and 0^0 is a fault.
std::optional<ExpressionFault> find_fault(const std::vector<ExpressionNode>& nodes, int stack_size, double t,
                                          bool constants_only) {
  struct Slot {
    double value;
    bool constant;
  };
  std::vector<Slot> stack(static_cast<std::size_t>(stack_size));
  int top = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const ExpressionNode& n = nodes[i];
    const int arity = n.arity();
    Slot* args = stack.data() + top - arity;
    double a[2] = {0.0, 0.0};
    bool constant = n.kind != Kind::kTime;
    bool finite_args = true;
    for (int k = 0; k < arity; ++k) {
      a[k] = args[k].value;
      constant = constant && args[k].constant;
      finite_args = finite_args && std::isfinite(a[k]);
    }
    Slot result{0.0, constant};
    if (n.kind == Kind::kTime) result.value = t;
    else if (constants_only && !constant) result.value = 0.0;  // not evaluated, never a fault
    else result.value = apply(n, a);
    if (!constants_only || constant) {
      if (finite_args && !std::isfinite(result.value))
        return ExpressionFault{static_cast<int>(i), result.value, fault_reason(n, a, result.value)};
      if (constants_only && n.kind == Kind::kPower && a[0] == 0.0 && a[1] == 0.0)
        return ExpressionFault{static_cast<int>(i), result.value, "0^0 is undefined"};
    }
    top -= arity;
    stack[top++] = result;
  }
  return std::nullopt;
}

}  // namespace

int ExpressionNode::arity() const {
  switch (kind) {
    case Kind::kNumber:
    case Kind::kTime: return 0;
    case Kind::kNegate: return 1;
    case Kind::kCall: return kExpressionFunctions[static_cast<int>(function)].arity;
    default: return 2;
  }
}

std::string ExpressionNode::symbol() const {
  switch (kind) {
    case Kind::kNumber: return shown(value);
    case Kind::kTime: return "t";
    case Kind::kNegate: return "-";
    case Kind::kAdd: return "+";
    case Kind::kSubtract: return "-";
    case Kind::kMultiply: return "*";
    case Kind::kDivide: return "/";
    case Kind::kPower: return "^";
    case Kind::kCall: return kExpressionFunctions[static_cast<int>(function)].name;
  }
  return "?";
}

double unit_step(double x) { return x >= 0.0 ? 1.0 : 0.0; }

Expression::Expression() : nodes_{ExpressionNode{}} {}

Expression::Expression(std::vector<ExpressionNode> postfix, ExpressionSource source)
    : nodes_(std::move(postfix)), source_(std::move(source)) {
  // The depth of every value on a simulated evaluation stack.
  std::vector<int> depths;
  for (const ExpressionNode& n : nodes_) {
    if (n.kind == Kind::kCall &&
        static_cast<std::size_t>(n.function) >= sizeof kExpressionFunctions / sizeof kExpressionFunctions[0])
      throw std::logic_error("Expression: unknown function");
    const int arity = n.arity();
    if (static_cast<int>(depths.size()) < arity) throw std::logic_error("Expression: a node lacks its arguments");
    int deepest = 0;
    for (int k = 0; k < arity; ++k) {
      deepest = std::max(deepest, depths.back());
      depths.pop_back();
    }
    depths.push_back(deepest + 1);
    stack_size_ = std::max(stack_size_, static_cast<int>(depths.size()));
  }
  if (depths.size() != 1) throw std::logic_error("Expression: not one complete tree in postfix order");
  depth_ = depths.back();
}

Expression Expression::number(double v, SourceLoc loc) {
  ExpressionNode n;
  n.kind = Kind::kNumber;
  n.value = v;
  n.loc = loc;
  return Expression({n});
}

double Expression::evaluate(double t) const {
  double inline_values[kInlineValues];
  std::vector<double> heap;
  double* stack = inline_values;
  if (stack_size_ > kInlineValues) {
    heap.resize(static_cast<std::size_t>(stack_size_));
    stack = heap.data();
  }
  int top = 0;
  for (const ExpressionNode& n : nodes_) {
    switch (n.kind) {
      case Kind::kNumber: stack[top++] = n.value; break;
      case Kind::kTime: stack[top++] = t; break;
      default: {
        const int arity = n.arity();
        const double value = apply(n, stack + top - arity);
        top -= arity;
        stack[top++] = value;
      }
    }
  }
  return stack[0];
}

bool Expression::is_constant() const {
  return std::none_of(nodes_.begin(), nodes_.end(), [](const ExpressionNode& n) { return n.kind == Kind::kTime; });
}

std::optional<ExpressionFault> Expression::fault_at(double t) const {
  return find_fault(nodes_, stack_size_, t, false);
}

std::optional<ExpressionFault> Expression::constant_fault() const {
  return find_fault(nodes_, stack_size_, 0.0, true);
}

std::string describe_fault(const Expression& e, const ExpressionFault& fault, double t) {
  char time[40];
  std::snprintf(time, sizeof time, "%.6g", t);
  const ExpressionSource& s = e.source();
  const std::string value = s.text.empty() ? std::string("the value") : "\"" + s.text + "\"";
  const char* unit = s.variable == "t" ? " s: " : " m: ";
  return (s.what.empty() ? "" : s.what + " ") + value + " is " + shown(fault.value) + " at " + s.variable + " = " +
         time + unit + fault.reason;
}

std::string node_location(const Expression& e, int node) {
  const SourceLoc loc = e.nodes()[static_cast<std::size_t>(node)].loc;
  const std::string& file = e.source().file;
  if (loc.line <= 0) return file;
  return file + ":" + std::to_string(loc.line) + ":" + std::to_string(loc.column);
}

}  // namespace mbfe::ir
