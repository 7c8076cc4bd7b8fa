// Expressions in t as GiNaC expressions (generator/symbolic/time_functions.h):
// long sums converted without recursion to what GiNaC builds from the same
// terms, and every GiNaC error on an expression a ModelError at its operator.
#include <gtest/gtest.h>
#include <ginac/ginac.h>

#include <cmath>
#include <string>

#include "frontend/expression_parser.h"
#include "frontend/parse_model.h"
#include "generator/emit/generate_solver.h"
#include "generator/symbolic/code_list.h"
#include "generator/symbolic/time_functions.h"
#include "ir/model_error.h"

namespace mbfe::gen {
namespace {

ir::Expression parsed(const std::string& text) {
  return frontend::parse_expression(text, "m.yaml", {9, 20}, "load #1: value");
}

/// The ModelError message of converting `text`, or "(converted)".
std::string conversion_error(const std::string& text) {
  const GiNaC::symbol t("t");
  try {
    to_ginac(parsed(text), t);
  } catch (const ir::ModelError& e) {
    return e.what();
  }
  return "(converted)";
}

TEST(TimeFunctions, LongSumEqualsTheSumGinacBuildsFromItsTerms) {
  // 1.01*sin(1.5*t) + 1.02*sin(2.5*t) + ... : 990 terms, 990 deep.
  const GiNaC::symbol t("t");
  std::string text;
  GiNaC::ex expected = 0;
  for (int k = 1; k <= 990; ++k) {
    text += (k > 1 ? " + " : "") + std::to_string(100 + k) + "/100*sin(" + std::to_string(k) + ".5*t)";
    expected += GiNaC::numeric(100 + k, 100) * GiNaC::sin(exact(k + 0.5) * t);
  }
  const GiNaC::ex converted = to_ginac(parsed(text), t);
  EXPECT_TRUE((converted - expected).is_zero());
  EXPECT_EQ(converted.nops(), 990u);  // one GiNaC sum, flat
}

TEST(TimeFunctions, UndefinedForEveryTIsAnErrorAtTheOperator) {
  // The text starts at column 20: an operator at offset k is at column 20 + k.
  EXPECT_EQ(conversion_error("1/(t-t)"),
            "m.yaml:9:21: load #1: value: a division by zero for every t (GiNaC: power::eval(): division by zero); "
            "expected a real, finite value in expression \"1/(t-t)\"");
  EXPECT_EQ(conversion_error("log(t-t)"),
            "m.yaml:9:20: load #1: value: the log of 0 for every t (GiNaC: log_eval(): log(0)); expected a real, "
            "finite value in expression \"log(t-t)\"");
  EXPECT_EQ(conversion_error("(t-t)^0"),
            "m.yaml:9:25: load #1: value: 0^0, which is undefined, for every t (0 raised to 0); expected a real, finite "
            "value in expression \"(t-t)^0\"");
  EXPECT_EQ(conversion_error("(t-t)^(-2)"),
            "m.yaml:9:25: load #1: value: a division by zero for every t (0 raised to a negative power); expected a "
            "real, finite value in expression \"(t-t)^(-2)\"");
  EXPECT_EQ(conversion_error("2 + sqrt(t-t-1)"),
            "m.yaml:9:24: load #1: value: 'sqrt' is not real for any t (a negative number under a root or a log); "
            "expected a real, finite value in expression \"2 + sqrt(t-t-1)\"");
  EXPECT_NE(conversion_error("log(t-t-1)").find("m.yaml:9:20: load #1: value: 'log' is not real"), std::string::npos);
  // Exact for GiNaC, but 1e600 in the generated code.
  EXPECT_EQ(conversion_error("t*1e300*1e300"),
            "m.yaml:9:27: load #1: value: '*' gives a number beyond 1.8e308 (it overflows a double); expected a "
            "real, finite value in expression \"t*1e300*1e300\"");
  EXPECT_EQ(conversion_error("t^2 + 1/(t+1)"), "(converted)");
}

TEST(TimeFunctions, LargeIntegerPowersOfNumbersAreTakenInDoubles) {
  // Exact, 1.0000001^1e9 has seven billion digits; the double is exp(1e9 log(1.0000001)).
  const GiNaC::symbol t("t");
  const GiNaC::ex big = to_ginac(parsed("1.0000001^1000000000*t"), t);
  const GiNaC::ex expected = exact(std::pow(1.0000001, 1e9)) * t;
  EXPECT_TRUE((big - expected).is_zero());
  // Up to kMaxExactExponent GiNaC stays exact: 2^1000 is an integer.
  const GiNaC::ex exact_power = to_ginac(parsed("2^1000"), t);
  EXPECT_TRUE((exact_power - GiNaC::pow(GiNaC::numeric(2), 1000)).is_zero());
  EXPECT_NE(conversion_error("(t-t+2)^2000").find("'^' overflows a double"), std::string::npos);
}

TEST(TimeFunctions, MotionWhoseDerivativeIsUndefinedIsAnErrorAtItsOperator) {
  const std::string text = R"yaml(model: m
bodies:
  - name: slider
    parent: ground
    joint: {type: prismatic, axis: [1, 0], motion: "0^t"}
    mass: 1
    inertia: 0
  - name: arm
    parent: slider
    joint: {type: revolute}
    mass: 1
    inertia: 1
)yaml";
  const ir::Model model = frontend::parse_model_text(text, "m.yaml");
  try {
    generate_solver(model);
    FAIL() << "generated";
  } catch (const ir::ModelError& e) {
    // At the '^' (the text starts at column 53).
    EXPECT_EQ(std::string(e.what()),
              "m.yaml:5:54: body 'slider': joint.motion: '^' raises 0 to a power in t (0, 1 or undefined by the "
              "exponent's sign, and without a derivative); expected a real, finite value in expression \"0^t\"");
  }
}

}  // namespace
}  // namespace mbfe::gen
