// CoupledImplicitSystem on the double pendulum on its beam (the hand-written
// reference solver, a slider and a pin contact, damped beam): the Newton
// matrix it factors, every row of it (rigid, beam and contact), against
// central differences of its own residual along the direction it solves
// for; and the residual at the accelerations it gives is zero.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <memory>
#include <random>
#include <string>

#include "runtime/coupled/coupled_implicit_system.h"
#include "tests/runtime/coupled/pendulum_on_beam.h"

namespace mbfe::runtime {
namespace {

using namespace pendulum_on_beam;

struct State {
  Eigen::VectorXd q, v, a, lambda;
};

// Tip on the beam at x = 0.6 m, the beam slightly bent and everything moving.
State random_state(const CoupledDynamics& dyn, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  State s;
  s.q = Eigen::VectorXd::NullaryExpr(dyn.n(), [&]() { return 1e-4 * u(rng); });
  s.q.head<2>() = pendulum_angles_for_tip(0.6);
  s.v = Eigen::VectorXd::NullaryExpr(dyn.n(), [&]() { return 1e-2 * u(rng); });
  s.v.head<2>() << 0.3, -0.5;
  s.a = Eigen::VectorXd::NullaryExpr(dyn.n(), [&]() { return u(rng); });
  s.lambda = Eigen::VectorXd::NullaryExpr(dyn.m(), [&]() { return 10.0 * u(rng); });
  return s;
}

// The residual of a step, [r; c], as the stepper sees it: a function of
// (a, lambda) through q = q_pred + c_q a, v = v_pred + c_v a.
struct StepResidual {
  CoupledImplicitSystem& sys;
  Eigen::VectorXd q_pred, v_pred;
  double c_q, c_v;
  Eigen::VectorXd operator()(const Eigen::VectorXd& a, const Eigen::VectorXd& lambda) const {
    Eigen::VectorXd r, c;
    sys.residual(0.0, q_pred + c_q * a, v_pred + c_v * a, a, lambda, c_q, r, c);
    Eigen::VectorXd out(r.size() + c.size());
    out << r, c;
    return out;
  }
};

// Central differences along (x, x_lambda), the step chosen so that the
// positions move by kPositionStep: the truncation error, ~kPositionStep^2
// times O(1e2) second derivatives, is ~1e-8; the round-off of the contact
// rows Phi / c_q, ~eps / c_q over a difference of 2 kPositionStep / (c_q |x|),
// is ~1e-11 |x|, |x| up to 5e3 here. Against b of O(1), where a missing or
// wrong term of the matrix is O(1).
constexpr double kPositionStep = 1e-5;  // rad or m
constexpr double kNewtonMatrixTol = 1e-6;
// The residual at the accelerations the system solves for: round-off of
// O(1e2) forces.
constexpr double kResidualTol = 1e-10;

class CoupledImplicit : public ::testing::TestWithParam<bool> {};  // true: slider; false: pin

TEST_P(CoupledImplicit, NewtonMatrixIsTheDerivativeOfTheResidual) {
  const testing::TestBeam beam = make_beam(8, /*damping=*/true);
  auto dyn = make_dynamics(GetParam() ? *double_pendulum_beam_model() : *double_pendulum_beam_pin_model(), beam);
  CoupledImplicitSystem sys(dyn);
  const int n = dyn->n(), m = dyn->m();
  ASSERT_GT(m, 0);
  for (const auto [c_q, c_v] : {std::pair{1e-6, 1e-3}, std::pair{2.5e-5, 5e-3}}) {
    const State s = random_state(*dyn, 11);
    const StepResidual residual{sys, s.q - c_q * s.a, s.v - c_v * s.a, c_q, c_v};
    sys.factorize(0.0, s.q, s.v, s.a, s.lambda, c_q, c_v);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const Eigen::VectorXd b = Eigen::VectorXd::NullaryExpr(n, [&]() { return u(rng); });
    const Eigen::VectorXd bc = Eigen::VectorXd::NullaryExpr(m, [&]() { return u(rng); });
    Eigen::VectorXd x, xl;
    sys.solve(b, bc, x, xl);
    const double e = kPositionStep / (c_q * x.cwiseAbs().maxCoeff());
    const Eigen::VectorXd jx =
        (residual(s.a + e * x, s.lambda + e * xl) - residual(s.a - e * x, s.lambda - e * xl)) / (2.0 * e);
    Eigen::VectorXd expected(n + m);
    expected << b, bc;
    const Eigen::VectorXd diff = jx - expected;
    EXPECT_LT(diff.head(2).cwiseAbs().maxCoeff(), kNewtonMatrixTol) << "rigid rows, c_q " << c_q;
    EXPECT_LT(diff.segment(2, n - 2).cwiseAbs().maxCoeff(), kNewtonMatrixTol) << "beam rows, c_q " << c_q;
    EXPECT_LT(diff.tail(m).cwiseAbs().maxCoeff(), kNewtonMatrixTol) << "contact rows, c_q " << c_q;
  }
}

TEST_P(CoupledImplicit, ResidualVanishesAtTheAccelerationsItGives) {
  const testing::TestBeam beam = make_beam(8, true);
  auto dyn = make_dynamics(GetParam() ? *double_pendulum_beam_model() : *double_pendulum_beam_pin_model(), beam);
  CoupledImplicitSystem sys(dyn);
  State s = random_state(*dyn, 3);
  sys.accelerations(0.0, s.q, s.v, s.a, s.lambda);
  Eigen::VectorXd r, c, r0;
  sys.residual(0.0, s.q, s.v, s.a, s.lambda, 1.0, r, c);
  sys.residual(0.0, s.q, s.v, Eigen::VectorXd::Zero(dyn->n()), Eigen::VectorXd::Zero(dyn->m()), 1.0, r0, c);
  EXPECT_LT(r.cwiseAbs().maxCoeff(), kResidualTol * r0.cwiseAbs().maxCoeff());
}

INSTANTIATE_TEST_SUITE_P(Contacts, CoupledImplicit, ::testing::Values(true, false),
                         [](const ::testing::TestParamInfo<bool>& i) { return std::string(i.param ? "slider" : "pin"); });

}  // namespace
}  // namespace mbfe::runtime
