// The nodal matrices of policy mass (docs/damping-adjustment.md, "Policy
// mass"), checked on a small beam against the dense modal definitions
//
//   M_adj = M Phi diag(m) Phi^T M,  C_adj = M Phi diag(c) Phi^T M,  K_adj = M Phi diag(k) Phi^T M,
//
// every mode, n x n: the sparse-plus-low-rank forms over the kept modes L
// only (U_L = M Phi_L, k* = omega_l^2, c* = (2 + margin) omega_l),
//
//   M_adj = K / k* + U_L diag(1 - k_L / k*) U_L^T
//   C_adj = (c* / k*) K + U_L diag(c_L - c* k_L / k*) U_L^T
//   K_adj = K
//   M_adj^-1 = k* K^-1 + Phi_L diag(1 - k* / k_L) Phi_L^T,
//   M_adj^-1 K = k* I + Phi_L diag(k_L - k*) U_L^T (the cap's), likewise C,
//
// and the state spectrum of (M_adj, C_adj, K) by the dense general
// eigen-solver against the cap's.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <complex>
#include <vector>

#include "runtime/damping/modal_adjustment.h"
#include "runtime/fem/beam_system.h"
#include "runtime/modal/modal_analysis.h"
#include "runtime/modal/state_spectrum.h"

