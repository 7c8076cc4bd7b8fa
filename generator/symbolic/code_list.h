// A straight-line program under construction: named intermediates defined once,
// structurally equal expressions defined only once (value numbering on GiNaC's
// structural hash and equality), and the kernels that read them.
#pragma once

#include <ginac/ginac.h>

#include <optional>
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

/// A loop printed after a kernel's outputs, the assembly step of the
/// composite-rigid-body algorithm: for every body k and every body j on the
/// path from k to the ground (j == k included),
///   target[j*n + k] = target[k*n + j] = sum_c left[j][c] * right[k][c],
/// and target[r*n + c] = 0 for pairs where neither body is an ancestor of the
/// other. `left` and `right` are local n x width arrays that the kernel's
/// outputs fill (straight-line code, O(N)); the loop keeps the code for the
/// N(N+1)/2 entries of a chain's M from growing quadratically.
struct AncestorPairAssembly {
  std::string target;       // row-major n x n output, e.g. "M"
  std::string size_name = "kNumCoordinates";  // the emitted constant that is n
  std::string left, right;  // local arrays, e.g. "motion_subspace", "composite_momentum"
  std::string left_doc, right_doc;  // what a row of each holds (a comment in the emitted code)
  int width = 0;                    // components per row
  std::vector<int> parent;  // per body, -1 for the ground; a parent comes before its children

  /// Passes of the loop per call: the (ancestor, descendant) pairs, j == k included.
  long pairs() const;
  /// True when some pair of bodies is on no common path (a branched tree):
  /// their entries are zero and the target is cleared first.
  bool has_unrelated_pairs() const;
  /// True when every body's parent is the body before it (an unbranched
  /// chain): the walk up the tree is then j - 1, no table lookup.
  bool is_chain() const;
  /// Arithmetic operations of one pass: width products, width - 1 sums.
  long operations_per_pass() const { return width > 0 ? 2L * width - 1 : 0; }
};

/// A generated function: its statements (only those its outputs need, in
/// definition order), its outputs, and optionally an assembly loop after them.
struct Kernel {
  std::string name;       // C++ function name
  std::string signature;  // parameter list, e.g. "const double* q, double* M"
  std::string doc;        // one-line comment above the function
  std::vector<Assignment> statements;
  std::vector<KernelOutput> outputs;
  std::optional<AncestorPairAssembly> assembly;
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

  /// The value a temporary stands for; nullptr for an input symbol.
  const GiNaC::ex* definition(const GiNaC::ex& symbol) const;

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
