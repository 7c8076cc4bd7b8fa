// Links (droppers) between two tensioned wires, elastic supports, point
// masses and a pantograph head pressing from below (docs/catenary.md),
// on a two-span catenary small enough to check by independent paths:
//   - the form finding (a sparse static solve of the beams and links) against
//     the static start of the whole coupled model (Gauss-Newton on its
//     dynamics): the contact wire at every dropper where `hold` puts it;
//   - generalized-alpha (index 3, the links' rank-one terms in its Newton
//     matrix) against RK4 on the partitioned formulation (the links as forces
//     only), through a crossing in which droppers go slack.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "api/mbfe.h"
#include "tests/support/recorded_rows.h"
#include "tests/support/two_span_catenary.h"
#include "runtime/simulation/static_start.h"

namespace mbfe {
namespace {


using Rows = test::RecordedRows;

// Both wires adjusted, each on its own (a cap at 2000 rad/s).
std::string adjusted_wires(const std::string& policy = "cap") {
  return test::with_wire_adjustment("{omega_limit: 2000.0, margin: 0.1, policy: " + policy + "}");
}

runtime::SimulationReport run(const Model& m, const char* integrator, double h, double t_end, long every, Rows& rows) {
  runtime::SimulationRequest r;
  r.integrator = runtime::parse_integrator(integrator);
  r.step = h;
  r.t_end = t_end;
  r.every = every;
  return m.simulate(r, rows);
}

TEST(Catenary, FormFindingPutsTheContactWireAtEveryDropperHold) {
  // The profile is the catenary's own: the head starts 1 m before the wire,
  // off it, so that the static start sees the wires and droppers alone.
  std::string text = test::kTwoSpanCatenary;
  const std::string on_wire = "motion: \"1.0 + 20*t\"";
  ASSERT_NE(text.find(on_wire), std::string::npos);
  text.replace(text.find(on_wire), on_wire.size(), "motion: \"-1.0 + 20*t\"");
  const Model model = Model::parse(text, "two_span.yaml");
  Rows rows;
  const runtime::SimulationReport report = run(model, "rk4", 1e-5, 1e-5, 1, rows);
  ASSERT_TRUE(report.message.empty()) << report.message;
  // The contract: within 1 mm of the profile. Both paths solve the same
  // linear statics; they agree to the static start's Gauss-Newton tolerance.
  constexpr double kProfileTol = 1e-3;
  constexpr double kSamePathTol = 1e-9;
  // The static start's tension against the form finding's: the same solve,
  // its Newton stopped at a residual; the bound's reason was not recorded.
  constexpr double kTensionRel = 1e-6;
  const std::vector<double>& start = rows.values.front();
  for (const ir::Link& link : model.ir().links) {
    const int node = static_cast<int>(std::lround(link.a.at / 0.5));  // 0.5 m elements
    const double w = start[rows.column("contact_wire_w" + std::to_string(node))];
    EXPECT_NEAR(w, *link.hold, kProfileTol) << link.name;
    EXPECT_NEAR(w, *link.hold, kSamePathTol) << link.name;
  }
  // And every dropper pulls in that state (it holds the wire up).
  const runtime::LinkFormFinding& ff = model.assembled().links();
  for (std::size_t k = 0; k < ff.tension.size(); ++k) {
    EXPECT_GT(ff.tension[k], 0.0) << model.ir().links[k].name;
    EXPECT_NEAR(start[rows.column("tension_" + model.ir().links[k].name)], ff.tension[k], kTensionRel * ff.tension[k]);
  }
}

TEST(Catenary, ImplicitAndExplicitAgreeThroughACrossingWithSlackDroppers) {
  const Model model = Model::parse(test::kTwoSpanCatenary, "two_span.yaml");
  constexpr double kEnd = 0.9;  // s: the head runs from 1 m to 19 m
  // s: both runs write rows at the same times, sums of their steps (round-off).
  constexpr double kRowTimeTol = 1e-9;
  Rows alpha, rk4;
  const runtime::SimulationReport ra = run(model, "generalized_alpha", 2e-4, kEnd, 5, alpha);
  const runtime::SimulationReport rr = run(model, "rk4", 2e-5, kEnd, 50, rk4);
  ASSERT_TRUE(ra.message.empty()) << ra.message;
  ASSERT_TRUE(rr.message.empty()) << rr.message;
  ASSERT_EQ(alpha.values.size(), rk4.values.size());
  // Some dropper goes slack in both runs, and the explicit run shows a tension of exactly 0.
  int slack_alpha = 0, slack_rk4 = 0;
  for (const auto& l : ra.links) slack_alpha += l.slackenings;
  for (const auto& l : rr.links) slack_rk4 += l.slackenings;
  EXPECT_GT(slack_alpha, 0);
  EXPECT_GT(slack_rk4, 0);
  bool zero_seen = false;
  for (const ir::Link& link : model.ir().links)
    for (const auto& r : rk4.values) zero_seen = zero_seen || r[rk4.column("tension_" + link.name)] == 0.0;
  EXPECT_TRUE(zero_seen);
  // The contact force: generalized-alpha at 2e-4 s against RK4 at 2e-5 s
  // (well under 0.1 % of the peak when measured); 1 % of the peak fails a missing link
  // term or a wrong sign.
  const int f = rk4.column("force_strip_contact");
  double peak = 0.0, err = 0.0;
  for (std::size_t i = 0; i < rk4.values.size(); ++i) {
    ASSERT_NEAR(alpha.values[i][0], rk4.values[i][0], kRowTimeTol);
    peak = std::max(peak, std::abs(rk4.values[i][f]));
    err = std::max(err, std::abs(alpha.values[i][f] - rk4.values[i][f]));
  }
  EXPECT_GT(peak, 30.0);  // the head presses: a contact from below
  EXPECT_LT(err, 1e-2 * peak);
}

TEST(Catenary, SparseStaticStartAgreesWithTheDenseOne) {
  // Large models find their static start by Newton on the sparse tangent of
  // the implicit integrators; the dense Gauss-Newton with a difference
  // Jacobian is the independent path, affordable on this small model. The
  // head presses on the wire at t = 0: contact, links and springs all count.
  const Model model = Model::parse(test::kTwoSpanCatenary, "two_span.yaml");
  const runtime::AssembledModel& am = model.assembled();
  Eigen::VectorXd q_dense, qd_dense, q_sparse, qd_sparse;
  am.initial_coordinates(q_dense, qd_dense);
  am.initial_coordinates(q_sparse, qd_sparse);
  auto dense = am.make_dynamics(false);
  runtime::coupled_static_state(model.ir(), *dense, q_dense, qd_dense);
  ASSERT_TRUE(runtime::coupled_static_state_sparse(model.ir(), am.make_dynamics(false), q_sparse, qd_sparse));
  // Both stop at round-off of the coordinates (1e-12 relative to ~0.01 m);
  // the dense one's difference Jacobian leaves ~1e-11 m.
  constexpr double kSameStateTol = 1e-9;
  EXPECT_LT((q_dense - q_sparse).cwiseAbs().maxCoeff(), kSameStateTol);
  EXPECT_GT(std::abs(q_sparse[1]), 1e-4);  // the head moved: not a trivial state
}


TEST(Catenary, SparseStaticStartOfAdjustedWiresAgreesWithTheDenseOne) {
  // Adjusted wires: the sparse tangent has c* M and k* M, their kept modes'
  // low-rank part enters by Woodbury. The dense Gauss-Newton on the adjusted
  // dynamics is again the independent path.
  const Model model = Model::parse(adjusted_wires(), "two_span_adjusted.yaml");
  const runtime::AssembledModel& am = model.assembled();
  Eigen::VectorXd q_dense, qd_dense, q_sparse, qd_sparse, q_original, qd_original;
  am.initial_coordinates(q_dense, qd_dense);
  q_sparse = q_original = q_dense;
  auto dense = am.make_dynamics(true);
  runtime::coupled_static_state(model.ir(), *dense, q_dense, qd_dense);
  ASSERT_TRUE(runtime::coupled_static_state_sparse(model.ir(), am.make_dynamics(true), q_sparse, qd_sparse));
  ASSERT_TRUE(runtime::coupled_static_state_sparse(model.ir(), am.make_dynamics(false), q_original, qd_original));
  // The sparse Newton stops at its round-off floor (the low-rank stiffness
  // cancels k* M terms ~1e6 times the wire's): ~1e-11 m here, like the dense one.
  constexpr double kSameStateTol = 1e-9;
  EXPECT_LT((q_dense - q_sparse).cwiseAbs().maxCoeff(), kSameStateTol);
  // The capped modes are softer than the original ones: a different state,
  // so the adjusted operators were the ones solved.
  EXPECT_GT((q_sparse - q_original).cwiseAbs().maxCoeff(), 1e3 * kSameStateTol);
}

TEST(Catenary, StaticStartOfWiresUnderThePolicyMassIsTheOriginalOne) {
  // The policy mass keeps the wires' stiffness (K_adj = K): its static state
  // is the original model's, found by both Newton paths on the adjusted
  // dynamics (B = K, the kept modes' mass correction by Woodbury).
  const Model model = Model::parse(adjusted_wires("mass"), "two_span_mass.yaml");
  const runtime::AssembledModel& am = model.assembled();
  Eigen::VectorXd q_dense, qd_dense, q_sparse, qd_sparse, q_original, qd_original;
  am.initial_coordinates(q_dense, qd_dense);
  q_sparse = q_original = q_dense;
  runtime::coupled_static_state(model.ir(), *am.make_dynamics(true), q_dense, qd_dense);
  ASSERT_TRUE(runtime::coupled_static_state_sparse(model.ir(), am.make_dynamics(true), q_sparse, qd_sparse));
  ASSERT_TRUE(runtime::coupled_static_state_sparse(model.ir(), am.make_dynamics(false), q_original, qd_original));
  // As above: each Newton stops at ~1e-11 m.
  constexpr double kSameStateTol = 1e-9;
  EXPECT_LT((q_sparse - q_original).cwiseAbs().maxCoeff(), kSameStateTol);
  EXPECT_LT((q_dense - q_original).cwiseAbs().maxCoeff(), kSameStateTol);
  EXPECT_GT(q_original.tail(am.make_dynamics(false)->nc()).cwiseAbs().maxCoeff(), 1e-3)
      << "the wires sag: not a trivial state";
}

TEST(Catenary, ImplicitIntegratorsRefuseAdjustedWires) {
  const Model model = Model::parse(adjusted_wires(), "two_span_adjusted.yaml");
  runtime::SimulationRequest r;
  r.integrator = runtime::parse_integrator("generalized_alpha");
  r.step = 1e-3;
  r.t_end = 0.01;
  r.adjust = true;
  Rows rows;
  try {
    model.simulate(r, rows);
    FAIL() << "generalized_alpha ran the adjusted wires";
  } catch (const runtime::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("(adjust off)"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mbfe
