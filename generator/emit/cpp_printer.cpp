#include "generator/emit/cpp_printer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "generator/symbolic/time_functions.h"
#include "ir/shortest_decimal.h"

namespace mbfe::gen {

using GiNaC::ex;
using GiNaC::is_a;
using GiNaC::numeric;

std::string print_double(double value) {
  if (!std::isfinite(value)) throw std::overflow_error("a constant of the model overflows a double");
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", ir::shortest_significant_digits(value), value);
  std::string text = buffer;
  // Whole numbers read best in fixed notation: "10.0", not "1e+01".
  if (value == std::floor(value) && std::fabs(value) < 1e15) {
    std::snprintf(buffer, sizeof buffer, "%.0f", value);
    text = buffer;
  }
  if (text.find_first_of(".en") == std::string::npos) text += ".0";
  return text;
}

namespace {

std::vector<ex> operands_sorted(const ex& e, const CppPrinter& printer) {
  std::vector<std::pair<std::string, ex>> keyed;
  for (std::size_t i = 0; i < e.nops(); ++i) keyed.emplace_back(printer.print(e.op(i)), e.op(i));
  std::sort(keyed.begin(), keyed.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<ex> out;
  for (auto& item : keyed) out.push_back(item.second);
  return out;
}

// A term of a sum is printed after " - " when its leading coefficient is negative.
bool is_negative_term(const ex& e) {
  if (is_a<numeric>(e)) return GiNaC::ex_to<numeric>(e).is_negative();
  if (is_a<GiNaC::mul>(e)) {
    const ex coeff = e.op(e.nops() - 1);  // GiNaC keeps the numeric coefficient last
    return is_a<numeric>(coeff) && GiNaC::ex_to<numeric>(coeff).is_negative();
  }
  return false;
}

bool is_small_positive_integer(const ex& e, int max) {
  if (!is_a<numeric>(e)) return false;
  const numeric& n = GiNaC::ex_to<numeric>(e);
  return n.is_pos_integer() && n.to_int() <= max;
}

}  // namespace

std::string CppPrinter::print(const ex& e) const {
  if (is_a<numeric>(e)) {
    const numeric& n = GiNaC::ex_to<numeric>(e);
    if (!n.is_real()) throw std::logic_error("complex constant in generated code");
    return print_double(n.to_double());
  }
  if (is_a<GiNaC::symbol>(e)) {
    const auto it = names_.find(e);
    if (it == names_.end())
      throw std::logic_error("symbol without a C++ name: " + GiNaC::ex_to<GiNaC::symbol>(e).get_name());
    return it->second;
  }
  if (is_a<GiNaC::add>(e)) return print_add(e);
  if (is_a<GiNaC::mul>(e)) return print_mul(e);
  if (is_a<GiNaC::power>(e)) return print_power(e);
  if (is_a<GiNaC::function>(e)) {
    const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    static const std::map<std::string, std::string> kCalls = {
        {"sin", "std::sin"}, {"cos", "std::cos"}, {"tan", "std::tan"},
        {"exp", "std::exp"}, {"log", "std::log"}, {"abs", "std::abs"}};
    std::vector<std::string> args;
    for (std::size_t i = 0; i < e.nops(); ++i) args.push_back(print(e.op(i)));
    if (std::string text = print_time_function(name, args); !text.empty()) return text;
    const auto it = kCalls.find(name);
    if (it == kCalls.end()) throw std::logic_error("unsupported function in generated code: " + name);
    std::string text = it->second + "(";
    for (std::size_t i = 0; i < e.nops(); ++i) text += (i ? ", " : "") + print(e.op(i));
    return text + ")";
  }
  throw std::logic_error("unsupported expression kind in generated code");
}

std::string CppPrinter::print_add(const ex& e) const {
  // Positive terms first, then negative ones, each group by its text, and a
  // constant at the end: "t1*t2 - t3 + 0.5" reads as a human would write it.
  std::vector<std::pair<std::string, bool>> positive, negative;  // (text of |term|, is constant)
  for (std::size_t i = 0; i < e.nops(); ++i) {
    const ex term = e.op(i);
    const bool minus = is_negative_term(term);
    (minus ? negative : positive).emplace_back(print(minus ? ex(-term) : term), is_a<numeric>(term));
  }
  auto by_text = [](const auto& a, const auto& b) { return a.second != b.second ? b.second : a.first < b.first; };
  std::sort(positive.begin(), positive.end(), by_text);
  std::sort(negative.begin(), negative.end(), by_text);
  // A constant goes last whichever its sign.
  std::vector<std::pair<std::string, bool>> ordered;  // (text, negative)
  std::vector<std::pair<std::string, bool>> constants;
  for (const auto& [text, constant] : positive) (constant ? constants : ordered).emplace_back(text, false);
  for (const auto& [text, constant] : negative) (constant ? constants : ordered).emplace_back(text, true);
  ordered.insert(ordered.end(), constants.begin(), constants.end());
  std::string text;
  for (std::size_t i = 0; i < ordered.size(); ++i) {
    const auto& [body, minus] = ordered[i];
    if (i == 0) text = minus ? "-" + body : body;
    else text += (minus ? " - " : " + ") + body;
  }
  return text;
}

std::string CppPrinter::print_factor(const ex& e) const {
  if (is_a<GiNaC::add>(e)) return "(" + print(e) + ")";
  if (is_a<numeric>(e) && GiNaC::ex_to<numeric>(e).is_negative()) return "(" + print(e) + ")";
  return print(e);
}

std::string CppPrinter::print_mul(const ex& e) const {
  numeric coeff = 1;
  std::vector<ex> numerator, denominator;
  for (const ex& factor : operands_sorted(e, *this)) {
    if (is_a<numeric>(factor)) {
      coeff *= GiNaC::ex_to<numeric>(factor);
    } else if (is_a<GiNaC::power>(factor) && is_a<numeric>(factor.op(1)) &&
               GiNaC::ex_to<numeric>(factor.op(1)).is_negative() &&
               GiNaC::ex_to<numeric>(factor.op(1)).is_integer()) {
      denominator.push_back(GiNaC::power(factor.op(0), -factor.op(1)));
    } else {
      numerator.push_back(factor);
    }
  }
  std::string text;
  const bool negative = coeff.is_negative();
  const numeric magnitude = GiNaC::abs(coeff);
  if (magnitude != 1 || numerator.empty()) text = print_double(magnitude.to_double());
  for (const ex& factor : numerator) text += (text.empty() ? "" : "*") + print_factor(factor);
  if (!denominator.empty()) {
    std::string den;
    for (const ex& factor : denominator) den += (den.empty() ? "" : "*") + print_factor(factor);
    text += "/" + (denominator.size() > 1 || is_a<GiNaC::power>(denominator[0]) ? "(" + den + ")" : den);
  }
  return negative ? "-" + text : text;
}

std::string CppPrinter::print_power(const ex& e) const {
  const ex base = e.op(0);
  const ex exponent = e.op(1);
  if (is_small_positive_integer(exponent, 4)) {
    std::string text;
    const std::string b = print_factor(base);
    for (int i = 0; i < GiNaC::ex_to<numeric>(exponent).to_int(); ++i) text += (i ? "*" : "") + b;
    return text;
  }
  if (is_a<numeric>(exponent) && GiNaC::ex_to<numeric>(exponent).is_integer() &&
      GiNaC::ex_to<numeric>(exponent).is_negative())
    return "1.0/(" + print(GiNaC::power(base, -exponent)) + ")";
  if (exponent == GiNaC::numeric(1, 2)) return "std::sqrt(" + print(base) + ")";
  return "std::pow(" + print(base) + ", " + print(exponent) + ")";
}

long CppPrinter::count_operations(const ex& e) {
  if (is_a<numeric>(e) || is_a<GiNaC::symbol>(e)) return 0;
  if (is_a<GiNaC::mul>(e)) {
    // Printed as num1*num2*.../(den1*den2*...): count the joins, not the
    // divisions each power would cost on its own.
    long ops = 0, numerators = 0, denominators = 0;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const ex& f = e.op(i);
      if (is_a<numeric>(f)) {
        if (GiNaC::abs(GiNaC::ex_to<numeric>(f)) != 1) ++numerators;  // a unit is a sign only
        continue;
      }
      const bool reciprocal = is_a<GiNaC::power>(f) && is_a<numeric>(f.op(1)) &&
                              GiNaC::ex_to<numeric>(f.op(1)).is_integer() &&
                              GiNaC::ex_to<numeric>(f.op(1)).is_negative();
      if (reciprocal) {
        ops += count_operations(GiNaC::power(f.op(0), -f.op(1)));
        ++denominators;
      } else {
        ops += count_operations(f);
        ++numerators;
      }
    }
    ops += std::max(0L, numerators - 1);
    if (denominators > 0) ops += 1 + (denominators - 1);  // one division, denominators multiplied
    return ops;
  }
  long inner = 0;
  for (std::size_t i = 0; i < e.nops(); ++i) inner += count_operations(e.op(i));
  if (is_a<GiNaC::add>(e)) return inner + static_cast<long>(e.nops()) - 1;
  if (is_a<GiNaC::power>(e)) {
    const ex exponent = e.op(1);
    if (is_a<numeric>(exponent) && GiNaC::ex_to<numeric>(exponent).is_integer()) {
      const long n = std::labs(GiNaC::ex_to<numeric>(exponent).to_long());
      const long ops = GiNaC::ex_to<numeric>(exponent).is_negative() ? n : n - 1;  // n-1 muls (+1 div)
      return inner - count_operations(exponent) + std::max(0L, ops);
    }
    return inner + 1;
  }
  return inner + 1;  // a function call
}

}  // namespace mbfe::gen
