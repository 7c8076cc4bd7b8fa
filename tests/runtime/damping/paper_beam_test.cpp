// The paper's result (Section 7, Table 1 right half, Fig. 5) reproduced on
// models/paper_beam.yaml, against the reference numbers of
// docs/reference-values.md (computed by scripts/reference_values.py).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "runtime/damping/beam_model.h"
#include "runtime/damping/beam_ode.h"
#include "runtime/structure/adjusted_parts.h"
#include "runtime/structure/nodal_beam_ode.h"
#include "runtime/damping/modal_adjustment.h"
#include "runtime/integrators/integrator.h"
#include "runtime/integrators/simulation_driver.h"
#include "frontend/parse_model.h"
#include "runtime/stability/step_limits.h"

namespace mbfe::runtime {
namespace {

// The reference values are printed with 6-7 significant digits; the dense
// 100-DOF eigen-solver is good to ~1e-10. 5e-6 relative is the printing.
constexpr double kReferenceRel = 5e-6;

const ir::Model& paper_model() {
  static const ir::Model m = frontend::load_model_file(std::string(MBFE_SOURCE_DIR) + "/models/paper_beam.yaml");
  return m;
}

const BeamModel& paper_beams() {
  static const BeamModel b = analyse_beams(paper_model());
  return b;
}

double max_modulus(const StateSpectrum& s) { return std::abs(s.eigenvalues.back()); }

TEST(PaperBeam, AdjustmentBlockIsThePapers) {
  const ir::Adjustment& a = paper_model().beams.at(0).adjustment;
  EXPECT_TRUE(a.present);
  EXPECT_EQ(a.policy, ir::AdjustmentPolicy::kCap);
  EXPECT_DOUBLE_EQ(a.omega_limit, 1e5);
  EXPECT_DOUBLE_EQ(a.margin, 0.1);
  EXPECT_DOUBLE_EQ(a.zeta_min, 0.05);
}

// The reference values are printed with four decimals.
constexpr double kFourDecimals = 5e-5;
// The floor sets c = 2 zeta omega exactly; the ratio is read back from the roots.
constexpr double kFloorRatioTol = 1e-12;

TEST(PaperBeam, AdjustedSpectrumMatchesTheReferenceValues) {
  const BeamModel& b = paper_beams();
  ASSERT_EQ(b.dof, 100);
  ASSERT_EQ(b.adjusted.eigenvalues.size(), 200u);
  EXPECT_NEAR(max_modulus(b.adjusted), 1.370156e5, kReferenceRel * 1.370156e5);
  // Every capped mode ends at the same fastest root: -1.370156e5 (real).
  EXPECT_EQ(b.adjusted.eigenvalues.back().imag(), 0.0);
  const auto first = b.adjusted.eigenvalues.front();
  EXPECT_NEAR(first.real(), -3.6817, kFourDecimals);
  EXPECT_NEAR(std::abs(first.imag()), 73.5417, kFourDecimals);
  const auto fe = parse_integrator("forward_euler");
  EXPECT_NEAR(stable_step(fe, b.original.eigenvalues).h, 1.52098e-8, kReferenceRel * 1.52098e-8);
  EXPECT_NEAR(stable_step(fe, b.adjusted.eigenvalues).h, 1.45969e-5, kReferenceRel * 1.45969e-5);
  // Table 1: the floor raises modes 1..3 to 5 % and leaves mode 5 pair (4.99 %) at 5 %.
  EXPECT_NEAR(-first.real() / std::abs(first), 0.05, kFloorRatioTol);
}

TEST(PaperBeam, LiteralEq25GivesOnly94x) {
  const BeamPart& p = paper_beams().beams.at(0);
  ir::Adjustment a = paper_model().beams.at(0).adjustment;
  a.policy = ir::AdjustmentPolicy::kPaperEq25;
  const StateSpectrum s = state_spectrum(adjust_modes(p.original, a).modes);
  EXPECT_NEAR(max_modulus(s), 1.40264e6, kReferenceRel * 1.40264e6);
  EXPECT_NEAR(stable_step(parse_integrator("forward_euler"), s.eigenvalues).h, 1.42588e-6, kReferenceRel * 1.42588e-6);
}

TEST(PaperBeam, KeepSlowReachesTheSameLimitAsCap) {
  const BeamPart& p = paper_beams().beams.at(0);
  ir::Adjustment a = paper_model().beams.at(0).adjustment;
  a.policy = ir::AdjustmentPolicy::kKeepSlow;
  const AdjustedModes keep = adjust_modes(p.original, a);
  EXPECT_FALSE(keep.uniform);
  const StateSpectrum s = state_spectrum(keep.modes);
  EXPECT_NEAR(max_modulus(s), 1.370156e5, kReferenceRel * 1.370156e5);
}

// Policy mass moves the capped modes' roots exactly where the cap does (only
// the modal mass carries the change, not the stiffness), so Table 1's right
// half and every stable step come out the same, to the round-off of the two
// divisions c / m and k / m.
constexpr double kMassPolicyRootRel = 1e-14;
// The stable steps of those roots: a bisection on the stability boundary
// from roots 1e-14 apart, to its own stopping tolerance.
constexpr double kStepLimitRel = 1e-12;

TEST(PaperBeam, MassPolicyReproducesTable1AndEveryStableStep) {
  const BeamPart& p = paper_beams().beams.at(0);
  ir::Adjustment a = paper_model().beams.at(0).adjustment;
  a.policy = ir::AdjustmentPolicy::kMass;
  const AdjustedModes mass = adjust_modes(p.original, a);
  EXPECT_EQ(mass.adjusted, p.adjusted.adjusted);
  const StateSpectrum s = state_spectrum(mass.modes);
  const StateSpectrum& cap = p.adjusted_spectrum;
  ASSERT_EQ(s.eigenvalues.size(), cap.eigenvalues.size());
  for (std::size_t i = 0; i < s.eigenvalues.size(); ++i)
    EXPECT_LE(std::abs(s.eigenvalues[i] - cap.eigenvalues[i]), kMassPolicyRootRel * std::abs(cap.eigenvalues[i]))
        << "eigenvalue " << i + 1;
  EXPECT_EQ(s.oscillatory_pairs, cap.oscillatory_pairs);
  EXPECT_NEAR(max_modulus(s), 1.370156e5, kReferenceRel * 1.370156e5);
  for (const IntegratorSpec& integrator : advisor_integrators()) {
    const StepLimit lm = stable_step(integrator, s.eigenvalues), lc = stable_step(integrator, cap.eigenvalues);
    EXPECT_EQ(lm.kind, lc.kind) << integrator.name;
    if (lc.kind == StepLimit::Kind::kFinite) EXPECT_NEAR(lm.h, lc.h, kStepLimitRel * lc.h) << integrator.name;
  }
}

/// Forward Euler from rest on the original (nodal, sparse) or adjusted (modal) model.
SimulationResult run_forward_euler(LinearSecondOrderSystem& ode, double h, double t_end) {
  SimulationOptions opt;
  opt.step = h;
  opt.t_end = t_end;
  opt.max_rows = 10;
  return run_simulation(ode, parse_integrator("forward_euler"), Eigen::VectorXd::Zero(ode.size()), opt,
                        [](double, const Eigen::VectorXd&) {});
}

// The paper's Fig. 5a: the original beam in nodal coordinates (sparse M, K, C).
TEST(PaperBeam, OriginalForwardEulerLimit) {
  const BeamPart& p = paper_beams().beams.at(0);
  NodalBeamOde ode(p.system.M, p.system.K, p.system.C, p.system.P);
  const auto bad = run_forward_euler(ode, 1.6e-8, 2e-4);
  EXPECT_EQ(bad.status, SimulationStatus::kDiverged);
  const auto good = run_forward_euler(ode, 1.5e-8, 2e-4);
  EXPECT_EQ(good.status, SimulationStatus::kCompleted);
  EXPECT_EQ(good.steps, 13334);
}

// The paper's result: stable at 1.4e-5 to t = 1 s, unstable at 1.5e-5.
TEST(PaperBeam, AdjustedForwardEulerLimitModal) {
  auto ode = modal_beam_ode(paper_beams(), true);
  const auto good = run_forward_euler(*ode, 1.4e-5, 1.0);
  EXPECT_EQ(good.status, SimulationStatus::kCompleted);
  EXPECT_EQ(good.steps, 71429);
  const auto bad = run_forward_euler(*ode, 1.5e-5, 1.0);
  EXPECT_EQ(bad.status, SimulationStatus::kDiverged);
}

TEST(PaperBeam, AdjustedForwardEulerLimitNodalLowRank) {
  const BeamPart& p = paper_beams().beams.at(0);
  const int n = static_cast<int>(p.system.M.rows());
  auto adj = std::make_shared<const LowRankStructure>(
      adjusted_parts(p.system.name, {{0, n}}, p.system.M, p.system.K, p.system.P, p.basis, p.adjusted));
  EXPECT_LT(adj->rank(), 25);  // only the kept low modes
  NodalBeamOde ode(adj);
  EXPECT_EQ(run_forward_euler(ode, 1.4e-5, 1.0).status, SimulationStatus::kCompleted);
  EXPECT_EQ(run_forward_euler(ode, 1.5e-5, 1.0).status, SimulationStatus::kDiverged);
}

}  // namespace
}  // namespace mbfe::runtime
