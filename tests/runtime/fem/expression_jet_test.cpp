// Value, slope and curvature of an expression in s by forward-mode
// differentiation, against derivatives worked by hand and against central
// differences of Expression::evaluate for every function the parser knows.
#include "runtime/fem/expression_jet.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "frontend/expression_parser.h"

namespace mbfe::runtime {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Forward mode is exact up to round-off on O(1) values.
constexpr double kExactTol = 1e-12;
// Central differences with step kStep: truncation error about kStep^2 |f'''| / 6
// (slope) and kStep^2 |f''''| / 12 (curvature), round-off eps |f| / kStep^2 in
// the curvature; the expressions below have derivatives of order 10 at most.
constexpr double kStep = 1e-4;
constexpr double kDifferenceTol = 1e-5;

ir::Expression parse(const std::string& text) {
  return frontend::parse_expression(text, "test.yaml", ir::SourceLoc{1, 1}, "profile.expression", "s");
}

TEST(ExpressionJet, SineProfileHasTheSlopeAndCurvatureWorkedByHand) {
  const ir::Expression e = parse("0.002*sin(2*pi*s/25)");
  for (double s : {0.0, 3.7, 12.5, 24.0}) {
    const Jet j = evaluate_jet(e, s);
    const double k = 2 * kPi / 25;
    EXPECT_NEAR(j.value, 0.002 * std::sin(k * s), kExactTol);
    EXPECT_NEAR(j.d1, 0.002 * k * std::cos(k * s), kExactTol);
    EXPECT_NEAR(j.d2, -0.002 * k * k * std::sin(k * s), kExactTol);
  }
}

TEST(ExpressionJet, QuotientAndVariablePowerMatchTheirClosedForms) {
  // f = s^s = exp(s log s): f' = f (log s + 1), f'' = f ((log s + 1)^2 + 1/s).
  const ir::Expression power = parse("s^s");
  // g = 1 / (1 + s^2): g' = -2s g^2, g'' = (6 s^2 - 2) g^3.
  const ir::Expression quotient = parse("1/(1 + s^2)");
  for (double s : {0.5, 1.0, 2.3}) {
    const Jet f = evaluate_jet(power, s);
    const double fv = std::pow(s, s), l = std::log(s) + 1;
    EXPECT_NEAR(f.value, fv, kExactTol * fv);
    EXPECT_NEAR(f.d1, fv * l, kExactTol * fv * 10);
    EXPECT_NEAR(f.d2, fv * (l * l + 1 / s), kExactTol * fv * 10);
    const Jet g = evaluate_jet(quotient, s);
    const double gv = 1 / (1 + s * s);
    EXPECT_NEAR(g.d1, -2 * s * gv * gv, kExactTol);
    EXPECT_NEAR(g.d2, (6 * s * s - 2) * gv * gv * gv, kExactTol);
  }
}

TEST(ExpressionJet, EveryFunctionAgreesWithCentralDifferences) {
  for (const char* text : {"sin(3*s) + cos(s^2)", "tan(0.3*s)", "exp(-s/2)*log(s + 2)", "sqrt(s + 1)",
                           "abs(s - 5)^3", "min(s, 2*s - 1) + max(0.1*s, 1)", "step(s - 9)*s^2",
                           "-(s^3 - 2)/(s + 4)", "2^(0.5*s)"}) {
    const ir::Expression e = parse(text);
    for (double s : {0.3, 1.7, 4.2, 6.1}) {
      const Jet j = evaluate_jet(e, s);
      const double fp = e.evaluate(s + kStep), f0 = e.evaluate(s), fm = e.evaluate(s - kStep);
      EXPECT_NEAR(j.value, f0, kExactTol * (1 + std::abs(f0))) << text << " at s = " << s;
      EXPECT_NEAR(j.d1, (fp - fm) / (2 * kStep), kDifferenceTol * (1 + std::abs(j.d1))) << text << " at s = " << s;
      EXPECT_NEAR(j.d2, (fp - 2 * f0 + fm) / (kStep * kStep), 10 * kDifferenceTol * (1 + std::abs(j.d2)))
          << text << " at s = " << s;
    }
  }
}

}  // namespace
}  // namespace mbfe::runtime
