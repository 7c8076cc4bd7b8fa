// Common-subexpression elimination keeps values and removes repeats.
#include <gtest/gtest.h>
#include <ginac/ginac.h>

#include <random>

#include "generator/emit/cpp_printer.h"
#include "generator/symbolic/code_list.h"
#include "generator/symbolic/cse.h"

namespace mbfe::gen {
namespace {

// Substitutes the statements back into the outputs: the value the kernel computes.
GiNaC::ex inline_kernel(const Kernel& k, const GiNaC::ex& e) {
  GiNaC::ex value = e;
  for (auto it = k.statements.rbegin(); it != k.statements.rend(); ++it) value = value.subs(it->lhs == it->rhs);
  return value;
}

TEST(Cse, HoistsRepeatedSubexpressionsAndKeepsValues) {
  GiNaC::symbol x("x"), y("y");
  const GiNaC::ex shared = GiNaC::sin(x) * y + GiNaC::pow(x, 2);
  Kernel k{"k", "", "", {}, {{"out[0]", shared * 3 + y}, {"out[1]", shared - x}, {"out[2]", GiNaC::cos(shared)}}};
  const Kernel before = k;
  const int added = eliminate_common_subexpressions(k);
  EXPECT_GE(added, 1);
  // Each output now refers to a temporary instead of repeating `shared`.
  long ops_before = 0, ops_after = 0;
  for (const auto& o : before.outputs) ops_before += CppPrinter::count_operations(o.value);
  for (const auto& s : k.statements) ops_after += CppPrinter::count_operations(s.rhs);
  for (const auto& o : k.outputs) ops_after += CppPrinter::count_operations(o.value);
  EXPECT_LT(ops_after, ops_before);
  // Same values at random points (exact rationals: no tolerance needed).
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> num(-50, 50);
  for (int trial = 0; trial < 20; ++trial) {
    const GiNaC::numeric xv(num(rng), 7), yv(num(rng), 11);
    for (std::size_t i = 0; i < k.outputs.size(); ++i) {
      const GiNaC::ex a = before.outputs[i].value.subs(GiNaC::lst{x == xv, y == yv});
      const GiNaC::ex b = inline_kernel(k, k.outputs[i].value).subs(GiNaC::lst{x == xv, y == yv});
      EXPECT_TRUE((a - b).evalf().is_zero() || GiNaC::abs((a - b).evalf()) < 1e-12) << i;
    }
  }
}

TEST(CodeList, DefinesEqualValuesOnce) {
  GiNaC::symbol q("q");
  CodeList code;
  const GiNaC::ex first = code.define(GiNaC::cos(q) * 2);
  const GiNaC::ex second = code.define(2 * GiNaC::cos(q));
  EXPECT_TRUE(first.is_equal(second));
  EXPECT_EQ(code.assignments().size(), 1u);
  EXPECT_TRUE(code.define(q).is_equal(q));  // symbols stay inline
}

}  // namespace
}  // namespace mbfe::gen
