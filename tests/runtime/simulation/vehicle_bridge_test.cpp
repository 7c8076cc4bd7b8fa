// Vehicles on a bridge: the slider_spring contact (kernels against finite
// differences, a force that never pulls, a dropped wheel that lifts off and
// lands), the static start (a parked vehicle against P L^3 / 48 EI plus the
// deck's own weight, and no transient), and a moving mass crossing against an
// independent model written here (the continuous beam's sine modes with the
// mass held on the deflected deck).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "api/mbfe.h"
#include "runtime/simulation/assembled_model.h"
#include "tests/support/cli.h"
#include "runtime/coupled/coupled_dynamics.h"

namespace mbfe {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLength = 20.0, kArea = 0.01, kInertia = 1e-4, kYoung = 2.1e11, kDensity = 7850.0;
constexpr double kWheelMass = 1000.0, kG = 9.81;

// Central differences with a step of 1e-6 on O(1) kernels: truncation ~1e-12
// against round-off ~1e-10 relative; 1e-7 leaves a margin.
constexpr double kFdTol = 1e-7;
// The same kernel at the same state evaluated twice: a last bit of delta (m).
constexpr double kSameEvaluationTol = 1e-15;
// The contact law's k delta + c delta' evaluated here: round-off, relative.
constexpr double kForceLawRoundOff = 1e-9;
// Newton converges to round-off of the equilibrium: 1e-9 of the deflection
// or the load.
constexpr double kNewtonRel = 1e-9;

/// The bridge with a wheel under a driven carriage; `motion` the carriage's
/// x(t), `extra` appended to the contact, `top` before `bodies:`.
std::string vehicle(const std::string& motion, const std::string& contact_extra, double gravity,
                    const std::string& wheel_load = "", const std::string& initial = "") {
  return "model: wheel_on_deck\n"
         "gravity: [0, " + std::to_string(-gravity) + "]\n"
         "bodies:\n"
         "  - name: carriage\n"
         "    parent: ground\n"
         "    joint: {type: prismatic, axis: [1, 0], motion: \"" + motion + "\"}\n"
         "    mass: 0.0\n    inertia: 0.0\n"
         "  - name: wheel\n"
         "    parent: carriage\n"
         "    joint: {type: prismatic, axis: [0, 1]}\n"
         "    mass: 1000.0\n    inertia: 0.0\n"
         "    points: {contact: [0.0, 0.0]}\n" +
         (wheel_load.empty() ? "" : "loads:\n  - {type: force, body: wheel, point: contact, value: " + wheel_load + "}\n") +
         "beams:\n"
         "  - name: deck\n"
         "    origin: [0.0, 0.0]\n"
         "    length: 20.0\n"
         "    elements: 40\n"
         "    section: {area: 0.01, inertia: 1.0e-4}\n"
         "    material: {youngs_modulus: 2.1e11, density: 7850}\n"
         "    supports: [{at: 0.0, type: pinned}, {at: 20.0, type: pinned}]\n"
         "    adjustment: {omega_limit: 2000.0, margin: 0.1, zeta_min: 0.0, policy: cap}\n"
         "contacts:\n"
         "  - {name: tyre, type: slider_spring, body: wheel, point: contact, beam: deck, " + contact_extra + "}\n" +
         initial;
}

class Rows : public runtime::SimulationObserver {
 public:
  void begin(const runtime::OutputLayout& layout) override { columns = layout.columns; }
  void row(const runtime::OutputRow& row) override {
    values.push_back(row.values);
    q.push_back(row.q);
  }
  int column(const std::string& name) const {
    for (std::size_t i = 0; i < columns.size(); ++i)
      if (columns[i] == name) return static_cast<int>(i);
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
  std::vector<std::string> columns;
  std::vector<std::vector<double>> values;
  std::vector<Eigen::VectorXd> q;
};

runtime::SimulationRequest rk4(double step, double t_end) {
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("rk4");
  request.step = step;
  request.t_end = t_end;
  request.every = 1;
  return request;
}

TEST(SliderSpring, KernelsAndForcesAgreeWithFiniteDifferences) {
  const Model model = Model::parse(vehicle("7.3 + 2*t", "stiffness: 5.0e6, damping: 1.0e3", kG), "spring_fd.yaml");
  const mbfe_model_v1& solver = *model.solver();
  ASSERT_EQ(solver.num_contacts, 1);
  const mbfe_contact_kernels_v1& k = solver.contacts[0];
  EXPECT_EQ(k.type, 2);
  EXPECT_EQ(k.stiffness, 5.0e6);
  EXPECT_EQ(k.damping, 1.0e3);
  std::mt19937 rng(20261123);
  std::uniform_real_distribution<double> u(-0.01, 0.01);
  const double le = 0.5;
  for (int trial = 0; trial < 20; ++trial) {
    double q[2] = {7.3 + 0.2 * u(rng) / 0.01, u(rng)};  // s inside element 14
    double qe[4] = {u(rng), u(rng), u(rng), u(rng)};
    const double s0 = 14 * le;
    double jb[2], je[4];
    k.jacobians(q, qe, s0, le, jb, je);
    const double h = 1e-6;
    for (int j = 0; j < 2; ++j) {
      double qp[2] = {q[0], q[1]}, qm[2] = {q[0], q[1]}, pp = 0, pm = 0;
      qp[j] += h;
      qm[j] -= h;
      k.phi(qp, qe, s0, le, &pp);
      k.phi(qm, qe, s0, le, &pm);
      EXPECT_NEAR(jb[j], (pp - pm) / (2 * h), kFdTol) << "dPhi/dq" << j;
    }
    for (int j = 0; j < 4; ++j) {
      double ep[4], em[4], pp = 0, pm = 0;
      std::copy(qe, qe + 4, ep);
      std::copy(qe, qe + 4, em);
      ep[j] += h;
      em[j] -= h;
      k.phi(q, ep, s0, le, &pp);
      k.phi(q, em, s0, le, &pm);
      EXPECT_NEAR(je[j], (pp - pm) / (2 * h), kFdTol) << "dPhi/dqe" << j;
    }
  }

  // The generalized forces of the whole coupled system: -(d delta/dq)^T N with
  // N = k delta + c delta', delta' by a central difference along the velocity.
  const std::shared_ptr<runtime::CoupledDynamics> dyn = model.assembled().make_dynamics(false);
  const int n = dyn->n();
  Eigen::VectorXd q = Eigen::VectorXd::Zero(n), qd = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) {
    q[i] = 1e-3 * u(rng);
    qd[i] = 0.1 * u(rng);
  }
  q[0] = 7.3;
  qd[0] = 2.0;
  q[1] = -0.002;  // the wheel presses into the deck
  // delta along the motion: the carriage is driven, so evaluate() takes its q
  // from the motion at t (7.3 + 2 t), the rest moves with qd.
  auto delta = [&](double t) {
    dyn->evaluate(t, q + t * qd, Eigen::VectorXd::Zero(n));
    return dyn->spring_state(0).delta;
  };
  const double d0 = delta(0.0);
  const double eps = 1e-7;
  const double rate = (delta(eps) - delta(-eps)) / (2 * eps);
  dyn->evaluate(0.0, q, qd);
  const runtime::SpringContactState st = dyn->spring_state(0);
  EXPECT_NEAR(st.delta, d0, kSameEvaluationTol);
  EXPECT_NEAR(st.rate, rate, kFdTol);
  EXPECT_NEAR(st.force, 5.0e6 * st.delta + 1.0e3 * st.rate, kForceLawRoundOff * std::abs(st.force));
  EXPECT_GT(st.force, 0.0);
}

TEST(SliderSpring, UnilateralNeverPulls) {
  const Model model = Model::parse(
      vehicle("10", "stiffness: 5.0e6, damping: 1.0e3, unilateral: true", kG), "never_pulls.yaml");
  const std::shared_ptr<runtime::CoupledDynamics> dyn = model.assembled().make_dynamics(false);
  const int n = dyn->n();
  std::mt19937 rng(7);
  std::normal_distribution<double> nd(0.0, 1.0);
  int pressed = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    Eigen::VectorXd q(n), qd(n);
    for (int i = 0; i < n; ++i) {
      q[i] = 1e-3 * nd(rng);
      qd[i] = 0.5 * nd(rng);
    }
    dyn->evaluate(0.0, q, qd);
    const runtime::SpringContactState& st = dyn->spring_state(0);
    EXPECT_GE(st.force, 0.0);
    if (st.delta <= 0.0) EXPECT_EQ(st.force, 0.0);
    pressed += st.force > 0.0;
  }
  EXPECT_GT(pressed, 100);  // both sides of the switch were visited
}

