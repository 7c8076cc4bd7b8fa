// BandedQr (runtime/modal/banded_qr.h) against a dense solve of the normal
// equations: (A^T A)^{-1} x for a random banded A, its rows given out of
// order and some of them wider than others; and a rank-deficient A refused.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <random>
#include <vector>

#include "runtime/modal/banded_qr.h"

namespace mbfe::runtime {
namespace {

// A of 3n rows over n = 40 columns, entries of order 1: A^T A has a
// condition number of a few hundred, so a backward-stable solve is good to
// about 1e-13 of the solution.
constexpr double kSolveRel = 1e-11;

TEST(BandedQr, SolvesTheNormalEquationsOfABandedMatrix) {
  constexpr int n = 40;
  std::mt19937 rng(20261124);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> width(1, 4);
  std::vector<Eigen::Triplet<double>> t;
  std::vector<int> order(3 * n);
  for (int r = 0; r < 3 * n; ++r) order[static_cast<std::size_t>(r)] = r;
  std::shuffle(order.begin(), order.end(), rng);  // rows not sorted by their first column
  for (int r = 0; r < 3 * n; ++r) {
    const int first = r % n, w = std::min(width(rng), n - first);
    for (int c = first; c < first + w; ++c) t.emplace_back(order[static_cast<std::size_t>(r)], c, u(rng));
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> A(3 * n, n);
  A.setFromTriplets(t.begin(), t.end());
  const BandedQr qr(A);
  EXPECT_EQ(qr.cols(), n);
  EXPECT_LE(qr.width(), 4);
  const Eigen::MatrixXd dense = Eigen::MatrixXd(A);
  const Eigen::MatrixXd normal = dense.transpose() * dense;
  for (int k = 0; k < 3; ++k) {
    Eigen::VectorXd x(n);
    for (int i = 0; i < n; ++i) x[i] = u(rng);
    Eigen::VectorXd y(n);
    qr.solve_normal(x.data(), y.data());
    const Eigen::VectorXd want = normal.ldlt().solve(x);
    EXPECT_LT((y - want).norm(), kSolveRel * want.norm());
  }
}

TEST(BandedQr, ARankDeficientMatrixIsRefused) {
  // Column 2 is never touched: A^T A is singular.
  Eigen::SparseMatrix<double, Eigen::RowMajor> A(4, 4);
  std::vector<Eigen::Triplet<double>> t = {{0, 0, 1.0}, {1, 1, 2.0}, {2, 3, 1.0}, {3, 0, 0.5}, {3, 1, 0.5}};
  A.setFromTriplets(t.begin(), t.end());
  EXPECT_THROW(BandedQr{A}, std::runtime_error);
}

}  // namespace
}  // namespace mbfe::runtime
