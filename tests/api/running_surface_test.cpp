// Slider contacts on a beam's running surface (`profile:`, `camber:`), through
// the generated kernels and the runtime: a quarter car on a sinusoidal rail
// against the closed-form steady-state response, a slider_pin's constraint
// against the profile's value, slope and curvature, and a slow vehicle on a
// bridge cambered for its dead load against the static deflection under the
// vehicle alone, and the static start of a wheel over a rail below the beam's
// axis against the closed-form static deflections.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <fstream>
#include <sstream>
#include <string>

#include "api/mbfe.h"
#include "tests/support/recorded_rows.h"

namespace mbfe {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// A quarter car at `speed` on a rigid rail (250 m, pinned every 2 m, a
/// steel section 1e4 times stiffer than the tyre's spring over an element)
/// whose running surface is a + 0.002 sin(2 pi s / 25): body 1000 kg on
/// 4e4 N/m and 2e3 N s/m over a 50 kg wheel, tyre 5e7 N/m and 1e4 N s/m.
std::string quarter_car(const std::string& profile) {
  std::ostringstream supports;
  for (int k = 0; k <= 125; ++k) supports << (k ? ", " : "") << "{at: " << 2 * k << ".0, type: pinned}";
  return R"yaml(model: quarter_car
gravity: [0, 0]
bodies:
  - {name: carriage, parent: ground, joint: {type: prismatic, axis: [1, 0], at: [0.0, 0.0], motion: "20*t"}, mass: 0.0, inertia: 0.0}
  - {name: body, parent: carriage, joint: {type: prismatic, axis: [0, 1], at: [0.0, 0.0]}, mass: 1000.0, inertia: 0.0}
  - {name: wheel, parent: body, joint: {type: prismatic, axis: [0, 1], at: [0.0, 0.0]}, mass: 50.0, inertia: 0.0,
     points: {contact: [0.0, 0.0]}}
loads:
  - {type: spring_damper, joint: wheel, stiffness: 4.0e4, damping: 2.0e3, rest: 0.0}
beams:
  - name: rail
    origin: [0.0, 0.0]
    length: 250.0
    elements: 125
    section: {area: 0.01, inertia: 1.0e-4}
    material: {youngs_modulus: 2.1e11, density: 7850}
    supports: [)yaml" + supports.str() + R"yaml(]
    profile: )yaml" + profile + R"yaml(
contacts:
  - {name: tyre, type: slider_spring, body: wheel, point: contact, beam: rail, stiffness: 5.0e7, damping: 1.0e4}
)yaml";
}

// Body M on (k, c) over wheel m on tyre (k_t, c_t) on a rigid surface moving
// as a e^{i omega t}: the body's complex amplitude from the 2x2 system
//   [k + i w c - M w^2,  -(k + i w c)                    ] [Y_b]   [0                 ]
//   [-(k + i w c),        k + k_t + i w (c + c_t) - m w^2] [Y_w] = [(k_t + i w c_t) a ]
double body_amplitude(double omega, double a) {
  using C = std::complex<double>;
  const double M = 1000, k = 4e4, c = 2e3, m = 50, kt = 5e7, ct = 1e4;
  const C a11(k - M * omega * omega, omega * c), a12(-k, -omega * c);
  const C a22(k + kt - m * omega * omega, omega * (c + ct)), b2 = C(kt, omega * ct) * a;
  return std::abs(-a12 * b2 / (a11 * a22 - a12 * a12));
}

TEST(ProfiledContacts, QuarterCarOnASinusoidalRailFollowsTheClosedFormResponse) {
  const Model model = Model::parse(quarter_car("{expression: \"0.002*sin(2*pi*s/25)\"}"), "quarter_car.yaml");
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("generalized_alpha");  // the rail's own modes are stiff
  request.step = 1e-3;
  request.t_end = 12.0;
  request.every = 1;
  test::RecordedRows rows;
  const runtime::SimulationReport report = model.simulate(request, rows);
  ASSERT_TRUE(report.message.empty()) << report.message;
  // Steady state: the body's free motion decays as exp(-zeta omega_n t) =
  // exp(-1/s t), 5e-5 of the start by t = 10 s; two periods of 1.25 s follow.
  const std::vector<double> t = rows.series("t"), y = rows.series("body");
  double lo = 1e9, hi = -1e9;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= 10.0) lo = std::min(lo, y[i]), hi = std::max(hi, y[i]);
  const double omega = 2 * kPi * 20.0 / 25.0;
  // Generalized-alpha's phase and amplitude errors at omega h = 5e-3, the
  // rail's deflection under the tyre (1e-8 m) and the decayed transient.
  constexpr double kAmplitudeTol = 1e-3;  // relative
  EXPECT_NEAR((hi - lo) / 2 / body_amplitude(omega, 0.002), 1.0, kAmplitudeTol);
}