TEST(SliderSpring, DroppedWheelLiftsOffAndLands) {
  // Parked over midspan, 5 cm above the deck: it falls (0.101 s), lands, and
  // an undamped tyre throws it up again.
  const Model model = Model::parse(vehicle("10", "stiffness: 5.0e6, damping: 0.0, unilateral: true", kG, "",
                                           "initial: {q: {wheel: 0.05}}\n"),
                                   "dropped.yaml");
  Rows rows;
  runtime::SimulationRequest request = rk4(2e-4, 1.0);
  request.adjust = true;
  const runtime::SimulationReport report = model.simulate(request, rows);
  ASSERT_TRUE(report.message.empty()) << report.message;
  ASSERT_EQ(report.springs.size(), 1u);
  const int force = rows.column("force_tyre");
  double landed_at = -1.0;
  for (const auto& r : rows.values) {
    EXPECT_GE(r[force], 0.0);
    if (landed_at < 0 && r[force] > 0) landed_at = r[0];
  }
  // Free fall from 0.05 m onto a deck that sags under its own weight first.
  EXPECT_GT(landed_at, std::sqrt(2 * 0.05 / kG));
  EXPECT_GE(report.springs[0].lift_offs, 1);
  EXPECT_GT(report.springs[0].time_off, landed_at);
}

