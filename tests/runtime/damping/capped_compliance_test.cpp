// The static half of the slope-error argument of
// docs/accuracy-vs-cost-coupled.md: the cap lowers a capped mode's modal
// stiffness from omega_j^2 to omega_l^2, so a point force (a contact) meets a
// structure that is too soft in its high modes, which shows in the slopes
// near the force more than in the displacements. Raising the capped modes'
// modal mass instead (the remedy proposed there) leaves every modal stiffness
// and so the static compliance exact.
//
// The paper beam (50 elements, every mode), a 10 N force at a quarter span
// (node 12): static responses by modal sums against K^-1 f (sparse LDLT).
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <memory>
#include <string>
#include <utility>

#include "frontend/parse_model.h"
#include "runtime/damping/beam_model.h"
#include "runtime/damping/modal_adjustment.h"

namespace mbfe::runtime {
namespace {

// K of the 50-element beam has cond ~1e10: its LDLT solve is good to ~1e-8
// relative (see adjustment_accuracy_test.cpp); the modal sums are exact.
constexpr double kStaticSolveRel = 1e-7;

struct Errors {
  double w = 0.0, slope = 0.0;  // max |error| / max |exact| over the w and w' DOFs
};

Errors relative_errors(const BeamSystem& sys, const Eigen::VectorXd& u, const Eigen::VectorXd& exact) {
  double ew = 0, es = 0, pw = 0, ps = 0;
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    const bool slope = sys.free_dof[k] % 2 == 1;
    (slope ? es : ew) = std::max(slope ? es : ew, std::abs(u[k] - exact[k]));
    (slope ? ps : pw) = std::max(slope ? ps : pw, std::abs(exact[k]));
  }
  return {ew / pw, es / ps};
}

TEST(CappedCompliance, TheCapSoftensTheSlopesNearAForceAndMassScalingDoesNot) {
  const ir::Model file = frontend::load_model_file(std::string(MBFE_SOURCE_DIR) + "/models/paper_beam.yaml");
  const BeamModel beams = analyse_beams(file);
  const BeamPart& b = beams.beams.at(0);
  ASSERT_TRUE(b.basis.complete);
  ir::Adjustment a = file.beams.at(0).adjustment;
  a.zeta_min = 0.0;  // stiffness is what matters here; the floor changes damping only
  const AdjustedModes capped = adjust_modes(b.original, a);
  ASSERT_GT(capped.adjusted, 0);

  Eigen::VectorXd f = Eigen::VectorXd::Zero(b.system.M.rows());
  const int w12 = b.system.full_to_free[2 * 12];
  ASSERT_GE(w12, 0);
  f[w12] = -10.0;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> kf(b.system.K);
  const Eigen::VectorXd exact = kf.solve(f);
  const Eigen::VectorXd modal_force = b.basis.phi.transpose() * f;
  Eigen::VectorXd cap_coords(modal_force.size()), mass_scaled_coords(modal_force.size());
  for (Eigen::Index j = 0; j < modal_force.size(); ++j) {
    cap_coords[j] = modal_force[j] / capped.modes[j].k;
    // Mass scaling: m_j = omega_j^2 / omega_l^2 on the capped modes, k_j kept.
    mass_scaled_coords[j] = modal_force[j] / (b.basis.omega[j] * b.basis.omega[j]);
  }
  const Errors cap = relative_errors(b.system, b.basis.phi * cap_coords, exact);
  const Errors mass_scaled = relative_errors(b.system, b.basis.phi * mass_scaled_coords, exact);
  // Measured: w 1.76e-5, slope 1.4e-3 of their peaks, the same pattern as the
  // coupled platform's dynamic errors (1.9e-5 and 1.9e-3): the cap's error is
  // this static one. Bounds at half and twice the measured values.
  EXPECT_GT(cap.slope, 0.7e-3);
  EXPECT_LT(cap.slope, 2.8e-3);
  EXPECT_GT(cap.slope, 40.0 * cap.w);
  EXPECT_LT(mass_scaled.w, kStaticSolveRel);
  EXPECT_LT(mass_scaled.slope, kStaticSolveRel);
}

// What a beam-only run starts from and settles on (runtime/simulation/beam_run.cpp:
// modal_beam_ode and modal_static_state), under the paper beam's own loads
// (its weight and 10 N at midspan), against K^-1 P of the original model.
TEST(CappedCompliance, ABeamRunUnderPolicyMassSettlesOnTheOriginalStaticDeflection) {
  ir::Model file = frontend::load_model_file(std::string(MBFE_SOURCE_DIR) + "/models/paper_beam.yaml");
  ir::Adjustment& a = file.beams.at(0).adjustment;
  a.zeta_min = 0.0;
  const auto static_deflection = [&](ir::AdjustmentPolicy policy) {
    a.policy = policy;
    const BeamModel beams = analyse_beams(file);
    const std::unique_ptr<ModalBeamOde> ode = modal_beam_ode(beams, true);
    const Eigen::VectorXd y = modal_static_state(beams, true, *ode);
    Eigen::VectorXd q;
    ode->positions(y, q);
    return std::make_pair(q, beams);
  };
  const auto [q_mass, beams] = static_deflection(ir::AdjustmentPolicy::kMass);
  const auto [q_cap, unused] = static_deflection(ir::AdjustmentPolicy::kCap);
  const BeamPart& b = beams.beams.at(0);
  ASSERT_GT(b.adjusted.adjusted, 0);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> kf(b.system.K);
  const Eigen::VectorXd exact = kf.solve(b.system.P);
  const Errors mass = relative_errors(b.system, q_mass, exact);
  const Errors cap = relative_errors(b.system, q_cap, exact);
  EXPECT_LT(mass.w, kStaticSolveRel);
  EXPECT_LT(mass.slope, kStaticSolveRel);
  // The cap's, measured: w 1.0e-5, slope 1.1e-3 (the midspan force loads the
  // capped modes as the quarter-span one above does; policy mass: 3.4e-9 and
  // 3.7e-9, the solve's round-off). Bounds at half the cap's.
  EXPECT_GT(cap.w, 0.5e-5);
  EXPECT_GT(cap.slope, 0.5e-3);
}

}  // namespace
}  // namespace mbfe::runtime