TEST(ProfiledContacts, QuarterCarOnATableSampledFromTheSameRailRespondsTheSame) {
  // The rail of the test above as a table every 0.1 m, next to the model file.
  const std::string dir = ::testing::TempDir();
  {
    std::ofstream table(dir + "/sine_rail.csv");
    table.precision(17);
    table << "s,offset\n";
    for (int k = 0; k <= 2500; ++k) table << 0.1 * k << "," << 0.002 * std::sin(2 * kPi * 0.1 * k / 25) << "\n";
  }
  const Model model = Model::parse(quarter_car("{file: sine_rail.csv}"), dir + "/quarter_car_table.yaml");
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("generalized_alpha");
  request.step = 1e-3;
  request.t_end = 12.0;
  request.every = 1;
  test::RecordedRows rows;
  const runtime::SimulationReport report = model.simulate(request, rows);
  ASSERT_TRUE(report.message.empty()) << report.message;
  const std::vector<double> t = rows.series("t"), y = rows.series("body");
  double lo = 1e9, hi = -1e9;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= 10.0) lo = std::min(lo, y[i]), hi = std::max(hi, y[i]);
  // The chords of a sine 0.1 m apart: the table is low by up to h^2 k^2 / 8 =
  // 8e-5 of the amplitude, and its kinks add harmonics at 200 rad/s, far
  // above the body's 6.3 rad/s, which the suspension filters.
  constexpr double kAmplitudeTol = 1e-3;  // relative
  EXPECT_NEAR((hi - lo) / 2 / body_amplitude(2 * kPi * 20.0 / 25.0, 0.002), 1.0, kAmplitudeTol);
}

// A point sliding on a 10 m beam (10 elements, pinned ends) whose surface is
// r(s) = 0.01 sin(s) + 0.002 s^2.
const std::string kSliderPin = R"yaml(model: slider_on_profile
gravity: [0, -9.81]
bodies:
  - {name: cart, parent: ground, joint: {type: prismatic, axis: [1, 0]}, mass: 1.0, inertia: 0.0}
  - {name: slider, parent: cart, joint: {type: prismatic, axis: [0, 1]}, mass: 1.0, inertia: 0.0, points: {p: [0.0, 0.0]}}
beams:
  - name: rail
    origin: [0.0, 0.0]
    length: 10.0
    elements: 10
    section: {area: 0.01, inertia: 1.0e-4}
    material: {youngs_modulus: 2.1e11, density: 7850}
    supports: [{at: 0.0, type: pinned}, {at: 10.0, type: pinned}]
    profile: {expression: "0.01*sin(s) + 0.002*s^2"}
contacts:
  - {name: glide, type: slider_pin, body: slider, point: p, beam: rail}
)yaml";

