#include "ir/expression.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mbfe::ir {

Expression Expression::number(double v) {
  Expression e;
  e.kind = Kind::kNumber;
  e.value = v;
  return e;
}

double unit_step(double x) { return x >= 0.0 ? 1.0 : 0.0; }

double Expression::evaluate(double t) const {
  switch (kind) {
    case Kind::kNumber: return value;
    case Kind::kTime: return t;
    case Kind::kNegate: return -args[0].evaluate(t);
    case Kind::kAdd: return args[0].evaluate(t) + args[1].evaluate(t);
    case Kind::kSubtract: return args[0].evaluate(t) - args[1].evaluate(t);
    case Kind::kMultiply: return args[0].evaluate(t) * args[1].evaluate(t);
    case Kind::kDivide: return args[0].evaluate(t) / args[1].evaluate(t);
    case Kind::kPower: return std::pow(args[0].evaluate(t), args[1].evaluate(t));
    case Kind::kCall: break;
  }
  const double a = args[0].evaluate(t);
  if (function == "sin") return std::sin(a);
  if (function == "cos") return std::cos(a);
  if (function == "tan") return std::tan(a);
  if (function == "exp") return std::exp(a);
  if (function == "log") return std::log(a);
  if (function == "sqrt") return std::sqrt(a);
  if (function == "abs") return std::fabs(a);
  if (function == "step") return unit_step(a);
  if (function == "min") return std::min(a, args[1].evaluate(t));
  if (function == "max") return std::max(a, args[1].evaluate(t));
  throw std::logic_error("Expression: unknown function " + function);
}

bool Expression::is_constant() const {
  if (kind == Kind::kTime) return false;
  return std::all_of(args.begin(), args.end(), [](const Expression& a) { return a.is_constant(); });
}

}  // namespace mbfe::ir
