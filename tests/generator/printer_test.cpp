// The C++ printer: exact constants, deterministic operand order, op counts.
#include <gtest/gtest.h>
#include <ginac/ginac.h>

#include <cstdlib>
#include <random>

#include "generator/emit/cpp_printer.h"
#include "generator/symbolic/code_list.h"

namespace mbfe::gen {
namespace {

TEST(PrintDouble, RoundTripsEveryDoubleExactly) {
  std::mt19937_64 rng(20261122);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-300, 300);
  for (int i = 0; i < 20000; ++i) {
    const double value = std::ldexp(mantissa(rng), exponent(rng));
    const std::string text = print_double(value);
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), value) << text;
    EXPECT_NE(text.find_first_of(".e"), std::string::npos) << "not a double literal: " << text;
  }
}

TEST(PrintDouble, PrefersShortForms) {
  EXPECT_EQ(print_double(0.1), "0.1");
  EXPECT_EQ(print_double(2.0), "2.0");
  EXPECT_EQ(print_double(-9.81), "-9.81");
  EXPECT_EQ(print_double(1.0 / 3.0), "0.3333333333333333");
}

TEST(Exact, IsTheDoubleItself) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> value(-1e6, 1e6);
  for (int i = 0; i < 1000; ++i) {
    const double v = value(rng);
    EXPECT_EQ(exact(v).to_double(), v);
  }
  EXPECT_EQ(exact(0.5), GiNaC::numeric(1, 2));
}

TEST(CppPrinter, OrderDoesNotDependOnSymbolCreationOrder) {
  // Two independent symbol sets created in opposite orders (GiNaC orders
  // operands by hashes of its own); the printed text must be the same.
  auto print_with = [](bool reversed) {
    GiNaC::symbol a("a"), b("b"), c("c");
    if (reversed) {
      GiNaC::symbol c2("c"), b2("b"), a2("a");
      SymbolNames names{{a2, "x[0]"}, {b2, "x[1]"}, {c2, "x[2]"}};
      return CppPrinter(names).print(3 * a2 * b2 - c2 * c2 + 0.5 * a2 - GiNaC::sin(b2) / c2);
    }
    SymbolNames names{{a, "x[0]"}, {b, "x[1]"}, {c, "x[2]"}};
    return CppPrinter(names).print(3 * a * b - c * c + 0.5 * a - GiNaC::sin(b) / c);
  };
  EXPECT_EQ(print_with(false), print_with(true));
}

TEST(CppPrinter, PrintsCompilableArithmetic) {
  GiNaC::symbol a("a"), b("b");
  SymbolNames names{{a, "a"}, {b, "b"}};
  CppPrinter printer(names);
  EXPECT_EQ(printer.print(a * a), "a*a");
  EXPECT_EQ(printer.print(a - b), "a - b");
  EXPECT_EQ(printer.print(-a * b), "-a*b");
  EXPECT_EQ(printer.print(a / b), "a/b");
  EXPECT_EQ(printer.print(GiNaC::cos(a)), "std::cos(a)");
}

TEST(CppPrinter, CountsOperations) {
  GiNaC::symbol a("a"), b("b"), c("c");
  EXPECT_EQ(CppPrinter::count_operations(a + b + c), 2);
  EXPECT_EQ(CppPrinter::count_operations(2 * a * b), 2);
  EXPECT_EQ(CppPrinter::count_operations(-a), 0);  // a sign is free
  EXPECT_EQ(CppPrinter::count_operations(a * a * a), 2);
  EXPECT_EQ(CppPrinter::count_operations(GiNaC::sin(a) + 1), 2);
  EXPECT_EQ(CppPrinter::count_operations(a / b), 1);
}

}  // namespace
}  // namespace mbfe::gen
