#include "generator/symbolic/code_list.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <functional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "ir/shortest_decimal.h"

namespace mbfe::gen {

long AncestorPairAssembly::pairs() const {
  long count = 0;
  for (std::size_t k = 0; k < parent.size(); ++k)
    for (int j = static_cast<int>(k); j >= 0; j = parent[j]) ++count;
  return count;
}

bool AncestorPairAssembly::has_unrelated_pairs() const {
  const long n = static_cast<long>(parent.size());
  return pairs() != n * (n + 1) / 2;  // every pair is related only in a chain
}

bool AncestorPairAssembly::is_chain() const {
  for (std::size_t i = 0; i < parent.size(); ++i)
    if (parent[i] != static_cast<int>(i) - 1) return false;
  return true;
}

bool is_atomic(const GiNaC::ex& e) {
  return GiNaC::is_a<GiNaC::numeric>(e) || GiNaC::is_a<GiNaC::symbol>(e);
}

GiNaC::numeric exact(double value) {
  if (!std::isfinite(value)) throw std::invalid_argument("non-finite number in the model");
  if (value == 0.0) return 0;
  // The shortest decimal that reads back as this double ("0.7", not the
  // dyadic 3152519739159347/2^52): the same double when printed, small
  // rationals in the algebra, and products rounded once, at the end.
  char text[64];
  std::snprintf(text, sizeof text, "%.*e", ir::shortest_significant_digits(value) - 1, value);
  // text = [-]d.ddde[+-]xx
  const std::string str = text;
  const std::size_t e = str.find('e');
  long long mantissa = 0;
  int fraction_digits = 0;
  bool after_point = false;
  for (std::size_t i = 0; i < e; ++i) {
    if (str[i] == '.') after_point = true;
    else if (std::isdigit(static_cast<unsigned char>(str[i]))) {
      mantissa = mantissa * 10 + (str[i] - '0');
      if (after_point) ++fraction_digits;
    }
  }
  const int exponent = std::atoi(str.c_str() + e + 1) - fraction_digits;
  GiNaC::numeric result = GiNaC::numeric(mantissa) * GiNaC::numeric(10).power(exponent);
  return value < 0 ? -result : result;
}

SignedKey signed_key(const GiNaC::ex& e) {
  using GiNaC::is_a;
  if (is_a<GiNaC::symbol>(e)) return {1, GiNaC::ex_to<GiNaC::symbol>(e).get_name()};
  if (is_a<GiNaC::numeric>(e)) {
    const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(e);
    std::ostringstream text;
    text << GiNaC::abs(n);
    return {n.is_negative() ? -1 : 1, text.str()};
  }
  if (is_a<GiNaC::add>(e)) {
    std::vector<std::string> terms;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const SignedKey t = signed_key(e.op(i));
      terms.push_back(t.key + (t.sign < 0 ? "-" : "+"));
    }
    std::sort(terms.begin(), terms.end());
    // The sign that makes the first term positive is the sum's sign.
    const int sign = terms.front().back() == '-' ? -1 : 1;
    std::string key = "(";
    for (const std::string& t : terms) {
      const char own = t.back();
      key += t.substr(0, t.size() - 1) + ((own == '-') == (sign < 0) ? "+" : "-") + ",";
    }
    return {sign, key + ")"};
  }
  if (is_a<GiNaC::mul>(e)) {
    int sign = 1;
    std::vector<std::string> factors;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const SignedKey f = signed_key(e.op(i));
      sign *= f.sign;
      if (f.key != "1") factors.push_back(f.key);  // a unit coefficient carries only a sign
    }
    if (factors.size() == 1) return {sign, factors.front()};  // -x has the key of x
    std::sort(factors.begin(), factors.end());
    std::string key = "*(";
    for (const std::string& f : factors) key += f + ",";
    return {sign, key + ")"};
  }
  if (is_a<GiNaC::power>(e)) {
    const SignedKey base = signed_key(e.op(0));
    const GiNaC::ex exponent = e.op(1);
    int sign = 1;
    if (is_a<GiNaC::numeric>(exponent) && GiNaC::ex_to<GiNaC::numeric>(exponent).is_integer())
      sign = GiNaC::ex_to<GiNaC::numeric>(exponent).is_even() ? 1 : base.sign;
    else if (base.sign < 0)
      return {1, "^(-" + base.key + "," + signed_key(exponent).key + ")"};
    return {sign, "^(" + base.key + "," + signed_key(exponent).key + ")"};
  }
  std::string key = is_a<GiNaC::function>(e) ? GiNaC::ex_to<GiNaC::function>(e).get_name() : "?";
  key += "(";
  for (std::size_t i = 0; i < e.nops(); ++i) {
    const SignedKey a = signed_key(e.op(i));
    key += (a.sign < 0 ? "-" : "") + a.key + ",";
  }
  return {1, key + ")"};
}

