// The damping of adjusted beams' discrete parts (DiscreteDampingForce;
// docs/damping-adjustment.md, "The discrete parts' damping"): an adjustment
// that changes no mode must be the original model. The two-span catenary of
// the tests has spring supports with masses and clamp masses on both wires;
// its adjusted form damps the kept modes by Rayleigh over the whole beam,
// which without the remainder damps the masses by alpha and the springs by
// beta where the original model does not (1.6e-5 of the contact wire's
// displacement over 0.1 s on the shipped catenary). With it, the cap above
// every mode runs the original model to round-off, in split coordinates and
// in the nodal low-rank form.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <vector>

#include "api/mbfe.h"
#include "runtime/integrators/integrator_spec.h"
#include "tests/support/recorded_rows.h"
#include "tests/support/two_span_catenary.h"

namespace mbfe {
namespace {

struct StateRows : test::RecordedRows {
  void row(const runtime::OutputRow& row) override {
    RecordedRows::row(row);
    q.push_back(row.q);
  }
  std::vector<Eigen::VectorXd> q;
};

runtime::SimulationRequest rk4_request(bool adjust, runtime::CoupledFormulation formulation) {
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("rk4");
  request.step = 2e-5;  // within the original model's RK4 limit
  request.t_end = 0.02;
  request.every = 1;
  request.static_start = true;  // the wires sagged: a start away from q = 0
  request.state_in_rows = true;
  request.adjust = adjust;
  request.formulation = formulation;
  return request;
}

/// Largest |q_a - q_b| over the rows, relative to each row's largest |q_b|.
double largest_difference(const StateRows& a, const StateRows& b) {
  EXPECT_EQ(a.q.size(), b.q.size());
  double worst = 0.0;
  for (std::size_t r = 0; r < std::min(a.q.size(), b.q.size()); ++r)
    worst = std::max(worst, (a.q[r] - b.q[r]).cwiseAbs().maxCoeff() / b.q[r].cwiseAbs().maxCoeff());
  return worst;
}

// Another summation order of the same equations over 1,000 RK4 steps, through
// droppers and a contact that switch on those sums: 1e-9 is far below the
// 1e-5 the discrete parts' damping made and far above the round-off.
constexpr double kSameMotionTol = 1e-9;

TEST(DiscreteDampingForce, AnAdjustmentThatChangesNoModeIsTheOriginalModel) {
  const Model model = Model::parse(test::with_wire_adjustment("{omega_limit: 1.0e9, policy: cap}"), "cap_all.yaml");
  StateRows original, split, nodal;
  model.simulate(rk4_request(false, runtime::CoupledFormulation::kPartitioned), original);
  const runtime::SimulationReport report =
      model.simulate(rk4_request(true, runtime::CoupledFormulation::kPartitioned), split);
  ASSERT_NE(report.variant.find("split coordinates"), std::string::npos) << report.variant;
  model.simulate(rk4_request(true, runtime::CoupledFormulation::kAugmented), nodal);
  EXPECT_LT(largest_difference(split, original), kSameMotionTol);
  EXPECT_LT(largest_difference(nodal, original), kSameMotionTol);
}

}  // namespace
}  // namespace mbfe
