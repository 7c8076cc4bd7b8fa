// SmallLu against Eigen's full-pivoting LU and SVD (independent algorithms).
#include "runtime/linalg/small_lu.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <random>

namespace mbfe::runtime {
namespace {

// Partial pivoting on matrices of condition <= ~1e4: backward stable, so the
// solution agrees with the full-pivoting one to ~cond * eps; 1e-10 leaves room.
constexpr double kSolveTol = 1e-10;

Eigen::MatrixXd random_matrix(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd a(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) a(i, j) = u(rng);
  return a;
}

TEST(SmallLu, SolvesLikeFullPivotingLu) {
  std::mt19937 rng(2026);
  SmallLu lu;
  for (int n = 1; n <= 8; ++n) {
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::MatrixXd a = random_matrix(rng, n) + 0.5 * Eigen::MatrixXd::Identity(n, n);
      const Eigen::FullPivLU<Eigen::MatrixXd> ref(a);
      if (ref.rcond() < 1e-4) continue;  // keep the comparison well-conditioned
      lu.compute(a);
      ASSERT_TRUE(lu.nonsingular());
      const Eigen::VectorXd b = random_matrix(rng, n).col(0);
      Eigen::VectorXd x;
      lu.solve(b, x);
      EXPECT_LE((x - ref.solve(b)).norm(), kSolveTol * (1.0 + x.norm())) << "n = " << n;
      const Eigen::MatrixXd bm = random_matrix(rng, n).leftCols(std::min(n, 3));
      Eigen::MatrixXd xm;
      lu.solve(bm, xm);
      EXPECT_LE((xm - ref.solve(bm)).norm(), kSolveTol * (1.0 + xm.norm())) << "n = " << n;
    }
  }
}

TEST(SmallLu, NeedsPivoting) {
  // A zero leading entry: without row exchanges the elimination divides by 0.
  Eigen::MatrixXd a(3, 3);
  a << 0, 2, 1,  //
      1, 1, 0,   //
      3, 0, 1;
  SmallLu lu;
  lu.compute(a);
  const Eigen::VectorXd b = Eigen::Vector3d(1, 2, 3);
  Eigen::VectorXd x;
  lu.solve(b, x);
  constexpr double kResidualRoundOff = 1e-14;  // a 3 x 3 system of O(1) entries: a residual of round-off
  EXPECT_LE((a * x - b).norm(), kResidualRoundOff);
}

// Two inverses of matrices with cond < 1e4: each good to ~cond * eps.
constexpr double kInverseNormRel = 1e-10;
// The identity: the bounds are one or two roundings of O(1) values.
constexpr double kIdentityTol = 1e-15;

TEST(SmallLu, BoundsHoldAgainstTheSvd) {
  std::mt19937 rng(31);
  SmallLu lu;
  for (int n = 1; n <= 6; ++n) {
    for (int trial = 0; trial < 20; ++trial) {
      Eigen::MatrixXd a = random_matrix(rng, n);
      lu.compute(a);
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a);
      const double smax = svd.singularValues()(0);
      const double smin = svd.singularValues()(n - 1);
      const Eigen::MatrixXd inv = Eigen::FullPivLU<Eigen::MatrixXd>(a).inverse();
      // Rounding of the inverse: relative ~cond * eps; the bounds hold up to that.
      const double slack = 1.0 + 1e-12 * smax / smin;
      EXPECT_LE(lu.sigma_min_lower(), smin * slack);
      EXPECT_LE(lu.rcond_lower(), smin / smax * slack);
      EXPECT_NEAR(lu.inverse_norm(), inv.norm(), kInverseNormRel * inv.norm());
      EXPECT_LE(lu.sigma_min_lower_cheap(), smin * slack);
      EXPECT_LE(lu.rcond_lower_cheap(), smin / smax * slack);
      // The bound is within sqrt(n) of the truth: ||A^-1||_F <= sqrt(n) / sigma_min.
      EXPECT_GE(lu.sigma_min_lower() * std::sqrt(n) * slack, smin);
    }
  }
}

TEST(SmallLu, SingularMatrixFailsEveryTest) {
  Eigen::MatrixXd a(3, 3);
  a << 1, 2, 3,  //
      2, 4, 6,   //
      0, 1, 1;
  SmallLu lu;
  lu.compute(a);
  EXPECT_FALSE(lu.nonsingular());
  EXPECT_FALSE(lu.sigma_min_lower() >= 1e-300);
  EXPECT_FALSE(lu.rcond_lower() >= 1e-300);
  EXPECT_FALSE(lu.sigma_min_lower_cheap() >= 1e-300);
  EXPECT_FALSE(lu.rcond_lower_cheap() >= 1e-300);

  a(0, 0) = NAN;
  lu.compute(a);
  EXPECT_FALSE(lu.sigma_min_lower() >= 1e-300);
  EXPECT_FALSE(lu.rcond_lower() >= 1e-300);
  EXPECT_FALSE(lu.sigma_min_lower_cheap() >= 1e-300);
  EXPECT_FALSE(lu.rcond_lower_cheap() >= 1e-300);
}

TEST(SmallLu, ZeroMatrixFailsAndIdentityPassesEveryTest) {
  SmallLu lu;
  lu.compute(Eigen::MatrixXd::Zero(3, 3));
  EXPECT_EQ(lu.sigma_min_lower(), 0.0);
  EXPECT_EQ(lu.rcond_lower(), 0.0);
  EXPECT_EQ(lu.sigma_min_lower_cheap(), 0.0);
  EXPECT_EQ(lu.rcond_lower_cheap(), 0.0);
  // The identity: sigma_min = 1, ||A||_F = sqrt(3), so the pivot bounds are
  // 1/3 and 1/sqrt(27), the inverse bounds 1/sqrt(3) and 1/3.
  lu.compute(Eigen::MatrixXd::Identity(3, 3));
  EXPECT_NEAR(lu.sigma_min_lower_cheap(), 1.0 / 3.0, kIdentityTol);
  EXPECT_NEAR(lu.rcond_lower_cheap(), 1.0 / std::sqrt(27.0), kIdentityTol);
  EXPECT_NEAR(lu.sigma_min_lower(), 1.0 / std::sqrt(3.0), kIdentityTol);
  EXPECT_NEAR(lu.rcond_lower(), 1.0 / 3.0, kIdentityTol);
}

TEST(SmallLu, EmptyMatrixIsRegular) {
  SmallLu lu;
  lu.compute(Eigen::MatrixXd(0, 0));
  EXPECT_EQ(lu.sigma_min_lower(), 1.0);
  EXPECT_EQ(lu.rcond_lower(), 1.0);
  Eigen::VectorXd x;
  lu.solve(Eigen::VectorXd(0), x);
  EXPECT_EQ(x.size(), 0);
}

}  // namespace
}  // namespace mbfe::runtime
