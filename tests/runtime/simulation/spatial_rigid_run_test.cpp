// Runs of spatial trees (dimension: 3) through the API: the shipped 3D double
// pendulum against its equations of motion written by hand and integrated
// here by the same RK4, its energy (kinetic from M, potential from the
// centres of mass placed here) over an undamped run, the CSV layout of
// mbfe simulate, its small swings (the linearisation mbfe stability takes);
// and a torque-free rigid body on a free joint, whose
// energy and angular momentum stay constant and whose quaternion stays unit.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "api/mbfe.h"
#include "tests/support/cli.h"
#include "tests/support/process.h"
#include "tests/support/recorded_rows.h"

namespace mbfe {
namespace {

std::string source_path(const std::string& relative) { return std::string(MBFE_SOURCE_DIR) + "/" + relative; }

runtime::SimulationRequest request(const char* integrator, double step, double t_end) {
  runtime::SimulationRequest r;
  r.integrator = runtime::parse_integrator(integrator);
  r.step = step;
  r.t_end = t_end;
  r.every = 1;
  return r;
}

// models/double_pendulum_3d.yaml by hand (tests/tool/cmd_eval_spatial_test.cpp
// derives these): M11 = B1 + m1 a1^2 + m2 L^2 + B2 c2^2 + C2 s2^2,
// M22 = A2 + m2 a2^2, M12 = 0, L = l1 + a2 c2; F1 = M11' q1' q2',
// F2 = -1/2 M11' q1'^2; Q1 = -g s1 (m1 a1 + m2 L), Q2 = -g m2 a2 c1 s2.
struct DoublePendulum3d {
  double m1 = 1.0, a1 = 0.5, l1 = 1.0, B1 = 0.08;
  double m2 = 0.8, a2 = 0.4, A2 = 0.043, B2 = 0.042, C2 = 0.003;
  double g = 9.81;

  // y = (q1, q2, v1, v2)
  Eigen::Vector4d rate(const Eigen::Vector4d& y) const {
    const double s1 = std::sin(y[0]), c1 = std::cos(y[0]), s2 = std::sin(y[1]), c2 = std::cos(y[1]);
    const double L = l1 + a2 * c2;
    const double m11 = B1 + m1 * a1 * a1 + m2 * L * L + B2 * c2 * c2 + C2 * s2 * s2;
    const double m22 = A2 + m2 * a2 * a2;
    const double dm11 = -2 * m2 * L * a2 * s2 + 2 * (C2 - B2) * s2 * c2;
    const double f1 = dm11 * y[2] * y[3], f2 = -0.5 * dm11 * y[2] * y[2];
    const double q1 = -g * s1 * (m1 * a1 + m2 * L), q2 = -g * m2 * a2 * c1 * s2;
    return {y[2], y[3], (q1 - f1) / m11, (q2 - f2) / m22};
  }

