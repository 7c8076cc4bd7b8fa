// The adjustment policies per mode, the low-rank form against eq (27), and
// the modal and nodal beam systems against each other.
#include <gtest/gtest.h>

#include <cmath>

#include "runtime/damping/beam_ode.h"
#include "runtime/damping/modal_adjustment.h"
#include "runtime/fem/beam_system.h"
#include "runtime/integrators/integrator.h"
#include "runtime/modal/modal_analysis.h"

namespace mbfe::runtime {
namespace {

/// A short version of the paper beam: 8 elements, pinned-pinned, 16 DOF.
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
  b.loads = {{0.5, ir::Expression::number(-10.0), 4, {}, {}}};
  return b;
}

ir::Adjustment cap(double omega_limit, double zeta_min = 0.0) {
  ir::Adjustment a;
  a.present = true;
  a.policy = ir::AdjustmentPolicy::kCap;
  a.omega_limit = omega_limit;
  a.margin = 0.1;
  a.zeta_min = zeta_min;
  return a;
}

// A root of 1.37e5 1/s computed two ways: ~1e-11 relative.
constexpr double kRootTol = 1e-6;

TEST(Policies, CapFloorAndEq25PerMode) {
  // Modes: (omega, c, k). Mode 0 lightly damped; 1 overdamped below the
  // limit; 2 overdamped far above it.
  std::vector<ModalDynamics> modes{{100.0, 0.2, 1e4}, {2e4, 6e4, 4e8}, {9e5, 1.2e8, 8.1e11}};
  const AdjustedModes a = adjust_modes(modes, cap(1e5, 0.05));
  EXPECT_EQ(a.change[0], ModeChange::kFloored);
  EXPECT_DOUBLE_EQ(a.modes[0].c, 2 * 0.05 * 100.0);
  EXPECT_EQ(a.change[1], ModeChange::kKept);  // fastest root 6e4 - 4e8/6e4... < 1e5
  EXPECT_EQ(a.change[2], ModeChange::kAdjusted);
  EXPECT_DOUBLE_EQ(a.modes[2].k, 1e10);
  EXPECT_DOUBLE_EQ(a.modes[2].c, 2.1e5);
  EXPECT_NEAR(fastest_root(a.modes[2].c, a.modes[2].k), (1.05 + std::sqrt(1.05 * 1.05 - 1)) * 1e5, kRootTol);
  ir::Adjustment eq25 = cap(1e5);
  eq25.policy = ir::AdjustmentPolicy::kPaperEq25;
  const AdjustedModes b = adjust_modes(modes, eq25);
  EXPECT_EQ(b.change[1], ModeChange::kKept);
  EXPECT_DOUBLE_EQ(b.modes[2].c, 2.1 * 9e5);
  EXPECT_DOUBLE_EQ(b.modes[2].k, 8.1e11);
  ir::Adjustment bad = cap(0.0);
  EXPECT_THROW(adjust_modes(modes, bad), std::invalid_argument);
}

TEST(Policies, MassKeepsTheStiffnessAndPutsTheRootsWhereTheCapDoes) {
  std::vector<ModalDynamics> modes{{100.0, 0.2, 1e4}, {2e4, 6e4, 4e8}, {9e5, 1.2e8, 8.1e11}};
  ir::Adjustment mass = cap(1e5, 0.05);
  mass.policy = ir::AdjustmentPolicy::kMass;
  const AdjustedModes capped = adjust_modes(modes, cap(1e5, 0.05));
  const AdjustedModes a = adjust_modes(modes, mass);
  EXPECT_EQ(a.policy, ir::AdjustmentPolicy::kMass);
  EXPECT_EQ(a.change, capped.change);  // the cap's selection and the same floor
  EXPECT_EQ(a.adjusted, 1);
  EXPECT_FALSE(a.uniform);  // the cap's low-rank form of K and C does not apply
  EXPECT_DOUBLE_EQ(a.k_star, 1e10);
  EXPECT_DOUBLE_EQ(a.c_star, 2.1e5);
  // Kept and floored modes as the cap leaves them, with a unit modal mass.
  for (int j : {0, 1}) {
    EXPECT_EQ(a.modes[j].m, 1.0);
    EXPECT_EQ(a.modes[j].k, capped.modes[j].k);
    EXPECT_EQ(a.modes[j].c, capped.modes[j].c);
  }
  // The adjusted mode: stiffness kept, m = k / omega_l^2, c = m (2 + margin) omega_l.
  EXPECT_EQ(a.modes[2].k, 8.1e11);
  EXPECT_DOUBLE_EQ(a.modes[2].m, 8.1e11 / 1e10);
  EXPECT_DOUBLE_EQ(a.modes[2].c, 81.0 * 2.1e5);
  // Its roots (of m r^2 + c r + k) are the cap's, to round-off.
  const auto r_mass = modal_roots(a.modes[2]);
  const auto r_cap = modal_roots(capped.modes[2].c, capped.modes[2].k);
  constexpr double kRoundoffRel = 1e-14;  // two divisions apart
  EXPECT_NEAR(r_mass.first.real(), r_cap.first.real(), kRoundoffRel * std::abs(r_cap.first));
  EXPECT_NEAR(r_mass.second.real(), r_cap.second.real(), kRoundoffRel * std::abs(r_cap.second));
  EXPECT_NEAR(fastest_root(a.modes[2]), (1.05 + std::sqrt(1.05 * 1.05 - 1)) * 1e5, kRootTol);
  // Nothing above the limit: nothing changed, and the form stays uniform.
  mass.omega_limit = 1e9;  // above every fastest root (the last mode's: ~1.2e8)
  const AdjustedModes none = adjust_modes(modes, mass);
  EXPECT_EQ(none.adjusted, 0);
  EXPECT_TRUE(none.uniform);
}

TEST(Policies, TheFloorReadsTheModalMass) {
  // A mode with its own modal mass 4, k = 4e4 (omega 100), c = 8: a damping
  // ratio c / (2 sqrt(k m)) = 0.01, raised to 0.05: c = 2 0.05 sqrt(k m) = 40.
  const std::vector<ModalDynamics> modes{{100.0, 8.0, 4e4, 4.0}};
  const AdjustedModes a = adjust_modes(modes, cap(1e5, 0.05));
  ASSERT_EQ(a.change[0], ModeChange::kFloored);
  EXPECT_DOUBLE_EQ(a.modes[0].c, 40.0);
  const auto r = modal_roots(a.modes[0]);
  EXPECT_NEAR(-r.first.real() / std::abs(r.first), 0.05, 1e-12);
}

TEST(LowRank, EqualsDenseEq27OnASmallBeam) {
  const BeamSystem sys = assemble_beam(small_beam(), {0.0, -9.81});
  const ModalBasis basis = modal_analysis(sys);
  ASSERT_TRUE(basis.complete);
  const auto original = rayleigh_modes(basis.omega, sys.rayleigh_alpha, sys.rayleigh_beta);
  // 8 elements: omega up to ~1e5; a limit of 1e4 caps about half the modes.
  const AdjustedModes adj = adjust_modes(original, cap(1e4, 0.05));
  ASSERT_GT(adj.adjusted, 2);
  ASSERT_LT(adj.adjusted, 14);
  const NodalAdjusted low = low_rank_adjusted(sys.M, basis, adj);
  const NodalAdjusted full = eq27_adjusted(sys.M, basis, adj);
  EXPECT_EQ(low.U.cols(), 16 - adj.adjusted);
  const Eigen::MatrixXd k_low = dense_matrix(low.K, sys.M, low.U), k_full = dense_matrix(full.K, sys.M, full.U);
  const Eigen::MatrixXd c_low = dense_matrix(low.C, sys.M, low.U), c_full = dense_matrix(full.C, sys.M, full.U);
  // Completeness M Phi Phi^T M = M holds to the eigen-solver's accuracy:
  // ~1e-12 of the largest entry for 16 DOF.
  constexpr double kCompleteTol = 1e-10;
  EXPECT_LT((k_low - k_full).norm(), kCompleteTol * k_full.norm());
  EXPECT_LT((c_low - c_full).norm(), kCompleteTol * c_full.norm());
  EXPECT_LT((k_full - k_full.transpose()).norm(), kCompleteTol * k_full.norm());
  // With nothing adjusted, eq (27) gives back the original K and C.
  ir::Adjustment none;
  none.policy = ir::AdjustmentPolicy::kNone;
  const NodalAdjusted orig = eq27_adjusted(sys.M, basis, adjust_modes(original, none));
  EXPECT_LT((dense_matrix(orig.K, sys.M, orig.U) - Eigen::MatrixXd(sys.K)).norm(), kCompleteTol * sys.K.norm());
  EXPECT_LT((dense_matrix(orig.C, sys.M, orig.U) - Eigen::MatrixXd(sys.C)).norm(), kCompleteTol * sys.C.norm());
}

/// Runs `steps` steps of `integrator` from rest; returns the nodal positions.
Eigen::VectorXd run_nodal(LinearSecondOrderSystem& ode, const char* integrator, double h, int steps) {
  auto st = make_stepper(parse_integrator(integrator), ode);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(ode.size());
  st->reset(0.0, y);
  for (int k = 0; k < steps; ++k) st->step(k * h, h, y);
  return y.head(ode.dof());
}

TEST(BeamOde, ModalAndNodalFormsAgreeForEveryIntegrator) {
  const BeamSystem sys = assemble_beam(small_beam(), {0.0, -9.81});
  const ModalBasis basis = modal_analysis(sys);
  const auto original = rayleigh_modes(basis.omega, sys.rayleigh_alpha, sys.rayleigh_beta);
  const AdjustedModes adj = adjust_modes(original, cap(1e4, 0.05));
  ModalBeamOde modal(basis, adj.modes, sys.M, sys.P);
  NodalBeamOde low(sys.M, low_rank_adjusted(sys.M, basis, adj), sys.P);
  NodalBeamOde dense(sys.M, eq27_adjusted(sys.M, basis, adj), sys.P);
  ModalBeamOde modal_orig(basis, original, sys.M, sys.P);
  NodalBeamOde nodal_orig(sys.M, sys.K, sys.C, sys.P);
  // Same model, other coordinates: the trajectories agree to round-off
  // amplified by the conditioning of Phi (~1e-9 relative here).
  constexpr double kSameModelTol = 1e-8;
  for (const char* integ : {"forward_euler", "rk4", "trapezoid", "backward_euler", "bdf2", "generalized_alpha"}) {
    const double h = 1e-5;
    const int steps = 300;
    Eigen::VectorXd qm = run_nodal(modal, integ, h, steps);
    qm = basis.phi * qm;
    const Eigen::VectorXd ql = run_nodal(low, integ, h, steps), qd = run_nodal(dense, integ, h, steps);
    ASSERT_GT(qm.norm(), 0.0);
    EXPECT_LT((ql - qm).norm(), kSameModelTol * qm.norm()) << integ;
    EXPECT_LT((qd - qm).norm(), kSameModelTol * qm.norm()) << integ;
    Eigen::VectorXd qo = basis.phi * run_nodal(modal_orig, integ, 1e-7, 100);
    const Eigen::VectorXd qn = run_nodal(nodal_orig, integ, 1e-7, 100);
    EXPECT_LT((qn - qo).norm(), kSameModelTol * qo.norm()) << integ << " (original)";
  }
}

}  // namespace
}  // namespace mbfe::runtime
