// Spectrum slicing (modal_below): every mode below a bound, from many
// shift-invert Lanczos runs, against the dense eigen-solver. The test beam is
// a tensioned wire over eight identical spans on stiff spring supports with
// clamp masses: nearly independent spans, whose eigenvalues come in clusters
// of eight (neighbours 7e-4 to 5e-3 apart, clusters 3e-2 and more), so that
// the runs' windows end inside clusters and their vectors must still be
// M-orthogonal to the next run's.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "runtime/fem/beam_system.h"
#include "runtime/modal/modal_analysis.h"

namespace mbfe::runtime {
namespace {

constexpr int kSpans = 8;
constexpr double kSpan = 10.0;        // m
constexpr int kElementsPerSpan = 20;  // 0.5 m elements

// A contact wire: 1.35 kg/m, EI = 195 N m^2, 20 kN, a 1e7 N/m support of 1 kg
// at every inner support (a catenary's are 300 N/m; these make the spans
// nearly independent), 0.195 kg clamps at 2.5 m and 7.5 m of a span.
ir::Beam periodic_wire() {
  ir::Beam b;
  b.name = "wire";
  b.length = kSpans * kSpan;
  b.elements = kSpans * kElementsPerSpan;
  b.youngs_modulus = 1.2e11;
  b.density = 8900.0;
  b.area = 1.35 / b.density;
  b.second_moment = 195.0 / b.youngs_modulus;
  b.tension = 20000.0;
  b.rayleigh_alpha = 0.06;
  b.rayleigh_beta = 7.6e-5;
  b.supports.push_back({0.0, ir::SupportType::kPinned, -1, 0.0, 0.0, 0.0, {}});
  for (int k = 1; k < kSpans; ++k) b.supports.push_back({k * kSpan, ir::SupportType::kSpring, -1, 1e7, 0.0, 1.0, {}});
  b.supports.push_back({b.length, ir::SupportType::kPinned, -1, 0.0, 0.0, 0.0, {}});
  for (int k = 0; k < kSpans; ++k)
    for (double at : {2.5, 7.5}) b.masses.push_back({k * kSpan + at, 0.195, -1, {}});
  return b;
}

// The dense solver's absolute eigenvalue error is ~eps lambda_max, a relative
// omega error of ~eps/2 (omega_max / omega_j)^2 on mode j; Lanczos converges to
// 1e-10 on the Ritz values. Mode j is compared within that sum, times 10.
double omega_tolerance(const ModalBasis& dense, int j) {
  const double spread = dense.omega[dense.omega.size() - 1] / dense.omega[j];
  return 10.0 * (1e-10 + std::numeric_limits<double>::epsilon() * spread * spread);
}

// M-orthonormality across runs and the distance to the dense subspace:
// measured 2e-13 at most. Lanczos converges far below its 1e-10 Ritz
// tolerance here; the bound that tolerance guarantees for a cluster split
// between runs (1e-10 over the 7e-4 gap) would be 1.4e-7. 1e-10 leaves room
// for other compilers and BLAS.
constexpr double kSubspaceTol = 1e-10;
// K phi - omega^2 M phi against omega^2 |M phi|: a converged Ritz pair.
constexpr double kResidualTol = 1e-8;

// The sliced modes of a bound that makes them end at the widest gap after
// modes 100..140.
struct Sliced {
  BeamSystem system;
  ModalBasis dense, sliced;
  int below = 0;  // dense modes below the bound
};

Sliced slice(int slice_modes) {
  Sliced out{assemble_beam(periodic_wire(), {0.0, 0.0}), {}, {}, 0};
  out.dense = modal_dense(out.system.M, out.system.K);
  // The widest gap follows mode `widest`: the bound goes just below that mode,
  // so the modes returned (0 .. widest) end at the gap.
  const Eigen::VectorXd& w = out.dense.omega;
  int widest = 100;
  for (int j = 100; j < 140; ++j)
    if (w[j + 1] / w[j] > w[widest + 1] / w[widest]) widest = j;
  const double bound = std::sqrt(out.dense.omega[widest - 1] * out.dense.omega[widest]);
  out.below = widest;
  SlicedModalOptions options;
  options.lower = -1.0;
  options.slice_modes = slice_modes;
  out.sliced = modal_below(out.system.M, out.system.K, bound, options);
  return out;
}

void expect_dense_modes(const Sliced& s) {
  const int k = s.below + 1;
  ASSERT_EQ(s.sliced.omega.size(), k);
  EXPECT_FALSE(s.sliced.complete);
  for (int j = 0; j < k; ++j)
    EXPECT_NEAR(s.sliced.omega[j] / s.dense.omega[j], 1.0, omega_tolerance(s.dense, j)) << "mode " << j + 1;
  const Eigen::MatrixXd& phi = s.sliced.phi;
  const Eigen::MatrixXd gram = phi.transpose() * (s.system.M * phi);
  EXPECT_LT((gram - Eigen::MatrixXd::Identity(k, k)).cwiseAbs().maxCoeff(), kSubspaceTol);
  for (int j = 0; j < k; ++j) {
    const Eigen::VectorXd mphi = s.system.M * phi.col(j);
    const double w2 = s.sliced.omega[j] * s.sliced.omega[j];
    EXPECT_LT((s.system.K * phi.col(j) - w2 * mphi).norm(), kResidualTol * w2 * mphi.norm()) << "mode " << j + 1;
  }
  // The same subspace as the dense modes 1..k (mode k + 1 is the widest gap
  // away): the dense modes lose nothing by projection onto the sliced ones.
  const Eigen::MatrixXd d = s.dense.phi.leftCols(k);
  const Eigen::MatrixXd residue = d - phi * (phi.transpose() * (s.system.M * d));
  EXPECT_LT(residue.cwiseAbs().maxCoeff(), kSubspaceTol * d.cwiseAbs().maxCoeff());
}

TEST(SpectrumSlicing, TheSpectrumComesInClustersOfEight) {
  // The premise of the next tests: seven of every eight neighbouring modes
  // lie within 1e-2 (a cluster), the eighth pair 3e-2 or more apart.
  const BeamSystem s = assemble_beam(periodic_wire(), {0.0, 0.0});
  const ModalBasis dense = modal_dense(s.M, s.K);
  int tight = 0;
  for (int j = 1; j < 137; ++j) tight += dense.omega[j] / dense.omega[j - 1] - 1.0 < 1e-2;
  EXPECT_EQ(tight, 7 * 17);
}

TEST(SpectrumSlicing, ManySmallRunsGiveTheDenseModes) {
  // 24 modes a run: about seven runs, each window three clusters wide.
  expect_dense_modes(slice(24));
}

TEST(SpectrumSlicing, TheDefaultRunSizeGivesTheDenseModes) { expect_dense_modes(slice(SlicedModalOptions{}.slice_modes)); }

TEST(SpectrumSlicing, ABoundNearTheTopGivesAllButTheTopMode) {
  // The bound below the second-highest mode: every mode but the highest.
  const BeamSystem s = assemble_beam(periodic_wire(), {0.0, 0.0});
  const ModalBasis dense = modal_dense(s.M, s.K);
  const Eigen::Index n = dense.omega.size();
  SlicedModalOptions options;
  options.lower = -1.0;
  options.slice_modes = 60;
  const ModalBasis sliced = modal_below(s.M, s.K, 0.5 * (dense.omega[n - 3] + dense.omega[n - 2]), options);
  ASSERT_EQ(sliced.omega.size(), n - 1);
  for (Eigen::Index j = 0; j < n - 1; ++j)
    EXPECT_NEAR(sliced.omega[j] / dense.omega[j], 1.0, omega_tolerance(dense, static_cast<int>(j))) << "mode " << j + 1;
}

TEST(SpectrumSlicing, EigenvalueCountMatchesTheDenseSpectrum) {
  const BeamSystem s = assemble_beam(periodic_wire(), {0.0, 0.0});
  const ModalBasis dense = modal_dense(s.M, s.K);
  for (int j : {1, 17, 64, 200}) {
    const double between = dense.omega[j - 1] * dense.omega[j];  // geometric mean, squared
    EXPECT_EQ(eigenvalues_below(s.M, s.K, between), j);
  }
  EXPECT_EQ(eigenvalues_below(s.M, s.K, -1.0), 0);
}

TEST(SpectrumSlicing, RefusesWhatItCannotDo) {
  const BeamSystem s = assemble_beam(periodic_wire(), {0.0, 0.0});
  const ModalBasis dense = modal_dense(s.M, s.K);
  const double top = 2.0 * dense.omega[dense.omega.size() - 1];
  EXPECT_THROW(modal_below(s.M, s.K, top), std::invalid_argument);  // every mode: the dense path's job
  EXPECT_THROW(modal_below(s.M, s.K, 0.0), std::invalid_argument);
  SlicedModalOptions above_lowest;
  above_lowest.lower = 4.0 * dense.omega[0] * dense.omega[0];
  EXPECT_THROW(modal_below(s.M, s.K, dense.omega[50], above_lowest), std::invalid_argument);
}

TEST(SpectrumSlicing, BeamAnalysisUsesItAboveTheDenseLimit) {
  const BeamSystem s = assemble_beam(periodic_wire(), {0.0, 0.0});
  const ModalBasis dense = modal_dense(s.M, s.K);
  ModalOptions options;
  options.dense_limit = 100;
  options.up_to_omega = 0.5 * (dense.omega[79] + dense.omega[80]);
  const ModalBasis sliced = modal_analysis(s, options);
  ASSERT_EQ(sliced.omega.size(), 81);
  EXPECT_GT(sliced.omega[80], options.up_to_omega);
  EXPECT_LT(sliced.omega[79], options.up_to_omega);
  options.dense_limit = 2000;  // within the dense limit: every mode, as before
  EXPECT_TRUE(modal_analysis(s, options).complete);
}

}  // namespace
}  // namespace mbfe::runtime
