// Order of accuracy of every integrator on problems with known solutions, the
// paper's Fig. 3, and the simulation driver's rows, divergence and a stop request.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <string>
#include <vector>

#include "runtime/integrators/integrator.h"
#include "runtime/integrators/simulation_driver.h"
#include "tests/runtime/integrators/test_systems.h"

namespace mbfe::runtime {
namespace {

using testing::Oscillator;
using testing::Riccati;
using testing::Scalar;

/// Error at t_end of a fixed-step run.
template <class System, class Exact>
double error_at(System& sys, const std::string& integrator, double h, double t_end, const Eigen::VectorXd& y0,
                Exact exact) {
  SimulationOptions opt;
  opt.step = h;
  opt.t_end = t_end;
  double t_last = 0.0, y_last = 0.0;
  const auto r = run_simulation(sys, parse_integrator(integrator), y0, opt, [&](double t, const Eigen::VectorXd& y) {
    t_last = t;
    y_last = y[0];
  });
  EXPECT_EQ(r.status, SimulationStatus::kCompleted) << integrator;
  return std::abs(y_last - exact(t_last));
}

// Observed order log2(e(h) / e(h/2)) of a p-th order method approaches p;
// +-0.15 leaves room for the h^(p+1) terms at these steps while telling
// every order apart.
constexpr double kOrderTol = 0.15;

struct OrderCase {
  const char* integrator;
  int order;
  double h;  // coarse step: asymptotic, and its error well above round-off
};

class OrderTest : public ::testing::TestWithParam<OrderCase> {};

TEST_P(OrderTest, NonlinearRiccati) {
  const OrderCase c = GetParam();
  Riccati sys;
  const Eigen::VectorXd y0 = Eigen::VectorXd::Constant(1, 1.0);
  const double e1 = error_at(sys, c.integrator, c.h, 1.0, y0, Riccati::exact);
  const double e2 = error_at(sys, c.integrator, c.h / 2, 1.0, y0, Riccati::exact);
  const double order = std::log2(e1 / e2);
  EXPECT_NEAR(order, c.order, kOrderTol) << c.integrator << " errors " << e1 << ", " << e2;
  EXPECT_EQ(parse_integrator(c.integrator).order(), c.order);
}

INSTANTIATE_TEST_SUITE_P(
    Integrators, OrderTest,
    ::testing::Values(OrderCase{"forward_euler", 1, 1e-3}, OrderCase{"backward_euler", 1, 1e-3},
                      OrderCase{"explicit_midpoint", 2, 1e-3}, OrderCase{"trapezoid", 2, 1e-2},
                      OrderCase{"rk4", 4, 5e-2}, OrderCase{"ab2", 2, 1e-2}, OrderCase{"bdf2", 2, 1e-2},
                      // Adams-Bashforth 3 through the general form.
                      OrderCase{"lmm:alpha=0,0,-1,1:beta=0.4166666666666667,-1.3333333333333333,"
                                "1.9166666666666667,0",
                                3, 1e-2},
                      // Adams-Moulton 2 (implicit, order 3).
                      OrderCase{"lmm:alpha=0,-1,1:beta=-0.08333333333333333,0.6666666666666666,"
                                "0.4166666666666667",
                                3, 2e-2}),
    [](const ::testing::TestParamInfo<OrderCase>& info) {
      std::string n = info.param.integrator;
      if (n.rfind("lmm:", 0) == 0) return std::string("lmm_") + std::to_string(info.index);
      return n;
    });

TEST(GeneralizedAlpha, SecondOrderOnDampedOscillator) {
  Oscillator sys(10.0, 0.05, 3.0);
  const Eigen::VectorXd y0 = Eigen::VectorXd::Zero(2);
  auto exact = [&](double t) { return sys.exact(t); };
  for (double rho : {0.0, 0.5, 0.9, 1.0}) {
    auto run = [&](double h) {
      SimulationOptions opt;
      opt.step = h;
      opt.t_end = 2.0;
      IntegratorSpec spec = parse_integrator("generalized_alpha");
      spec.rho_inf = rho;
      double q = 0.0, tl = 0.0;
      run_simulation(sys, spec, y0, opt, [&](double t, const Eigen::VectorXd& y) {
        tl = t;
        q = y[0];
      });
      return std::abs(q - exact(tl));
    };
    const double e1 = run(2e-3), e2 = run(1e-3);
    EXPECT_NEAR(std::log2(e1 / e2), 2.0, kOrderTol) << "rho_inf " << rho;
  }
}

// One implicit step of a 2x2 linear system vs its closed form: values ~1e-2, rounding ~1e-18.
constexpr double kOneStepTol = 1e-15;

TEST(Implicit, LinearSystemsUseTheExactShiftedSolve) {
  // Backward Euler and the trapezoid rule on the linear oscillator: one Newton
  // iteration with the exact (I - c J)^-1 must reproduce the closed-form
  // one-step maps.
  Oscillator sys(10.0, 0.05, 3.0);
  Eigen::Matrix2d a;
  a << 0, 1, -100, -1;
  const Eigen::Vector2d b(0, 3);
  const double h = 0.01;
  Eigen::VectorXd y = Eigen::VectorXd::Zero(2);
  auto be = make_stepper(parse_integrator("backward_euler"), sys);
  be->reset(0, y);
  be->step(0, h, y);
  const Eigen::Vector2d y_be = (Eigen::Matrix2d::Identity() - h * a).inverse() * (h * b);
  EXPECT_NEAR((y - Eigen::VectorXd(y_be)).norm(), 0.0, kOneStepTol);
  y.setZero();
  auto tr = make_stepper(parse_integrator("trapezoid"), sys);
  tr->reset(0, y);
  tr->step(0, h, y);
  const Eigen::Vector2d y_tr = (Eigen::Matrix2d::Identity() - 0.5 * h * a).inverse() * (h * b);
  EXPECT_NEAR((y - Eigen::VectorXd(y_tr)).norm(), 0.0, kOneStepTol);
}

// The paper's Fig. 3: explicit midpoint on y' = -y, y0 = 1 is unstable at
// h = 0.1 and at h = 0.01 (its parasitic root is below -1 for every h > 0).
TEST(PaperFigure3, ExplicitMidpointDivergesOnDecay) {
  for (double h : {0.1, 0.01}) {
    Scalar sys({-1.0, 0.0});
    SimulationOptions opt;
    opt.step = h;
    opt.t_end = 60.0;
    const Eigen::VectorXd y0 = Eigen::Vector2d(1.0, 0.0);
    const auto r = run_simulation(sys, parse_integrator("explicit_midpoint"), y0, opt, [](double, const auto&) {});
    EXPECT_EQ(r.status, SimulationStatus::kDiverged) << "h = " << h;
    EXPECT_LT(r.t, 60.0);
    // The same problem with the trapezoid rule decays.
    const auto ok = run_simulation(sys, parse_integrator("trapezoid"), y0, opt, [](double, const auto&) {});
    EXPECT_EQ(ok.status, SimulationStatus::kCompleted);
  }
}

TEST(Driver, RowsAreDecimatedAndEndOnTEnd) {
  Scalar sys({-1.0, 0.0});
  SimulationOptions opt;
  opt.step = 1e-3;
  opt.t_end = 1.0005;  // 1000 full steps + a shortened one
  opt.every = 100;
  std::vector<double> ts;
  const auto r = run_simulation(sys, parse_integrator("rk4"), Eigen::Vector2d(1, 0), opt,
                                [&](double t, const auto&) { ts.push_back(t); });
  EXPECT_EQ(r.steps, 1001);
  ASSERT_EQ(ts.size(), 12u);  // t0, 10 decimated, the last
  EXPECT_DOUBLE_EQ(ts.front(), 0.0);
  EXPECT_DOUBLE_EQ(ts.back(), 1.0005);
  EXPECT_EQ(r.rows, 12);
  opt.every = 0;
  opt.max_rows = 10;
  ts.clear();
  run_simulation(sys, parse_integrator("rk4"), Eigen::Vector2d(1, 0), opt,
                 [&](double t, const auto&) { ts.push_back(t); });
  EXPECT_LE(ts.size(), 12u);
}

TEST(Driver, DivergenceIsReportedWithTheLastGoodState) {
  Scalar sys({-3.0, 0.0});  // forward Euler limit 2/3
  SimulationOptions opt;
  opt.step = 0.7;
  opt.t_end = 1000.0;
  double last_t = -1.0, last_y = 0.0;
  const auto r = run_simulation(sys, parse_integrator("forward_euler"), Eigen::Vector2d(1, 0), opt,
                                [&](double t, const Eigen::VectorXd& y) {
                                  last_t = t;
                                  last_y = y[0];
                                });
  ASSERT_EQ(r.status, SimulationStatus::kDiverged);
  EXPECT_EQ(r.integrator, "forward_euler");
  EXPECT_DOUBLE_EQ(r.step, 0.7);
  // |1 - 2.1| = 1.1 per step. The documented rule, replayed: |y_k| = 1.1^k
  // must stay <= 1e6 x max(|y0|, R), R = max |y| up to the last power-of-two step.
  std::int64_t expected = 0;
  double running = 1.0, trailing = 0.0;
  for (std::int64_t k = 1;; ++k) {
    const double norm = std::pow(1.1, static_cast<double>(k));
    if (norm > 1e6 * std::max(1.0, trailing)) break;
    expected = k;
    running = std::max(running, norm);
    if ((k & (k - 1)) == 0) trailing = running;
  }
  EXPECT_EQ(r.steps, expected);
  EXPECT_LT(expected, 512);
  EXPECT_DOUBLE_EQ(last_t, r.t);
  EXPECT_LE(std::abs(last_y), r.bound);
  EXPECT_GT(r.norm, r.bound);
  EXPECT_NE(describe(r).find("diverged at t = "), std::string::npos);
}

TEST(Driver, KeepGoingStopsTheRunAfterTheLastAcceptedRow) {
  // The caller's stop request (a Ctrl-C seen by the command line) arrives
  // through keep_going, asked before each step: the rows written so far stay,
  // the status says interrupted.
  Scalar sys({-1.0, 0.0});
  SimulationOptions opt;
  opt.step = 1e-3;
  opt.t_end = 10.0;
  opt.every = 1;
  int rows = 0;
  opt.keep_going = [&](double, std::int64_t) { return rows < 50; };
  const auto r = run_simulation(sys, parse_integrator("rk4"), Eigen::Vector2d(1, 0), opt,
                                [&](double, const auto&) { ++rows; });
  EXPECT_EQ(r.status, SimulationStatus::kInterrupted);
  EXPECT_EQ(r.steps, 49);
  EXPECT_EQ(r.rows, 50);
}

TEST(Driver, InterruptStopsAStepwiseRun) {
  Scalar sys({-1.0, 0.0});
  SimulationOptions opt;
  opt.step = 1e-3;
  opt.t_end = 10.0;
  FixedStepRun run(sys, parse_integrator("rk4"), Eigen::Vector2d(1, 0), opt);
  for (int k = 0; k < 20; ++k) ASSERT_TRUE(run.step());
  run.interrupt();
  EXPECT_TRUE(run.finished());
  EXPECT_FALSE(run.step());
  EXPECT_EQ(run.result().status, SimulationStatus::kInterrupted);
  EXPECT_EQ(run.steps(), 20);
  EXPECT_DOUBLE_EQ(run.t(), 20 * 1e-3);
}

TEST(Driver, AStepLongerThanTheRunIsShortenedToTheRun) {
  // --step 1e300 --t-end 1 took no step and said completed. Now one step of
  // the whole run; oracle: RK4 on y' = -y is y1 = R(-h) y0 with
  // R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24, here R(-1) = 3/8.
  Scalar sys({-1.0, 0.0});
  SimulationOptions opt;
  opt.step = 1e300;
  opt.t_end = 1.0;
  for (const char* name : {"rk4", "ab2"}) {  // one-step and multistep alike
    std::vector<double> ts, ys;
    const auto r = run_simulation(sys, parse_integrator(name), Eigen::Vector2d(1, 0), opt,
                                  [&](double t, const Eigen::VectorXd& y) {
                                    ts.push_back(t);
                                    ys.push_back(y[0]);
                                  });
    EXPECT_EQ(r.status, SimulationStatus::kCompleted) << name;
    EXPECT_EQ(r.steps, 1) << name;
    EXPECT_EQ(r.step, 1.0) << name;
    ASSERT_EQ(ts.size(), 2u) << name;
    EXPECT_EQ(ts.back(), 1.0) << name;
    if (std::string(name) == "rk4") EXPECT_DOUBLE_EQ(ys.back(), 0.375);
  }
}

TEST(Driver, AStepCountBeyondTwoToThe53IsRefused) {
  // --step 1e-10 --t-end 1e9: 1e19 steps overflowed the int64 count, which
  // came out negative: 0 steps, "completed".
  Scalar sys({-1.0, 0.0});
  SimulationOptions opt;
  opt.step = 1e-10;
  opt.t_end = 1e9;
  try {
    run_simulation(sys, parse_integrator("rk4"), Eigen::Vector2d(1, 0), opt, [](double, const auto&) {});
    ADD_FAILURE() << "1e19 steps were taken on";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("needs 1e+19 steps"), std::string::npos) << what;
    EXPECT_NE(what.find("more than the limit of 9007199254740992 (2^53)"), std::string::npos) << what;
  }
}

/// The oracle for last_step_by: what Simulator::advance_to did before, count
/// from the steps taken while the next step ends at or before t.
std::int64_t counted_last_step(const FixedStepRun& run, double t) {
  std::int64_t k = run.steps();
  while (k < run.total_steps() && run.time_of(k + 1) <= t) ++k;
  return k;
}

TEST(Driver, LastStepByLandsWhereCountingTheStepsDid) {
  struct Case {
    double t0, step, t_end;
    const char* integrator;
    int taken;  // steps taken before asking
  };
  // 0.1 is not a double: 3 * 0.1 > 0.3; a partial last step (rk4) and none
  // (ab2 stops at the last full step); a run from t0 > 0 part-way through;
  // 1e6 steps, where t0 + k h has drifted from k * 1e-4 by many ulps.
  const std::vector<Case> cases = {{0.0, 0.1, 1.0, "rk4", 0},     {0.0, 0.1, 1.05, "rk4", 0},
                                   {0.0, 0.1, 1.05, "ab2", 0},    {0.3, 1e-3, 2.0, "rk4", 7},
                                   {0.0, 1e-4, 100.0, "rk4", 3}};
  Scalar sys({-1e-3, 0.0});
  for (const Case& c : cases) {
    SimulationOptions opt;
    opt.t0 = c.t0;
    opt.step = c.step;
    opt.t_end = c.t_end;
    FixedStepRun run(sys, parse_integrator(c.integrator), Eigen::Vector2d(1, 0), opt);
    for (int k = 0; k < c.taken; ++k) ASSERT_TRUE(run.step());
    const std::int64_t total = run.total_steps();
    std::vector<double> times = {-1.0, c.t0, c.t_end, c.t_end + c.step, 1e300, INFINITY, -INFINITY, NAN};
    for (const std::int64_t k : {std::int64_t{0}, std::int64_t{1}, std::int64_t{2}, std::int64_t{3}, std::int64_t{7},
                                 total / 3, total / 2, total - 2, total - 1, total}) {
      if (k < 0 || k > total) continue;
      const double on = run.time_of(k);
      // On the grid, a hair either side, with Simulator::advance_to's slack,
      // between two steps, and as a decimal that misses the grid (k * h).
      for (const double t : {on, std::nextafter(on, -INFINITY), std::nextafter(on, INFINITY), on + 1e-9 * c.step,
                             on + 0.5 * c.step, c.t0 + static_cast<double>(k) * c.step, static_cast<double>(k) * c.step})
        times.push_back(t);
    }
    for (const double t : times)
      EXPECT_EQ(run.last_step_by(t), counted_last_step(run, t))
          << c.integrator << " h = " << c.step << " t_end = " << c.t_end << " t = " << t;
  }
}

TEST(Driver, LastStepByFindsAStepFarAheadAtOnce) {
  // 1e15 steps of 1e-12 s: counting to t = 0.5 s would take hours. The step
  // found is the one the definition names: it ends at or before t, the next after.
  Scalar sys({-1e-3, 0.0});
  SimulationOptions opt;
  opt.step = 1e-12;
  opt.t_end = 1e3;
  FixedStepRun run(sys, parse_integrator("rk4"), Eigen::Vector2d(1, 0), opt);
  for (const double t : {0.5, 0.123456789, 999.999999999}) {
    const std::int64_t k = run.last_step_by(t);
    EXPECT_LE(run.time_of(k), t) << t;
    EXPECT_GT(run.time_of(k + 1), t) << t;
  }
  EXPECT_EQ(run.last_step_by(2e3), run.total_steps());
}

TEST(Parse, NamesAndErrors) {
  EXPECT_EQ(parse_integrator("forward_euler").kind, IntegratorKind::kForwardEuler);
  EXPECT_TRUE(parse_integrator("bdf2").implicit());
  EXPECT_FALSE(parse_integrator("ab2").implicit());
  EXPECT_THROW(parse_integrator("euler"), std::invalid_argument);
  EXPECT_THROW(parse_integrator("lmm:alpha=1:beta=1"), std::invalid_argument);
  EXPECT_THROW(parse_integrator("lmm:alpha=-1,x:beta=0,1"), std::invalid_argument);
  Riccati sys;
  EXPECT_THROW(make_stepper(parse_integrator("generalized_alpha"), sys), std::invalid_argument);
}

}  // namespace
}  // namespace mbfe::runtime
