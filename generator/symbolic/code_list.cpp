#include "symbolic/code_list.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <stdexcept>

namespace mbfe::gen {

bool is_atomic(const GiNaC::ex& e) {
  return GiNaC::is_a<GiNaC::numeric>(e) || GiNaC::is_a<GiNaC::symbol>(e);
}

GiNaC::numeric exact(double value) {
  if (!std::isfinite(value)) throw std::invalid_argument("non-finite number in the model");
  if (value == 0.0) return 0;
  int exponent = 0;
  const double fraction = std::frexp(value, &exponent);  // value = fraction * 2^exponent
  const auto mantissa = static_cast<long long>(std::ldexp(fraction, 53));  // exact: 53 bits
  return GiNaC::numeric(mantissa) * GiNaC::numeric(2).power(exponent - 53);
}

GiNaC::ex CodeList::define(const GiNaC::ex& value) {
  if (is_atomic(value)) return value;
  if (auto it = by_value_.find(value); it != by_value_.end()) return assignments_[it->second].lhs;
  // Names are only for debugging: the emitter renumbers per kernel.
  GiNaC::symbol lhs("tmp" + std::to_string(assignments_.size()));
  by_value_.emplace(value, assignments_.size());
  by_symbol_.emplace(lhs, assignments_.size());
  assignments_.push_back({lhs, value});
  return lhs;
}

namespace {

void collect_symbols(const GiNaC::ex& e, std::vector<GiNaC::ex>& out) {
  if (GiNaC::is_a<GiNaC::symbol>(e)) {
    out.push_back(e);
    return;
  }
  for (std::size_t i = 0; i < e.nops(); ++i) collect_symbols(e.op(i), out);
}

}  // namespace

std::vector<Assignment> CodeList::closure(const std::vector<KernelOutput>& outputs) const {
  std::set<std::size_t> needed;
  std::vector<GiNaC::ex> pending;
  for (const auto& out : outputs) collect_symbols(out.value, pending);
  while (!pending.empty()) {
    const GiNaC::ex sym = pending.back();
    pending.pop_back();
    const auto it = by_symbol_.find(sym);
    if (it == by_symbol_.end() || !needed.insert(it->second).second) continue;  // input, or seen
    collect_symbols(assignments_[it->second].rhs, pending);
  }
  std::vector<Assignment> result;
  result.reserve(needed.size());
  for (std::size_t index : needed) result.push_back(assignments_[index]);  // std::set: sorted
  return result;
}

}  // namespace mbfe::gen
