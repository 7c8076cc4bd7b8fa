// The per-beam adjustment of a beam beyond the dense modal analysis: its
// low-rank operators from every mode the cap keeps, found by spectrum slicing
// (docs/beams-and-modal.md, "Every mode below a bound"). The two-span
// catenary's wires are loaded twice, once within the dense limit (every mode,
// dense) and once with the limit below their size (sliced); the adjusted
// model must be the same, with the policy cap and with the policy mass
// (which changes the same modes).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <string>

#include "api/mbfe.h"
#include "runtime/simulation/assembled_model.h"
#include "tests/support/two_span_catenary.h"

namespace mbfe {
namespace {

// A cap that keeps about half of each wire's modes.
std::string adjustment_block(const std::string& policy) {
  return "{omega_limit: 800.0, margin: 0.1, policy: " + policy + "}";
}
constexpr int kBelowTheWires = 40;  // DOF; each wire has about 80

// 10 modes a Lanczos run: several runs per wire, as in a large one.
constexpr int kSmallRuns = 10;

class LargeBeamAdjustment : public testing::TestWithParam<std::string> {};

Model load(int dense_limit, const std::string& cap) {
  LoadOptions options;
  options.beams.dense_limit = dense_limit;
  options.beams.slice_modes = kSmallRuns;
  return Model::parse(test::with_wire_adjustment(cap), "large_beam.yaml", options);
}

TEST_P(LargeBeamAdjustment, SlicedWiresKeepTheDenseKeptModes) {
  const Model dense = load(runtime::BeamAnalysisOptions{}.dense_limit, adjustment_block(GetParam()));
  const Model sliced = load(kBelowTheWires, adjustment_block(GetParam()));
  ASSERT_EQ(dense.assembled().beams().beams.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const runtime::BeamPart& d = dense.assembled().beams().beams[k];
    const runtime::BeamPart& s = sliced.assembled().beams().beams[k];
    ASSERT_GT(s.system.M.rows(), kBelowTheWires);
    EXPECT_TRUE(d.basis.complete);
    EXPECT_FALSE(s.dense);
    EXPECT_FALSE(s.basis.complete);
    const int kept = static_cast<int>(d.adjusted.modes.size()) - d.adjusted.adjusted;
    ASSERT_GT(kept, 10) << "the cap should keep some modes";
    ASSERT_LT(kept + 1, d.system.M.rows()) << "and adjust some";
    // Every kept mode and the first adjusted one.
    ASSERT_EQ(s.basis.omega.size(), kept + 1);
    EXPECT_EQ(s.adjusted.change.back(), runtime::ModeChange::kAdjusted);
    EXPECT_EQ(s.adjusted.adjusted, 1);
  }
}

TEST_P(LargeBeamAdjustment, SlicedWiresGiveTheDenseAccelerations) {
  const Model dense = load(runtime::BeamAnalysisOptions{}.dense_limit, adjustment_block(GetParam()));
  const Model sliced = load(kBelowTheWires, adjustment_block(GetParam()));
  auto dyn_dense = dense.assembled().make_dynamics(true);
  auto dyn_sliced = sliced.assembled().make_dynamics(true);
  Eigen::VectorXd q, qd;
  dense.assembled().initial_coordinates(q, qd);
  std::mt19937 rng(20261123);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = dyn_dense->nb(); i < q.size(); ++i) {
    q[i] = 1e-3 * u(rng);
    qd[i] = 1e-2 * u(rng);
  }
  Eigen::VectorXd a_dense, a_sliced, l_dense, l_sliced;
  dyn_dense->evaluate(0.0, q, qd);
  dyn_dense->solve_augmented(0.0, a_dense, l_dense);
  dyn_sliced->evaluate(0.0, q, qd);
  dyn_sliced->solve_augmented(0.0, a_sliced, l_sliced);
  // The same operators from two eigen-solvers, whose kept modes agree to the
  // sliced runs' Ritz tolerance (1e-10) over the spectrum's relative gaps:
  // 5e-16 of the largest acceleration measured, 1e-9 leaves room.
  constexpr double kSameOperatorTol = 1e-9;
  const double scale = a_dense.cwiseAbs().maxCoeff();
  EXPECT_LT((a_sliced - a_dense).cwiseAbs().maxCoeff(), kSameOperatorTol * scale);
  // The original operators differ: the check tells them apart.
  Eigen::VectorXd a_original, l_original;
  auto dyn_original = dense.assembled().make_dynamics(false);
  dyn_original->evaluate(0.0, q, qd);
  dyn_original->solve_augmented(0.0, a_original, l_original);
  EXPECT_GT((a_original - a_dense).cwiseAbs().maxCoeff(), 1e-3 * scale);
}

TEST_P(LargeBeamAdjustment, ACapAboveNearlyEveryModeLeavesTheOriginalModelRunning) {
  // Slicing is for the modes below a cap that keeps some; a cap above nearly
  // every mode is refused at its block when the adjusted model is asked for.
  const Model model = load(kBelowTheWires, "{omega_limit: 1.0e6, margin: 0.1, policy: " + GetParam() + "}");
  EXPECT_FALSE(model.assembled().beams().beams[0].kept_modes_unavailable.empty());
  EXPECT_NO_THROW(model.assembled().make_dynamics(false));
  try {
    model.assembled().resolve_adjusted(true);
    FAIL() << "the adjusted model was accepted";
  } catch (const runtime::InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("large_beam.yaml:"), std::string::npos) << what;
    EXPECT_NE(what.find("could not be found"), std::string::npos) << what;
    EXPECT_NE(what.find("(adjust off)"), std::string::npos) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(Policies, LargeBeamAdjustment, testing::Values("cap", "mass"),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace mbfe