namespace {

std::vector<GiNaC::ex> operands_by_signed_key(const GiNaC::ex& e) {
  std::vector<std::pair<std::string, GiNaC::ex>> keyed;
  for (std::size_t i = 0; i < e.nops(); ++i) {
    const SignedKey k = signed_key(e.op(i));
    keyed.emplace_back(k.key + (k.sign < 0 ? "-" : "+"), e.op(i));
  }
  std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<GiNaC::ex> out;
  for (auto& item : keyed) out.push_back(item.second);
  return out;
}

// Rebuilds a function call with canonical arguments.
struct CanonicalArguments : GiNaC::map_function {
  explicit CanonicalArguments(std::function<GiNaC::ex(const GiNaC::ex&)> f) : fn(std::move(f)) {}
  GiNaC::ex operator()(const GiNaC::ex& e) override { return fn(e); }
  std::function<GiNaC::ex(const GiNaC::ex&)> fn;
};

}  // namespace

GiNaC::ex CodeList::temporary_of_sum(const GiNaC::ex& sum) {
  const int sign = signed_key(sum).sign;
  const GiNaC::ex positive = sign < 0 ? GiNaC::ex(-sum) : sum;
  const GiNaC::ex temp = define_canonical(positive);
  return sign < 0 ? GiNaC::ex(-temp) : temp;
}

GiNaC::ex CodeList::canonical(const GiNaC::ex& e) {
  using GiNaC::is_a;
  if (is_atomic(e)) return e;
  auto as_operand = [this](const GiNaC::ex& x) {
    const GiNaC::ex c = canonical(x);
    return is_a<GiNaC::add>(c) ? temporary_of_sum(c) : c;
  };
  if (is_a<GiNaC::add>(e)) {
    GiNaC::ex sum = 0;
    for (const GiNaC::ex& term : operands_by_signed_key(e)) sum += canonical(term);
    return sum;
  }
  if (is_a<GiNaC::mul>(e)) {
    GiNaC::ex product = 1;
    for (const GiNaC::ex& factor : operands_by_signed_key(e)) product *= as_operand(factor);
    return product;
  }
  if (is_a<GiNaC::power>(e)) return GiNaC::pow(as_operand(e.op(0)), e.op(1));
  CanonicalArguments args(as_operand);
  return e.map(args);
}

GiNaC::ex CodeList::define(const GiNaC::ex& value) {
  if (is_atomic(value)) return value;
  return define_canonical(canonical(value));
}

GiNaC::ex CodeList::define_canonical(const GiNaC::ex& value) {
  if (is_atomic(value)) return value;
  if (auto it = by_value_.find(value); it != by_value_.end()) return assignments_[it->second].lhs;
  // Names are only for debugging: the emitter renumbers per kernel.
  GiNaC::symbol lhs("tmp" + std::to_string(assignments_.size()));
  by_value_.emplace(value, assignments_.size());
  by_symbol_.emplace(lhs, assignments_.size());
  assignments_.push_back({lhs, value});
  return lhs;
}

const GiNaC::ex* CodeList::definition(const GiNaC::ex& symbol) const {
  const auto it = by_symbol_.find(symbol);
  return it == by_symbol_.end() ? nullptr : &assignments_[it->second].rhs;
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
