// The accuracy estimate of an adjusted run (runtime/simulation/adjustment_estimate.h)
// against the adjusted model's own static answer: a pinned beam without
// gravity under a single point load, whose static deflection at the load
// (what a beam run starts from, modal_static_state) the adjustment changes by
// exactly the estimated relative static change of the point compliance.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "frontend/parse_model.h"
#include "runtime/damping/beam_model.h"
#include "runtime/simulation/adjustment_estimate.h"
#include "runtime/simulation/assembled_model.h"

namespace mbfe::runtime {
namespace {

// The modal static state and the estimate both sum 80 modes of a beam whose K
// has cond ~1e9; the estimate's point compliance comes from a sparse LDLT solve.
constexpr double kStaticRel = 1e-7;

std::string beam_text(const std::string& policy) {
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
         "    adjustment: {omega_limit: 2.0e4, margin: 0.1, zeta_min: 0.05, policy: " +
         policy + "}\n";
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

}  // namespace
}  // namespace mbfe::runtime
