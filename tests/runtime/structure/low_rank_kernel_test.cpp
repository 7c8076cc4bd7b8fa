// The low-rank correction of an adjusted beam, both forms, against a plain
// triple loop in long double (an independent oracle: no Eigen, no SIMD).
#include "runtime/structure/low_rank_kernel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace mbfe::runtime {
namespace {

// Both forms sum n products per entry in double; their error is a few ulps of
// the sum of |terms|, far below this bound (relative to that sum).
constexpr double kRoundoffTol = 1e-13;

struct Case {
  LowRankCorrection op;
  Eigen::VectorXd q, qd, a0;
};

Case random_case(std::mt19937& rng, int n, int m) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto fill = [&](Eigen::MatrixXd& x, int rows, int cols) {
    x.resize(rows, cols);
    for (int j = 0; j < cols; ++j)
      for (int i = 0; i < rows; ++i) x(i, j) = u(rng);
  };
  Case c;
  fill(c.op.U, n, m);
  fill(c.op.phi, n, m);
  Eigen::MatrixXd v;
  fill(v, m, 2);
  c.op.d_C = 10.0 * v.col(0);
  c.op.d_K = 1e6 * v.col(1);  // stiffness-like corrections are large, damping ones small
  fill(v, n, 3);
  c.q = v.col(0);
  c.qd = v.col(1);
  c.a0 = v.col(2);
  return c;
}

// The oracle, and the scale of its terms (for a relative tolerance).
void oracle(const Case& c, std::vector<long double>& a, std::vector<long double>& scale) {
  const int n = static_cast<int>(c.op.U.rows()), m = static_cast<int>(c.op.U.cols());
  a.assign(c.a0.data(), c.a0.data() + n);
  scale.assign(n, 1.0L);
  for (int j = 0; j < m; ++j) {
    long double uq = 0, uv = 0, size = 0;
    for (int k = 0; k < n; ++k) {
      uq += static_cast<long double>(c.op.U(k, j)) * c.q(k);
      uv += static_cast<long double>(c.op.U(k, j)) * c.qd(k);
      size += std::abs(c.op.U(k, j)) * (std::abs(c.op.d_K(j) * c.q(k)) + std::abs(c.op.d_C(j) * c.qd(k)));
    }
    const long double r = c.op.d_C(j) * uv + c.op.d_K(j) * uq;
    for (int k = 0; k < n; ++k) {
      a[k] -= r * c.op.phi(k, j);
      scale[k] += size * std::abs(c.op.phi(k, j));
    }
  }
}

void expect_matches(const Case& c, void (*form)(const LowRankCorrection&, const double*,
                                                 const double*, double*),
                    const char* name) {
  std::vector<long double> want, scale;
  oracle(c, want, scale);
  Eigen::VectorXd a = c.a0;
  form(c.op, c.q.data(), c.qd.data(), a.data());
  for (int k = 0; k < a.size(); ++k) {
    EXPECT_LE(std::abs(static_cast<long double>(a(k)) - want[k]), kRoundoffTol * scale[k])
        << name << ": n = " << a.size() << ", m = " << c.op.U.cols() << ", entry " << k;
  }
}

// Sizes around the AVX2 form's blocks (4 rows per step, modes in blocks of 4
// then one by one) and the paper's beam (100 free DOFs, 19 kept modes).
const int kSizes[][2] = {{1, 1}, {3, 2}, {4, 1}, {7, 3}, {8, 5}, {9, 4}, {100, 19}, {101, 19}, {100, 0}};

TEST(LowRankKernel, EigenFormMatchesOracle) {
  std::mt19937 rng(1905);
  for (const auto& nm : kSizes) expect_matches(random_case(rng, nm[0], nm[1]), subtract_low_rank_eigen, "eigen");
}

TEST(LowRankKernel, Avx2FormMatchesOracle) {
  if (!avx2_available()) GTEST_SKIP() << "no AVX2 + FMA on this processor or in this build";
  std::mt19937 rng(1905);
  for (const auto& nm : kSizes) expect_matches(random_case(rng, nm[0], nm[1]), subtract_low_rank_avx2, "avx2");
}

TEST(LowRankKernel, ShapeMismatchIsRejected) {
  std::mt19937 rng(3);
  Case c = random_case(rng, 10, 3);
  EXPECT_NO_THROW(check_shape(c.op));
  c.op.d_K.resize(2);
  EXPECT_THROW(check_shape(c.op), std::invalid_argument);
}

TEST(LowRankKernel, DispatchMatchesOracle) {
  std::mt19937 rng(7);
  expect_matches(random_case(rng, 100, 19), subtract_low_rank, "dispatch");
}

}  // namespace
}  // namespace mbfe::runtime
