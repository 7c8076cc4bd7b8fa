// A straight-line program under construction: named intermediates defined once,
// structurally equal expressions defined only once (value numbering on GiNaC's
// structural hash and equality), and the kernels that read them.
#pragma once

#include <ginac/ginac.h>

#include <string>
#include <unordered_map>
#include <vector>

namespace mbfe::gen {

/// One `const double lhs = rhs;` statement.
struct Assignment {
  GiNaC::symbol lhs;
  GiNaC::ex rhs;
};

/// One output of a kernel: `target = value;`, e.g. `M[3] = t7;`.
struct KernelOutput {
  std::string target;
  GiNaC::ex value;
};

/// A generated function: its statements (only those its outputs need, in
/// definition order) and its outputs.
struct Kernel {
  std::string name;       // C++ function name
  std::string signature;  // parameter list, e.g. "const double* q, double* M"
  std::string doc;        // one-line comment above the function
  std::vector<Assignment> statements;
  std::vector<KernelOutput> outputs;
};

class CodeList {
 public:
  /// Returns `value` itself when printing it costs nothing (a number or a
  /// symbol); otherwise a temporary that holds it, shared with every earlier
  /// call for a structurally equal value.
  GiNaC::ex define(const GiNaC::ex& value);

  /// `value` rebuilt in a canonical form that does not depend on GiNaC's
  /// hash order: every sum that is a factor, a base or a function argument
  /// becomes a temporary of the sum with its leading term positive (GiNaC
  /// otherwise folds a -1 into whichever sum it happens to meet first), and
  /// operands are visited in a sign-independent structural order.
  GiNaC::ex canonical(const GiNaC::ex& value);

  const std::vector<Assignment>& assignments() const { return assignments_; }

  /// The statements that `outputs` depend on, in definition order.
  std::vector<Assignment> closure(const std::vector<KernelOutput>& outputs) const;

 private:
  GiNaC::ex define_canonical(const GiNaC::ex& value);
  GiNaC::ex temporary_of_sum(const GiNaC::ex& sum);
  std::vector<Assignment> assignments_;
  std::unordered_map<GiNaC::ex, std::size_t, std::hash<GiNaC::ex>, GiNaC::ex_is_equal> by_value_;
  std::unordered_map<GiNaC::ex, std::size_t, std::hash<GiNaC::ex>, GiNaC::ex_is_equal> by_symbol_;
};

/// A structural key of `e` up to sign, and that sign: `e` and the same value
/// with a -1 folded into any of its sums get the same key. Symbols are keyed
/// by their GiNaC names (deterministic: inputs and numbered temporaries).
struct SignedKey {
  int sign = 1;
  std::string key;
};
SignedKey signed_key(const GiNaC::ex& e);

/// True for numbers and symbols: things printed without an operation.
bool is_atomic(const GiNaC::ex& e);

/// The shortest decimal rational that reads back as the given finite double
/// (0.7 -> 7/10): exact arithmetic in the derivation, so products with 0 and 1
/// vanish and every constant is rounded to a double once, when printed.
GiNaC::numeric exact(double value);

}  // namespace mbfe::gen
