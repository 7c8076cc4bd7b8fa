#include "runtime/fem/expression_jet.h"

#include <cmath>
#include <vector>

namespace mbfe::runtime {

namespace {

using Kind = ir::ExpressionNode::Kind;
using ir::Function;

/// f(a) from f(a), f'(a), f''(a) by the chain rule.
Jet chain(const Jet& a, double f, double f1, double f2) {
  return {f, f1 * a.d1, f2 * a.d1 * a.d1 + f1 * a.d2};
}

Jet power(const Jet& a, const Jet& b) {
  if (b.d1 == 0.0 && b.d2 == 0.0) {  // a constant exponent: a^n, defined for a < 0 too
    const double n = b.value;
    const double f = std::pow(a.value, n);
    const double f1 = n == 0.0 ? 0.0 : n * std::pow(a.value, n - 1.0);
    const double f2 = (n == 0.0 || n == 1.0) ? 0.0 : n * (n - 1.0) * std::pow(a.value, n - 2.0);
    return chain(a, f, f1, f2);
  }
  // a^b = exp(b log a): g = b log a, f' = f g', f'' = f (g'' + g'^2).
  const double f = std::pow(a.value, b.value);
  const double la = std::log(a.value);
  const double g1 = b.d1 * la + b.value * a.d1 / a.value;
  const double g2 = b.d2 * la + 2.0 * b.d1 * a.d1 / a.value +
                    b.value * (a.d2 / a.value - a.d1 * a.d1 / (a.value * a.value));
  return {f, f * g1, f * (g2 + g1 * g1)};
}

Jet call(Function f, const Jet& a, const Jet& b) {
  const double x = a.value;
  switch (f) {
    case Function::kSin: return chain(a, std::sin(x), std::cos(x), -std::sin(x));
    case Function::kCos: return chain(a, std::cos(x), -std::sin(x), -std::cos(x));
    case Function::kTan: {
      const double t = std::tan(x);
      return chain(a, t, 1.0 + t * t, 2.0 * t * (1.0 + t * t));
    }
    case Function::kExp: {
      const double e = std::exp(x);
      return chain(a, e, e, e);
    }
    case Function::kLog: return chain(a, std::log(x), 1.0 / x, -1.0 / (x * x));
    case Function::kSqrt: {
      const double r = std::sqrt(x);
      return chain(a, r, 0.5 / r, -0.25 / (r * x));
    }
    case Function::kAbs: return x < 0.0 ? Jet{-x, -a.d1, -a.d2} : a;
    case Function::kMin: return b.value < a.value ? b : a;
    case Function::kMax: return b.value > a.value ? b : a;
    case Function::kStep: return {ir::unit_step(x), 0.0, 0.0};
  }
  return {};
}

}  // namespace

Jet evaluate_jet(const ir::Expression& e, double x) {
  std::vector<Jet> stack;
  stack.reserve(e.nodes().size());
  for (const ir::ExpressionNode& n : e.nodes()) {
    switch (n.kind) {
      case Kind::kNumber: stack.push_back({n.value, 0.0, 0.0}); continue;
      case Kind::kTime: stack.push_back({x, 1.0, 0.0}); continue;
      case Kind::kNegate: {
        Jet& a = stack.back();
        a = {-a.value, -a.d1, -a.d2};
        continue;
      }
      case Kind::kCall:
        if (n.arity() == 1) {
          stack.back() = call(n.function, stack.back(), Jet{});
          continue;
        }
        break;
      default: break;
    }
    const Jet b = stack.back();
    stack.pop_back();
    Jet& a = stack.back();
    switch (n.kind) {
      case Kind::kAdd: a = {a.value + b.value, a.d1 + b.d1, a.d2 + b.d2}; break;
      case Kind::kSubtract: a = {a.value - b.value, a.d1 - b.d1, a.d2 - b.d2}; break;
      case Kind::kMultiply:
        a = {a.value * b.value, a.d1 * b.value + a.value * b.d1,
             a.d2 * b.value + 2.0 * a.d1 * b.d1 + a.value * b.d2};
        break;
      case Kind::kDivide: {
        const double q = a.value / b.value;
        const double q1 = (a.d1 - q * b.d1) / b.value;
        const double q2 = (a.d2 - 2.0 * q1 * b.d1 - q * b.d2) / b.value;
        a = {q, q1, q2};
        break;
      }
      case Kind::kPower: a = power(a, b); break;
      case Kind::kCall: a = call(n.function, a, b); break;
      default: break;
    }
  }
  return stack.back();
}

}  // namespace mbfe::runtime