TEST(ProfiledContacts, SliderPinConstraintReadsTheProfilesValueSlopeAndCurvature) {
  const Model model = Model::parse(kSliderPin, "slider_on_profile.yaml");
  constexpr double kKernelTol = 1e-12;  // generated kernels: round-off on O(1) values
  // Straight beam: Phi = r(s) - y, J_b = [r'(s), -1], gamma = -r''(s) x'^2.
  State state;
  state.q = {3.3, 0.02};
  state.qd = {2.0, -0.5};
  const Evaluation e = model.evaluate(state);
  ASSERT_TRUE(e.has_constraints);
  const double s = 3.3;
  EXPECT_NEAR(e.phi[0], 0.01 * std::sin(s) + 0.002 * s * s - 0.02, kKernelTol);
  EXPECT_NEAR(e.jb(0, 0), 0.01 * std::cos(s) + 0.004 * s, kKernelTol);
  EXPECT_NEAR(e.jb(0, 1), -1.0, kKernelTol);
  EXPECT_NEAR(e.gamma[0], -(-0.01 * std::sin(s) + 0.004) * 4.0, kKernelTol);
  // Bent beam: J_b against central differences of Phi, gamma against the
  // second difference of Phi along q + q' tau (q'' = 0: d2Phi/dtau2 = -gamma).
  state.qc.resize(20);
  state.qcd.resize(20);
  for (int i = 0; i < 20; ++i) {
    state.qc[i] = 1e-3 * std::sin(0.7 * i + 0.3);
    state.qcd[i] = 2e-3 * std::cos(1.3 * i);
  }
  const Evaluation bent = model.evaluate(state);
  constexpr double h = 1e-4;              // step of the differences
  constexpr double kDifferenceTol = 1e-7; // h^2 |Phi'''| / 6 and round-off 1e-16 / h^2
  for (int j = 0; j < 2; ++j) {
    State plus = state, minus = state;
    plus.q[j] += h;
    minus.q[j] -= h;
    EXPECT_NEAR(bent.jb(0, j), (model.evaluate(plus).phi[0] - model.evaluate(minus).phi[0]) / (2 * h),
                kDifferenceTol);
  }
  State plus = state, minus = state;
  for (int j = 0; j < 2; ++j) plus.q[j] += h * state.qd[j], minus.q[j] -= h * state.qd[j];
  for (int i = 0; i < 20; ++i) plus.qc[i] += h * state.qcd[i], minus.qc[i] -= h * state.qcd[i];
  const double second = (model.evaluate(plus).phi[0] - 2 * bent.phi[0] + model.evaluate(minus).phi[0]) / (h * h);
  // The second difference divides the round-off by h^2, not 2 h: a bound a
  // thousand times the first difference's.
  constexpr double kSecondDifferenceTol = 1e3 * kDifferenceTol;
  EXPECT_NEAR(bent.gamma[0], -second, kSecondDifferenceTol);
}

/// A 20 t mass on a tyre (1e9 N/m, 2e6 N s/m) driven at 1 m/s across a 30 m
/// simply supported concrete deck (10 t/m, EI = 5.256e10 N m^2; own-weight
/// sag 19.7 mm) from s = 5 m, gravity on, static start; `camber` is the
/// beam's camber line ("" for none).
std::string slow_vehicle(const std::string& camber) {
  return R"yaml(model: slow_vehicle
gravity: [0, -9.81]
bodies:
  - {name: carriage, parent: ground, joint: {type: prismatic, axis: [1, 0], at: [5.0, 0.0], motion: "1.0*t"}, mass: 0.0, inertia: 0.0}
  - {name: body, parent: carriage, joint: {type: prismatic, axis: [0, 1], at: [0.0, 0.0]}, mass: 20000.0, inertia: 0.0,
     points: {contact: [0.0, 0.0]}}
beams:
  - name: deck
    origin: [0.0, 0.0]
    length: 30.0
    elements: 30
    section: {area: 4.0, inertia: 1.46}
    material: {youngs_modulus: 3.6e10, density: 2500}
    damping: {rayleigh: {alpha: 0.457, beta: 7.24e-5}}
    supports: [{at: 0.0, type: pinned}, {at: 30.0, type: pinned}]
    )yaml" + camber + R"yaml(
contacts:
  - {name: tyre, type: slider_spring, body: body, point: contact, beam: deck, stiffness: 1.0e9, damping: 2.0e6, unilateral: true}
initial: {static: true}
)yaml";
}