TEST(StaticStart, ParkedVehicleDeflectsAsTheClosedFormAndStaysThere) {
  const Model model = Model::parse(
      vehicle("10", "stiffness: 5.0e6, damping: 1.0e3, unilateral: true", kG, "", "initial: {static: true}\n"),
      "parked.yaml");
  // Hermite elements are exact at the nodes for point loads and uniform load.
  const double EI = kYoung * kInertia, q_weight = kDensity * kArea * kG, P = kWheelMass * kG;
  const double expected = P * std::pow(kLength, 3) / (48 * EI) + 5 * q_weight * std::pow(kLength, 4) / (384 * EI);
  // The original stiffness: the first row is the static start itself (a few
  // steps at the unadjusted model's stable step).
  Rows original;
  runtime::SimulationRequest request = rk4(1e-6, 1e-5);
  request.adjust = false;
  request.probes = {runtime::parse_probe("deck@10")};
  ASSERT_TRUE(model.simulate(request, original).message.empty());
  const int mid = original.column("deck@10");
  EXPECT_NEAR(-original.values[0][mid], expected, kNewtonRel * expected);
  // The tyre's force at the static start; why this bound is wider than the
  // deflection's was not recorded.
  constexpr double kFirstRowForceRel = 1e-6;
  EXPECT_NEAR(original.values[0][original.column("force_tyre")], P, kFirstRowForceRel * P);

  // The adjusted model (what the model runs with): its own equilibrium, where
  // the adjustment's stiffness of the modes above omega_limit moves the
  // midspan by a fraction of a millimetre, and no transient: the first 0.1 s
  // stay within 1e-6 (m) of the static state.
  Rows adjusted;
  request = rk4(2e-4, 0.1);
  request.adjust = true;
  request.probes = {runtime::parse_probe("deck@10")};
  request.state_in_rows = true;  // the drift below reads every coordinate
  const runtime::SimulationReport report = model.simulate(request, adjusted);
  ASSERT_TRUE(report.message.empty()) << report.message;
  constexpr double kAdjustedStaticShift = 1e-3;  // relative, measured 5.2e-4
  EXPECT_NEAR(-adjusted.values[0][mid], expected, kAdjustedStaticShift * expected);
  double drift = 0.0;
  for (const Eigen::VectorXd& q : adjusted.q) drift = std::max(drift, (q - adjusted.q[0]).cwiseAbs().maxCoeff());
  // m: a start at its own equilibrium stays there; the reason for 1e-6 was
  // not recorded.
  constexpr double kEquilibriumDrift = 1e-6;
  EXPECT_LT(drift, kEquilibriumDrift);
}

