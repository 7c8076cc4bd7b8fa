// The beam in nodal coordinates (runtime/structure/nodal_beam_ode.h) against
// the modal form (runtime/damping/beam_ode.h): the same model in other
// coordinates, so every integrator gives the same trajectory, original and
// adjusted (the low-rank form and eq (27) over every mode).
#include <gtest/gtest.h>

#include "runtime/damping/beam_ode.h"
#include "runtime/damping/modal_adjustment.h"
#include "runtime/fem/beam_system.h"
#include "runtime/integrators/integrator.h"
#include "runtime/modal/modal_analysis.h"
#include "runtime/structure/adjusted_parts.h"
#include "runtime/structure/nodal_beam_ode.h"

namespace mbfe::runtime {
namespace {

/// A short version of the paper beam: 8 elements, pinned-pinned, 16 DOF,
/// 10 N at midspan.
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

ir::Adjustment cap(double omega_limit, double zeta_min) {
  ir::Adjustment a;
  a.present = true;
  a.policy = ir::AdjustmentPolicy::kCap;
  a.omega_limit = omega_limit;
  a.margin = 0.1;
  a.zeta_min = zeta_min;
  return a;
}

/// The adjusted modes as eq (27) over every mode: no base part, every mode's
/// adjusted k and c in the low rank.
LowRankStructure::Parts every_mode(const BeamSystem& sys, const ModalBasis& basis, const AdjustedModes& adj) {
  const int n = static_cast<int>(basis.omega.size());
  LowRankStructure::Parts p;
  p.name = "b";
  p.ranges = {{0, n}};
  p.M = sys.M;
  p.K = sys.K;
  p.P = sys.P;
  p.phi = basis.phi;
  p.k = basis.omega.array().square().matrix();
  p.mass = {1.0, Eigen::VectorXd::Zero(n)};
  p.damping = {0.0, Eigen::VectorXd(n)};
  p.stiffness = {0.0, Eigen::VectorXd(n)};
  for (int j = 0; j < n; ++j) {
    p.damping.d[j] = adj.modes[j].c;
    p.stiffness.d[j] = adj.modes[j].k;
  }
  p.every_mode = true;
  return p;
}

/// Runs `steps` steps of `integrator` from rest; returns the positions.
Eigen::VectorXd run(LinearSecondOrderSystem& ode, const char* integrator, double h, int steps) {
  auto st = make_stepper(parse_integrator(integrator), ode);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(ode.size());
  st->reset(0.0, y);
  for (int k = 0; k < steps; ++k) st->step(k * h, h, y);
  return y.head(ode.dof());
}

TEST(NodalBeamOde, ModalAndNodalFormsAgreeForEveryIntegrator) {
  const BeamSystem sys = assemble_beam(small_beam(), {0.0, -9.81});
  const ModalBasis basis = modal_analysis(sys);
  const auto original = rayleigh_modes(basis.omega, sys.rayleigh_alpha, sys.rayleigh_beta);
  const AdjustedModes adj = adjust_modes(original, cap(1e4, 0.05));
  const int n = static_cast<int>(sys.M.rows());
  ModalBeamOde modal(basis, adj.modes, sys.M, sys.P);
  NodalBeamOde low(std::make_shared<const LowRankStructure>(adjusted_parts("b", {{0, n}}, sys.M, sys.K, sys.P, basis, adj)));
  NodalBeamOde dense(std::make_shared<const LowRankStructure>(every_mode(sys, basis, adj)));
  ModalBeamOde modal_orig(basis, original, sys.M, sys.P);
  NodalBeamOde nodal_orig(sys.M, sys.K, sys.C, sys.P);
  // Same model, other coordinates: the trajectories agree to round-off
  // amplified by the conditioning of Phi (~1e-9 relative here).
  constexpr double kSameModelTol = 1e-8;
  for (const char* integ : {"forward_euler", "rk4", "trapezoid", "backward_euler", "bdf2", "generalized_alpha"}) {
    const double h = 1e-5;
    const int steps = 300;
    const Eigen::VectorXd qm = basis.phi * run(modal, integ, h, steps);
    const Eigen::VectorXd ql = run(low, integ, h, steps), qd = run(dense, integ, h, steps);
    ASSERT_GT(qm.norm(), 0.0);
    EXPECT_LT((ql - qm).norm(), kSameModelTol * qm.norm()) << integ;
    EXPECT_LT((qd - qm).norm(), kSameModelTol * qm.norm()) << integ;
    const Eigen::VectorXd qo = basis.phi * run(modal_orig, integ, 1e-7, 100);
    const Eigen::VectorXd qn = run(nodal_orig, integ, 1e-7, 100);
    EXPECT_LT((qn - qo).norm(), kSameModelTol * qo.norm()) << integ << " (original)";
  }
}

}  // namespace
}  // namespace mbfe::runtime