TEST(ProfiledContacts, StaticCamberLeavesASlowVehicleOnAStraightRail) {
  const double W = 20000 * 9.81, k = 1e9, L = 30, EI = 3.6e10 * 1.46, q = 4.0 * 2500 * 9.81;
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("generalized_alpha");
  request.step = 2e-3;
  request.t_end = 8.0;
  request.every = 1;
  // Quasi-static (speed parameter v / (2 f L) = 1/240): the body sits on the
  // surface under its weight, the tyre compressed W / k, and the surface under
  // it is the deck's deflection under the vehicle alone, W a^2 (L - a)^2 /
  // (3 EI L) at a = 5 + t (the finite elements are exact at the nodes and
  // within 1e-8 m between). The dynamic part is below 1 % of the 2 mm.
  constexpr double kHeightTol = 2e-5;   // m
  constexpr double kForceTol = 5e-3;    // relative: the deck's 4 Hz response to the moving load
  for (const bool camber : {true, false}) {
    const Model model = Model::parse(slow_vehicle(camber ? "camber: static" : ""), "slow_vehicle.yaml");
    test::RecordedRows rows;
    const runtime::SimulationReport report = model.simulate(request, rows);
    ASSERT_TRUE(report.message.empty()) << report.message;
    const std::vector<double> t = rows.series("t"), y = rows.series("body"), force = rows.series("force_tyre");
    for (std::size_t i = 0; i < t.size(); i += 100) {
      const double a = 5.0 + t[i];
      const double under_vehicle = -W * a * a * (L - a) * (L - a) / (3 * EI * L);
      const double sag = -q * a * (L * L * L - 2 * L * a * a + a * a * a) / (24 * EI);
      const double expected = under_vehicle - W / k + (camber ? 0.0 : sag);
      EXPECT_NEAR(y[i], expected, kHeightTol) << (camber ? "camber" : "no camber") << ", t = " << t[i];
      if (camber) EXPECT_NEAR(force[i] / W, 1.0, kForceTol) << "t = " << t[i];
    }
  }
}

// A 10 kg pan head pressed up with 100 N against a contact wire from below
// (`side: below`: delta = y_P - surface) while driven along it at 1 m/s; the
// wire (20 m, pinned every metre, stiff) has a height irregularity.
const std::string kPanUnderWire = R"yaml(model: pan_under_wire
gravity: [0, 0]
bodies:
  - {name: carriage, parent: ground, joint: {type: prismatic, axis: [1, 0], at: [1.0, 0.0], motion: "1.0*t"}, mass: 0.0, inertia: 0.0}
  - {name: head, parent: carriage, joint: {type: prismatic, axis: [0, 1], at: [0.0, 0.0]}, mass: 10.0, inertia: 0.0,
     points: {strip: [0.0, 0.0]}}
loads:
  - {type: force, body: head, value: [0, 100.0]}
beams:
  - name: wire
    origin: [0.0, 0.0]
    length: 20.0
    elements: 20
    section: {area: 0.01, inertia: 1.0e-4}
    material: {youngs_modulus: 2.1e11, density: 7850}
    supports: [{at: 0.0, type: pinned}, {at: 1.0, type: pinned}, {at: 2.0, type: pinned}, {at: 3.0, type: pinned}, {at: 4.0, type: pinned}, {at: 5.0, type: pinned}, {at: 6.0, type: pinned}, {at: 7.0, type: pinned}, {at: 8.0, type: pinned}, {at: 9.0, type: pinned}, {at: 10.0, type: pinned}, {at: 11.0, type: pinned}, {at: 12.0, type: pinned}, {at: 13.0, type: pinned}, {at: 14.0, type: pinned}, {at: 15.0, type: pinned}, {at: 16.0, type: pinned}, {at: 17.0, type: pinned}, {at: 18.0, type: pinned}, {at: 19.0, type: pinned}, {at: 20.0, type: pinned}]
    profile: {expression: "0.005*sin(2*pi*s/10)"}
contacts:
  - {name: strip, type: slider_spring, side: below, body: head, point: strip, beam: wire, stiffness: 1.0e6, damping: 1.0e3,
     unilateral: true}
initial: {static: true, q: {head: 0.01}}
)yaml";

TEST(ProfiledContacts, PanHeadUnderAWireFollowsItsHeightIrregularity) {
  const Model model = Model::parse(kPanUnderWire, "pan_under_wire.yaml");
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("generalized_alpha");
  request.step = 1e-3;
  request.t_end = 5.0;
  request.every = 1;
  test::RecordedRows rows;
  const runtime::SimulationReport report = model.simulate(request, rows);
  ASSERT_TRUE(report.message.empty()) << report.message;
  // Quasi-static (0.63 rad/s against the head's 316 rad/s on the strip): the
  // head sits F / k = 1e-4 m into the wire's surface, y = r(s) + F / k. The
  // damper's c v r'(s) (up to 3 N of the 100) shifts it by up to 3e-6 m.
  constexpr double kHeightTol = 1e-5;  // m, against a 5 mm irregularity
  constexpr double kPressTol = 5.0;    // N, of the 100 N press: the damper's c v r'(s) adds up to 3 N
  const std::vector<double> t = rows.series("t"), y = rows.series("head"), force = rows.series("force_strip");
  for (std::size_t i = 0; i < t.size(); i += 50) {
    const double s = 1.0 + t[i];
    EXPECT_NEAR(y[i], 0.005 * std::sin(2 * kPi * s / 10) + 1e-4, kHeightTol) << "t = " << t[i];
    EXPECT_NEAR(force[i], 100.0, kPressTol) << "t = " << t[i];
  }
}

