// Driven joints (`motion:`) in models with closed loops, where each drive is
// a driving constraint beside the loops' rows: the crank-driven four-bar
// against its position analysis and its drive torque in closed form (one
// degree of freedom, Lagrange: tau = m_eff theta'' + 1/2 m_eff' theta'^2 +
// V'), a free pendulum on a driven four-bar and a spatial slider-crank
// driven at its slider against the power balance (the drive's work equals
// the change of energy), both formulations agreeing, a static start that
// holds the drive against gravity, the advisor on a linkage with no degree
// of freedom left, and the errors of a linkage driven more than its loops
// allow.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "api/mbfe.h"
#include "tests/support/cli.h"
#include "tests/support/four_bar_oracle.h"
#include "tests/support/process.h"
#include "tests/support/recorded_rows.h"

namespace mbfe {
namespace {

using runtime::CoupledFormulation;

// kFourBarBodies with the crank's joint given `motion`, `extra` bodies, and
// `initial` entries of initial.q after the coupler's and the rocker's.
std::string four_bar_model(const std::string& name, const std::string& motion, const std::string& extra = "",
                           const std::string& initial = "", bool static_start = false) {
  std::string bodies = test::kFourBarBodies;
  const std::string free_crank = "joint: {type: revolute}, mass: 0.4";
  bodies.replace(bodies.find(free_crank), free_crank.size(),
                 "joint: {type: revolute, motion: \"" + motion + "\"}, mass: 0.4");
  const std::string loops = "constraints:\n";
  bodies.insert(bodies.find(loops), extra);
  return "model: " + name + "\ngravity: [0, -9.81]\n" + bodies +
         "initial: {q: {coupler: -0.5357560074605321, rocker: 1.2995365385792519" + initial + "}" +
         (static_start ? ", static: true" : "") + "}\n";
}

runtime::SimulationRequest request(double step, double t_end, CoupledFormulation formulation) {
  runtime::SimulationRequest r;
  r.integrator = runtime::parse_integrator("rk4");
  r.step = step;
  r.t_end = t_end;
  r.every = 1;
  r.formulation = formulation;
  return r;
}

test::RecordedRows run(const Model& model, double step, double t_end, CoupledFormulation formulation) {
  test::RecordedRows rows;
  const runtime::SimulationReport report = model.simulate(request(step, t_end, formulation), rows);
  EXPECT_EQ(report.message, "");
  return rows;
}

// The work of a drive, the integral of its force times its rate, from the
// first row to each even row, by Simpson's rule over rows equally spaced in
// t (O(h^4), as RK4's own error); NaN at odd rows.
std::vector<double> drive_work(const test::RecordedRows& rows, const std::string& body) {
  const std::vector<double> t = rows.series("t"), tau = rows.series(body + "_drive"),
                            rate = rows.series(body + "_dot");
  std::vector<double> work(t.size(), NAN);
  work[0] = 0.0;
  for (std::size_t k = 2; k < t.size(); k += 2) {
    const double h = 0.5 * (t[k] - t[k - 2]);
    work[k] = work[k - 2] + h / 3.0 * (tau[k - 2] * rate[k - 2] + 4.0 * tau[k - 1] * rate[k - 1] + tau[k] * rate[k]);
  }
  return work;
}

// Kinetic energy from the kernels' M at each row (nq, nv coordinates after t).
double kinetic_energy(const Model& model, const std::vector<double>& row, int nq, int nv) {
  State s;
  s.q.assign(row.begin() + 1, row.begin() + 1 + nq);
  s.qd.assign(row.begin() + 1 + nq, row.begin() + 1 + nq + nv);
  const Evaluation e = model.evaluate(s);
  const Eigen::Map<const Eigen::VectorXd> v(s.qd.data(), nv);
  return 0.5 * v.dot(e.M * v);
}

TEST(DrivenLoops, CrankDrivenFourBarFollowsItsPositionAnalysisAndTorque) {
  // With the crank driven the four-bar has no degree of freedom left: every
  // row is the closure's (Newton to 1e-13), J v = nu and J a = gamma solved
  // exactly, so the run is kinematics and inverse dynamics at round-off.
  // Measured: angles 4e-14 rad off the position analysis, torques 7e-8 N m
  // off the closed form, whose m_eff' is a difference of differences (the
  // torque swings between -2.3 and 1.4 N m).
  constexpr double kAngleTol = 1e-12;  // rad
  constexpr double kTorqueTol = 1e-6;  // N m
  constexpr double kOmega = 2.0;        // rad/s, the motion's rate
  const test::FourBar bar;
  const Model model = Model::parse(four_bar_model("four_bar_crank_driven", "1 + 2*t"), "four_bar_crank_driven.yaml");
  for (const CoupledFormulation f : {CoupledFormulation::kPartitioned, CoupledFormulation::kAugmented}) {
    SCOPED_TRACE(f == CoupledFormulation::kPartitioned ? "partitioned" : "augmented");
    const test::RecordedRows rows = run(model, 1e-3, 2.0, f);
    ASSERT_EQ(rows.columns.back(), "crank_drive");
    EXPECT_EQ(rows.units.back(), "N m");
    const int crank = rows.column("crank"), coupler = rows.column("coupler"), rocker = rows.column("rocker");
    double worst_angle = 0.0, worst_torque = 0.0;
    for (const std::vector<double>& r : rows.values) {
      const double theta = 1.0 + kOmega * r[0];
      EXPECT_EQ(r[crank], theta);  // the drive's row is solved exactly
      double phi, psi;
      bar.angles(theta, phi, psi);
      // Relative joint angles, unwrapped against the closed form's atan2.
      const double coupler_error = std::remainder(r[coupler] - (phi - theta), 2 * test::FourBar::kPi);
      const double rocker_error = std::remainder(r[rocker] - psi, 2 * test::FourBar::kPi);
      worst_angle = std::max({worst_angle, std::abs(coupler_error), std::abs(rocker_error)});
      constexpr double h = 1e-4;
      const double dm = (bar.effective_mass(theta + h) - bar.effective_mass(theta - h)) / (2 * h);
      const double torque = 0.5 * dm * kOmega * kOmega + bar.slope(theta);
      worst_torque = std::max(worst_torque, std::abs(r.back() - torque));
    }
    EXPECT_LT(worst_angle, kAngleTol);
    EXPECT_LT(worst_torque, kTorqueTol);
  }
}

TEST(DrivenLoops, AFreePendulumOnADrivenFourBarBalancesTheDrivesWork) {
  // A pendulum on the crank, free to swing, while the crank is driven with
  // an accelerating motion: one degree of freedom, integrated by RK4 at 1
  // ms. Energy of the whole (kinetic from the kernels' M, potential placed
  // here by hand) changes by the drive's work (4.8 J over 2 s): measured
  // 6e-10 J apart; the two formulations' RK4 errors differ by 5e-9.
  constexpr double kBalanceTol = 1e-8;    // J
  constexpr double kAgreementTol = 1e-7;  // rad, rad/s, N m
  const std::string pendulum =
      "  - {name: pendulum, parent: crank, joint: {type: revolute, at: [0.1, 0]}, mass: 0.5, inertia: 0.002,"
      " com: [0.15, 0], points: {bob: [0.3, 0]}}\n";
  const Model model =
      Model::parse(four_bar_model("four_bar_pendulum", "1 + 2*t + 0.3*sin(5*t)", pendulum, ", pendulum: 0.4"),
                   "four_bar_pendulum.yaml");
  const test::RecordedRows partitioned = run(model, 1e-3, 2.0, CoupledFormulation::kPartitioned);
  const test::RecordedRows augmented = run(model, 1e-3, 2.0, CoupledFormulation::kAugmented);
  ASSERT_EQ(partitioned.columns, augmented.columns);
  ASSERT_EQ(partitioned.values.size(), augmented.values.size());
  const std::vector<double> work = drive_work(partitioned, "crank");
  auto potential = [](const std::vector<double>& r) {
    // Rows: t, crank, coupler, rocker, pendulum, then the rates.
    const double y_pendulum = 0.1 * std::sin(r[1]) + 0.15 * std::sin(r[1] + r[4]);
    return 9.81 * 0.5 * y_pendulum +
           test::FourBar().potential(r[1]);  // the four-bar's bodies by its position analysis
  };
  std::vector<double> energy;
  for (const std::vector<double>& r : partitioned.values)
    energy.push_back(kinetic_energy(model, r, 4, 4) + potential(r));
  double worst_balance = 0.0, worst_agreement = 0.0, pendulum_swing = 0.0;
  const std::vector<double> swing = partitioned.series("pendulum");
  pendulum_swing = *std::max_element(swing.begin(), swing.end()) - *std::min_element(swing.begin(), swing.end());
  for (std::size_t k = 0; k < energy.size(); ++k) {
    if (k % 2 == 0) worst_balance = std::max(worst_balance, std::abs(energy[k] - energy.front() - work[k]));
    for (std::size_t i = 1; i < partitioned.values[k].size(); ++i)
      worst_agreement = std::max(worst_agreement, std::abs(partitioned.values[k][i] - augmented.values[k][i]));
  }
  EXPECT_GT(std::abs(work.back()), 0.1);  // the drive did work worth checking
  EXPECT_GT(pendulum_swing, 0.3);         // rad: the free coordinate moved
  EXPECT_LT(worst_balance, kBalanceTol);
  EXPECT_LT(worst_agreement, kAgreementTol);
}

TEST(DrivenLoops, AStaticStartHoldsTheDriveAndSettlesTheRest) {
  // The crank held at 1 rad by its drive, a pendulum hung from it released
  // near its lower equilibrium: the static start hangs it straight down
  // (absolute angle -pi/2) and the drive holds the four-bar's gravity moment
  // V'(1) plus the pendulum's, m g 0.1 cos(1) (its own weight acts on the
  // vertical through its pivot). Newton's static start stops at round-off;
  // V' is the oracle's central difference.
  constexpr double kAngleTol = 1e-12;  // rad
  constexpr double kTorqueTol = 1e-8;  // N m
  const std::string pendulum =
      "  - {name: pendulum, parent: crank, joint: {type: revolute, at: [0.1, 0]}, mass: 0.5, inertia: 0.002,"
      " com: [0.15, 0]}\n";
  const Model model = Model::parse(four_bar_model("four_bar_held", "1", pendulum, ", pendulum: -2.0", true),
                                   "four_bar_held.yaml");
  const test::RecordedRows rows = run(model, 1e-3, 0.1, CoupledFormulation::kPartitioned);
  ASSERT_FALSE(rows.values.empty());
  const std::vector<double>& first = rows.values.front();
  const std::vector<double>& last = rows.values.back();
  const double hanging = -test::FourBar::kPi / 2 - 1.0;
  const double torque = test::FourBar().slope(1.0) + 0.5 * 9.81 * 0.1 * std::cos(1.0);
  for (const std::vector<double>* r : {&first, &last}) {
    EXPECT_NEAR((*r)[rows.column("pendulum")], hanging, kAngleTol);
    EXPECT_NEAR((*r)[rows.column("crank_drive")], torque, kTorqueTol);
  }
}

TEST(DrivenLoops, ASpatialSliderCrankDrivenAtItsSliderBalancesTheDrivesWork) {
  // models/slider_crank_3d.yaml with its slider (after the rod's quaternion:
  // its entry of q is not its entry of v) driven about mid-stroke, from the
  // state the free mechanism reaches at t = 0.2 s; the rod's spin stays free.
  // Measured at RK4's 0.1 ms: balance 7e-15 J on energies of a few mJ, the
  // formulations 6e-14 apart, loop residual 2e-14 m.
  constexpr double kBalanceTol = 1e-11;   // J
  constexpr double kAgreementTol = 1e-10;
  constexpr double kResidualTol = 1e-12;  // m
  const std::string text = R"yaml(model: slider_crank_driven
dimension: 3
gravity: [0, 0, -9.81]
bodies:
  - {name: crank, parent: ground, joint: {type: revolute, axis: [0, 0, 1]}, mass: 0.5,
     inertia: [0.0002, 0.0008, 0.0009, 0, 0, 0], com: [0.05, 0, 0], points: {pin: [0.1, 0, 0]}}
  - {name: rod, parent: crank, joint: {type: spherical, at: [0.1, 0, 0]}, mass: 0.3,
     inertia: [0.00002, 0.004, 0.004, 0, 0, 0], com: [0.2, 0, 0], points: {end: [0.4, 0, 0]}}
  - {name: slider, parent: ground, joint: {type: prismatic, axis: [1, 0, 0], at: [0, 0.05, 0.1],
     motion: "0.39717386519351244 + 0.03*sin(4*t)"}, mass: 0.5, inertia: [0.0003, 0.0003, 0.0003, 0, 0, 0]}
constraints:
  - {name: rod_slider, type: point, a: {body: rod, point: end}, b: {body: slider, at: [0, 0, 0]}}
initial:
  q: {crank: 1.440357391494596,
      rod: [0.7004648730835159, 0.10437052520137201, -0.2753217023466923, -0.6501182317565039]}
)yaml";
  const Model model = Model::parse(text, "slider_crank_driven.yaml");
  const test::RecordedRows partitioned = run(model, 1e-4, 1.0, CoupledFormulation::kPartitioned);
  const test::RecordedRows augmented = run(model, 1e-4, 1.0, CoupledFormulation::kAugmented);
  ASSERT_EQ(partitioned.columns.back(), "slider_drive");
  EXPECT_EQ(partitioned.units.back(), "N");
  ASSERT_EQ(partitioned.values.size(), augmented.values.size());
  const std::vector<double> work = drive_work(partitioned, "slider");
  const int slider = partitioned.column("slider"), residual = partitioned.column("loop_residual");
  double worst_balance = 0.0, worst_agreement = 0.0, worst_residual = 0.0;
  double first_energy = 0.0;
  for (std::size_t k = 0; k < partitioned.values.size(); ++k) {
    const std::vector<double>& r = partitioned.values[k];
    EXPECT_EQ(r[slider], 0.39717386519351244 + 0.03 * std::sin(4 * r[0]));
    const Eigen::Quaterniond rod(r[2], r[3], r[4], r[5]);
    const double z_rod = (rod.normalized().toRotationMatrix() * Eigen::Vector3d(0.2, 0, 0)).z();
    const double energy = kinetic_energy(model, r, 6, 5) + 9.81 * (0.3 * z_rod + 0.5 * 0.1);
    if (k == 0) first_energy = energy;
    if (k % 2 == 0) worst_balance = std::max(worst_balance, std::abs(energy - first_energy - work[k]));
    worst_residual = std::max(worst_residual, r[residual]);
    for (std::size_t i = 1; i < r.size(); ++i)
      worst_agreement = std::max(worst_agreement, std::abs(r[i] - augmented.values[k][i]));
  }
  double largest_work = 0.0;
  for (std::size_t k = 0; k < work.size(); k += 2) largest_work = std::max(largest_work, std::abs(work[k]));
  EXPECT_GT(largest_work, 1e-3);  // J: the drive did work worth checking
  EXPECT_LT(worst_balance, kBalanceTol);
  EXPECT_LT(worst_agreement, kAgreementTol);
  EXPECT_LT(worst_residual, kResidualTol);
}

TEST(DrivenLoops, TheAdvisorSaysAKinematicLinkageHasNothingToLimitTheStep) {
  // models/four_bar_driven.yaml: the loop and the drive fix all three
  // coordinates (once a crash: a linearisation in no coordinates), from the
  // state as written and from a static start (once a crash too: a Newton
  // solve in no unknowns).
  for (const std::string& start : {std::string(), std::string(" --set initial.static=true")}) {
    SCOPED_TRACE(start);
    const test::CliRun r = test::run_cli("stability models/four_bar_driven.yaml" + start);
    ASSERT_EQ(r.status, 0) << r.all();
    EXPECT_NE(r.out.find("rigid, 0 DOF"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("rk4                 unconditional"), std::string::npos) << r.out;
  }
}

TEST(DrivenLoops, AKinematicLinkageStartsStaticAtItsMotion) {
  // No free coordinate: the static start is the closure at t = 0, and the
  // run is the one from the state as written.
  const Model model = Model::load(std::string(MBFE_SOURCE_DIR) + "/models/four_bar_driven.yaml");
  runtime::SimulationRequest given = request(1e-3, 0.1, CoupledFormulation::kPartitioned);
  given.static_start = false;
  runtime::SimulationRequest at_rest = given;
  at_rest.static_start = true;
  test::RecordedRows a, b;
  EXPECT_EQ(model.simulate(given, a).message, "");
  EXPECT_EQ(model.simulate(at_rest, b).message, "");
  ASSERT_EQ(a.values.size(), b.values.size());
  EXPECT_EQ(a.values.back(), b.values.back());
}

TEST(DrivenLoops, ALinkageDrivenMoreThanItsLoopsAllowIsRefused) {
  const test::TempDir dir;
  // Crank and rocker both driven: 2 loop rows + 2 drives on 3 coordinates.
  std::string text = four_bar_model("four_bar_over_driven", "1 + 2*t");
  const std::string rocker = "joint: {type: revolute, at: [0.6, 0]}";
  text.replace(text.find(rocker), rocker.size(), "joint: {type: revolute, at: [0.6, 0], motion: \"1.3\"}");
  text.replace(text.find(", rocker: 1.2995365385792519"), std::string(", rocker: 1.2995365385792519").size(), "");
  const std::string path = (dir / "over_driven.yaml").string();
  test::spit(path, text);
  const test::CliRun r = test::run_cli("simulate " + path + " --t-end 0.01 --out " + (dir / "o.csv").string());
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_NE(r.err.find("its loops have 2 constraint rows and its driven joints 2 but the tree only 3"),
            std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace mbfe
