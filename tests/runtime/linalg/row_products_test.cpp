// The row kernels against Eigen's own products of the same rows: a random
// row-major matrix with a column count that is odd (the kernels' pairs of
// lanes leave a tail) and row lists of every length from 0 to 9 (their
// passes of four leave 0 to 3 rows over), repeated rows included.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <stdexcept>
#include <vector>

#include "runtime/linalg/row_products.h"

namespace mbfe::runtime {
namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The kernels sum in another order than Eigen: entries of order 1 over 37
// columns differ by round-off, a few 1e-16 each.
constexpr double kRoundOff = 1e-13;
constexpr Eigen::Index kRows = 23, kCols = 37;

RowMajor random_matrix(std::mt19937& rng, Eigen::Index rows, Eigen::Index cols) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  RowMajor a(rows, cols);
  for (Eigen::Index i = 0; i < a.size(); ++i) a.data()[i] = u(rng);
  return a;
}

std::vector<int> random_rows(std::mt19937& rng, int count) {
  std::uniform_int_distribution<int> pick(0, kRows - 1);
  std::vector<int> rows(static_cast<std::size_t>(count));
  for (int& r : rows) r = pick(rng);
  if (count >= 2) rows[1] = rows[0];  // a row read twice (two forces at one DOF)
  return rows;
}

TEST(RowProducts, DotRowsEqualsEigenDots) {
  std::mt19937 rng(7);
  const RowMajor a = random_matrix(rng, kRows, kCols);
  const Eigen::VectorXd x = random_matrix(rng, kCols, 1), y = random_matrix(rng, kCols, 1);
  for (int n = 0; n <= 9; ++n) {
    const std::vector<int> rows = random_rows(rng, n);
    std::vector<double> ox(static_cast<std::size_t>(n), -7.0), oy(static_cast<std::size_t>(n), -7.0);
    dot_rows(a.data(), kCols, rows.data(), n, x.data(), y.data(), ox.data(), oy.data());
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(ox[i], a.row(rows[i]).dot(x), kRoundOff) << n << " rows, row " << i;
      EXPECT_NEAR(oy[i], a.row(rows[i]).dot(y), kRoundOff) << n << " rows, row " << i;
    }
  }
}

TEST(RowProducts, AddRowsEqualsEigenSum) {
  std::mt19937 rng(11);
  const RowMajor a = random_matrix(rng, kRows, kCols);
  for (int n = 0; n <= 9; ++n) {
    const std::vector<int> rows = random_rows(rng, n);
    const Eigen::VectorXd c = random_matrix(rng, n, 1);
    const Eigen::VectorXd g0 = random_matrix(rng, kCols, 1);
    Eigen::VectorXd expected = g0, g = g0;
    for (int i = 0; i < n; ++i) expected += c[i] * a.row(rows[i]).transpose();
    add_rows(a.data(), kCols, rows.data(), c.data(), n, g.data());
    EXPECT_LE((g - expected).cwiseAbs().maxCoeff(), kRoundOff) << n << " rows";
  }
}

TEST(RowProducts, TransposedProductEqualsEigen) {
  std::mt19937 rng(13);
  for (Eigen::Index rows : {Eigen::Index{0}, Eigen::Index{1}, Eigen::Index{6}, kRows}) {
    const RowMajor a = random_matrix(rng, rows, kCols);
    for (int k = 1; k <= 4; ++k) {
      const Eigen::MatrixXd x = random_matrix(rng, rows, k);
      Eigen::MatrixXd g = Eigen::MatrixXd::Constant(kCols, 4, -7.0);  // columns past k stay as they were
      transposed_product(a.data(), rows, kCols, x.data(), k, g.data());
      const Eigen::MatrixXd expected = a.transpose() * x;
      EXPECT_LE((g.leftCols(k) - expected).cwiseAbs().maxCoeff(), kRoundOff) << rows << " rows, " << k << " columns";
      if (k < 4) EXPECT_EQ(g(0, k), -7.0);
    }
  }
  const RowMajor a = random_matrix(rng, 3, kCols);
  Eigen::MatrixXd g(kCols, 5);
  EXPECT_THROW(transposed_product(a.data(), 3, kCols, g.data(), 5, g.data()), std::invalid_argument);
}

}  // namespace
}  // namespace mbfe::runtime
