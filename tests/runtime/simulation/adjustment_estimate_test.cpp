// The accuracy estimate of an adjusted run (runtime/simulation/adjustment_estimate.h)
// against the adjusted model's own static answer: a pinned beam without
// gravity under a single point load, whose static deflection at the load
// (what a beam run starts from, modal_static_state) the adjustment changes by
// exactly the estimated relative static change of the point compliance.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "frontend/parse_model.h"
#include "ir/model_error.h"
#include "runtime/damping/beam_model.h"
#include "runtime/simulation/adjustment_estimate.h"
#include "runtime/simulation/assembled_model.h"

namespace mbfe::runtime {
namespace {

// The modal static state and the estimate both sum 80 modes of a beam whose K
// has cond ~1e9; the estimate's point compliance comes from a sparse LDLT solve.
constexpr double kStaticRel = 1e-7;

std::string beam_text(const std::string& policy, const std::string& limit = "omega_limit: 2.0e4") {
  return "model: estimate_beam\n"
         "gravity: [0, 0]\n"
         "beams:\n"
         "  - name: deck\n"
         "    origin: [0.0, 0.0]\n"
         "    length: 1.0\n"
         "    elements: 40\n"
         "    section: {shape: square, side: 0.005}\n"
         "    material: {youngs_modulus: 2.1e11, density: 7860}\n"
         "    supports: [{at: 0.0, type: pinned}, {at: 1.0, type: pinned}]\n"
         "    damping: {rayleigh: {alpha: 3.0e-3, beta: 1.5e-4}}\n"
         "    loads: [{type: point, at: 0.3, value: -10.0}]\n"
         "    adjustment: {" + limit + ", margin: 0.1, zeta_min: 0.05, policy: " + policy + "}\n";
}

/// The deflection at s of the static state under the model's loads, original or adjusted.
double static_deflection(const AssembledModel& model, bool adjusted, double s) {
  const BeamModel& beams = model.beams();
  auto ode = modal_beam_ode(beams, adjusted);
  const Eigen::VectorXd y = modal_static_state(beams, adjusted, *ode);
  const BeamPart& b = beams.beams.at(0);
  const Eigen::VectorXd q = b.basis.phi * y.head(b.basis.omega.size());
  return deflection_at(b.system, q, s);
}

TEST(AdjustmentEstimate, TheCapsEstimateIsTheChangeOfTheStaticDeflectionUnderThePointLoad) {
  const AssembledModel model(frontend::parse_model_text(beam_text("cap"), "estimate_beam.yaml"), nullptr);
  ASSERT_GT(model.beams().beams.at(0).adjusted.adjusted, 0);
  const AdjustmentEstimate estimate = estimate_adjustment(model, {parse_probe("deck@0.7")});
  ASSERT_EQ(estimate.points.size(), 2u);
  const AdjustmentEstimatePoint& load = estimate.points[0];
  EXPECT_EQ(load.what, "point load");
  EXPECT_EQ(load.beam, "deck");
  EXPECT_DOUBLE_EQ(load.s, 0.3);
  const double w = static_deflection(model, false, 0.3), w_adj = static_deflection(model, true, 0.3);
  const double measured = std::abs(w_adj - w) / std::abs(w);
  EXPECT_NEAR(load.static_change, measured, kStaticRel);
  EXPECT_EQ(load.omega, 0.0);  // a constant load: quasi-static
  EXPECT_EQ(load.estimate, load.static_change);
  EXPECT_GT(load.static_change, 1e-4);  // the cap at 2e4 rad/s softens the point (4.2e-4)
  // The compliance itself: w = F c under F = -10 N.
  EXPECT_NEAR(load.compliance, w / -10.0, kStaticRel * std::abs(w / 10.0));
  EXPECT_EQ(estimate.points[1].what, "probe deck@0.7");
  EXPECT_GE(estimate.max, load.static_change);
  EXPECT_GE(estimate.max, estimate.points[1].static_change);
  EXPECT_TRUE(estimate.not_estimated.empty());
}

// A moving load's path is sampled at nodes and element middles: the cap
// softens a beam most inside its elements (the modes it changes carry the
// element-scale part of the compliance), so the largest change on the path
// lies at an element's middle. The oracle is the static compliance at a
// place by dense solves, e^T K^-1 e against e^T K_adj^-1 e with eq (27)'s
// K_adj = (M Phi) diag(k) (M Phi)^T (80 DOF, every mode), at the place
// reported and at every node.
TEST(AdjustmentEstimate, AMovingLoadsLargestChangeIsInsideAnElement) {
  const std::string point_load = "{type: point, at: 0.3, value: -10.0}";
  std::string moving = beam_text("cap");
  moving.replace(moving.find(point_load), point_load.size(), "{type: moving, value: -10.0, speed: 1.0}");
  const AssembledModel model(frontend::parse_model_text(moving, "moving.yaml"), nullptr);
  const AdjustmentEstimate estimate = estimate_adjustment(model, {});
  ASSERT_EQ(estimate.points.size(), 1u);
  const AdjustmentEstimatePoint& path = estimate.points[0];
  ASSERT_EQ(path.what, "moving load");
  constexpr double kElement = 1.0 / 40;  // m: the beam's element length
  EXPECT_NEAR(std::fmod(path.s / kElement, 1.0), 0.5, 1e-9) << "at s = " << path.s;

  const BeamPart& b = model.beams().beams.at(0);
  ASSERT_TRUE(b.basis.complete);
  const Eigen::MatrixXd M(b.system.M), K(b.system.K);
  const Eigen::MatrixXd U = M * b.basis.phi;
  Eigen::VectorXd k(U.cols());
  for (Eigen::Index j = 0; j < k.size(); ++j) k[j] = b.adjusted.modes[j].k;
  const Eigen::MatrixXd K_adj = U * k.asDiagonal() * U.transpose();
  const auto dense_change = [&](double s) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(M.rows());
    const BeamPointWeights w = point_weights(b.system, s);
    for (int a = 0; a < 4; ++a)
      if (w.free_index[a] >= 0) e[w.free_index[a]] += w.w[a];
    const double c = e.dot(K.ldlt().solve(e)), c_adj = e.dot(K_adj.ldlt().solve(e));
    return std::abs(c_adj - c) / c;
  };
  // Dense LDLT of an 80-DOF K with cond ~1e9 near a support, where the
  // compliance is smallest.
  constexpr double kDenseRel = 1e-5;
  EXPECT_NEAR(path.static_change, dense_change(path.s), kDenseRel * path.static_change);
  // Larger than at every node the supports do not hold (at a support the
  // relative change is round-off over round-off).
  for (int node = 1; node < 40; ++node)
    EXPECT_GT(path.static_change, dense_change(node * kElement)) << "node " << node;
}

TEST(AdjustmentEstimate, PolicyMassChangesNoStaticCompliance) {
  const AssembledModel model(frontend::parse_model_text(beam_text("mass"), "estimate_beam.yaml"), nullptr);
  const AdjustmentEstimate estimate = estimate_adjustment(model, {});
  ASSERT_EQ(estimate.points.size(), 1u);
  EXPECT_LT(estimate.max, kStaticRel);
  EXPECT_TRUE(adjustment_notice(estimate, model.ir()).empty());
}

TEST(AdjustmentEstimate, TheNoticeNamesThePlaceTheFigureAndTheRemedy) {
  AdjustmentEstimate estimate;
  AdjustmentEstimatePoint wheel;
  wheel.what = "contact 'wheel' (slider_spring)";
  wheel.beam = "deck";
  wheel.s = 12.5;
  wheel.moving = true;
  wheel.omega = 816.5;
  wheel.estimate = 0.042;
  estimate.points.push_back(wheel);
  estimate.largest = 0;
  estimate.max = 0.042;
  const AssembledModel model(frontend::parse_model_text(beam_text("cap"), "estimate_beam.yaml"), nullptr);
  EXPECT_EQ(adjustment_notice(estimate, model.ir()),
            "adjustment estimate: the adjusted modes of beam 'deck' change the compliance at contact "
            "'wheel' (slider_spring) (largest at s = 12.5 m, at 816 rad/s) by 4.2 % (policy cap, omega_limit 2e+04 rad/s); "
            "raise omega_limit or use policy: mass (docs/damping-adjustment.md, \"The accuracy estimate\")");
  estimate.max = estimate.points[0].estimate = kAdjustmentNoticeThreshold;
  EXPECT_TRUE(adjustment_notice(estimate, model.ir()).empty());  // above 1 % only
}

// omega_limit: auto against the adjusted model's static answer: at the chosen
// limit the deflection under the load changes by at most the tolerance, 2 %
// below it by more (the cap's static change grows as the limit falls).
TEST(AdjustmentEstimate, AutoChoosesTheLowestLimitWhoseStaticChangeMeetsTheTolerance) {
  constexpr double kTolerance = 1e-4;
  const AssembledModel model(
      frontend::parse_model_text(beam_text("cap", "omega_limit: auto, tolerance: 1.0e-4"), "auto.yaml"), nullptr);
  const ir::Adjustment& chosen = model.ir().beams.at(0).adjustment;
  EXPECT_TRUE(chosen.omega_limit_auto);
  const double limit = chosen.omega_limit;
  const auto change_at = [&](double omega_limit) {
    std::ostringstream text;
    text << std::setprecision(17) << "omega_limit: " << omega_limit;
    const AssembledModel given(frontend::parse_model_text(beam_text("cap", text.str()), "given.yaml"), nullptr);
    const double w = static_deflection(given, false, 0.3), w_adj = static_deflection(given, true, 0.3);
    return std::abs(w_adj - w) / std::abs(w);
  };
  EXPECT_LE(change_at(limit), kTolerance * (1.0 + kStaticRel));
  EXPECT_GT(change_at(0.98 * limit), kTolerance);
  const AdjustmentEstimate estimate = estimate_adjustment(model, {});
  ASSERT_EQ(estimate.limits.size(), 1u);
  EXPECT_TRUE(estimate.limits[0].chosen);
  EXPECT_EQ(estimate.limits[0].omega_limit, limit);
}

TEST(AdjustmentEstimate, ToleranceGoesWithAutoAndBelowOne) {
  try {
    frontend::parse_model_text(beam_text("cap", "omega_limit: 2.0e4, tolerance: 0.01"), "t.yaml");
    FAIL() << "a tolerance with a given omega_limit was accepted";
  } catch (const ir::ModelError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("t.yaml:13:", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("tolerance goes with omega_limit: auto"), std::string::npos) << e.what();
  }
  try {
    frontend::parse_model_text(beam_text("cap", "omega_limit: auto, tolerance: 1.5"), "t.yaml");
    FAIL() << "a tolerance of 1.5 was accepted";
  } catch (const ir::ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("must be < 1, a relative change (got 1.5)"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mbfe::runtime
