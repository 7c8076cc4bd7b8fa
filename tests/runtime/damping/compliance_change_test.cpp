// The accuracy estimate's compliance change (runtime/damping/compliance_change.h)
// against the point receptance computed directly: dense complex solves of the
// nodal equations, e^T (K - Omega^2 M + i Omega C)^-1 e with the original
// matrices, and with the adjusted ones of eq (27) (M Phi diag(m, c, k) Phi^T M)
// for the adjusted model. The paper beam, 50 elements (100 DOF), every mode;
// the point is the deflection at a quarter span (node 12).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <complex>
#include <string>

#include "frontend/parse_model.h"
#include "runtime/damping/beam_model.h"
#include "runtime/damping/compliance_change.h"
#include "runtime/damping/modal_adjustment.h"

namespace mbfe::runtime {
namespace {

using Complex = std::complex<double>;

// The dense receptances of a 100-DOF beam whose K has cond ~1e10: a complex
// LU solve keeps ~1e-6 of the change relative to the compliance it is a
// share of (the change itself is a difference of two solves).
constexpr double kDenseRel = 1e-5;
// A cap at 2e4 rad/s changes the modes above the 17th; the force's frequency
// is 0.3 of it.
constexpr double kOmegaLimit = 2.0e4;  // rad/s
constexpr double kForceOmega = 6.0e3;  // rad/s
// Beyond a partial basis the original response is taken to first order in
// Omega^2 / k_j; with Omega = 0.3 omega_l and k_j >= omega_l^2 the next term
// is below (0.09)^2 of the tail's share.
constexpr double kTailExpansionRel = 1e-2;

/// e^T (K - Omega^2 M + i Omega C)^-1 e, dense.
Complex receptance(const Eigen::MatrixXd& M, const Eigen::MatrixXd& C, const Eigen::MatrixXd& K,
                   const Eigen::VectorXd& e, double omega) {
  const Eigen::MatrixXcd A = K.cast<Complex>() - omega * omega * M.cast<Complex>() + Complex(0.0, omega) * C.cast<Complex>();
  const Eigen::VectorXcd x = A.partialPivLu().solve(e.cast<Complex>());
  return e.cast<Complex>().dot(x);
}

struct Beam {
  BeamPart part;
  Eigen::VectorXd e;
};

Beam paper_beam() {
  const ir::Model file = frontend::load_model_file(std::string(MBFE_SOURCE_DIR) + "/models/paper_beam.yaml");
  Beam b{analyse_beams(file).beams.at(0), Eigen::VectorXd()};
  b.e = Eigen::VectorXd::Zero(b.part.system.M.rows());
  b.e[b.part.system.full_to_free.at(2 * 12)] = 1.0;
  return b;
}

ir::Adjustment adjustment(ir::AdjustmentPolicy policy) {
  ir::Adjustment a;
  a.present = true;
  a.omega_limit = kOmegaLimit;
  a.margin = 0.1;
  a.zeta_min = 0.0;
  a.policy = policy;
  return a;
}

/// The oracle: |H_adj(Omega) - H(Omega)| by dense nodal solves.
double dense_change(const BeamPart& b, const AdjustedModes& adjusted, const Eigen::VectorXd& e, double omega) {
  const Eigen::MatrixXd M(b.system.M), C(b.system.C), K(b.system.K);
  const Eigen::MatrixXd U = M * b.basis.phi;
  const Eigen::Index n = U.cols();
  Eigen::VectorXd m(n), c(n), k(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    m[j] = adjusted.modes[j].m;
    c[j] = adjusted.modes[j].c;
    k[j] = adjusted.modes[j].k;
  }
  const Eigen::MatrixXd Ma = U * m.asDiagonal() * U.transpose();
  const Eigen::MatrixXd Ca = U * c.asDiagonal() * U.transpose();
  const Eigen::MatrixXd Ka = U * k.asDiagonal() * U.transpose();
  return std::abs(receptance(Ma, Ca, Ka, e, omega) - receptance(M, C, K, e, omega));
}

/// The quasi-static compliance at Omega (the estimate's denominator), from the modes.
double quasi_static(const BeamPart& b, const Eigen::VectorXd& e, double series, double omega) {
  double s = series;
  for (Eigen::Index j = 0; j < b.basis.omega.size(); ++j) {
    const double p = b.basis.phi.col(j).dot(e);
    if (b.basis.omega[j] > omega) s += p * p / (b.basis.omega[j] * b.basis.omega[j]);
  }
  return s;
}

TEST(ComplianceChange, EveryModeMatchesTheDenseReceptanceForCapAndMass) {
  const Beam b = paper_beam();
  ASSERT_TRUE(b.part.basis.complete);
  const ComplianceChangeEstimator estimator(b.part.system.M, b.part.system.K, b.part.system.C, b.part.basis,
                                            b.part.original);
  const double series = 1.0 / 2.0e6;  // a contact spring of 2e6 N/m in series
  for (const ir::AdjustmentPolicy policy : {ir::AdjustmentPolicy::kCap, ir::AdjustmentPolicy::kMass}) {
    const AdjustedModes adjusted = adjust_modes(b.part.original, adjustment(policy));
    ASSERT_GT(adjusted.adjusted, 0);
    for (const double omega : {0.0, kForceOmega}) {
      SCOPED_TRACE("policy " + std::to_string(static_cast<int>(policy)) + ", Omega " + std::to_string(omega));
      const auto point = estimator.point({b.e, series, omega});
      const ComplianceChange got = estimator.evaluate(point, adjusted);
      const double scale = quasi_static(b.part, b.e, series, omega);
      EXPECT_NEAR(got.quasi_static, scale, kDenseRel * scale);
      const double expected = dense_change(b.part, adjusted, b.e, omega) / scale;
      EXPECT_NEAR(got.change, expected, kDenseRel);
      if (omega == 0.0) {
        const Eigen::MatrixXd K(b.part.system.K);
        const double compliance = b.e.dot(K.ldlt().solve(b.e));
        EXPECT_NEAR(got.compliance, compliance, kDenseRel * compliance);
        EXPECT_NEAR(got.static_change, dense_change(b.part, adjusted, b.e, 0.0) / (series + compliance), kDenseRel);
      }
      if (policy == ir::AdjustmentPolicy::kCap) {
        // The cap softens the point: 4e-4 of its compliance at a quarter span.
        EXPECT_GT(got.static_change, 1e-4);
      } else {
        // Mass keeps every modal stiffness: no static change beyond round-off.
        EXPECT_LT(got.static_change, kDenseRel);
      }
    }
  }
}

// The band figure: the reported largest value against the dense receptances
// at the frequency reported, and on a coarser grid of the band none larger
// (the coarse frequencies are among the estimator's 512, so a larger dense
// value there would be a wrong change or a wrong largest).
TEST(ComplianceChange, BandChangeMatchesTheDenseReceptance) {
  const Beam b = paper_beam();
  const ComplianceChangeEstimator estimator(b.part.system.M, b.part.system.K, b.part.system.C, b.part.basis,
                                            b.part.original);
  const double series = 1.0 / 2.0e6;  // a contact spring of 2e6 N/m in series
  constexpr int kCoarse = 16;         // dense checks over the band: every 32nd of the estimator's frequencies
  for (const ir::AdjustmentPolicy policy : {ir::AdjustmentPolicy::kCap, ir::AdjustmentPolicy::kMass}) {
    SCOPED_TRACE("policy " + std::to_string(static_cast<int>(policy)));
    const AdjustedModes adjusted = adjust_modes(b.part.original, adjustment(policy));
    const ComplianceChange got = estimator.evaluate(estimator.point({b.e, series, kForceOmega}), adjusted, /*band=*/true);
    const auto band = [&](double omega) {
      return dense_change(b.part, adjusted, b.e, omega) / quasi_static(b.part, b.e, series, omega);
    };
    // Under both policies the band's largest lies inside it, above the
    // static figure (the capped modes' change grows towards the cap).
    ASSERT_GT(got.band_omega, 0.0);
    EXPECT_NEAR(got.band_change, band(got.band_omega), kDenseRel * got.band_change);
    EXPECT_GE(got.band_change, got.change);
    EXPECT_GE(got.band_change, got.static_change);
    for (int i = 1; i <= kCoarse; ++i) {
      const double omega = kForceOmega * i / kCoarse;
      EXPECT_LE(band(omega), got.band_change * (1.0 + kDenseRel)) << "at " << omega << " rad/s";
    }
  }
}

TEST(ComplianceChange, APartialBasisMatchesTheCompleteOne) {
  const Beam b = paper_beam();
  const ComplianceChangeEstimator complete(b.part.system.M, b.part.system.K, b.part.system.C, b.part.basis,
                                           b.part.original);
  for (const ir::AdjustmentPolicy policy : {ir::AdjustmentPolicy::kCap, ir::AdjustmentPolicy::kMass}) {
    const AdjustedModes all = adjust_modes(b.part.original, adjustment(policy));
    // The modes the policy keeps and the first it changes: what a large
    // beam's sliced basis holds.
    int kept = 0;
    while (all.change[kept] == ModeChange::kKept) ++kept;
    const int m = kept + 1;
    ModalBasis partial{b.part.basis.omega.head(m), b.part.basis.phi.leftCols(m), false};
    std::vector<ModalDynamics> original(b.part.original.begin(), b.part.original.begin() + m);
    const AdjustedModes adjusted = adjust_modes(original, adjustment(policy));
    const ComplianceChangeEstimator estimator(b.part.system.M, b.part.system.K, b.part.system.C, partial, original);
    for (const double omega : {0.0, kForceOmega}) {
      SCOPED_TRACE("policy " + std::to_string(static_cast<int>(policy)) + ", Omega " + std::to_string(omega));
      const ComplianceChange want = complete.evaluate(complete.point({b.e, 0.0, omega}), all);
      const ComplianceChange got = estimator.evaluate(estimator.point({b.e, 0.0, omega}), adjusted);
      EXPECT_NEAR(got.quasi_static, want.quasi_static, kDenseRel * want.quasi_static);
      EXPECT_NEAR(got.changed_share, want.changed_share, kDenseRel);
      EXPECT_NEAR(got.static_change, want.static_change, kDenseRel);
      EXPECT_NEAR(got.change, want.change, omega == 0.0 ? kDenseRel : kTailExpansionRel * want.change + kDenseRel);
    }
  }
}

// A batch's points are computed by blocks of matrix products, one point
// alone by a block of one: the same sums in another order.
constexpr double kBatchRel = 1e-10;

TEST(ComplianceChange, ManyPointsAtOnceGiveWhatEachGivesAlone) {
  const Beam b = paper_beam();
  const AdjustedModes all = adjust_modes(b.part.original, adjustment(ir::AdjustmentPolicy::kCap));
  int kept = 0;
  while (all.change[kept] == ModeChange::kKept) ++kept;
  const int m = kept + 1;  // a partial basis: the tail's moments are computed too
  ModalBasis partial{b.part.basis.omega.head(m), b.part.basis.phi.leftCols(m), false};
  std::vector<ModalDynamics> original(b.part.original.begin(), b.part.original.begin() + m);
  const ComplianceChangeEstimator estimator(b.part.system.M, b.part.system.K, b.part.system.C, partial, original);
  // Every free DOF a point of its own (100 points: several blocks), each
  // with its own spring and frequency, so a point given another's block
  // slot shows.
  std::vector<CompliancePoint> batch;
  for (Eigen::Index i = 0; i < b.part.system.M.rows(); ++i) {
    CompliancePoint p{Eigen::VectorXd::Unit(b.part.system.M.rows(), i), 1e-9 * static_cast<double>(i + 1),
                      10.0 * static_cast<double>(i)};
    batch.push_back(p);
  }
  const std::vector<ComplianceChangeEstimator::Point> got = estimator.points(batch);
  ASSERT_EQ(got.size(), batch.size());
  for (std::size_t i = 0; i < batch.size(); ++i) {
    SCOPED_TRACE("point " + std::to_string(i));
    const ComplianceChangeEstimator::Point want = estimator.point(batch[i]);
    EXPECT_EQ(got[i].series_compliance, want.series_compliance);
    EXPECT_EQ(got[i].omega, want.omega);
    EXPECT_NEAR(got[i].compliance, want.compliance, kBatchRel * want.compliance);
    EXPECT_NEAR(got[i].tail0, want.tail0, kBatchRel * want.tail0);
    EXPECT_NEAR(got[i].tail1, want.tail1, kBatchRel * want.tail1);
    EXPECT_NEAR(got[i].tail2, want.tail2, kBatchRel * want.tail2);
    ASSERT_EQ(got[i].p2.size(), want.p2.size());
    EXPECT_LE((got[i].p2 - want.p2).norm(), kBatchRel * want.p2.norm());
  }
}

}  // namespace
}  // namespace mbfe::runtime
