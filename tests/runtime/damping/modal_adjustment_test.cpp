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
