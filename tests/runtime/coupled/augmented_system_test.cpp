// The augmented formulation's accelerations on the double pendulum on its
// beam (slider and pin contacts, damped beam), checked by what they must
// satisfy: the equations of motion written out densely from the hand-coded
// pendulum (tests/reference) and the test beam's own M, C, K and P, with
// the multipliers it reports; and Phi'' = 0 along q(t) = q + q' t + q'' t^2 / 2,
// by a central second difference of Phi itself (no Jacobian rate involved).
#include "runtime/coupled/augmented_system.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <string>

#include "tests/runtime/coupled/pendulum_on_beam.h"

namespace mbfe::runtime {
namespace {

using namespace pendulum_on_beam;

// Equations of motion with terms up to ~1e3 (the beam's stiffness times its
// deflection, the multipliers): a saddle-point solve's round-off.
constexpr double kMotionTol = 1e-8;
// Second difference of Phi at step h = 1e-5 s: its truncation, O(h^2), is
// ~5e-6 m/s^2 on the slider (measured: 100x less per 10x smaller h), its
// round-off eps |q| / h^2 ~ 2e-6 m/s^2. The velocity terms gamma = -J' q'
// stand for are ~0.5 m/s^2 here: a wrong gamma or J misses by that.
constexpr double kDifferenceStep = 1e-5;
constexpr double kConstraintAccelerationTol = 5e-5;

class Augmented : public ::testing::TestWithParam<bool> {};  // true: slider; false: pin

TEST_P(Augmented, AccelerationsSatisfyTheEquationsOfMotionAndKeepPhiStill) {
  const bool slider = GetParam();
  const testing::TestBeam beam = make_beam(8, true);
  auto dyn = make_dynamics(slider ? *double_pendulum_beam_model() : *double_pendulum_beam_pin_model(), beam);
  AugmentedSystem aug(dyn);
  const int n = dyn->n(), nc = n - 2, m = dyn->m();

  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd q = Eigen::VectorXd::NullaryExpr(n, [&]() { return 1e-4 * u(rng); });
  Eigen::VectorXd qd = Eigen::VectorXd::NullaryExpr(n, [&]() { return 1e-2 * u(rng); });
  q.head<2>() = pendulum_angles_for_tip(slider ? 0.6 : reference::kPinAt);
  qd.head<2>() << 0.4, -0.7;

  Eigen::VectorXd y(2 * n), ydot;
  y << q, qd;
  aug.rhs(0.0, y, ydot);
  const Eigen::VectorXd a = ydot.tail(n);
  const Eigen::VectorXd lambda = aug.report(0.0, y).lambda;
  ASSERT_EQ(lambda.size(), m);

  // M a + F - Q + J^T lambda = 0, rigid rows from the hand-coded pendulum,
  // beam rows from the beam's matrices.
  const auto& p = double_pendulum_beam_params().pendulum;
  ConstraintValues cv;
  dyn->constraints().evaluate(0.0, q.data(), q.data() + 2, nullptr, nullptr, cv);
  const Eigen::MatrixXd Jc = cv.jc_dense(nc);
  const Eigen::Vector2d qb = q.head<2>(), qbd = qd.head<2>();
  const Eigen::Vector2d rigid = reference::mass_matrix(p, qb) * a.head<2>() + reference::inertial_forces(p, qb, qbd) -
                                reference::generalized_forces(p, qb) + cv.jb.transpose() * lambda;
  const Eigen::VectorXd flexible = beam.beam.M * a.tail(nc) + beam.C * qd.tail(nc) + beam.K * q.tail(nc) -
                                   beam.beam.P + Jc.transpose() * lambda;
  const double scale = std::max((beam.K * q.tail(nc)).cwiseAbs().maxCoeff(), lambda.cwiseAbs().maxCoeff());
  EXPECT_LT(rigid.cwiseAbs().maxCoeff(), kMotionTol * scale);
  EXPECT_LT(flexible.cwiseAbs().maxCoeff(), kMotionTol * scale);

  // Phi'' = 0 along the motion the accelerations start.
  const double h = kDifferenceStep;
  auto phi_at = [&](double t) {
    const Eigen::VectorXd qt = q + t * qd + (0.5 * t * t) * a;
    ConstraintValues c;
    dyn->constraints().evaluate(0.0, qt.data(), qt.data() + 2, nullptr, nullptr, c);
    return Eigen::VectorXd(c.phi);
  };
  const Eigen::VectorXd phi_dd = (phi_at(h) - 2.0 * phi_at(0.0) + phi_at(-h)) / (h * h);
  EXPECT_LT(phi_dd.cwiseAbs().maxCoeff(), kConstraintAccelerationTol) << phi_dd.transpose();
}

TEST(Augmented, WrongSizedStateIsRefused) {
  const testing::TestBeam beam = make_beam(4, false);
  AugmentedSystem aug(make_dynamics(*double_pendulum_beam_model(), beam));
  Eigen::VectorXd ydot;
  EXPECT_THROW(aug.rhs(0.0, Eigen::VectorXd::Zero(3), ydot), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Contacts, Augmented, ::testing::Values(true, false),
                         [](const ::testing::TestParamInfo<bool>& i) { return std::string(i.param ? "slider" : "pin"); });

}  // namespace
}  // namespace mbfe::runtime
