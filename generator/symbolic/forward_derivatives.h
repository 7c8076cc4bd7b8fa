// Derivatives of a straight-line program (CodeList) by the chain rule, forward
// through its temporaries: d t_k / d x = sum_s (d rhs_k / d s) (d s / d x)
// over the symbols s that rhs_k reads, each derivative itself a temporary of
// the same CodeList (shared, never expanded). What automatic differentiation
// does at run time, done once in the generator: the Jacobian kernels are
// straight-line code of the same size class as the kernels they differentiate.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "generator/symbolic/code_list.h"

namespace mbfe::gen {

class ForwardDerivatives {
 public:
  /// Derivatives with respect to `variables` (input symbols of `code`).
  ForwardDerivatives(CodeList& code, std::vector<GiNaC::symbol> variables);

  /// d value / d variables[i]: 0, a number, or an expression over temporaries
  /// and inputs of the code list.
  GiNaC::ex derivative(const GiNaC::ex& value, int i);

 private:
  GiNaC::ex of_symbol(const GiNaC::ex& symbol, int i);

  CodeList& code_;
  std::vector<GiNaC::symbol> variables_;
  std::map<std::pair<std::string, int>, GiNaC::ex> memo_;  // (temporary's name, variable)
};

}  // namespace mbfe::gen
