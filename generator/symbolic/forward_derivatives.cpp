#include "generator/symbolic/forward_derivatives.h"

#include <algorithm>

namespace mbfe::gen {

namespace {

/// The distinct symbols of `e`, by name: a deterministic order, whatever
/// GiNaC's hash order of the operands.
std::vector<GiNaC::ex> symbols_of(const GiNaC::ex& e) {
  std::map<std::string, GiNaC::ex> found;
  std::vector<GiNaC::ex> pending{e};
  while (!pending.empty()) {
    const GiNaC::ex x = pending.back();
    pending.pop_back();
    if (GiNaC::is_a<GiNaC::symbol>(x)) {
      found.emplace(GiNaC::ex_to<GiNaC::symbol>(x).get_name(), x);
      continue;
    }
    for (std::size_t i = 0; i < x.nops(); ++i) pending.push_back(x.op(i));
  }
  std::vector<GiNaC::ex> out;
  for (auto& [name, s] : found) out.push_back(s);
  return out;
}

}  // namespace

ForwardDerivatives::ForwardDerivatives(CodeList& code, std::vector<GiNaC::symbol> variables)
    : code_(code), variables_(std::move(variables)) {}

GiNaC::ex ForwardDerivatives::derivative(const GiNaC::ex& value, int i) {
  GiNaC::ex sum = 0;
  for (const GiNaC::ex& s : symbols_of(value)) {
    const GiNaC::ex ds = of_symbol(s, i);
    if (ds.is_zero()) continue;
    sum += value.diff(GiNaC::ex_to<GiNaC::symbol>(s)) * ds;
  }
  return code_.define(sum);
}

GiNaC::ex ForwardDerivatives::of_symbol(const GiNaC::ex& symbol, int i) {
  if (symbol.is_equal(variables_[i])) return 1;
  const GiNaC::ex* rhs = code_.definition(symbol);
  if (rhs == nullptr) return 0;  // another input
  const auto key = std::make_pair(GiNaC::ex_to<GiNaC::symbol>(symbol).get_name(), i);
  if (auto it = memo_.find(key); it != memo_.end()) return it->second;
  const GiNaC::ex rhs_copy = *rhs;  // derivative() may grow the code list
  const GiNaC::ex d = derivative(rhs_copy, i);
  memo_.emplace(key, d);
  return d;
}

}  // namespace mbfe::gen
