// The static start: solve_static on systems with closed-form roots and on a
// mechanism; coupled_static_state (Gauss-Newton with a difference Jacobian)
// on the double pendulum on its beam, against the other solver,
// coupled_static_state_sparse (Newton on the implicit integrators' tangent),
// and against the augmented system's own accelerations at the state found.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "ir/model.h"
#include "runtime/coupled/augmented_system.h"
#include "runtime/simulation/static_start.h"
#include "tests/runtime/coupled/pendulum_on_beam.h"

namespace mbfe::runtime {
namespace {

using namespace pendulum_on_beam;

// Newton converged quadratically on O(1) unknowns: round-off.
constexpr double kRootTol = 1e-12;

TEST(SolveStatic, FindsTheClosedFormRoot) {
  // x0^2 + x1^2 = 4 and x0 = x1 from (1, 0.5): (sqrt 2, sqrt 2).
  const StaticResidualFn residual = [](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    r.resize(2);
    r << x[0] * x[0] + x[1] * x[1] - 4.0, x[0] - x[1];
  };
  const StaticSolution s = solve_static(residual, Eigen::Vector2d(1.0, 0.5), {"a", "b"});
  EXPECT_NEAR(s.x[0], std::sqrt(2.0), kRootTol);
  EXPECT_NEAR(s.x[1], std::sqrt(2.0), kRootTol);
  EXPECT_GT(s.iterations, 1);
  EXPECT_LT(s.residual, kRootTol);
}

TEST(SolveStatic, BadlyScaledUnknownsStillConverge) {
  // A stiff spring (1e9 N/m) and a soft one (1 N/m) in series under 10 N:
  // x0 = 10 / 1e9, x1 = x0 + 10 / 1; the equilibration makes both columns count.
  const StaticResidualFn residual = [](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    r.resize(2);
    r << 1e9 * x[0] - 1.0 * (x[1] - x[0]), 1.0 * (x[1] - x[0]) - 10.0;
  };
  const StaticSolution s = solve_static(residual, Eigen::Vector2d::Zero(), {"stiff", "soft"});
  EXPECT_NEAR(s.x[0], 1e-8, kRootTol * 1e-8);
  EXPECT_NEAR(s.x[1], 10.0 + 1e-8, kRootTol * 10.0);
}

TEST(SolveStatic, AMechanismIsNamed) {
  // x0 + x1 is held, x0 - x1 is not; x2 is.
  const StaticResidualFn residual = [](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    r.resize(3);
    r << x[0] + x[1] - 1.0, 2.0 * (x[0] + x[1]) - 2.0, x[2] - 3.0;
  };
  try {
    solve_static(residual, Eigen::Vector3d(0.2, 0.1, 0.0), {"left", "right", "held"});
    FAIL() << "a mechanism was solved";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("mechanism"), std::string::npos) << what;
    EXPECT_NE(what.find("rank 2 of 3"), std::string::npos) << what;
    EXPECT_EQ(what.find("'held'"), std::string::npos) << what;
  }
}

TEST(SolveStatic, AnUnknownTheResidualMissesButForRoundOffIsAMechanism) {
  // A body falling freely: its acceleration is g wherever it is, but for a
  // round-off that depends on its position (the factorisation of M does not
  // give the same last bit everywhere). The difference column of x1 is
  // that round-off alone: a mechanism, not a direction Newton may step along
  // by the inverse of the noise.
  const StaticResidualFn residual = [](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    r.resize(2);
    const double g = -9.81;
    r << x[0] - 1.0, g + 4.0 * std::numeric_limits<double>::epsilon() * std::abs(g) * std::sin(1e6 * x[1]);
  };
  try {
    solve_static(residual, Eigen::Vector2d(0.0, 0.3), {"held", "height"});
    FAIL() << "a free fall was solved";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("the structure is a mechanism: nothing holds 'height' in place"), std::string::npos) << what;
  }
}

// The two solvers stop at their own step tolerances (1e-12 or so of the
// state, relative); the accelerations at the state found are its residual,
// ~1e-9 of the O(10) m/s^2 of gravity. A wrong equilibrium misses by O(1e-3)
// m and O(1) m/s^2.
constexpr double kSameEquilibriumTol = 1e-8;  // m or rad
constexpr double kAtRestTol = 1e-7;           // m/s^2 or rad/s^2
constexpr double kClosedTol = 1e-10;          // m, |Phi|
// The guess is this far from the equilibrium at least (the beam sags, the
// slider slides by millimetres): a solver that returned it could not pass.
constexpr double kMovedAtLeast = 1e-5;        // m or rad

class PendulumStatics : public ::testing::TestWithParam<bool> {};  // true: slider; false: pin

TEST_P(PendulumStatics, DenseAndSparseSolversFindTheSameRestState) {
  const bool slider = GetParam();
  const testing::TestBeam beam = make_beam(10, true);
  const mbfe_model_v1& rigid = slider ? *double_pendulum_beam_model() : *double_pendulum_beam_pin_model();
  auto dyn = make_dynamics(rigid, beam);
  ir::Model model;  // names the model in errors only
  model.name = "pendulum_on_beam";
  Eigen::VectorXd q0 = Eigen::VectorXd::Zero(dyn->n());
  q0.head<2>() = slider ? double_pendulum_beam_params().q0 : pendulum_angles_for_tip(reference::kPinAt);

  Eigen::VectorXd q_dense = q0, qd_dense, q_sparse = q0, qd_sparse;
  coupled_static_state(model, *dyn, q_dense, qd_dense);
  ASSERT_TRUE(coupled_static_state_sparse(model, make_dynamics(rigid, beam), q_sparse, qd_sparse));
  EXPECT_LT((q_dense - q_sparse).cwiseAbs().maxCoeff(), kSameEquilibriumTol);
  EXPECT_EQ(qd_dense, Eigen::VectorXd::Zero(dyn->n()));
  // It moved: the guess was not the answer (the beam sags, the slider slides).
  EXPECT_GT((q_dense - q0).cwiseAbs().maxCoeff(), kMovedAtLeast);

  // At rest there, by the augmented system's own right-hand side.
  AugmentedSystem aug(make_dynamics(rigid, beam));
  const Eigen::VectorXd y = aug.initial_state(0.0, q_dense, qd_dense);
  Eigen::VectorXd ydot;
  aug.rhs(0.0, y, ydot);
  EXPECT_LT(ydot.cwiseAbs().maxCoeff(), kAtRestTol);
  ConstraintValues cv;
  dyn->constraints().evaluate(0.0, q_dense.data(), q_dense.data() + 2, nullptr, nullptr, cv);
  EXPECT_LT(cv.phi.cwiseAbs().maxCoeff(), kClosedTol);
}

INSTANTIATE_TEST_SUITE_P(Contacts, PendulumStatics, ::testing::Values(true, false),
                         [](const ::testing::TestParamInfo<bool>& i) { return std::string(i.param ? "slider" : "pin"); });

}  // namespace
}  // namespace mbfe::runtime
