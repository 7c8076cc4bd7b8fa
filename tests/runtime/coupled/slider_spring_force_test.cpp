// The slider_spring force element under Hertz's law N = C_H delta^1.5
// (docs/contacts.md): the force against the law, none when apart even
// bilateral, the closed-form tangent against finite differences of the
// force, a wheel resting on the deck at delta = (W / C_H)^(2/3) (static start
// and a settled run), and an implicit run against an explicit one.
#include "runtime/coupled/slider_spring_force.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "api/mbfe.h"
#include "runtime/coupled/coupled_dynamics.h"
#include "runtime/simulation/assembled_model.h"

namespace mbfe {
namespace {

constexpr double kG = 9.81, kWheelMass = 1000.0;
constexpr double kHertz = 1.0e10;  // N/m^1.5: a wheel on a rail is of this order
// The generated force against C_H delta^1.5 evaluated here: one pow and a
// product, round-off relative to the force.
constexpr double kForceRoundOff = 1e-12;
// s: two runs' row times, sums of different steps to the same times.
constexpr double kRowTimeTol = 1e-12;

/// A wheel on a vertical prismatic joint under a carriage parked (or driven)
/// along a simply supported deck; `contact` the slider_spring's law keys.
std::string wheel_on_deck(const std::string& contact, const std::string& motion = "10",
                          const std::string& initial = "", const std::string& deck_damping = "") {
  return "model: hertz_wheel\n"
         "gravity: [0, " + std::to_string(-kG) + "]\n"
         "bodies:\n"
         "  - {name: carriage, parent: ground, joint: {type: prismatic, axis: [1, 0], motion: \"" + motion +
         "\"}, mass: 0.0, inertia: 0.0}\n"
         "  - {name: wheel, parent: carriage, joint: {type: prismatic, axis: [0, 1]}, mass: 1000.0, inertia: 0.0,\n"
         "     points: {contact: [0.0, 0.0]}}\n"
         "beams:\n"
         "  - name: deck\n"
         "    origin: [0.0, 0.0]\n"
         "    length: 20.0\n"
         "    elements: 10\n"
         "    section: {area: 0.01, inertia: 1.0e-4}\n"
         "    material: {youngs_modulus: 2.1e11, density: 7850}\n"
         "    supports: [{at: 0.0, type: pinned}, {at: 20.0, type: pinned}]\n" +
         deck_damping +
         "contacts:\n"
         "  - {name: tyre, type: slider_spring, body: wheel, point: contact, beam: deck, " + contact + "}\n" + initial;
}

class Rows : public runtime::SimulationObserver {
 public:
  void begin(const runtime::OutputLayout& layout) override { columns = layout.columns; }
  void row(const runtime::OutputRow& row) override { values.push_back(row.values); }
  std::size_t column(const std::string& name) const {
    for (std::size_t i = 0; i < columns.size(); ++i)
      if (columns[i] == name) return i;
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
  std::vector<std::string> columns;
  std::vector<std::vector<double>> values;
};

/// The penetration delta = w(s) - y_wheel of a row (the point is the wheel's origin).
double penetration(const Rows& rows, std::size_t r) {
  return rows.values[r][rows.column("deflection_tyre")] - rows.values[r][rows.column("wheel")];
}

TEST(HertzContact, ForceFollowsTheLawAndIsZeroWhenApart) {
  for (const char* unilateral : {"false", "true"}) {
    const Model model = Model::parse(
        wheel_on_deck("law: hertz, coefficient: 1.0e10, damping: 0.0, unilateral: " + std::string(unilateral)),
        "hertz.yaml");
    const std::shared_ptr<runtime::CoupledDynamics> dyn = model.assembled().make_dynamics(false);
    const int n = dyn->n();
    std::mt19937 rng(20261124);
    std::normal_distribution<double> nd(0.0, 1.0);
    int pressed = 0, apart = 0;
    for (int trial = 0; trial < 200; ++trial) {
      Eigen::VectorXd q(n), qd(n);
      for (int i = 0; i < n; ++i) {
        q[i] = 1e-4 * nd(rng);
        qd[i] = 0.1 * nd(rng);
      }
      dyn->evaluate(0.0, q, qd);
      const runtime::SpringContactState& st = dyn->spring_state(0);
      if (st.delta > 0.0) {
        ++pressed;
        EXPECT_NEAR(st.force, kHertz * std::pow(st.delta, 1.5), kForceRoundOff * st.force);
      } else {
        ++apart;
        EXPECT_EQ(st.force, 0.0) << "delta " << st.delta << ", unilateral " << unilateral;
      }
    }
    EXPECT_GT(pressed, 20);
    EXPECT_GT(apart, 20);
  }
}

TEST(HertzContact, TangentMatchesFiniteDifferencesOfTheForce) {
  const Model model = Model::parse(wheel_on_deck("law: hertz, coefficient: 1.0e10, damping: 3.0e3"), "hertz.yaml");
  const std::shared_ptr<runtime::CoupledDynamics> dyn = model.assembled().make_dynamics(false);
  const runtime::CoupledModel& cm = dyn->model();
  ASSERT_EQ(cm.slider_springs().size(), 1u);
  const runtime::SliderSpringForce& spring = *cm.slider_springs()[0];
  EXPECT_TRUE(spring.law().hertz);
  const int nb = cm.nb(), n = cm.n();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd q(n), qd(n);
  for (int i = 0; i < n; ++i) {
    q[i] = 1e-5 * u(rng);
    qd[i] = 1e-2 * u(rng);
  }
  q[0] = 10.0;   // the carriage over midspan (driven: its column is not compared)
  q[1] = -2e-4;  // the wheel presses into the deck
  auto force = [&](const Eigen::VectorXd& qq, const Eigen::VectorXd& vv) {
    auto state = spring.make_state();
    Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
    runtime::ForceSink sink{f.data(), f.data() + nb};
    runtime::ForceArgs x{0.0, qq.data(), vv.data(), qq.data() + nb, vv.data() + nb};
    spring.add_force(x, *state, sink);
    return f;
  };
  auto state = spring.make_state();
  {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
    runtime::ForceSink sink{f.data(), f.data() + nb};
    runtime::ForceArgs x{0.0, q.data(), qd.data(), q.data() + nb, qd.data() + nb};
    spring.add_force(x, *state, sink);
    ASSERT_GT(static_cast<const runtime::SliderSpringForce::State&>(*state).contact.delta, 0.0);
  }
  std::vector<Eigen::Triplet<double>> kq, kv;
  runtime::TangentSink sink_q(kq), sink_v(kv);
  const runtime::ForceArgs x{0.0, q.data(), qd.data(), q.data() + nb, qd.data() + nb};
  spring.add_tangent(x, *state, 1.0, 0.0, sink_q);
  spring.add_tangent(x, *state, 0.0, 1.0, sink_v);
  Eigen::SparseMatrix<double> Kq(n, n), Kv(n, n);
  Kq.setFromTriplets(kq.begin(), kq.end());
  Kv.setFromTriplets(kv.begin(), kv.end());
  const Eigen::MatrixXd tangent_q(Kq), tangent_v(Kv);
  // The carriage's column moves the point along the beam, where the gradient
  // itself changes (left out of the tangent, slider_spring_force.h); along
  // the wheel and the beam DOFs the gradient is constant and the tangent exact.
  // Central differences of a delta^1.5 law at delta ~ 2e-4 with h = 1e-9 m:
  // truncation ~ (h / delta)^2 = 1e-11 relative, round-off ~ 1e-16 / 1e-9 of
  // the force, 1e-6 relative of the largest entry.
  constexpr double kFdRelTol = 1e-5;
  const double h = 1e-9;
  const double scale = tangent_q.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  for (int j = 1; j < n; ++j) {
    Eigen::VectorXd qp = q, qm = q;
    qp[j] += h;
    qm[j] -= h;
    const Eigen::VectorXd fd = -(force(qp, qd) - force(qm, qd)) / (2 * h);
    for (int i = 1; i < n; ++i)
      EXPECT_NEAR(tangent_q(i, j), fd[i], kFdRelTol * scale) << "d f_" << i << " / d q_" << j;
    Eigen::VectorXd vp = qd, vm = qd;
    vp[j] += 1e-3;
    vm[j] -= 1e-3;
    const Eigen::VectorXd fdv = -(force(q, vp) - force(q, vm)) / 2e-3;  // linear in the rates: exact
    // Exact but for the round-off of forces of the Hertz stiffness's size
    // divided by 2e-3, relative to the largest rate tangent.
    constexpr double kLinearDifferenceTol = 1e-9;
    for (int i = 1; i < n; ++i)
      EXPECT_NEAR(tangent_v(i, j), fdv[i], kLinearDifferenceTol * (1.0 + tangent_v.cwiseAbs().maxCoeff()))
          << "d f_" << i << " / d v_" << j;
  }
}

TEST(HertzContact, AWheelRestsAtTheHertzianPenetration) {
  const double W = kWheelMass * kG;
  const double expected = std::pow(W / kHertz, 2.0 / 3.0);  // 9.87e-5 m
  // Newton converges to round-off of the equilibrium.
  constexpr double kStaticTol = 1e-9;
  const Model parked = Model::parse(
      wheel_on_deck("law: hertz, coefficient: 1.0e10, damping: 2.0e4", "10", "initial: {static: true}\n"),
      "parked.yaml");
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("generalized_alpha");
  request.step = 1e-3;
  request.t_end = 0.01;
  request.every = 1;
  Rows rows;
  ASSERT_TRUE(parked.simulate(request, rows).message.empty());
  EXPECT_NEAR(penetration(rows, 0), expected, kStaticTol * expected);
  EXPECT_NEAR(rows.values[0][rows.column("force_tyre")], W, kStaticTol * W);

  // Dropped onto the deck from touching, with the contact and the deck
  // damped: it settles where the static start starts.
  const Model dropped = Model::parse(
      wheel_on_deck("law: hertz, coefficient: 1.0e10, damping: 2.0e4", "10", "",
                    "    damping: {rayleigh: {alpha: 20.0, beta: 1.0e-4}}\n"),
      "dropped.yaml");
  request.t_end = 5.0;
  Rows settled;
  ASSERT_TRUE(dropped.simulate(request, settled).message.empty());
  // What is left of the transient after 5 s: the slowest mode (the wheel
  // bouncing on the deck, its mass undamped by the deck's alpha) shrinks by a
  // factor of 100 or more every second; seen 2e-10 of delta.
  constexpr double kSettledTol = 1e-7;
  EXPECT_NEAR(penetration(settled, settled.values.size() - 1), expected, kSettledTol * expected);
}

TEST(HertzContact, ImplicitAndExplicitRunsAgree) {
  // The wheel crossing at 20 m/s, from touching: the tyre force of
  // generalized_alpha against RK4 on the same original model.
  const Model model = Model::parse(
      wheel_on_deck("law: hertz, coefficient: 1.0e10, damping: 2.0e4, unilateral: true", "2 + 20*t"),
      "crossing.yaml");
  runtime::SimulationRequest explicit_run;
  explicit_run.integrator = runtime::parse_integrator("rk4");
  explicit_run.step = 2e-6;
  explicit_run.t_end = 0.4;
  explicit_run.every = 50;
  explicit_run.adjust = false;
  runtime::SimulationRequest implicit_run = explicit_run;
  implicit_run.integrator = runtime::parse_integrator("generalized_alpha");
  implicit_run.step = 2e-5;
  implicit_run.every = 5;
  Rows a, b;
  const runtime::SimulationReport ra = model.simulate(explicit_run, a);
  ASSERT_TRUE(ra.message.empty()) << ra.message;
  const runtime::SimulationReport rb = model.simulate(implicit_run, b);
  ASSERT_TRUE(rb.message.empty()) << rb.message;
  ASSERT_EQ(a.values.size(), b.values.size());
  const std::size_t f = a.column("force_tyre");
  double worst = 0.0, peak = 0.0;
  for (std::size_t r = 0; r < a.values.size(); ++r) {
    EXPECT_NEAR(a.values[r][0], b.values[r][0], kRowTimeTol);
    worst = std::max(worst, std::abs(a.values[r][f] - b.values[r][f]));
    peak = std::max(peak, std::abs(a.values[r][f]));
  }
  EXPECT_GT(peak, kWheelMass * kG);
  // Generalized-alpha is second order: at h = 2e-5 s its error on the
  // wheel's contact oscillation (about 100 Hz) is a fraction of a percent.
  constexpr double kAgreement = 0.01;  // of the peak force
  EXPECT_LT(worst, kAgreement * peak);
}

}  // namespace
}  // namespace mbfe
