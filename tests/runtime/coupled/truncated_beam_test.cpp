// Policy truncate in split coordinates (SplitBeamSystem, CoupledDynamics::
// split_accelerations; docs/damping-adjustment.md, "Policy truncate"): a
// truncated beam moves in its modes below omega_limit alone, q = Phi_T xi,
// xi'' = Phi_T^T f - c_j xi' - omega_j^2 xi. Checked against the closed-form
// step response of those modes (a dense eigensolver of the test's own), and
// against the original model when the truncation keeps every mode; the paths
// that cannot integrate a truncated beam refuse it; the stability advisor's
// linearisation in the kept modes (TruncatedTangents) against the uncoupled
// roots and against the nodal tangents projected here.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <tuple>
#include <vector>

#include "api/mbfe.h"
#include "runtime/advisor/model_spectrum.h"
#include "runtime/coupled/coupled_tangents.h"
#include "runtime/coupled/truncated_tangents.h"
#include "runtime/structure/low_rank_structure.h"
#include "runtime/errors/invalid_input.h"
#include "runtime/integrators/integrator_spec.h"
#include "tests/support/recorded_rows.h"
#include "tests/support/two_span_catenary.h"

namespace mbfe {
namespace {

// A pinned-pinned steel beam (EI = 2e5 N m^2, rhoA = 7.8 kg/m, 10 m: omega_n
// about 15.8 n^2 rad/s) under its own weight, started at rest and undeflected,
// beside a cart on a spring that nothing connects to it.
std::string simple_beam(const std::string& adjustment) {
  return R"yaml(model: truncated_beam
gravity: [0, -9.81]
bodies:
  - name: cart
    parent: ground
    joint: {type: prismatic, axis: [1, 0], at: [0, 2]}
    mass: 1.0
    inertia: 0
loads:
  - {type: spring_damper, joint: cart, stiffness: 100, damping: 1, rest: 0.0}
beams:
  - name: deck
    origin: [0, 0]
    length: 10.0
    elements: 20
    section: {area: 1.0e-3, inertia: 1.0e-6}
    material: {youngs_modulus: 2.0e11, density: 7800}
    supports: [{at: 0, type: pinned}, {at: 10, type: pinned}]
    damping: {rayleigh: {alpha: 0.2, beta: 1.0e-4}}
    adjustment: )yaml" +
         adjustment + "\n";
}

// Rows with every coordinate.
struct StateRows : test::RecordedRows {
  void row(const runtime::OutputRow& row) override {
    RecordedRows::row(row);
    t.push_back(row.t);
    q.push_back(row.q);
  }
  std::vector<double> t;
  std::vector<Eigen::VectorXd> q;
};

runtime::SimulationRequest rk4_request(double step, double t_end) {
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("rk4");
  request.step = step;
  request.t_end = t_end;
  request.every = 1;
  request.static_start = false;
  request.state_in_rows = true;
  return request;
}

// xi'' + c xi' + k xi = p from rest, with the roots r1, r2 of r^2 + c r + k
// (a complex pair or, for the overdamped high modes, two real ones; never equal here):
// xi = p / k (1 + (r2 e^{r1 t} - r1 e^{r2 t}) / (r1 - r2)).
double step_response(double p, double c, double k, double t) {
  const std::complex<double> d = std::sqrt(std::complex<double>(c * c - 4.0 * k));
  const std::complex<double> r1 = 0.5 * (-c + d), r2 = 0.5 * (-c - d);
  return p / k * (1.0 + ((r2 * std::exp(r1 * t) - r1 * std::exp(r2 * t)) / (r1 - r2)).real());
}

TEST(TruncatedBeam, FollowsTheClosedFormResponseOfItsKeptModes) {
  // Modes 1 to 4 (15.8 to 253 rad/s) kept; gravity excites 1 and 3 of them
  // and 5, 7, ... (395 rad/s and up) of those removed.
  constexpr double kOmegaT = 300.0;
  const Model model = Model::parse(simple_beam("{omega_limit: 300.0, policy: truncate}"), "truncated.yaml");
  const runtime::BeamSystem& beam = model.assembled().beams().beams.front().system;
  const Eigen::MatrixXd M(beam.M), K(beam.K);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(K, M);  // M-orthonormal, ascending
  const Eigen::VectorXd& k = modes.eigenvalues();
  const Eigen::MatrixXd& phi = modes.eigenvectors();
  const Eigen::VectorXd p = phi.transpose() * beam.P;
  int kept = 0;
  while (kept < k.size() && std::sqrt(k[kept]) <= kOmegaT) ++kept;
  ASSERT_EQ(kept, 4);

  constexpr double kStep = 1e-4;  // h omega_4 = 0.025: RK4's own error far below the tolerance
  StateRows rows;
  const runtime::SimulationReport report = model.simulate(rk4_request(kStep, 0.3), rows);
  ASSERT_NE(report.variant.find("split coordinates"), std::string::npos) << report.variant;
  EXPECT_EQ(report.variant.rfind("truncated modes, ", 0), 0u) << report.variant;
  // RK4 at h omega <= 0.025 over 3,000 steps: 2e-11 of the deflection
  // measured; the removed modes make 6e-4 of it (checked below).
  constexpr double kClosedFormTol = 1e-7;
  double worst = 0.0, scale = 0.0, removed = 0.0;
  for (std::size_t r = 0; r < rows.q.size(); ++r) {
    const double t = rows.t[r];
    Eigen::VectorXd truncated = Eigen::VectorXd::Zero(M.rows()), full = truncated;
    for (int j = 0; j < k.size(); ++j) {
      const double c = beam.rayleigh_alpha + beam.rayleigh_beta * k[j];
      const Eigen::VectorXd part = phi.col(j) * step_response(p[j], c, k[j], t);
      full += part;
      if (j < kept) truncated += part;
    }
    const Eigen::VectorXd got = rows.q[r].tail(M.rows());
    worst = std::max(worst, (got - truncated).cwiseAbs().maxCoeff());
    removed = std::max(removed, (full - truncated).cwiseAbs().maxCoeff());
    scale = std::max(scale, truncated.cwiseAbs().maxCoeff());
  }
  ASSERT_GT(scale, 0.0);
  EXPECT_LT(worst / scale, kClosedFormTol);
  // The test tells a truncated beam from the whole one.
  EXPECT_GT(removed / scale, 100.0 * kClosedFormTol);
  std::printf("[ truncate ] closed form: largest difference %.3g of the deflection (removed modes: %.3g)\n",
              worst / scale, removed / scale);
}

TEST(TruncatedBeam, AboveEveryModeItIsTheCapThatChangesNothing) {
  // The two-span catenary (droppers that go slack, a unilateral contact
  // driven along): truncation above its highest mode keeps every mode, so it
  // is the low-rank model with nothing capped, which split coordinates
  // integrate as s + Phi (eta - zeta) (checked against the nodal low-rank
  // form in tests/api/split_coordinates_test.cpp). Here s and zeta stay 0
  // and q = Phi eta alone.
  const Model truncated_model = Model::parse(
      test::with_wire_adjustment("{omega_limit: 1.0e9, policy: truncate}"), "truncate_all.yaml");
  const Model cap_model =
      Model::parse(test::with_wire_adjustment("{omega_limit: 1.0e9, policy: cap}"), "cap_all.yaml");
  constexpr double kStep = 2e-5;  // within the original model's RK4 limit
  runtime::SimulationRequest request = rk4_request(kStep, 0.02);
  request.static_start = true;  // the wires sagged: a start away from q = 0
  StateRows truncated, cap;
  const runtime::SimulationReport report = truncated_model.simulate(request, truncated);
  ASSERT_NE(report.variant.find("split coordinates"), std::string::npos) << report.variant;
  cap_model.simulate(request, cap);
  ASSERT_EQ(truncated.q.size(), cap.q.size());
  // Another summation order (Phi eta against s + Phi (eta - zeta)), on
  // contacts and droppers that switch on those sums: 5e-16 measured.
  constexpr double kSameMotionTol = 1e-9;
  double worst = 0.0;
  for (std::size_t r = 0; r < cap.q.size(); ++r) {
    const double scale = cap.q[r].cwiseAbs().maxCoeff();
    worst = std::max(worst, (truncated.q[r] - cap.q[r]).cwiseAbs().maxCoeff() / scale);
  }
  EXPECT_LT(worst, kSameMotionTol);
  std::printf("[ truncate ] every mode kept: largest relative difference from the cap %.3g\n", worst);
}

TEST(TruncatedBeam, PathsThatCannotIntegrateItRefuse) {
  const Model model = Model::parse(simple_beam("{omega_limit: 300.0, policy: truncate}"), "truncated.yaml");
  runtime::SimulationRequest request = rk4_request(1e-4, 1e-3);
  request.formulation = runtime::CoupledFormulation::kAugmented;
  StateRows rows;
  try {
    model.simulate(request, rows);
    ADD_FAILURE() << "the augmented formulation integrated a truncated beam";
  } catch (const runtime::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("policy truncate"), std::string::npos) << e.what();
  }
  // The original model stays available.
  EXPECT_NO_THROW(runtime::model_spectrum(model.assembled(), false));
}

