// The implicit stage y - c f(t, y) = r: on y' = -y^2 against the root of the
// quadratic c y^2 + y - r = 0 (Newton through the default finite-difference
// solve_shifted), on a linear oscillator in one exact iteration against
// (I - c A)^-1 (r + c b), and a stage without a solution reported.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>
#include <string>

#include "runtime/integrators/newton_stage.h"
#include "tests/runtime/integrators/test_systems.h"

namespace mbfe::runtime {
namespace {

// Newton stops when its correction is below 1e-12 (1 + |y|); it converges
// quadratically, so the iterate is far closer than that.
constexpr double kStageTol = 1e-12;
// One solve of a 2 x 2 system with entries up to 100: round-off.
constexpr double kLinearTol = 1e-14;

TEST(NewtonStage, NonlinearStageIsTheRootOfItsQuadratic) {
  testing::Riccati sys;  // f(y) = -y^2
  EXPECT_FALSE(is_linear(sys));
  NewtonWork w;
  w.resize(1);
  for (const auto [c, r] : {std::pair{0.01, 1.0}, std::pair{0.5, 2.0}, std::pair{2.0, 0.3}}) {
    Eigen::VectorXd y = Eigen::VectorXd::Constant(1, r);  // start from the explicit guess
    newton_solve(sys, false, 0.0, c, Eigen::VectorXd::Constant(1, r), y, w);
    const double root = (-1.0 + std::sqrt(1.0 + 4.0 * c * r)) / (2.0 * c);  // y + c y^2 = r, y > 0
    EXPECT_NEAR(y[0], root, kStageTol) << "c = " << c << ", r = " << r;
  }
}

TEST(NewtonStage, LinearStageTakesOneExactIteration) {
  testing::Oscillator sys(10.0, 0.05, 3.0);  // y' = A y + b
  ASSERT_TRUE(is_linear(sys));
  Eigen::Matrix2d A;
  A << 0, 1, -100, -1;
  const Eigen::Vector2d b(0, 3);
  const double c = 0.02;
  const Eigen::Vector2d r(0.01, -0.3);
  NewtonWork w;
  w.resize(2);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(2);
  newton_solve(sys, true, 0.0, c, Eigen::VectorXd(r), y, w);
  // y - c (A y + b) = r
  const Eigen::Vector2d expected = (Eigen::Matrix2d::Identity() - c * A).partialPivLu().solve(r + c * b);
  EXPECT_LT((y - Eigen::VectorXd(expected)).cwiseAbs().maxCoeff(), kLinearTol);
}

TEST(NewtonStage, StageWithoutASolutionIsReported) {
  // y + c y^2 = r has no real root for 1 + 4 c r < 0.
  testing::Riccati sys;
  NewtonWork w;
  w.resize(1);
  Eigen::VectorXd y = Eigen::VectorXd::Constant(1, 0.3);
  try {
    newton_solve(sys, false, 1.5, 1.0, Eigen::VectorXd::Constant(1, -1.0), y, w);
    FAIL() << "Newton converged to " << y[0] << " on a stage without a real root";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("t = 1.5"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mbfe::runtime
