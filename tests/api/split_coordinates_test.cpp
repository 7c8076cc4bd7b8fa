// Low-rank adjusted beams in split coordinates (SplitBeamSystem;
// docs/damping-adjustment.md, "Split coordinates"): the same ODE as the
// nodal low-rank form the partitioned formulation integrates, so RK4 on both
// must give the same motion to round-off. The model is the two-span catenary
// with both wires adjusted, slack droppers, a unilateral contact driven along
// and a moving load on the messenger: every kind of force the split form
// reads or applies at a few DOFs. Each test runs with the policy cap
// (B = M) and the policy mass (B = K), whose split coordinates differ in
// their base solve and modal values; the state's layout under policy
// truncate has a test of its own.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <string>

#include "api/mbfe.h"
#include "runtime/integrators/integrator.h"
#include "runtime/integrators/integrator_spec.h"
#include "runtime/coupled/coordinate_partitioning.h"
#include "runtime/coupled/split_beam_system.h"
#include "tests/support/recorded_rows.h"
#include "tests/support/perturbed_state.h"
#include "tests/support/two_span_catenary.h"

namespace mbfe {
namespace {

// One DOF made nodal alone (a dot product over the kept modes) against the
// whole matrix-vector product: the same sum in another order, a few ulps of
// its largest term.
constexpr double kSummationOrderTol = 1e-13;

// Keeps about half of each wire's modes (about 80 DOF each).
std::string adjustment_block(const std::string& policy) {
  return "{omega_limit: 800.0, margin: 0.1, policy: " + policy + "}";
}

class SplitCoordinates : public testing::TestWithParam<std::string> {};

Model load(const std::string& policy) {
  std::string text = test::with_wire_adjustment(adjustment_block(policy));
  // A force running along the messenger: a load that changes with time.
  text = test::with_messenger_moving_load(text);
  return Model::parse(text, "split_coordinates.yaml");
}

// The seed of this file's perturbed states.
constexpr unsigned kStateSeed = 20261123;

void perturbed_state(const Model& model, int nb, Eigen::VectorXd& q, Eigen::VectorXd& qd) {
  test::perturbed_state(model, nb, kStateSeed, q, qd);
}

TEST_P(SplitCoordinates, RoundTripToNodalCoordinates) {
  const Model model = load(GetParam());
  auto dyn = model.assembled().make_dynamics(true);
  runtime::SplitBeamSystem split(dyn);
  ASSERT_EQ(dyn->split_structures().size(), 2u);
  Eigen::VectorXd q0, qd0, q, qd;
  perturbed_state(model, dyn->nb(), q0, qd0);
  dyn->impose_motion(0.0, q0, qd0);
  const Eigen::VectorXd y = split.initial_state(0.0, q0, qd0);
  split.full_state(0.0, y, q, qd);
  // q = s + Phi_L (eta - zeta) with eta = zeta: s itself, exactly.
  EXPECT_EQ((q - q0).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((qd - qd0).cwiseAbs().maxCoeff(), 0.0);
  // The listed DOFs of full_state_at are those of full_state, after motion.
  Eigen::VectorXd y1 = y;
  y1.segment(dyn->n(), dyn->num_split_coordinates()).setRandom();
  split.full_state(0.0, y1, q, qd);
  ASSERT_GT((q - q0).cwiseAbs().maxCoeff(), 0.0) << "eta - zeta moves the nodal coordinates";
  const std::vector<int> dofs = {3, 17, dyn->nc() - 5};
  Eigen::VectorXd qa, qda;
  split.full_state_at(0.0, y1, dofs, qa, qda);
  const double scale = q.cwiseAbs().maxCoeff(), rate_scale = qd.cwiseAbs().maxCoeff();
  for (int c : dofs) {
    EXPECT_NEAR(qa[dyn->nb() + c], q[dyn->nb() + c], kSummationOrderTol * scale) << "DOF " << c;
    EXPECT_NEAR(qda[dyn->nb() + c], qd[dyn->nb() + c], kSummationOrderTol * rate_scale) << "DOF " << c;
  }
  EXPECT_EQ(qa.head(dyn->nb()), q.head(dyn->nb()));
}

TEST_P(SplitCoordinates, AReportDescribesTheStateItWasAskedFor) {
  // report() keeps its last answer for a second call at the same state; the
  // springs and links it leaves in the dynamics must still be that state's.
  const Model model = load(GetParam());
  auto dyn = model.assembled().make_dynamics(true);
  runtime::SplitBeamSystem split(dyn);
  Eigen::VectorXd q0, qd0;
  perturbed_state(model, dyn->nb(), q0, qd0);
  dyn->impose_motion(0.0, q0, qd0);
  const Eigen::VectorXd y1 = split.initial_state(0.0, q0, qd0);
  Eigen::VectorXd y2 = y1, ydot;
  y2.head(dyn->n()).tail(dyn->nc()) *= 0.5;  // the wires elsewhere: other link tensions
  split.report(0.0, y1);
  const double tension = dyn->link_state(0).tension;
  split.rhs(0.0, y2, ydot);
  ASSERT_NE(dyn->link_state(0).tension, tension);
  split.report(0.0, y1);
  EXPECT_EQ(dyn->link_state(0).tension, tension);
  split.report(0.0, y1);
  EXPECT_EQ(dyn->link_state(0).tension, tension);
}

TEST_P(SplitCoordinates, RungeKuttaFollowsTheNodalLowRankForm) {
  const Model model = load(GetParam());
  auto dyn_nodal = model.assembled().make_dynamics(true);
  auto dyn_split = model.assembled().make_dynamics(true);
  runtime::PartitionedSystem nodal(dyn_nodal);
  runtime::SplitBeamSystem split(dyn_split);
  Eigen::VectorXd q0, qd0;
  perturbed_state(model, dyn_nodal->nb(), q0, qd0);
  dyn_nodal->impose_motion(0.0, q0, qd0);
  Eigen::VectorXd yn = nodal.initial_state(0.0, q0, qd0);
  Eigen::VectorXd ys = split.initial_state(0.0, q0, qd0);
  const runtime::IntegratorSpec rk4 = runtime::parse_integrator("rk4");
  auto step_nodal = runtime::make_stepper(rk4, nodal);
  auto step_split = runtime::make_stepper(rk4, split);
  step_nodal->reset(0.0, yn);
  step_split->reset(0.0, ys);
  // Within the adjusted RK4 limit of the two-span wires at this cap.
  constexpr double kStep = 5e-4;
  constexpr int kSteps = 400;  // 0.2 s: the head crosses 3 m, the load 3 m
  // The two forms sum in another order (a few rows of Phi_L against passes
  // over U and Phi_L) and the contact and droppers switch on those sums:
  // 4e-12 relative measured over the run; 1e-9 leaves room and still fails
  // for any wrong term (dropping Phi_L^T f gives 2).
  constexpr double kSameMotionTol = 1e-9;
  Eigen::VectorXd qn, qdn, qs, qds;
  double worst = 0.0, worst_rate = 0.0, max_force = 0.0;
  int slack_seen = 0;
  for (int k = 0; k < kSteps; ++k) {
    const double t = k * kStep;
    step_nodal->step(t, kStep, yn);
    step_split->step(t, kStep, ys);
    nodal.full_state(t + kStep, yn, qn, qdn);
    split.full_state(t + kStep, ys, qs, qds);
    const double scale = qn.tail(dyn_nodal->nc()).cwiseAbs().maxCoeff();
    const double rate_scale = qdn.tail(dyn_nodal->nc()).cwiseAbs().maxCoeff();
    worst = std::max(worst, (qs - qn).cwiseAbs().maxCoeff() / scale);
    worst_rate = std::max(worst_rate, (qds - qdn).cwiseAbs().maxCoeff() / rate_scale);
    nodal.report(t + kStep, yn);
    split.report(t + kStep, ys);
    for (int l = 0; l < static_cast<int>(dyn_nodal->model().links().size()); ++l) {
      // A tension is the stiffness times a difference of displacements.
      EXPECT_NEAR(dyn_split->link_state(l).tension, dyn_nodal->link_state(l).tension,
                  kSameMotionTol * dyn_nodal->model().links()[l]->stiffness() * scale)
          << "link " << l << " at step " << k;
      slack_seen += dyn_nodal->link_state(l).slack ? 1 : 0;
    }
    max_force = std::max(max_force, dyn_nodal->spring_state(0).force);
  }
  EXPECT_LT(worst, kSameMotionTol);
  EXPECT_LT(worst_rate, kSameMotionTol);
  // The run exercises what the split form must get right.
  EXPECT_GT(slack_seen, 0) << "no dropper went slack";
  EXPECT_GT(max_force, 0.0) << "the contact never pressed";
  std::printf("[ split    ] policy %s: largest relative difference over %d rk4 steps: q %.3g, q' %.3g\n",
              GetParam().c_str(), kSteps, worst, worst_rate);
}

TEST_P(SplitCoordinates, SimulateTakesThemAndLeavesRowsWithoutCoordinates) {
  const Model model = load(GetParam());
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("rk4");
  request.step = 5e-4;
  request.t_end = 0.01;
  request.static_start = false;
  request.probes = {runtime::parse_probe("contact_wire@5")};
  struct Rows : test::RecordedRows {
    void row(const runtime::OutputRow& row) override {
      RecordedRows::row(row);
      coordinates = row.q.size();
    }
    Eigen::Index coordinates = -1;
  } rows;
  const runtime::SimulationReport report = model.simulate(request, rows);
  EXPECT_NE(report.variant.find("split coordinates"), std::string::npos) << report.variant;
  EXPECT_EQ(rows.coordinates, 0) << "a row with probes holds no coordinates unless asked";
  request.state_in_rows = true;
  Rows full;
  model.simulate(request, full);
  EXPECT_EQ(full.coordinates, model.assembled().make_dynamics(true)->n());
  // The same probe column either way.
  const std::vector<double> a = full.series("contact_wire@5"), b = rows.series("contact_wire@5");
  ASSERT_EQ(a.size(), b.size());
  const double scale = *std::max_element(a.begin(), a.end());
  ASSERT_GT(scale, 0.0);
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_NEAR(a[k], b[k], kSummationOrderTol * scale) << "row " << k;
  // The augmented formulation integrates the nodal low-rank form.
  request.formulation = runtime::CoupledFormulation::kAugmented;
  Rows augmented;
  const runtime::SimulationReport nodal = model.simulate(request, augmented);
  EXPECT_EQ(nodal.variant.find("split coordinates"), std::string::npos) << nodal.variant;
}

// Policy truncate: a truncated wire's uniform part and its zeta are 0 at all
// times, and the state leaves them out. Its size, names and round trip to
// nodal coordinates against the wire's kept modes computed here.
TEST(SplitCoordinatesTruncated, TheStateLeavesTheZerosOut) {
  const Model model = load("truncate");
  auto dyn = model.assembled().make_dynamics(true);
  runtime::SplitBeamSystem split(dyn);
  ASSERT_EQ(dyn->split_structures().size(), 2u);
  const int n = dyn->n(), nb = dyn->nb(), ne = dyn->num_split_coordinates();
  int left_out = 0, kept_modes = 0;
  for (int k : dyn->split_structures()) {
    const auto& st = *dyn->model().structures()[static_cast<std::size_t>(k)];
    ASSERT_TRUE(st.truncated());
    left_out += st.ranges().front().size + st.rank();
    kept_modes += st.rank();
  }
  ASSERT_GT(kept_modes, 0);
  EXPECT_EQ(split.size(), 2 * (n + ne - left_out));
  // Names: the rigid coordinates, each kept mode's eta, their rates; no zeta.
  int etas = 0;
  for (int i = 0; i < split.size(); ++i) {
    const std::string name = split.name(i);
    EXPECT_EQ(name.find("_zeta"), std::string::npos) << name;
    if (name.find("_eta") != std::string::npos) ++etas;
  }
  EXPECT_EQ(etas, 2 * kept_modes);
  EXPECT_EQ(split.name(0), dyn->model().coordinate_names()[0]);
  // The round trip projects each wire on its kept modes, q = Phi (Phi^T M q0).
  Eigen::VectorXd q0, qd0, q, qd;
  perturbed_state(model, nb, q0, qd0);
  dyn->impose_motion(0.0, q0, qd0);
  const Eigen::VectorXd y = split.initial_state(0.0, q0, qd0);
  ASSERT_EQ(y.size(), split.size());
  split.full_state(0.0, y, q, qd);
  EXPECT_EQ(q.head(nb), q0.head(nb));
  EXPECT_EQ(qd.head(nb), qd0.head(nb));
  for (int k : dyn->split_structures()) {
    const auto& st = *dyn->model().structures()[static_cast<std::size_t>(k)];
    const auto& r = st.ranges().front();
    const Eigen::VectorXd q_wire = q0.segment(nb + r.offset, r.size), qd_wire = qd0.segment(nb + r.offset, r.size);
    const Eigen::VectorXd want = st.phi() * (st.phi().transpose() * (st.M() * q_wire));
    const Eigen::VectorXd want_rate = st.phi() * (st.phi().transpose() * (st.M() * qd_wire));
    EXPECT_LE((q.segment(nb + r.offset, r.size) - want).cwiseAbs().maxCoeff(),
              kSummationOrderTol * want.cwiseAbs().maxCoeff())
        << st.name();
    EXPECT_LE((qd.segment(nb + r.offset, r.size) - want_rate).cwiseAbs().maxCoeff(),
              kSummationOrderTol * want_rate.cwiseAbs().maxCoeff())
        << st.name();
  }
  // The right-hand side is of the packed state: its first half is y's rates.
  Eigen::VectorXd ydot;
  split.rhs(0.0, y, ydot);
  ASSERT_EQ(ydot.size(), y.size());
  EXPECT_EQ(ydot.head(y.size() / 2), y.tail(y.size() / 2));
}

INSTANTIATE_TEST_SUITE_P(Policies, SplitCoordinates, testing::Values("cap", "mass"),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace mbfe