TEST(TruncatedBeam, TheAdvisorLinearisesTheKeptModes) {
  // The cart on its spring (m 1 kg, k 100 N/m, c 1 N s/m) and the beam's four
  // kept modes (Rayleigh c_j = alpha + beta omega_j^2) are uncoupled: the
  // truncated model's spectrum is their roots, ten in all, and nothing of the
  // removed modes (the fastest root is the fourth mode's, 253 rad/s).
  // Dense eigensolvers on both sides, matrices of 1e5 at most: 1e-9.
  constexpr double kRootTol = 1e-9;  // relative to |lambda|
  const Model model = Model::parse(simple_beam("{omega_limit: 300.0, policy: truncate}"), "truncated.yaml");
  const runtime::BeamSystem& beam = model.assembled().beams().beams.front().system;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(Eigen::MatrixXd(beam.K),
                                                                        Eigen::MatrixXd(beam.M));
  std::vector<std::complex<double>> expected;
  auto roots = [&](double m, double c, double k) {
    const std::complex<double> d = std::sqrt(std::complex<double>(c * c - 4.0 * m * k));
    expected.push_back((-c + d) / (2.0 * m));
    expected.push_back((-c - d) / (2.0 * m));
  };
  roots(1.0, 1.0, 100.0);
  for (int j = 0; j < 4; ++j) {
    const double k = modes.eigenvalues()[j];
    roots(1.0, beam.rayleigh_alpha + beam.rayleigh_beta * k, k);
  }
  const runtime::ModelSpectrum s = runtime::model_spectrum(model.assembled(), true);
  EXPECT_EQ(s.coordinates, 5);  // the cart and four modal amplitudes
  ASSERT_EQ(s.full.eigenvalues.size(), expected.size());
  EXPECT_TRUE(s.full.complete);
  for (const std::complex<double>& e : expected) {
    double nearest = INFINITY;
    for (const std::complex<double>& l : s.full.eigenvalues) nearest = std::min(nearest, std::abs(l - e));
    EXPECT_LT(nearest, kRootTol * std::abs(e)) << e;
  }
}

