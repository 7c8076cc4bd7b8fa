// solve_ldlt against Eigen's own SimplicialLDLT::solve: the same operations in
// the same order, so the same bits, on a random sparse SPD matrix (with the
// AMD ordering, which permutes) and on one factored without ordering.
#include "runtime/linalg/sparse_ldlt_solve.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <random>
#include <vector>

namespace {

Eigen::SparseMatrix<double> random_spd(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> pick(0, n - 1);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, 2.0 * n);  // diagonally dominant: SPD
  for (int k = 0; k < 3 * n; ++k) {
    const int i = pick(rng), j = pick(rng);
    if (i == j) continue;
    const double v = u(rng);
    t.emplace_back(i, j, v);
    t.emplace_back(j, i, v);
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

template <typename Factor>
void expect_same_bits(const Eigen::SparseMatrix<double>& a, std::mt19937& rng) {
  Factor f(a);
  ASSERT_EQ(f.info(), Eigen::Success);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd b(a.rows()), x(a.rows()), work;
  for (int trial = 0; trial < 3; ++trial) {
    for (Eigen::Index i = 0; i < b.size(); ++i) b[i] = u(rng);
    const Eigen::VectorXd expected = f.solve(b);
    mbfe::runtime::solve_ldlt(f, b, x, work);
    for (Eigen::Index i = 0; i < b.size(); ++i) ASSERT_EQ(x[i], expected[i]) << "entry " << i;
  }
}

TEST(SparseLdltSolve, SameBitsAsEigensSolveWithAmdOrdering) {
  std::mt19937 rng(20261124);
  expect_same_bits<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(random_spd(60, rng), rng);
}

TEST(SparseLdltSolve, SameBitsAsEigensSolveWithoutOrdering) {
  std::mt19937 rng(7);
  expect_same_bits<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>>>(
      random_spd(40, rng), rng);
}

TEST(SparseLdltSolve, IntoASegmentOfALargerVector) {
  std::mt19937 rng(11);
  const Eigen::SparseMatrix<double> a = random_spd(30, rng);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> f(a);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(30, -1.0, 2.0);
  Eigen::VectorXd whole = Eigen::VectorXd::Constant(50, 7.0), work;
  mbfe::runtime::solve_ldlt(f, b, whole.segment(10, 30), work);
  EXPECT_EQ(whole.head(10), Eigen::VectorXd::Constant(10, 7.0));
  EXPECT_EQ(whole.tail(10), Eigen::VectorXd::Constant(10, 7.0));
  constexpr double kResidualRoundOff = 1e-12;  // a 30 x 30 SPD solve: a residual of round-off
  EXPECT_LE((a * whole.segment(10, 30) - b).cwiseAbs().maxCoeff(), kResidualRoundOff);
}

}  // namespace