  // The centres of mass in the ground frame: link 1 turned by Ry(q1), link 2
  // by Ry(q1) Rx(q2) about link 1's tip (0, 0, -l1).
  double potential(double q1, double q2) const {
    const Eigen::Matrix3d r1 = Eigen::AngleAxisd(q1, Eigen::Vector3d::UnitY()).toRotationMatrix();
    const Eigen::Matrix3d r2 = r1 * Eigen::AngleAxisd(q2, Eigen::Vector3d::UnitX()).toRotationMatrix();
    const Eigen::Vector3d com1 = r1 * Eigen::Vector3d(0, 0, -a1);
    const Eigen::Vector3d com2 = r1 * Eigen::Vector3d(0, 0, -l1) + r2 * Eigen::Vector3d(0, 0, -a2);
    return g * (m1 * com1.z() + m2 * com2.z());
  }
};

TEST(SpatialRigidRun, DoublePendulum3dFollowsItsEquationsByHand) {
  // The same RK4 with the same step on the same equations: what differs is
  // the kernels' rounding, grown over 1 s of a double pendulum's motion.
  constexpr double kTrajectoryTol = 1e-10;
  constexpr double kStep = 1e-3, kEnd = 1.0;
  const Model model = Model::load(source_path("models/double_pendulum_3d.yaml"));
  test::RecordedRows rows;
  const runtime::SimulationReport report = model.simulate(request("rk4", kStep, kEnd), rows);
  ASSERT_EQ(report.message, "");
  ASSERT_EQ(rows.columns, (std::vector<std::string>{"t", "link1", "link2", "link1_dot", "link2_dot"}));
  EXPECT_EQ(rows.units, (std::vector<std::string>{"s", "rad", "rad", "rad/s", "rad/s"}));

  const DoublePendulum3d p;
  Eigen::Vector4d y(0.6, -0.4, 0.0, 1.5);  // the model's initial: block
  const int steps = static_cast<int>(std::lround(kEnd / kStep));
  for (int k = 0; k < steps; ++k) {
    const Eigen::Vector4d k1 = p.rate(y), k2 = p.rate(y + 0.5 * kStep * k1), k3 = p.rate(y + 0.5 * kStep * k2),
                          k4 = p.rate(y + kStep * k3);
    y += kStep / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  const std::vector<double>& last = rows.values.back();
  constexpr double kTimeRoundOff = 1e-12;  // s: 1000 sums of the step
  EXPECT_NEAR(last[0], kEnd, kTimeRoundOff);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(last[1 + i], y[i], kTrajectoryTol) << rows.columns[1 + i];
}

TEST(SpatialRigidRun, UndampedDoublePendulum3dConservesEnergy) {
  // RK4 at 1 ms over 5 s: the energy error is O(h^4), measured 2e-10 J of
  // about 10 J (swing amplitude 0.6 rad, 1.5 rad/s).
  constexpr double kEnergyTol = 1e-8;  // J
  const Model model = Model::load(source_path("models/double_pendulum_3d.yaml"));
  test::RecordedRows rows;
  ASSERT_EQ(model.simulate(request("rk4", 1e-3, 5.0), rows).message, "");
  const DoublePendulum3d p;
  double first = NAN, worst = 0.0, swing = 0.0;
  for (const std::vector<double>& r : rows.values) {
    State s;
    s.q = {r[1], r[2]};
    s.qd = {r[3], r[4]};
    const Evaluation e = model.evaluate(s);
    const Eigen::Vector2d v(r[3], r[4]);
    const double energy = 0.5 * v.dot(e.M * v) + p.potential(r[1], r[2]);
    if (std::isnan(first)) first = energy;
    worst = std::max(worst, std::abs(energy - first));
    swing = std::max(swing, std::abs(r[2]));
  }
  EXPECT_LT(worst, kEnergyTol);
  EXPECT_GT(swing, 0.4);  // it moved
}

TEST(SpatialRigidRun, SimulateWritesTheRigidLayoutAndSidecar) {
  const test::TempDir dir;
  const std::string out = (dir / "dp3d.csv").string();
  const test::CliRun r = test::run_cli("simulate models/double_pendulum_3d.yaml --t-end 0.05 --out " + out);
  ASSERT_EQ(r.status, 0) << r.all();
  const test::Csv csv = test::read_csv(out);
  EXPECT_EQ(csv.header, (std::vector<std::string>{"t", "link1", "link2", "link1_dot", "link2_dot"}));
  EXPECT_EQ(csv.rows.size(), 51u);
  std::ifstream sidecar(out + ".json");
  EXPECT_TRUE(sidecar.good());
}

TEST(SpatialRigidRun, DoublePendulum3dLinearisesToItsSmallSwings) {
  // Hanging straight down (q = 0) the two swings decouple (M12 = 0, and the
  // gravity stiffnesses are diagonal): omega1^2 = g (m1 a1 + m2 (l1 + a2)) /
  // M11(0), omega2^2 = g m2 a2 / M22. The linearisation takes central
  // differences (relative step 1e-6): ~1e-9 relative.
  constexpr double kLinearizationTol = 1e-6;  // rad/s
  const DoublePendulum3d p;
  const double m11 = p.B1 + p.m1 * p.a1 * p.a1 + p.m2 * (p.l1 + p.a2) * (p.l1 + p.a2) + p.B2;
  const double omega1 = std::sqrt(p.g * (p.m1 * p.a1 + p.m2 * (p.l1 + p.a2)) / m11);
  const double omega2 = std::sqrt(p.g * p.m2 * p.a2 / (p.A2 + p.m2 * p.a2 * p.a2));
  const runtime::ModelSpectrum spectrum = Model::load(source_path("models/double_pendulum_3d.yaml")).spectrum(false);
  EXPECT_TRUE(spectrum.at_equilibrium);
  ASSERT_EQ(spectrum.full.eigenvalues.size(), 4u);
  // Sorted by modulus, +imag first in each pair.
  EXPECT_NEAR(spectrum.full.eigenvalues[0].imag(), omega1, kLinearizationTol);
  EXPECT_NEAR(spectrum.full.eigenvalues[2].imag(), omega2, kLinearizationTol);
  EXPECT_NEAR(spectrum.full.eigenvalues[2].real(), 0.0, kLinearizationTol);
}

// A torque-free rigid body on a free joint (no gravity): centre of mass at
// the body frame's origin, inertia with products, spinning near its
// intermediate axis (the unstable one, so the motion is not trivial).
const char* kTumbler = R"(model: tumbler
dimension: 3
gravity: [0, 0, 0]
bodies:
  - name: box
    parent: ground
    joint: {type: free}
    mass: 2.0
    inertia: [0.03, 0.05, 0.07, 0.004, -0.002, 0.003]
    points: {corner: [0.1, 0.2, 0.3]}
initial:
  q: {box: [0.1, -0.2, 0.3, 0.8, 0.2, -0.4, 0.4]}
  qd: {box: [0.5, 0.0, -0.3, 0.05, 6.0, 0.1]}
)";

TEST(SpatialRigidRun, TorqueFreeBodyConservesEnergyAndAngularMomentum) {
  // RK4 at 1 ms over 4 s of a body turning at ~1 rev/s: energy and angular
  // momentum drift by O(h^4), measured below 1e-9 relative.
  constexpr double kConservedTol = 1e-8;
  // Renormalised after every step: a unit quaternion to round-off.
  constexpr double kUnitTol = 1e-14;
  const Model model = Model::parse(kTumbler, "tumbler.yaml");
  test::RecordedRows rows;
  ASSERT_EQ(model.simulate(request("rk4", 1e-3, 4.0), rows).message, "");
  EXPECT_EQ(rows.columns, (std::vector<std::string>{"t", "box_x", "box_y", "box_z", "box_qw", "box_qx", "box_qy",
                                                    "box_qz", "box_vx", "box_vy", "box_vz", "box_wx", "box_wy",
                                                    "box_wz"}));
  EXPECT_EQ(rows.units[4], "1");
  EXPECT_EQ(rows.units[11], "rad/s");
  Eigen::Matrix3d inertia;
  inertia << 0.03, 0.004, -0.002, 0.004, 0.05, 0.003, -0.002, 0.003, 0.07;
  double energy0 = NAN;
  Eigen::Vector3d momentum0;
  double worst_energy = 0.0, worst_momentum = 0.0, worst_unit = 0.0, turned = 0.0;
  for (const std::vector<double>& r : rows.values) {
    const Eigen::Quaterniond quat(r[4], r[5], r[6], r[7]);
    worst_unit = std::max(worst_unit, std::abs(quat.norm() - 1.0));
    const Eigen::Vector3d velocity(r[8], r[9], r[10]), omega(r[11], r[12], r[13]);
    // Angular momentum about the centre of mass, ground frame: R I omega_body.
    const Eigen::Vector3d momentum = quat.normalized().toRotationMatrix() * (inertia * omega);
    const double energy = 0.5 * 2.0 * velocity.squaredNorm() + 0.5 * omega.dot(inertia * omega);
    if (std::isnan(energy0)) {
      energy0 = energy;
      momentum0 = momentum;
    }
    worst_energy = std::max(worst_energy, std::abs(energy - energy0) / energy0);
    worst_momentum = std::max(worst_momentum, (momentum - momentum0).norm() / momentum0.norm());
    turned = std::max(turned, std::abs(r[13] - rows.values.front()[13]));
    // The kinetic energy the kernels' M gives agrees with the one above.
    if (&r == &rows.values.back()) {
      State s;
      s.q.assign(r.begin() + 1, r.begin() + 8);
      s.qd.assign(r.begin() + 8, r.end());
      const Evaluation e = model.evaluate(s);
      const Eigen::Map<const Eigen::VectorXd> v(r.data() + 8, 6);
      constexpr double kSameEnergyRoundOff = 1e-12;  // J: the same quadratic form summed in another order
      EXPECT_NEAR(0.5 * v.dot(e.M * v), energy, kSameEnergyRoundOff);
    }
  }
  EXPECT_LT(worst_energy, kConservedTol);
  EXPECT_LT(worst_momentum, kConservedTol);
  EXPECT_LT(worst_unit, kUnitTol);
  EXPECT_GT(turned, 1.0);  // the spin tumbles: omega's components change
}

}  // namespace
}  // namespace mbfe