/// A 1000 kg wheel at midspan of a 20 m simply supported steel deck with
/// gravity on, on a compression-only tyre `law` ("stiffness: 5.0e6,
/// unilateral: true" or "law: hertz, coefficient: ..."), whose rail lies
/// 2 mm below the deck's axis under it: r(s) = -0.004 + 0.002 cos(2 pi s / 5),
/// r(10) = -0.002, r'(10) = 0. Started at height 0, the wheel touches the
/// axis but not the rail.
std::string wheel_over_a_low_rail(const std::string& law) {
  return R"yaml(model: wheel_over_a_low_rail
gravity: [0, -9.81]
bodies:
  - {name: carriage, parent: ground, joint: {type: prismatic, axis: [1, 0], at: [10.0, 0.0], motion: "0*t"}, mass: 0.0, inertia: 0.0}
  - {name: wheel, parent: carriage, joint: {type: prismatic, axis: [0, 1], at: [0.0, 0.0]}, mass: 1000.0, inertia: 0.0,
     points: {contact: [0.0, 0.0]}}
beams:
  - name: deck
    origin: [0.0, 0.0]
    length: 20.0
    elements: 40
    section: {area: 0.01, inertia: 1.0e-4}
    material: {youngs_modulus: 2.1e11, density: 7850}
    supports: [{at: 0.0, type: pinned}, {at: 20.0, type: pinned}]
    profile: {expression: "-0.004 + 0.002*cos(2*pi*s/5)"}
contacts:
  - {name: tyre, type: slider_spring, body: wheel, point: contact, beam: deck, )yaml" + law + R"yaml(}
initial: {static: true}
)yaml";
}

TEST(ProfiledContacts, StaticStartSeatsTheWheelOnARailBelowTheAxis) {
  // Closed form: the deck at midspan sags under its own weight and the
  // wheel's, 5 q L^4 / (384 EI) + W L^3 / (48 EI) (Hermite elements are exact
  // at the nodes; s = 10 is one), the tyre carries the weight W, and the
  // wheel sits at r(10) + w(10) minus the tyre's compression: W / k for the
  // linear tyre, (W / C_H)^(2/3) for Hertz's.
  const double W = 1000 * 9.81, L = 20, EI = 2.1e11 * 1e-4, q = 7850 * 0.01 * 9.81;
  const double w_mid = -(5 * q * L * L * L * L / (384 * EI) + W * L * L * L / (48 * EI));
  const double r_mid = -0.002, k = 5e6, C_H = 1e10;
  // The static Newton converges to 1e-12 of the coordinates, or stalls below
  // 1e-9 of them (0.15 m here): heights to 1e-9 m, the force to 1e-6 of W.
  constexpr double kHeightTol = 1e-9;  // m
  constexpr double kForceTol = 1e-6;   // relative
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("rk4");
  request.step = 1e-5;
  request.t_end = 1e-5;
  request.every = 1;
  for (const auto& [law, compression] :
       {std::pair<std::string, double>{"stiffness: 5.0e6, unilateral: true", W / k},
        {"law: hertz, coefficient: 1.0e10", std::pow(W / C_H, 2.0 / 3.0)}}) {
    const Model model = Model::parse(wheel_over_a_low_rail(law), "wheel_over_a_low_rail.yaml");
    test::RecordedRows rows;
    const runtime::SimulationReport report = model.simulate(request, rows);
    ASSERT_TRUE(report.message.empty()) << law << ": " << report.message;
    ASSERT_FALSE(rows.values.empty());
    EXPECT_NEAR(rows.series("force_tyre")[0] / W, 1.0, kForceTol) << law;
    EXPECT_NEAR(rows.series("deflection_tyre")[0], w_mid, kHeightTol) << law;
    EXPECT_NEAR(rows.series("wheel")[0], r_mid + w_mid - compression, kHeightTol) << law;
  }
}

}  // namespace
}  // namespace mbfe
