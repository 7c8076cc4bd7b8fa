#include "generator/symbolic/time_functions.h"

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "generator/symbolic/code_list.h"
#include "ir/model_error.h"

// GiNaC's function macros declare at namespace scope.
namespace mbfe::gen {

DECLARE_FUNCTION_1P(mbfe_step)
DECLARE_FUNCTION_1P(mbfe_sign)
DECLARE_FUNCTION_1P(mbfe_fabs)
DECLARE_FUNCTION_2P(mbfe_fmin)
DECLARE_FUNCTION_2P(mbfe_fmax)

namespace {

using GiNaC::ex;

bool is_number(const ex& x) { return GiNaC::is_exactly_a<GiNaC::numeric>(x) && GiNaC::ex_to<GiNaC::numeric>(x).is_real(); }
GiNaC::numeric num(const ex& x) { return GiNaC::ex_to<GiNaC::numeric>(x); }

ex step_eval(const ex& x) {
  if (is_number(x)) return num(x).is_negative() ? 0 : 1;
  return mbfe_step(x).hold();
}
ex step_deriv(const ex&, unsigned) { return 0; }

ex sign_eval(const ex& x) {
  if (is_number(x)) return num(x).is_zero() ? 0 : (num(x).is_negative() ? -1 : 1);
  return mbfe_sign(x).hold();
}
ex sign_deriv(const ex&, unsigned) { return 0; }

ex fabs_eval(const ex& x) {
  if (is_number(x)) return GiNaC::abs(num(x));
  return mbfe_fabs(x).hold();
}
ex fabs_deriv(const ex& x, unsigned) { return mbfe_sign(x); }

ex fmin_eval(const ex& a, const ex& b) {
  if (is_number(a) && is_number(b)) return num(a) < num(b) ? a : b;
  return mbfe_fmin(a, b).hold();
}
// d min(a, b) / da = 1 where a <= b.
ex fmin_deriv(const ex& a, const ex& b, unsigned p) {
  return p == 0 ? mbfe_step(b - a) : 1 - mbfe_step(b - a);
}

ex fmax_eval(const ex& a, const ex& b) {
  if (is_number(a) && is_number(b)) return num(a) < num(b) ? b : a;
  return mbfe_fmax(a, b).hold();
}
ex fmax_deriv(const ex& a, const ex& b, unsigned p) {
  return p == 0 ? mbfe_step(a - b) : 1 - mbfe_step(a - b);
}

}  // namespace

REGISTER_FUNCTION(mbfe_step, eval_func(step_eval).derivative_func(step_deriv))
REGISTER_FUNCTION(mbfe_sign, eval_func(sign_eval).derivative_func(sign_deriv))
REGISTER_FUNCTION(mbfe_fabs, eval_func(fabs_eval).derivative_func(fabs_deriv))
REGISTER_FUNCTION(mbfe_fmin, eval_func(fmin_eval).derivative_func(fmin_deriv))
REGISTER_FUNCTION(mbfe_fmax, eval_func(fmax_eval).derivative_func(fmax_deriv))

namespace {

// A number to an integer power is computed exactly by GiNaC: 0.5^100000000
// would take 30 million digits and seconds, 0.5^1e10 all the memory. Beyond
// this exponent the power of two numbers is taken in double arithmetic.
constexpr long kMaxExactExponent = 1024;

/// x^y when both are numbers and y is an integer beyond kMaxExactExponent.
std::optional<ex> large_numeric_power(const ex& x, const ex& y) {
  if (!is_number(x) || !is_number(y) || !num(y).is_integer()) return std::nullopt;
  if (GiNaC::abs(num(y)) <= kMaxExactExponent) return std::nullopt;
  const double value = std::pow(num(x).to_double(), num(y).to_double());
  if (!std::isfinite(value)) throw std::overflow_error("the power is beyond 1.8e308");
  return ex(exact(value));
}

/// Node `n` of arguments `a` as a GiNaC expression (GiNaC evaluates it at once,
/// so 1/(t - t) throws here).
ex convert(const ir::ExpressionNode& n, const ex* a, const GiNaC::symbol& t) {
  using Kind = ir::ExpressionNode::Kind;
  switch (n.kind) {
    case Kind::kNumber: return exact(n.value);
    case Kind::kTime: return t;
    case Kind::kNegate: return -a[0];
    case Kind::kAdd: return a[0] + a[1];
    case Kind::kSubtract: return a[0] - a[1];
    case Kind::kMultiply: return a[0] * a[1];
    case Kind::kDivide: return a[0] / a[1];
    case Kind::kPower: {
      if (const auto folded = large_numeric_power(a[0], a[1])) return *folded;
      return GiNaC::pow(a[0], a[1]);
    }
    case Kind::kCall: break;
  }
  switch (n.function) {
    case ir::Function::kSin: return GiNaC::sin(a[0]);
    case ir::Function::kCos: return GiNaC::cos(a[0]);
    case ir::Function::kTan: return GiNaC::tan(a[0]);
    case ir::Function::kExp: return GiNaC::exp(a[0]);
    case ir::Function::kLog: return GiNaC::log(a[0]);
    case ir::Function::kSqrt: return GiNaC::sqrt(a[0]);
    case ir::Function::kAbs: return mbfe_fabs(a[0]);
    case ir::Function::kStep: return mbfe_step(a[0]);
    case ir::Function::kMin: return mbfe_fmin(a[0], a[1]);
    case ir::Function::kMax: return mbfe_fmax(a[0], a[1]);
  }
  throw std::logic_error("to_ginac: unknown function");
}

/// True when a number in `x` is not real (sqrt(t - t - 1) is I, log(t - t - 1) is I*Pi).
bool has_non_real_number(const ex& x) {
  for (auto it = x.preorder_begin(); it != x.preorder_end(); ++it)
    if (GiNaC::is_a<GiNaC::numeric>(*it) && !GiNaC::ex_to<GiNaC::numeric>(*it).is_real()) return true;
  return false;
}

/// What a GiNaC exception at node `n` means, in the words of the model file.
std::string what_failed(const ir::ExpressionNode& n, const std::string& ginac_message) {
  using Kind = ir::ExpressionNode::Kind;
  if (ginac_message.find("pow(0,0)") != std::string::npos) return "0^0, which is undefined,";
  if (n.kind == Kind::kDivide || n.kind == Kind::kPower) return "a division by zero";
  if (n.kind == Kind::kCall && n.function == ir::Function::kLog) return "the log of 0";
  return "'" + n.symbol() + "' undefined";
}

/// True when `x`, or the number that multiplies it, is beyond the range of a
/// double: t*1e300*1e300 is exact for GiNaC but prints as inf.
bool beyond_double(const ex& x) {
  static const GiNaC::numeric kLargest = exact(std::numeric_limits<double>::max());
  ex coefficient = x;
  if (GiNaC::is_exactly_a<GiNaC::mul>(x)) coefficient = x.op(x.nops() - 1);
  return is_number(coefficient) && GiNaC::abs(num(coefficient)) > kLargest;
}

[[noreturn]] void undefined(const ir::Expression& e, const ir::ExpressionNode& n, const std::string& why) {
  const ir::ExpressionSource& s = e.source();
  throw ir::ModelError(s.file, n.loc,
                       s.what + ": " + why + "; expected a real, finite value in expression \"" + s.text + "\"");
}

}  // namespace

ex to_ginac(const ir::Expression& e, const GiNaC::symbol& t) {
  // A postfix walk with a stack of converted arguments: no recursion, however
  // deep the tree.
  std::vector<ex> stack;
  for (const ir::ExpressionNode& n : e.nodes()) {
    const std::size_t arity = static_cast<std::size_t>(n.arity());
    const ex* args = stack.data() + stack.size() - arity;
    // 0^x with x in t: GiNaC keeps it, but its derivative 0^x log(0) throws
    // from inside GiNaC's differentiation, which then leaks what it had built.
    if (n.kind == ir::ExpressionNode::Kind::kPower && is_number(args[0]) && num(args[0]).is_zero() &&
        !is_number(args[1]))
      undefined(e, n, "'^' raises 0 to a power in t (0, 1 or undefined by the exponent's sign, and without a "
                      "derivative)");
    // 0^0 and 0^-k: GiNaC's pow() throws from the evaluation of the power it
    // has just allocated, and leaks it; say it here instead.
    if (n.kind == ir::ExpressionNode::Kind::kPower && is_number(args[0]) && num(args[0]).is_zero() &&
        is_number(args[1]) && num(args[1]).is_real() && !num(args[1]).is_positive())
      undefined(e, n, std::string(num(args[1]).is_zero() ? "0^0, which is undefined," : "a division by zero") +
                          " for every t (0 raised to " + (num(args[1]).is_zero() ? "0" : "a negative power") + ")");
    ex value;
    try {
      value = convert(n, args, t);
    } catch (const std::domain_error& error) {  // GiNaC's pole_error: 1/(t-t), log(t-t), (t-t)^0
      undefined(e, n, what_failed(n, error.what()) + " for every t (GiNaC: " + error.what() + ")");
    } catch (const std::overflow_error& error) {  // large_numeric_power
      undefined(e, n, "'" + n.symbol() + "' overflows a double (" + error.what() + ")");
    } catch (const std::runtime_error& error) {  // GiNaC's numeric range errors
      undefined(e, n, what_failed(n, error.what()) + " for every t (GiNaC: " + error.what() + ")");
    }
    if (beyond_double(value))
      undefined(e, n, "'" + n.symbol() + "' gives a number beyond 1.8e308 (it overflows a double)");
    // Only powers and functions turn real arguments into complex values.
    if ((n.kind == ir::ExpressionNode::Kind::kPower || n.kind == ir::ExpressionNode::Kind::kCall) &&
        has_non_real_number(value))
      undefined(e, n, "'" + n.symbol() + "' is not real for any t (a negative number under a root or a log)");
    stack.resize(stack.size() - arity);
    stack.push_back(value);
  }
  return stack.back();
}

ex window_factor(const ir::TimeWindow& window, const GiNaC::symbol& t) {
  ex factor = 1;
  if (std::isfinite(window.start)) factor = factor * mbfe_step(t - exact(window.start));
  if (std::isfinite(window.stop)) factor = factor * (1 - mbfe_step(t - exact(window.stop)));
  return factor;
}

std::string print_time_function(const std::string& name, const std::vector<std::string>& args) {
  if (name == "mbfe_step") return "(" + args[0] + " >= 0.0 ? 1.0 : 0.0)";
  if (name == "mbfe_sign") return "((" + args[0] + " > 0.0) - (" + args[0] + " < 0.0))";
  if (name == "mbfe_fabs") return "std::fabs(" + args[0] + ")";
  if (name == "mbfe_fmin") return "std::fmin(" + args[0] + ", " + args[1] + ")";
  if (name == "mbfe_fmax") return "std::fmax(" + args[0] + ", " + args[1] + ")";
  return {};
}

}  // namespace mbfe::gen
