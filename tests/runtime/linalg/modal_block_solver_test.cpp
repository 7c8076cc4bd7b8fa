// ModalBlockSolver against a dense LU of the same matrix: two low-rank
// blocks (M-orthonormal modes of a tridiagonal pair, some of them kept), a
// rest block, and couplings between all three, with the entries given as
// repeated triplets the way the Newton matrix is assembled.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <random>
#include <vector>

#include "runtime/linalg/modal_block_solver.h"

namespace mbfe::runtime {
namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Dense LU and the Woodbury form in another order: the matrices here have
// condition numbers near 1e4, so 1e-10 relative is round-off with room.
constexpr double kSameSolutionTol = 1e-10;

struct Block {
  Eigen::SparseMatrix<double> M, K;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor, k_factor;
  RowMajor phi;
  Eigen::VectorXd k;  // the kept modes' K-values (eigenvalues)
};

// A tridiagonal SPD mass and stiffness; phi: the first `kept` M-orthonormal modes.
void make_block(int n, int kept, double scale, Block& b) {
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n), K = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    M(i, i) = 4.0 * scale;
    K(i, i) = 2.0 + 0.1 * i;
    if (i + 1 < n) {
      M(i, i + 1) = M(i + 1, i) = scale;
      K(i, i + 1) = K(i + 1, i) = -1.0;
    }
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);
  b.phi = eig.eigenvectors().leftCols(kept);
  b.k = eig.eigenvalues().head(kept);
  b.M = M.sparseView();
  b.K = K.sparseView();
  b.factor.compute(b.M);
  b.k_factor.compute(b.K);
}

TEST(ModalBlockSolver, MatchesADenseLuOfTheSameMatrix) {
  std::mt19937 rng(20261124);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n_rest_front = 3, n1 = 12, n2 = 9, n_rest_back = 4;
  const int size = n_rest_front + n1 + n2 + n_rest_back;
  Block b1, b2;
  make_block(n1, 5, 1.0, b1);
  make_block(n2, 4, 0.5, b2);
  const int row1 = n_rest_front, row2 = n_rest_front + n1;
  // Block 1 is a multiple of its M, block 2 of its K (the policy mass's
  // Newton matrix), each plus U diag(d) U^T.
  std::vector<ModalBlock> blocks(2);
  blocks[0] = {row1, &b1.factor, &b1.phi, nullptr, 3.0, Eigen::VectorXd::Zero(5)};
  blocks[1] = {row2, &b2.k_factor, &b2.phi, &b2.k, 2.0, Eigen::VectorXd::Zero(4)};
  for (int j = 0; j < 5; ++j) blocks[0].d[j] = 1.0 + u(rng);
  for (int j = 0; j < 4; ++j) blocks[1].d[j] = (-0.5 + 0.2 * u(rng)) * b2.k[j];  // alpha b + d stays positive
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(size, size);
  for (int k = 0; k < 2; ++k) {
    const ModalBlock& blk = blocks[k];
    const Block& b = k == 0 ? b1 : b2;
    const Eigen::MatrixXd base = Eigen::MatrixXd(k == 0 ? b.M : b.K);
    const Eigen::MatrixXd U = Eigen::MatrixXd(b.M) * Eigen::MatrixXd(*blk.phi);
    dense.block(blk.row, blk.row, base.rows(), base.rows()) += blk.alpha * base + U * blk.d.asDiagonal() * U.transpose();
  }
  std::vector<Eigen::Triplet<double>> entries;
  auto add = [&](int i, int j, double v) {
    entries.emplace_back(i, j, v);
    dense(i, j) += v;
  };
  // The rest: diagonally dominant, not symmetric.
  std::vector<int> rest;
  for (int i = 0; i < n_rest_front; ++i) rest.push_back(i);
  for (int i = row2 + n2; i < size; ++i) rest.push_back(i);
  for (int i : rest) {
    add(i, i, 10.0);
    for (int j : rest)
      if (j != i) add(i, j, u(rng));
  }
  // Couplings: rank-one springs between the blocks and the rest, twice on one pair.
  const std::vector<std::vector<int>> springs = {{1, row1 + 2}, {row1 + 7, row2 + 3}, {row1 + 7, row2 + 3},
                                                 {row2 + 8, size - 1}, {0, row1 + 11, row2}};
  for (const std::vector<int>& s : springs) {
    std::vector<double> g;
    for (std::size_t a = 0; a < s.size(); ++a) g.push_back(u(rng));
    for (std::size_t a = 0; a < s.size(); ++a)
      for (std::size_t c = 0; c < s.size(); ++c) add(s[a], s[c], 2.0 * g[a] * g[c]);
  }
  add(row1 + 4, row1 + 4, 0.7);  // a coupling on a block's own diagonal
  ModalBlockSolver solver;
  solver.factorize(size, entries, blocks);
  EXPECT_EQ(solver.num_coupled(), 10);  // the distinct rows the couplings touch
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(dense);
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::VectorXd b(size), x;
    for (int i = 0; i < size; ++i) b[i] = u(rng);
    solver.solve(b, x);
    const Eigen::VectorXd expected = lu.solve(b);
    EXPECT_LT((x - expected).cwiseAbs().maxCoeff(), kSameSolutionTol * expected.cwiseAbs().maxCoeff());
    EXPECT_LT((dense * x - b).cwiseAbs().maxCoeff(), kSameSolutionTol * b.cwiseAbs().maxCoeff());
  }
}

TEST(ModalBlockSolver, RefusesASingularBlock) {
  Block b;
  make_block(6, 2, 1.0, b);
  std::vector<ModalBlock> blocks(1);
  blocks[0] = {0, &b.factor, &b.phi, nullptr, 2.0, Eigen::Vector2d(1.0, -2.0)};  // alpha + d_2 = 0
  ModalBlockSolver solver;
  try {
    solver.factorize(6, {}, blocks);
    FAIL() << "a block with alpha + d = 0 is singular";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("singular in a low-rank beam"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mbfe::runtime