namespace mbfe::runtime {
namespace {

/// 8 elements of the paper beam's section, pinned-pinned (16 DOF), with
/// Rayleigh damping: omega from ~70 to ~1e5 rad/s.
ir::Beam small_beam() {
  ir::Beam b;
  b.name = "b";
  b.length = 1.0;
  b.elements = 8;
  b.area = 25e-6;
  b.second_moment = 0.005 * 0.005 * 0.005 * 0.005 / 12.0;
  b.youngs_modulus = 2.1e11;
  b.density = 7860;
  b.supports = {{0.0, ir::SupportType::kPinned, 0, {}}, {1.0, ir::SupportType::kPinned, 8, {}}};
  b.rayleigh_alpha = 3e-3;
  b.rayleigh_beta = 1.5e-4;
  return b;
}

ir::Adjustment adjustment(ir::AdjustmentPolicy policy) {
  ir::Adjustment a;
  a.present = true;
  a.policy = policy;
  a.omega_limit = 1e4;  // caps about half of the 16 modes
  a.margin = 0.1;
  a.zeta_min = 0.05;    // floors the low modes' damping: c_L is not Rayleigh's
  return a;
}

// The dense oracle rests on M Phi Phi^T M = M, which the 16-DOF eigen-solver
// keeps to ~1e-12 of the largest entry; the forms below add a dense K^-1 (K's
// condition ~1e8 here).
constexpr double kDenseRel = 1e-9;
// Eigenvalues from 70 to 1.4e4 1/s by the nonsymmetric QR of a 32 x 32 matrix:
// ~1e-12 of the largest modulus; repeated (capped) ones split by up to
// sqrt(eps) of it before the pairing below, so they are compared as sets.
constexpr double kEigenRel = 1e-6;

double relative(const Eigen::MatrixXd& a, const Eigen::MatrixXd& oracle) { return (a - oracle).norm() / oracle.norm(); }

TEST(MassPolicyNodal, SparsePlusLowRankFormsEqualTheModalDefinitions) {
  const BeamSystem sys = assemble_beam(small_beam(), {0.0, 0.0});
  const ModalBasis basis = modal_analysis(sys);
  ASSERT_TRUE(basis.complete);
  const int n = static_cast<int>(basis.omega.size());
  const auto original = rayleigh_modes(basis.omega, sys.rayleigh_alpha, sys.rayleigh_beta);
  const AdjustedModes mass = adjust_modes(original, adjustment(ir::AdjustmentPolicy::kMass));
  ASSERT_GT(mass.adjusted, 2);
  ASSERT_LT(mass.adjusted, n - 2);
  ASSERT_GT(mass.floored, 0);

  const Eigen::MatrixXd M(sys.M), K(sys.K);
  const Eigen::MatrixXd MPhi = M * basis.phi;
  Eigen::VectorXd m(n), c(n), k(n);
  for (int j = 0; j < n; ++j) {
    m[j] = mass.modes[j].m;
    c[j] = mass.modes[j].c;
    k[j] = mass.modes[j].k;
  }
  const Eigen::MatrixXd m_oracle = MPhi * m.asDiagonal() * MPhi.transpose();
  const Eigen::MatrixXd c_oracle = MPhi * c.asDiagonal() * MPhi.transpose();
  const Eigen::MatrixXd k_oracle = MPhi * k.asDiagonal() * MPhi.transpose();

  // The kept modes: the first ones (the capped modes are a tail).
  int kept = 0;
  while (kept < n && mass.change[kept] != ModeChange::kAdjusted) ++kept;
  ASSERT_EQ(kept, n - mass.adjusted);
  const double ks = mass.k_star, cs = mass.c_star;
  const Eigen::MatrixXd phi_l = basis.phi.leftCols(kept);
  const Eigen::MatrixXd u_l = M * phi_l;
  const Eigen::VectorXd k_l = k.head(kept), c_l = c.head(kept);
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(kept);

  const Eigen::MatrixXd m_adj = K / ks + u_l * (ones - k_l / ks).asDiagonal() * u_l.transpose();
  const Eigen::MatrixXd c_adj = (cs / ks) * K + u_l * (c_l - (cs / ks) * k_l).asDiagonal() * u_l.transpose();
  EXPECT_LT(relative(m_adj, m_oracle), kDenseRel);
  EXPECT_LT(relative(c_adj, c_oracle), kDenseRel);
  EXPECT_LT(relative(K, k_oracle), kDenseRel);  // K_adj = K: the stiffness is kept

  const Eigen::MatrixXd k_inv = K.llt().solve(Eigen::MatrixXd::Identity(n, n));
  const Eigen::MatrixXd m_adj_inv = ks * k_inv + phi_l * (ones - ks * k_l.cwiseInverse()).asDiagonal() * phi_l.transpose();
  const Eigen::MatrixXd m_oracle_inv = m_oracle.llt().solve(Eigen::MatrixXd::Identity(n, n));
  EXPECT_LT(relative(m_adj_inv, m_oracle_inv), kDenseRel);

  // The explicit right-hand side: M_adj^-1 K and M_adj^-1 C_adj are the cap's
  // operators k* I + Phi_L diag(k_L - k*) U_L^T and c* I + Phi_L diag(c_L - c*) U_L^T.
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd cap_k = ks * I + phi_l * (k_l - ks * ones).asDiagonal() * u_l.transpose();
  const Eigen::MatrixXd cap_c = cs * I + phi_l * (c_l - cs * ones).asDiagonal() * u_l.transpose();
  EXPECT_LT(relative(m_oracle_inv * K, cap_k), kDenseRel);
  EXPECT_LT(relative(m_oracle_inv * c_oracle, cap_c), kDenseRel);

  // The roots of the nodal model (M_adj, C_adj, K) are the cap's.
  const AdjustedModes cap = adjust_modes(original, adjustment(ir::AdjustmentPolicy::kCap));
  std::vector<std::complex<double>> nodal = dense_state_eigenvalues(m_adj, c_adj, K);
  std::vector<std::complex<double>> capped = state_spectrum(cap.modes).eigenvalues;
  ASSERT_EQ(nodal.size(), capped.size());
  const auto by_value = [](const std::complex<double>& a, const std::complex<double>& b) {
    return a.real() != b.real() ? a.real() < b.real() : a.imag() < b.imag();
  };
  std::sort(nodal.begin(), nodal.end(), by_value);
  std::sort(capped.begin(), capped.end(), by_value);
  const double largest = std::abs(capped.front());
  for (std::size_t i = 0; i < nodal.size(); ++i)
    EXPECT_LT(std::abs(nodal[i] - capped[i]), kEigenRel * largest) << "eigenvalue " << i << ": " << nodal[i]
                                                                    << " against " << capped[i];
}

}  // namespace
}  // namespace mbfe::runtime
