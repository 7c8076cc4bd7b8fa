// Prints GiNaC expressions as C++ in an order of our own.
//
// GiNaC keeps the operands of sums and products in an order that depends on
// hashes seeded from memory addresses, so its own printer gives different text
// from run to run. This printer sorts operands by their printed text, which
// makes the output byte-identical across runs and machines.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <string>

namespace mbfe::gen {

/// Names under which symbols are printed (inputs like "q[0]", temporaries like "t3").
using SymbolNames = std::map<GiNaC::ex, std::string, GiNaC::ex_is_less>;

class CppPrinter {
 public:
  explicit CppPrinter(const SymbolNames& names) : names_(names) {}

  /// C++ text of `e`. @throws std::logic_error for a symbol without a name or
  /// an expression kind the emitter does not support.
  std::string print(const GiNaC::ex& e) const;

  /// Arithmetic operations in the printed form of `e`: each +, -, *, / and
  /// each call of a math function counts one; a unary minus counts none.
  static long count_operations(const GiNaC::ex& e);

 private:
  std::string print_add(const GiNaC::ex& e) const;
  std::string print_mul(const GiNaC::ex& e) const;
  std::string print_power(const GiNaC::ex& e) const;
  std::string print_factor(const GiNaC::ex& e) const;
  const SymbolNames& names_;
};

/// The shortest decimal text that reads back as exactly the same double
/// (at most 17 significant digits), always with a '.' or an exponent.
std::string print_double(double value);


}  // namespace mbfe::gen
