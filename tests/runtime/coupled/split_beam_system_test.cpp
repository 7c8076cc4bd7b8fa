// A coupled model in split coordinates (runtime/coupled/split_beam_system.h;
// docs/damping-adjustment.md, "Split coordinates"), checked against the nodal
// low-rank form at one state: its right-hand side mapped back to nodal
// coordinates, q_c'' = s'' + Phi_L (eta'' - zeta''), is the nodal form's
// acceleration; and the invariant zeta = Phi_L^T M s that makes the split
// form the same ODE is kept by an RK4 step. The model is the two-span
// catenary of tests/support with both wires adjusted by a cap (a low-rank
// form keeping about half of each wire's 80 modes), slack droppers and a
// contact: the smallest model at hand that has every force the split form
// reads.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <string>

#include "api/mbfe.h"
#include "runtime/coupled/coupled_dynamics.h"
#include "runtime/coupled/partition_choice.h"
#include "runtime/coupled/split_beam_system.h"
#include "runtime/integrators/integrator.h"
#include "runtime/integrators/integrator_spec.h"
#include "runtime/simulation/assembled_model.h"
#include "runtime/structure/low_rank_structure.h"
#include "tests/support/perturbed_state.h"
#include "tests/support/two_span_catenary.h"

namespace mbfe::runtime {
namespace {

// The two forms sum the same terms in another order (a base solve and a
// few rows of Phi_L against passes over U and Phi_L): 1e-9 of the largest
// acceleration, the bound tests/api/split_coordinates_test.cpp holds whole
// runs to, and it fails for a wrong term (the kept modes' stiffness
// change dropped).

constexpr double kSummationOrderTol = 1e-9;
// zeta - Phi_L^T M s after one step: a linear invariant, kept to round-off
// of the sums that form zeta and s (relative to the largest |zeta|).
constexpr double kInvariantTol = 1e-11;

Model load_catenary() {
  // The model text of tests/api/split_coordinates_test.cpp (policy cap), so
  // that the two tests share one compiled solver.
  std::string text = test::with_wire_adjustment("{omega_limit: 800.0, margin: 0.1, policy: cap}");
  text = test::with_messenger_moving_load(text);
  return Model::parse(text, "split_coordinates.yaml");
}

// The seed of this file's perturbed states.
constexpr unsigned kStateSeed = 20261124;

void perturbed_state(const Model& model, int nb, Eigen::VectorXd& q, Eigen::VectorXd& qd) {
  test::perturbed_state(model, nb, kStateSeed, q, qd);
}

TEST(SplitBeamSystem, RightHandSideMappedToNodalIsTheLowRankAcceleration) {
  const Model model = load_catenary();
  auto dyn_nodal = model.assembled().make_dynamics(true);
  auto dyn_split = model.assembled().make_dynamics(true);
  SplitBeamSystem split(dyn_split);
  const int n = dyn_split->n(), nb = dyn_split->nb(), ne = dyn_split->num_split_coordinates();
  ASSERT_EQ(dyn_split->split_structures().size(), 2u);
  Eigen::VectorXd q, qd;
  perturbed_state(model, nb, q, qd);
  constexpr double t = 0.01;
  dyn_nodal->impose_motion(t, q, qd);

  // The oracle: the nodal low-rank form, every rigid coordinate independent.
  Partition independent;
  for (int i = 0; i < nb; ++i) independent.independent.push_back(i);
  Eigen::VectorXd qdd_nodal, lambda;
  dyn_nodal->evaluate(t, q, qd);
  dyn_nodal->solve_partitioned(t, independent, qdd_nodal, lambda);

  const Eigen::VectorXd y = split.initial_state(t, q, qd);
  ASSERT_EQ(y.size(), 2 * (n + ne));
  Eigen::VectorXd ydot;
  split.rhs(t, y, ydot);
  ASSERT_EQ(ydot.size(), y.size());
  EXPECT_TRUE(ydot.head(n + ne) == y.tail(n + ne)) << "the first half is the rates";
  Eigen::VectorXd qdd = ydot.segment(n + ne, n);  // s'' in the split beams' slots
  const Eigen::VectorXd edd = ydot.tail(ne);
  for (std::size_t k = 0; k < dyn_split->split_structures().size(); ++k) {
    const LowRankStructure& st = *dyn_split->model().structures()[dyn_split->split_structures()[k]];
    const int m = st.rank(), at = dyn_split->split_offsets()[k];
    const LowRankStructure::Range& r = st.ranges().front();
    ASSERT_EQ(st.ranges().size(), 1u);
    const Eigen::MatrixXd phi = st.phi();
    qdd.segment(nb + r.offset, r.size) += phi * (edd.segment(at, m) - edd.segment(at + m, m));
  }
  const double scale = qdd_nodal.tail(n - nb).cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  EXPECT_LT((qdd - qdd_nodal).tail(n - nb).cwiseAbs().maxCoeff(), kSummationOrderTol * scale);
  const double rigid_scale = qdd_nodal.head(nb).cwiseAbs().maxCoeff();
  EXPECT_LT((qdd - qdd_nodal).head(nb).cwiseAbs().maxCoeff(), kSummationOrderTol * std::max(rigid_scale, scale));
}

TEST(SplitBeamSystem, RungeKuttaKeepsZetaEqualToTheKeptModesOfS) {
  const Model model = load_catenary();
  auto dyn = model.assembled().make_dynamics(true);
  SplitBeamSystem split(dyn);
  const int n = dyn->n(), nb = dyn->nb();
  Eigen::VectorXd q, qd;
  perturbed_state(model, nb, q, qd);
  dyn->impose_motion(0.0, q, qd);
  Eigen::VectorXd y = split.initial_state(0.0, q, qd);
  auto stepper = make_stepper(parse_integrator("rk4"), split);
  stepper->reset(0.0, y);
  constexpr double kStep = 5e-4;  // within the adjusted RK4 limit of the wires at this cap
  const Eigen::VectorXd y0 = y;
  for (int step = 0; step < 4; ++step) stepper->step(step * kStep, kStep, y);
  ASSERT_GT((y - y0).cwiseAbs().maxCoeff(), 0.0);
  for (std::size_t k = 0; k < dyn->split_structures().size(); ++k) {
    const LowRankStructure& st = *dyn->model().structures()[dyn->split_structures()[k]];
    const int m = st.rank(), at = dyn->split_offsets()[k];
    const LowRankStructure::Range& r = st.ranges().front();
    const Eigen::MatrixXd phi = st.phi();
    const Eigen::MatrixXd M = Eigen::MatrixXd(st.M());
    const Eigen::VectorXd s = y.segment(nb + r.offset, r.size);
    const Eigen::VectorXd zeta = y.segment(n + at + m, m);
    const Eigen::VectorXd eta = y.segment(n + at, m);
    const Eigen::VectorXd kept = phi.transpose() * (M * s);
    ASSERT_GT((eta - zeta).cwiseAbs().maxCoeff(), 0.0) << "the kept modes moved apart from s's";
    EXPECT_LT((zeta - kept).cwiseAbs().maxCoeff(), kInvariantTol * zeta.cwiseAbs().maxCoeff())
        << "structure " << st.name();
  }
}

TEST(SplitBeamSystem, StructuresOnTwoThreadsGiveTheSameBitsAsOnOne) {
  const Model model = load_catenary();
  auto dyn_one = model.assembled().make_dynamics(true);
  auto dyn_two = model.assembled().make_dynamics(true);
  SplitBeamSystem one(dyn_one), two(dyn_two);
  // The two-span wires are below the size at which two threads pay: the
  // default is one thread; two are asked for.
  EXPECT_FALSE(dyn_one->threaded_structures());
  dyn_two->set_threaded_structures(true);
  ASSERT_TRUE(dyn_two->threaded_structures());
  const int nb = dyn_one->nb();
  Eigen::VectorXd q, qd;
  perturbed_state(model, nb, q, qd);
  dyn_one->impose_motion(0.0, q, qd);
  Eigen::VectorXd y1 = one.initial_state(0.0, q, qd), y2 = two.initial_state(0.0, q, qd);
  auto step_one = make_stepper(parse_integrator("rk4"), one);
  auto step_two = make_stepper(parse_integrator("rk4"), two);
  step_one->reset(0.0, y1);
  step_two->reset(0.0, y2);
  constexpr double kStep = 5e-4;
  const Eigen::VectorXd y0 = y1;
  for (int step = 0; step < 20; ++step) {
    step_one->step(step * kStep, kStep, y1);
    step_two->step(step * kStep, kStep, y2);
  }
  ASSERT_GT((y1 - y0).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_TRUE(y1 == y2) << "largest difference " << (y1 - y2).cwiseAbs().maxCoeff();
}

TEST(SplitBeamSystem, TheReportedStateIsNotEvaluatedAgainUnlessALoadSetFromOutsideMayHaveChanged) {
  const Model model = load_catenary();
  auto dyn = model.assembled().make_dynamics(true);
  auto dyn_fresh = model.assembled().make_dynamics(true);
  SplitBeamSystem split(dyn), fresh(dyn_fresh);
  Eigen::VectorXd q, qd;
  perturbed_state(model, dyn->nb(), q, qd);
  dyn->impose_motion(0.01, q, qd);
  const Eigen::VectorXd y = split.initial_state(0.01, q, qd);
  Eigen::VectorXd other = y;
  other[0] += 1e-3;
  Eigen::VectorXd ydot, want;
  split.rhs(0.01, other, ydot);  // the dynamics describe another state
  split.report(0.01, y);
  split.rhs(0.01, y, ydot);  // the reported state: the report's derivative
  fresh.rhs(0.01, y, want);
  EXPECT_TRUE(ydot == want) << "largest difference " << (ydot - want).cwiseAbs().maxCoeff();

  // A load the caller sets after the report changes the derivative at the
  // same state: it is evaluated again, on both systems alike.
  double value = 0.0;
  const auto load = [&value](double) { return value; };
  // Between droppers, away from the middle support at 10 m.
  dyn->set_applied_load(0, 6.5, load);
  dyn_fresh->set_applied_load(0, 6.5, load);
  split.report(0.01, y);
  value = 500.0;  // N
  const Eigen::VectorXd before = want;  // without the load
  split.rhs(0.01, y, ydot);
  fresh.rhs(0.01, y, want);
  ASSERT_GT((want - before).cwiseAbs().maxCoeff(), 0.0) << "the load acts";
  EXPECT_TRUE(ydot == want) << "largest difference " << (ydot - want).cwiseAbs().maxCoeff();
}

}  // namespace
}  // namespace mbfe::runtime
