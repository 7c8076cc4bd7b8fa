// WoodburyCorrection against a dense LU of A + W D W^T itself: W with two
// blocks of non-zero rows (two low-rank structures), D with a zero and a
// negative entry, and the singular case the capacity matrix must report.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/linalg/woodbury.h"

namespace mbfe::runtime {
namespace {

// Two dense solves of a 14 x 14 system with condition number near 1e2 that
// take different routes: 1e-11 relative is round-off with a wide margin.
constexpr double kSameSolutionTol = 1e-11;

// A^-1 b alone misses the answer by more than this (relative): the update
// matters, so a correction that did nothing could not pass.
constexpr double kUpdateMatters = 1e-8;

constexpr int kN = 14;

struct Problem {
  Eigen::MatrixXd A, W;
  Eigen::VectorXd D;
  std::vector<WoodburyCorrection::Block> blocks;
};

// A: diagonally dominant (regular, not symmetric); W: columns 0-1 live in
// rows 2-5, columns 2-4 in rows 8-12, everything else zero.
Problem make_problem() {
  std::mt19937 rng(2515);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Problem p;
  p.A = Eigen::MatrixXd::NullaryExpr(kN, kN, [&]() { return u(rng); });
  p.A.diagonal().array() += 2.0 * kN;
  p.blocks = {{2, 4, 0, 2}, {8, 5, 2, 3}};
  p.W = Eigen::MatrixXd::Zero(kN, 5);
  for (const auto& b : p.blocks)
    for (int i = 0; i < b.rows; ++i)
      for (int j = 0; j < b.cols; ++j) p.W(b.row + i, b.col + j) = u(rng);
  p.D.resize(5);
  p.D << 3.0, 0.0, -0.5, 12.0, 1.5;  // a zero entry: the form never inverts D
  return p;
}

Eigen::VectorXd corrected_solve(const Problem& p, const Eigen::VectorXd& b) {
  const Eigen::PartialPivLU<Eigen::MatrixXd> a_lu(p.A);
  WoodburyCorrection w;
  w.factorize(p.W, p.D, a_lu.solve(p.W), p.blocks, "test matrix");
  Eigen::VectorXd x = a_lu.solve(b);
  w.correct(x);
  return x;
}

TEST(Woodbury, SolvesTheUpdatedMatrixLikeADenseLU) {
  const Problem p = make_problem();
  const Eigen::MatrixXd updated = p.A + p.W * p.D.asDiagonal() * p.W.transpose();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::VectorXd b = Eigen::VectorXd::NullaryExpr(kN, [&]() { return u(rng); });
    const Eigen::VectorXd reference = updated.partialPivLu().solve(b);
    const Eigen::VectorXd x = corrected_solve(p, b);
    EXPECT_LT((x - reference).norm(), kSameSolutionTol * reference.norm()) << "trial " << trial;
    // The correction is not a no-op here: A^-1 b alone is far from the answer.
    EXPECT_GT((p.A.partialPivLu().solve(b) - reference).norm(), kUpdateMatters * reference.norm());
  }
}

TEST(Woodbury, ZeroWidthLeavesTheSolveAlone) {
  WoodburyCorrection w;
  w.factorize(Eigen::MatrixXd(kN, 0), Eigen::VectorXd(0), Eigen::MatrixXd(kN, 0), {}, "test matrix");
  EXPECT_EQ(w.width(), 0);
  Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(kN, 1.0, 2.0);
  const Eigen::VectorXd before = x;
  w.correct(x);
  EXPECT_EQ(x, before);
}

TEST(Woodbury, SingularUpdateIsReportedByName) {
  // A = I, W = e_3, D = -1: A + W D W^T has a zero row, and so does the
  // capacity matrix 1 + D W^T A^-1 W = 0.
  const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(6, 6);
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(6, 1);
  W(3, 0) = 1.0;
  WoodburyCorrection w;
  try {
    w.factorize(W, Eigen::VectorXd::Constant(1, -1.0), W, {{3, 1, 0, 1}}, "the beam's Newton matrix");
    FAIL() << "a singular capacity matrix was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("the beam's Newton matrix"), std::string::npos) << e.what();
  }
  // D = -0.5 keeps it regular: (I + W D W^T)^-1 scales row 3 by 2.
  w.factorize(W, Eigen::VectorXd::Constant(1, -0.5), W, {{3, 1, 0, 1}}, "regular");
  Eigen::VectorXd x = Eigen::VectorXd::Ones(6);
  w.correct(x);
  EXPECT_DOUBLE_EQ(x[3], 2.0);
  EXPECT_DOUBLE_EQ(x[2], 1.0);
}

TEST(Woodbury, MismatchedSizesAreRejected) {
  WoodburyCorrection w;
  EXPECT_THROW(w.factorize(Eigen::MatrixXd::Zero(4, 2), Eigen::VectorXd::Zero(3), Eigen::MatrixXd::Zero(4, 2), {}, "x"),
               std::invalid_argument);
  EXPECT_THROW(w.factorize(Eigen::MatrixXd::Zero(4, 2), Eigen::VectorXd::Zero(2), Eigen::MatrixXd::Zero(5, 2), {}, "x"),
               std::invalid_argument);
}

}  // namespace
}  // namespace mbfe::runtime