TEST(TruncatedBeam, TheAdvisorRefusesATruncatedBeamBesideANodalOne) {
  // The two-span catenary with only its messenger truncated: the kept-mode
  // projection needs every beam truncated; the refusal is an input error at
  // the adjustment block (exit 2), not an internal one.
  std::string text = test::kTwoSpanCatenary;
  const std::string damping = "damping: {rayleigh: {alpha: 0.0, beta: 1.0e-4}}";
  text.insert(text.find(damping) + damping.size(), "\n    adjustment: {omega_limit: 1000.0, policy: truncate}");
  const Model model = Model::parse(text, "half_truncated.yaml");
  try {
    runtime::model_spectrum(model.assembled(), true);
    ADD_FAILURE() << "the advisor linearised a model with a truncated and a nodal beam";
  } catch (const runtime::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("only when every beam of the model is truncated"), std::string::npos)
        << e.what();
  }
}

TEST(TruncatedBeam, TheProjectedTangentsAreTheNodalOnesOnTheKeptModes) {
  // The two-span catenary with both wires truncated at 1000 rad/s: contact,
  // droppers and the pantograph couple the wires. The reduced matrices from
  // the closed-form modal terms and the force elements' rows of Phi_L,
  // against T^T X T formed here by the nodal tangents' own products (the
  // structures' low-rank operators applied to each kept mode).
  constexpr double kProjectionTol = 1e-9;  // relative to the largest entry
  const Model model =
      Model::parse(test::with_wire_adjustment("{omega_limit: 1000.0, policy: truncate}"), "two_span.yaml");
  const std::shared_ptr<runtime::CoupledDynamics> dynamics = model.assembled().make_dynamics(true);
  Eigen::VectorXd q, qd;
  model.assembled().initial_coordinates(q, qd);
  dynamics->impose_motion(0.0, q, qd);
  const runtime::CoupledTangents tangents(*dynamics, 0.0, q, qd);
  const runtime::TruncatedTangents reduced(tangents);
  // T: the free rigid coordinates, then each wire's kept modes at its rows.
  const int rigid = tangents.rigid_size();
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(tangents.size(), reduced.size());
  T.topLeftCorner(rigid, rigid).setIdentity();
  int column = rigid;
  for (const auto& st : dynamics->model().structures()) {
    const runtime::LowRankStructure::Range& r = st->ranges().front();
    T.block(rigid + r.offset, column, r.size, st->rank()) = st->phi();
    column += st->rank();
  }
  ASSERT_EQ(column, reduced.size());
  ASSERT_GT(reduced.modal_size(), 50);  // both wires, tens of modes each (84)
  Eigen::MatrixXd m(reduced.size(), reduced.size()), c = m, k = m;
  Eigen::VectorXd y;
  for (int j = 0; j < reduced.size(); ++j) {
    const Eigen::VectorXd t = T.col(j);
    tangents.apply_mass(t, y);
    m.col(j) = T.transpose() * y;
    tangents.apply_damping(t, y);
    c.col(j) = T.transpose() * y;
    tangents.apply_stiffness(t, y);
    k.col(j) = T.transpose() * y;
  }
  for (auto [got, want, name] : {std::tuple{&reduced.mass(), &m, "M"}, std::tuple{&reduced.damping(), &c, "C"},
                                 std::tuple{&reduced.stiffness(), &k, "K"}}) {
    const double scale = want->cwiseAbs().maxCoeff();
    EXPECT_LT((*got - *want).cwiseAbs().maxCoeff(), kProjectionTol * scale) << name;
  }
  // The contact and the droppers couple the two wires' modes.
  const int messenger_modes = dynamics->model().structures().front()->rank();
  EXPECT_GT(reduced.stiffness().block(rigid, rigid + messenger_modes, messenger_modes, 4).cwiseAbs().maxCoeff(), 0.0);
}

}  // namespace
}  // namespace mbfe
