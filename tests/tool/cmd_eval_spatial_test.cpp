// `mbfe eval --json` on spatial models and closed loops: the shipped 3D double
// pendulum against its equations derived by hand, and the shipped loop
// models closed at their initial states, with the shapes and errors of the
// spatial flags.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/cli.h"
#include "tests/support/process.h"

namespace mbfe {
namespace {

// Closed form against generated code, entries of order 1: a few ulps each.
constexpr double kClosedFormTol = 1e-12;
// The loops' initial states are given to 16 digits: Phi ~ 1e-16 m.
constexpr double kClosureTol = 1e-14;

std::string list(const std::vector<double>& v) {
  std::ostringstream os;
  os.precision(17);
  for (std::size_t i = 0; i < v.size(); ++i) os << (i ? "," : "") << v[i];
  return os.str();
}

nlohmann::json eval(const std::string& model, const std::vector<double>& q, const std::vector<double>& v) {
  const test::CliRun r = test::run_cli("eval " + model + " --json --q " + list(q) + " --qd " + list(v));
  EXPECT_EQ(r.status, 0) << r.all();
  return nlohmann::json::parse(r.out);
}

// models/double_pendulum_3d.yaml: link 1 turns by q1 about the ground's y
// axis, link 2 by q2 about link 1's x axis at its tip (0, 0, -l1); centres of
// mass at (0, 0, -a) in their frames, principal inertias (A, B, C). With
// c = cos, s = sin, L = l1 + a2 c2, the centre of mass of link 2 is at
// (-s1 L, a2 s2, -c1 L), link 2's frame is Ry(q1) Rx(q2), and
//   M11 = B1 + m1 a1^2 + m2 L^2 + B2 c2^2 + C2 s2^2,  M22 = A2 + m2 a2^2,  M12 = 0
// (the two swings are orthogonal: d com2/dq1 . d com2/dq2 = 0, and the
// inertia products vanish for a diagonal tensor). Lagrange's equations with
// T = 1/2 M11(q2) q1'^2 + 1/2 M22 q2'^2 and V = -g (m1 a1 c1 + m2 c1 L):
//   F1 = M11' q1' q2',  F2 = -1/2 M11' q1'^2,  M11' = -2 m2 L a2 s2 + 2 (C2 - B2) s2 c2,
//   Q1 = -g s1 (m1 a1 + m2 L),  Q2 = -g m2 a2 c1 s2.
struct DoublePendulum3d {
  double m1 = 1.0, a1 = 0.5, l1 = 1.0, B1 = 0.08;
  double m2 = 0.8, a2 = 0.4, A2 = 0.043, B2 = 0.042, C2 = 0.003;
  double g = 9.81;
};

TEST(SpatialEval, DoublePendulum3dMatchesItsEquationsByHand) {
  const DoublePendulum3d p;
  std::mt19937 rng(1234);
  std::uniform_real_distribution<double> angle(-3.0, 3.0), rate(-2.0, 2.0);
  for (int trial = 0; trial < 5; ++trial) {
    const double q1 = angle(rng), q2 = angle(rng), v1 = rate(rng), v2 = rate(rng);
    const nlohmann::json out = eval("models/double_pendulum_3d.yaml", {q1, q2}, {v1, v2});
    const auto M = out.at("M").get<std::vector<std::vector<double>>>();
    const auto F = out.at("F").get<std::vector<double>>();
    const auto Q = out.at("Q").get<std::vector<double>>();
    const double s1 = std::sin(q1), c1 = std::cos(q1), s2 = std::sin(q2), c2 = std::cos(q2);
    const double L = p.l1 + p.a2 * c2;
    const double m11 = p.B1 + p.m1 * p.a1 * p.a1 + p.m2 * L * L + p.B2 * c2 * c2 + p.C2 * s2 * s2;
    const double m22 = p.A2 + p.m2 * p.a2 * p.a2;
    const double dm11 = -2 * p.m2 * L * p.a2 * s2 + 2 * (p.C2 - p.B2) * s2 * c2;
    EXPECT_NEAR(M[0][0], m11, kClosedFormTol);
    EXPECT_NEAR(M[1][1], m22, kClosedFormTol);
    EXPECT_NEAR(M[0][1], 0.0, kClosedFormTol);
    EXPECT_NEAR(M[1][0], 0.0, kClosedFormTol);
    EXPECT_NEAR(F[0], dm11 * v1 * v2, kClosedFormTol);
    EXPECT_NEAR(F[1], -0.5 * dm11 * v1 * v1, kClosedFormTol);
    EXPECT_NEAR(Q[0], -p.g * s1 * (p.m1 * p.a1 + p.m2 * L), kClosedFormTol);
    EXPECT_NEAR(Q[1], -p.g * p.m2 * p.a2 * c1 * s2, kClosedFormTol);
  }
}

// models/bogie.yaml, by hand: at q = 0 the wheel loads (a quarter of the
// 6241 kg at each wheel) carry the weight and each axle's spring, preloaded by
// half the frame's weight, holds its wheelset, so Q = 0; lifting axle 1 by
// 1 mm against the frame leaves -k 1 mm = -2440 N on its heave. With the
// frame rolling at w and the wheelsets spinning at W about their axles
// (principal moment B = 112 kg m^2 about them), each wheelset's angular
// momentum B W e_y turns at w e_x: the velocity term of the frame's yaw is
// the gyroscopic moment of both, F_wz = 2 B W w; the mass of the whole is M_xx.
TEST(SpatialEval, BogieRestsOnItsSpringsAndFeelsTheWheelsetsGyroscopicMoment) {
  constexpr double kMass = 2615 + 2 * 1813, kStiffness = 2.44e6, kSpinInertia = 112;
  constexpr double kWheelLoad = kMass * 9.81 / 4;
  const double roll = 0.1, spin = 20 / 0.46, lift = 1e-3;
  const std::vector<double> rest{0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  const auto Q0 = eval("models/bogie.yaml", rest, std::vector<double>(12, 0.0)).at("Q").get<std::vector<double>>();
  for (double q : Q0) EXPECT_LT(std::fabs(q), 1e-12 * kWheelLoad);
  std::vector<double> lifted = rest;
  lifted[7] = lift;  // axle1_heave
  const std::vector<double> v{20, 0, 0.05, roll, 0, 0, 0, 0, spin, 0, 0, spin};
  const nlohmann::json out = eval("models/bogie.yaml", lifted, v);
  const auto F = out.at("F").get<std::vector<double>>();
  const auto Q = out.at("Q").get<std::vector<double>>();
  const auto M = out.at("M").get<std::vector<std::vector<double>>>();
  EXPECT_NEAR(Q[6], -kStiffness * lift, kClosedFormTol * kWheelLoad);
  EXPECT_NEAR(F[5], 2 * kSpinInertia * spin * roll, kClosedFormTol * 1e3);
  EXPECT_DOUBLE_EQ(M[0][0], kMass);
}

TEST(SpatialEval, ShippedLoopsAreClosedAtTheirInitialStates) {
  struct Case {
    const char* model;
    std::vector<double> q, v;
    std::size_t rows, velocities;
  };
  const Case cases[] = {
      {"models/four_bar.yaml", {1.0, -0.5357560074605321, 1.2995365385792519}, {2.0, 0, 0}, 2, 3},
      {"models/slider_crank_3d.yaml",
       {0.0, 0.9899856611293864, 0.0, -0.12626445504008477, 0.06313222752004238, 0.48405728739343046},
       {10.0, 0, 0, 0, 0},
       3,
       5}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.model);
    const nlohmann::json loops = eval(c.model, c.q, c.v).at("loops");
    const auto phi = loops.at("Phi").get<std::vector<double>>();
    const auto J = loops.at("J").get<std::vector<std::vector<double>>>();
    ASSERT_EQ(phi.size(), c.rows);
    ASSERT_EQ(J.size(), c.rows);
    ASSERT_EQ(J[0].size(), c.velocities);
    for (double r : phi) EXPECT_LT(std::fabs(r), kClosureTol);
  }
}

TEST(SpatialEval, CoordinateCountsAreCheckedAndNamed) {
  const test::CliRun r = test::run_cli("eval models/slider_crank_3d.yaml --q 0,1,0,0,0");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--q has 5 entries, expected 6 (position coordinates in model order)"), std::string::npos)
      << r.err;
  const test::CliRun text = test::run_cli("eval models/slider_crank_3d.yaml");
  EXPECT_EQ(text.status, 0) << text.all();
  EXPECT_NE(text.out.find("position coordinates: crank rod_qw rod_qx rod_qy rod_qz slider"), std::string::npos)
      << text.out;
  EXPECT_NE(text.out.find("velocity coordinates: crank rod_wx rod_wy rod_wz slider"), std::string::npos) << text.out;
}

TEST(SpatialEval, AQuaternionOffUnitLengthIsRefused) {
  // The rod's quaternion (1, 0, 0, 1), norm sqrt(2): the kernels would read
  // it as a rotation and give numbers that mean nothing.
  const test::CliRun r = test::run_cli("eval models/slider_crank_3d.yaml --q 0.3,1,0,0,1,0.4 --json");
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_NE(r.err.find("--q: the quaternion of body 'rod' (rod_qw .. rod_qz) has norm 1.414213562, expected 1 (within "
                       "1e-06)"),
            std::string::npos)
      << r.err;
  // Within the tolerance (a quaternion written with 8 digits) it is read.
  const test::CliRun close = test::run_cli("eval models/slider_crank_3d.yaml --q 0.3,0.70710678,0,0,0.70710678,0.4");
  EXPECT_EQ(close.status, 0) << close.all();
}

TEST(SpatialEval, SimulateRefusesASpatialModelWithBeams) {
  const test::TempDir dir;
  const std::string path = (dir / "beam3d.yaml").string();
  std::ofstream(path) << "model: beam3d\ndimension: 3\ngravity: [0, 0, -9.81]\n"
                         "bodies:\n  - {name: a, parent: ground, joint: {type: revolute}, mass: 1, "
                         "inertia: [1, 1, 1, 0, 0, 0]}\n"
                         "beams:\n  - {name: b, length: 1, elements: 2}\n";
  const test::CliRun r = test::run_cli("simulate " + path + " --t-end 0.01");
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_NE(r.err.find("beam3d.yaml:6:1: beams: a spatial model (dimension: 3) cannot have beams: 3D beams do not "
                       "exist yet"),
            std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace mbfe