TEST(StaticStart, AFineStiffDeckUnderASoftlySprungBodyIsNoMechanism) {
  // models/vehicle_bridge_30m.yaml with 60 deck elements, original model: the
  // static Jacobian spans 80 1/s^2 (the car body on its springs) to ~1e13
  // (the rotations of 0.5 m elements), and the mechanism test once took that
  // condition number for a missing support. The equilibrium is statics by
  // hand: each axle carries half the body and its wheelset, 112,815 N.
  std::string yaml = test::read_text(std::string(MBFE_SOURCE_DIR) + "/models/vehicle_bridge_30m.yaml");
  const std::string from = "    elements: 30\n";
  ASSERT_NE(yaml.find(from), std::string::npos);
  yaml.replace(yaml.find(from), from.size(), "    elements: 60\n");
  LoadOptions options;
  options.cache_by_sources = true;  // the shipped model's solver: the beams are not in it
  const Model model = Model::parse(yaml, "vehicle_bridge_60.yaml", options);
  Rows rows;
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("generalized_alpha");
  request.step = 1e-5;
  request.t_end = 1e-5;
  request.every = 1;
  request.adjust = false;
  const runtime::SimulationReport report = model.simulate(request, rows);
  ASSERT_TRUE(report.message.empty()) << report.message;
  constexpr double kAxleLoad = (20000.0 / 2.0 + 1500.0) * 9.81;
  // Newton to round-off of the forces (1e-12 relative) and the central
  // differences' half stiffness at a just-touching contact, gone after one step.
  EXPECT_NEAR(rows.values[0][rows.column("force_front_approach")], kAxleLoad, kNewtonRel * kAxleLoad);
  EXPECT_NEAR(rows.values[0][rows.column("force_rear_approach")], kAxleLoad, kNewtonRel * kAxleLoad);
}

