// The shipped pantograph-catenary model in its two-span version (what CI
// runs of docs/validation-en50318.md), over the first half second of the run:
//  - the original model: generalized-alpha against RK4 on the partitioned
//    formulation (the explicit path, an independent formulation of the
//    links, contact and supports);
//  - the adjusted model with RK4 at 1e-3 s, 3.7 times the original model's
//    RK4 limit (the model's default run): its contact-force statistics against
//    those of generalized-alpha on the original model, within the 2 % the
//    validation asks of it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "api/mbfe.h"
#include "runtime/signal/force_statistics.h"
#include "tests/support/recorded_rows.h"

namespace mbfe {
namespace {

using test::RecordedRows;

constexpr double kEnd = 0.5;  // s: the head runs from 2 m to 43.7 m, past four droppers' spans

runtime::SimulationReport run(const Model& m, const char* integrator, double h, long every,
                              std::optional<bool> adjust, RecordedRows& rows) {
  runtime::SimulationRequest r;
  r.integrator = runtime::parse_integrator(integrator);
  r.step = h;
  r.t_end = kEnd;
  r.every = every;
  r.adjust = adjust;
  return m.simulate(r, rows);
}

const Model& two_span_model() {
  static const Model model = Model::load(std::string(MBFE_SOURCE_DIR) + "/models/pantograph_catenary_2span.yaml");
  return model;
}

TEST(PantographCatenary, TwoSpanModelImplicitMatchesExplicit) {
  const Model& model = two_span_model();
  RecordedRows alpha, rk4;
  const runtime::SimulationReport ra = run(model, "generalized_alpha", 2e-4, 5, false, alpha);
  const runtime::SimulationReport rr = run(model, "rk4", 1e-4, 10, false, rk4);
  ASSERT_TRUE(ra.message.empty()) << ra.message;
  ASSERT_TRUE(rr.message.empty()) << rr.message;
  ASSERT_EQ(alpha.values.size(), rk4.values.size());
  const std::vector<double> fa = alpha.series("force_strip"), fr = rk4.series("force_strip");
  double peak = 0.0, err = 0.0, sum = 0.0;
  for (std::size_t i = 0; i < fr.size(); ++i) {
    peak = std::max(peak, std::abs(fr[i]));
    err = std::max(err, std::abs(fa[i] - fr[i]));
    sum += fr[i];
  }
  // Measured 0.6 N of a 286 N peak over 0.8 s; 1 % of the peak.
  EXPECT_LT(err, 1e-2 * peak);
  // The head stays on the wire, and the force averages near the static 115 N
  // (a conservative catenary: the mean contact force is the static force,
  // within what half a second of a span's waves leaves).
  EXPECT_EQ(rr.springs.at(0).lift_offs, 0);
  const double mean = sum / static_cast<double>(fr.size());
  EXPECT_GT(mean, 80.0);
  EXPECT_LT(mean, 150.0);
}

runtime::ForceStatistics contact_force_statistics(const RecordedRows& rows) {
  runtime::ForceStatisticsOptions o;
  o.lowpass_hz = 20.0;  // EN 50318's band
  o.from = 0.1;         // s: past the first tenth of a second of the filter's reach
  return runtime::force_statistics(rows.series("t"), rows.series("force_strip"), o);
}

TEST(PantographCatenary, TwoSpanAdjustedExplicitMatchesOriginalImplicit) {
  const Model& model = two_span_model();
  RecordedRows adjusted, original;
  // The model's own run: RK4 on the adjusted wires at 1e-3 s (its stable
  // limit 1.36e-3 s; the original model's is 2.7e-4 s, docs/catenary.md).
  const runtime::SimulationReport ra = run(model, "rk4", 1e-3, 1, std::nullopt, adjusted);
  const runtime::SimulationReport ro = run(model, "generalized_alpha", 2e-4, 5, false, original);
  ASSERT_TRUE(ra.message.empty()) << ra.message;
  ASSERT_TRUE(ro.message.empty()) << ro.message;
  ASSERT_NE(ra.variant.find("adjusted"), std::string::npos) << ra.variant;
  const runtime::ForceStatistics a = contact_force_statistics(adjusted);
  const runtime::ForceStatistics o = contact_force_statistics(original);
  // The validation's 2 %, of the mean force for the statistics that can come
  // near zero (the statistical minimum), of the quantity itself otherwise.
  // Measured over this window: 0.04 % (statistical max) to 0.8 % (min); at
  // 1.35e-3 s, just under the adjusted model's RK4 limit, the mean is 2.3 %
  // off and the minimum 3.6 %.
  constexpr double kRelative = 0.02;
  EXPECT_NEAR(a.mean, o.mean, kRelative * o.mean);
  EXPECT_NEAR(a.std, o.std, kRelative * o.std);
  EXPECT_NEAR(a.max, o.max, kRelative * o.max);
  EXPECT_NEAR(a.min, o.min, kRelative * o.min);
  EXPECT_NEAR(a.statistical_max, o.statistical_max, kRelative * o.statistical_max);
  EXPECT_NEAR(a.statistical_min, o.statistical_min, kRelative * o.mean);
  EXPECT_EQ(a.loss_percent, 0.0);
  EXPECT_EQ(o.loss_percent, 0.0);
}

}  // namespace
}  // namespace mbfe