/// The independent model: a mass held on the deflected deck (rigid contact),
/// w(x, t) = sum_j a_j(t) sin(j pi x / L), the deck's own weight left out (the
/// FE model gets no gravity and a force of m g on the wheel instead):
///   (mu L / 2) (a_j'' + w_j^2 a_j) = -N phi_j(s),   m (y'' + g) = N,
///   y = w(s, t), s = v t:  y'' = sum_j (a_j'' phi_j + 2 v a_j' phi_j' + v^2 a_j phi_j'').
std::vector<double> independent_midspan(double v, double h, int steps, int modes) {
  const double mu = kDensity * kArea, EI = kYoung * kInertia;
  Eigen::VectorXd a = Eigen::VectorXd::Zero(modes), ad = Eigen::VectorXd::Zero(modes);
  auto accel = [&](double t, const Eigen::VectorXd& x, const Eigen::VectorXd& xd) {
    const double s = v * t;
    Eigen::VectorXd phi(modes), dphi(modes), ddphi(modes), w2(modes);
    for (int j = 0; j < modes; ++j) {
      const double k = (j + 1) * kPi / kLength;
      phi[j] = s <= kLength ? std::sin(k * s) : 0.0;
      dphi[j] = s <= kLength ? k * std::cos(k * s) : 0.0;
      ddphi[j] = -k * k * phi[j];
      w2[j] = std::pow(k, 4) * EI / mu;
    }
    // (mu L/2) a'' + m phi phi^T a'' = -(mu L/2) w^2 a - m phi (g + 2 v phi'.a' + v^2 phi''.a)
    const double c = mu * kLength / 2.0;
    Eigen::MatrixXd A = c * Eigen::MatrixXd::Identity(modes, modes) + kWheelMass * phi * phi.transpose();
    Eigen::VectorXd b = -c * w2.cwiseProduct(x) -
                        kWheelMass * phi * (kG + 2 * v * dphi.dot(xd) + v * v * ddphi.dot(x));
    return Eigen::VectorXd(A.ldlt().solve(b));
  };
  std::vector<double> out;
  double t = 0.0;
  auto midspan = [&] {
    double w = 0.0;
    for (int j = 0; j < modes; ++j) w += a[j] * std::sin((j + 1) * kPi / 2.0);
    return w;
  };
  out.push_back(midspan());
  for (int i = 0; i < steps; ++i) {
    const Eigen::VectorXd k1a = ad, k1v = accel(t, a, ad);
    const Eigen::VectorXd k2a = ad + 0.5 * h * k1v, k2v = accel(t + 0.5 * h, a + 0.5 * h * k1a, k2a);
    const Eigen::VectorXd k3a = ad + 0.5 * h * k2v, k3v = accel(t + 0.5 * h, a + 0.5 * h * k2a, k3a);
    const Eigen::VectorXd k4a = ad + h * k3v, k4v = accel(t + h, a + h * k3a, k4a);
    a += h / 6.0 * (k1a + 2 * k2a + 2 * k3a + k4a);
    ad += h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    t += h;
    out.push_back(midspan());
  }
  return out;
}

TEST(MovingMass, CrossingAgreesWithAnIndependentModalModel) {
  // A stiff, bilateral, damped tyre stands in for the rigid contact of the
  // independent model; its own weight is a force on the wheel.
  const double v = 20.0, h = 1e-4, t_end = 1.0;
  const Model model = Model::parse(
      vehicle("20*t", "stiffness: 1.0e9, damping: 2.0e5", 0.0, "[0, -9810.0]", "initial: {static: true}\n"),
      "moving_mass_check.yaml");
  Rows rows;
  runtime::SimulationRequest request = rk4(h, t_end);
  request.adjust = true;
  request.probes = {runtime::parse_probe("deck@10")};
  const runtime::SimulationReport report = model.simulate(request, rows);
  ASSERT_TRUE(report.message.empty()) << report.message;
  const std::vector<double> reference = independent_midspan(v, h, static_cast<int>(std::lround(t_end / h)), 25);
  ASSERT_EQ(rows.values.size(), reference.size());
  const int mid = rows.column("deck@10");
  double peak = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    peak = std::max(peak, std::abs(reference[i]));
    worst = std::max(worst, std::abs(rows.values[i][mid] - reference[i]));
  }
  // What separates the two: the tyre's compliance (m g / k = 1e-5 m against a
  // 0.08 m deflection, and its 1000 rad/s mode), 25 modes against 40
  // elements, and the adjusted damping of the modes above 2000 rad/s.
  constexpr double kAgreement = 0.005;  // of the peak midspan deflection (measured 0.14 %)
  EXPECT_LT(worst, kAgreement * peak) << "peak " << peak;
  // The mass matters: the same weight as a moving force (bridge_moving_force.yaml)
  // peaks at 0.0969 m during the crossing; the mass's inertia adds 16 %.
  EXPECT_GT(peak, 0.105);
}

}  // namespace
}  // namespace mbfe
