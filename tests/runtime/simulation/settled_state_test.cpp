// The equilibrium a model released at rest settles into, damped
// (quaternion_settled_state, loop_settled_state), on two models written here
// as ABI kernels: a body on a spherical joint whose one stable equilibrium
// is the identity rotation by construction, and the four-bar of
// tests/support/four_bar_oracle.h, whose stable equilibrium is the lowest
// point of its potential found there from the closed-form position analysis.
// Both start near an unstable equilibrium, which Newton alone would find.
// Also: the velocity given is dropped, and a motion that never comes to rest
// and scales that are not scales leave the state as it was.
#include "runtime/simulation/settled_state.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "ir/model.h"
#include "runtime/abi/mbfe_model_abi.h"
#include "runtime/multibody/loop_systems.h"
#include "runtime/multibody/rigid_coordinates.h"
#include "runtime/multibody/rigid_system.h"
#include "tests/support/four_bar_oracle.h"

namespace mbfe::runtime {
namespace {

// Newton polishes an isolated equilibrium to round-off of O(1) accelerations:
// the rotation matrix's entries to this.
constexpr double kEquilibriumTol = 1e-9;
// Relaxation stops when the rates are below 1e-6 omega_min (1 + |q|) (under
// 1e-5 rad/s here); the tilt left at that rate is about rate / omega (2e-6 rad).
constexpr double kRestedTol = 1e-5;
// The four-bar oracle's dV/dtheta is a central difference (step 1e-5 rad,
// truncation ~1e-11 N m); Newton's residual is at round-off: angles to this.
constexpr double kAngleTol = 1e-8;

// ---------------------------------------------------------------------------
// A body on a spherical joint at the origin: centre of mass kArm below the
// joint in the body frame, gravity -z, and a "compass" spring of potential
// -k (R e_x).e_x that turns its x axis towards the ground's. Its stable
// equilibrium is R = 1, isolated when k > 0 (k = 0 leaves it free to yaw);
// a turn by pi about x is an unstable one. `spin`: a torque about its z axis
// that keeps it turning. Globals: the ABI takes plain C function pointers.
constexpr double kMass = 2.0, kArm = 0.5, kIa = 0.05, kIb = 0.1, kG = 9.81;
double g_compass = 1.0;  // N m
double g_spin = 0.0;     // N m

// Moments of inertia about the joint, body frame.
Eigen::Vector3d ball_inertia() { return {kIa + kMass * kArm * kArm, kIa + kMass * kArm * kArm, kIb}; }

Eigen::Matrix3d rotation(const double* q) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  Eigen::Matrix3d R;
  R << 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),  //
      2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),   //
      2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y);
  return R;
}

void ball_mass(const double*, double* M) {
  Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>{M} = ball_inertia().asDiagonal().toDenseMatrix();
}
void ball_inertial(const double*, const double* v, double* F) {
  const Eigen::Vector3d w(v[0], v[1], v[2]);
  Eigen::Map<Eigen::Vector3d>{F} = w.cross(ball_inertia().cwiseProduct(w));
}
// Torques in the body frame: Q = R^T a x b for a potential a . (R b).
void ball_forces(const double* q, const double*, double, double* Q) {
  const Eigen::Matrix3d Rt = rotation(q).transpose();
  const Eigen::Vector3d c(0.0, 0.0, -kArm), weight(0.0, 0.0, -kMass * kG), ex = Eigen::Vector3d::UnitX();
  Eigen::Map<Eigen::Vector3d>{Q} =
      c.cross(Rt * weight) + g_compass * ex.cross(Rt * ex) + Eigen::Vector3d(0.0, 0.0, g_spin);
}
// q' = 1/2 q (0, w), Hamilton's product.
void ball_rates(const double* q, const double* v, double* qdot) {
  qdot[0] = 0.5 * (-q[1] * v[0] - q[2] * v[1] - q[3] * v[2]);
  qdot[1] = 0.5 * (q[0] * v[0] + q[2] * v[2] - q[3] * v[1]);
  qdot[2] = 0.5 * (q[0] * v[1] - q[1] * v[2] + q[3] * v[0]);
  qdot[3] = 0.5 * (q[0] * v[2] + q[1] * v[1] - q[2] * v[0]);
}
const char* const kBallQ[] = {"ball_qw", "ball_qx", "ball_qy", "ball_qz"};
const char* const kBallV[] = {"ball_wx", "ball_wy", "ball_wz"};

mbfe_model_v1 ball_kernels() {
  mbfe_model_v1 m{};
  m.abi_version = MBFE_MODEL_ABI_VERSION;
  m.model_name = "compass_ball";
  m.num_coordinates = 4;
  m.coordinate_names = kBallQ;
  m.mass_matrix = ball_mass;
  m.inertial_forces = ball_inertial;
  m.generalized_forces = ball_forces;
  m.dimension = 3;
  m.num_velocities = 3;
  m.velocity_names = kBallV;
  m.position_derivative = ball_rates;
  return m;
}

ir::Model ball_ir() {
  ir::Model m;
  m.name = "compass_ball";
  m.dimension = 3;
  ir::Body b;
  b.name = "ball";
  b.joint.type = ir::JointType::kSpherical;
  b.mass = kMass;
  b.inertia3 = {kIa, kIa, kIb, 0.0, 0.0, 0.0};
  m.bodies.push_back(b);
  return m;
}

// Its modes at R = 1: about x gravity alone, about y gravity and the
// compass, about z the compass alone (rad/s).
double ball_omega_min() { return std::sqrt(g_compass / kIb); }
double ball_omega_max() { return std::sqrt((kMass * kG * kArm + g_compass) / ball_inertia().x()); }

// y = [q; 0] with q the turn by `angle` rad about `axis`.
Eigen::VectorXd ball_state(double angle, const Eigen::Vector3d& axis) {
  const Eigen::Vector3d n = axis.normalized();
  Eigen::VectorXd y = Eigen::VectorXd::Zero(7);
  y << std::cos(angle / 2), std::sin(angle / 2) * n, 0.0, 0.0, 0.0;
  return y;
}

class QuaternionSettledState : public ::testing::Test {
 protected:
  void SetUp() override {
    g_compass = 1.0;
    g_spin = 0.0;
  }
  void TearDown() override { SetUp(); }
  const ir::Model ir_ = ball_ir();
  const mbfe_model_v1 kernels_ = ball_kernels();
  RigidSystem system_{kernels_, body_inertias(ir_), rigid_coordinates(ir_)};
};

TEST_F(QuaternionSettledState, FallsFromNearlyUpsideDownToTheStableEquilibrium) {
  // 2.9 rad about an axis near x: close to the unstable turn by pi about x.
  Eigen::VectorXd y = ball_state(2.9, Eigen::Vector3d(1.0, 0.3, -0.2));
  ASSERT_TRUE(quaternion_settled_state(ir_, system_, ball_omega_min(), ball_omega_max(), y));
  const Eigen::Matrix3d R = rotation(y.data());
  EXPECT_LT((R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), kEquilibriumTol) << R;
  EXPECT_EQ(y.tail(3).norm(), 0.0);
  EXPECT_NEAR(y.head(4).norm(), 1.0, kEquilibriumTol);
}

TEST_F(QuaternionSettledState, TheGivenVelocityIsDropped) {
  // Released at rest from q: what it was moving at does not count.
  Eigen::VectorXd at_rest = ball_state(1.2, Eigen::Vector3d(0.2, -1.0, 0.4));
  Eigen::VectorXd moving = at_rest;
  moving.tail(3) << 30.0, -12.0, 45.0;
  ASSERT_TRUE(quaternion_settled_state(ir_, system_, ball_omega_min(), ball_omega_max(), at_rest));
  ASSERT_TRUE(quaternion_settled_state(ir_, system_, ball_omega_min(), ball_omega_max(), moving));
  for (int i = 0; i < 7; ++i) EXPECT_EQ(moving[i], at_rest[i]) << "entry " << i;
}

TEST_F(QuaternionSettledState, AnEquilibriumThatIsNotIsolatedKeepsTheRestedState) {
  // Without the compass the body hangs at any yaw: Newton finds a mechanism,
  // and the relaxed state, hanging, is kept.
  g_compass = 0.0;
  const double omega = std::sqrt(kMass * kG * kArm / ball_inertia().x());
  Eigen::VectorXd y = ball_state(1.0, Eigen::Vector3d(0.3, 1.0, 0.5));
  ASSERT_TRUE(quaternion_settled_state(ir_, system_, omega, omega, y));
  const Eigen::Vector3d down = rotation(y.data()) * Eigen::Vector3d(0.0, 0.0, -1.0);
  EXPECT_LT((down - Eigen::Vector3d(0.0, 0.0, -1.0)).norm(), kRestedTol) << down.transpose();
  EXPECT_LT(y.tail(3).norm(), kRestedTol);
  EXPECT_NEAR(y.head(4).norm(), 1.0, kEquilibriumTol);
}

TEST_F(QuaternionSettledState, AMotionThatNeverRestsLeavesTheStateAsItWas) {
  // A steady torque about z three times the compass's largest: it turns for ever.
  g_spin = 3.0 * g_compass;
  const Eigen::VectorXd y0 = ball_state(0.4, Eigen::Vector3d(0.0, 1.0, 1.0));
  Eigen::VectorXd y = y0;
  EXPECT_FALSE(quaternion_settled_state(ir_, system_, ball_omega_min(), ball_omega_max(), y));
  for (int i = 0; i < 7; ++i) EXPECT_EQ(y[i], y0[i]) << "entry " << i;
}

TEST_F(QuaternionSettledState, ScalesThatAreNotScalesLeaveTheStateAsItWas) {
  // From the equilibrium itself, where any relaxation would stop at once.
  const Eigen::VectorXd y0 = ball_state(0.0, Eigen::Vector3d::UnitX());
  const double lo = ball_omega_min(), hi = ball_omega_max();
  const double inf = std::numeric_limits<double>::infinity();
  for (const auto& [omega_min, omega_max] : {std::pair{0.0, hi}, std::pair{hi, lo}, std::pair{lo, inf}}) {
    Eigen::VectorXd y = y0;
    EXPECT_FALSE(quaternion_settled_state(ir_, system_, omega_min, omega_max, y))
        << "omega_min " << omega_min << ", omega_max " << omega_max;
    EXPECT_EQ((y - y0).norm(), 0.0);
  }
}

// ---------------------------------------------------------------------------
// The four-bar of four_bar_oracle.h as ABI kernels: q = (crank angle,
// coupler angle relative to the crank, rocker angle), the coupler's end held
// to the rocker's by a point loop. A point of a body is a sum of arms
// r (cos phi, sin phi), phi = sum_j turns[j] q_j, from a ground point.
const test::FourBar kBar;
double g_crank_torque = 0.0;  // N m on the crank

struct Arm {
  double length;
  std::array<double, 3> turns;
};
struct ChainPoint {
  Eigen::Vector2d origin;
  std::vector<Arm> arms;
};

double arm_angle(const Arm& arm, const double* q) {
  return arm.turns[0] * q[0] + arm.turns[1] * q[1] + arm.turns[2] * q[2];
}

Eigen::Vector2d position(const ChainPoint& p, const double* q) {
  Eigen::Vector2d x = p.origin;
  for (const Arm& a : p.arms) x += a.length * Eigen::Vector2d(std::cos(arm_angle(a, q)), std::sin(arm_angle(a, q)));
  return x;
}
Eigen::Matrix<double, 2, 3> jacobian(const ChainPoint& p, const double* q) {
  Eigen::Matrix<double, 2, 3> J = Eigen::Matrix<double, 2, 3>::Zero();
  for (const Arm& a : p.arms)
    for (int j = 0; j < 3; ++j)
      J.col(j) += a.turns[j] * a.length * Eigen::Vector2d(-std::sin(arm_angle(a, q)), std::cos(arm_angle(a, q)));
  return J;
}
// (dJ/dt) v: each arm's centripetal term.
Eigen::Vector2d jacobian_rate_times(const ChainPoint& p, const double* q, const double* v) {
  Eigen::Vector2d out = Eigen::Vector2d::Zero();
  for (const Arm& a : p.arms) {
    const double rate = arm_angle(a, v);
    out -= a.length * rate * rate * Eigen::Vector2d(std::cos(arm_angle(a, q)), std::sin(arm_angle(a, q)));
  }
  return out;
}

struct BarLink {
  double mass, inertia;
  std::array<double, 3> turns;  // its absolute angle
  ChainPoint com;
};
std::vector<BarLink> links() {
  const Eigen::Vector2d O(0.0, 0.0), D(kBar.d, 0.0);
  return {{kBar.m_crank, kBar.i_crank, {1, 0, 0}, {O, {{0.1, {1, 0, 0}}}}},
          {kBar.m_coupler, kBar.i_coupler, {1, 1, 0}, {O, {{kBar.a, {1, 0, 0}}, {0.35, {1, 1, 0}}}}},
          {kBar.m_rocker, kBar.i_rocker, {0, 0, 1}, {D, {{0.25, {0, 0, 1}}}}}};
}
const ChainPoint kCouplerEnd{{0.0, 0.0}, {{kBar.a, {1, 0, 0}}, {kBar.b, {1, 1, 0}}}};
const ChainPoint kRockerEnd{{kBar.d, 0.0}, {{kBar.c, {0, 0, 1}}}};

void bar_mass(const double* q, double* M) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (const BarLink& l : links()) {
    const Eigen::Matrix<double, 2, 3> J = jacobian(l.com, q);
    const Eigen::Vector3d s(l.turns[0], l.turns[1], l.turns[2]);
    m += l.mass * J.transpose() * J + l.inertia * s * s.transpose();
  }
  Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>{M} = m;
}
void bar_inertial(const double* q, const double* v, double* F) {
  Eigen::Vector3d f = Eigen::Vector3d::Zero();
  for (const BarLink& l : links()) f += l.mass * jacobian(l.com, q).transpose() * jacobian_rate_times(l.com, q, v);
  Eigen::Map<Eigen::Vector3d>{F} = f;
}
void bar_forces(const double* q, const double*, double, double* Q) {
  Eigen::Vector3d f(g_crank_torque, 0.0, 0.0);
  for (const BarLink& l : links())
    f += jacobian(l.com, q).transpose() * Eigen::Vector2d(0.0, -l.mass * test::FourBar::kGravity);
  Eigen::Map<Eigen::Vector3d>{Q} = f;
}
void bar_loop(const double* q, double* phi) {
  Eigen::Map<Eigen::Vector2d>{phi} = position(kCouplerEnd, q) - position(kRockerEnd, q);
}
void bar_loop_jacobian(const double* q, double* J) {
  Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>>{J} = jacobian(kCouplerEnd, q) - jacobian(kRockerEnd, q);
}
void bar_loop_gamma(const double* q, const double* v, double* gamma) {
  Eigen::Map<Eigen::Vector2d>{gamma} =
      -(jacobian_rate_times(kCouplerEnd, q, v) - jacobian_rate_times(kRockerEnd, q, v));
}
const char* const kBarNames[] = {"crank", "coupler", "rocker"};
const mbfe_loop_constraint_v1 kBarLoops[] = {{"coupler_rocker", 0, 0, 2}};

mbfe_model_v1 bar_kernels() {
  mbfe_model_v1 m{};
  m.abi_version = MBFE_MODEL_ABI_VERSION;
  m.model_name = "four_bar";
  m.num_coordinates = 3;
  m.coordinate_names = kBarNames;
  m.mass_matrix = bar_mass;
  m.inertial_forces = bar_inertial;
  m.generalized_forces = bar_forces;
  m.dimension = 2;
  m.num_loop_rows = 2;
  m.num_loops = 1;
  m.loops = kBarLoops;
  m.loop_constraints = bar_loop;
  m.loop_jacobian = bar_loop_jacobian;
  m.loop_gamma = bar_loop_gamma;
  return m;
}

ir::Model bar_ir() {
  ir::Model m;
  m.name = "four_bar";
  const double masses[] = {kBar.m_crank, kBar.m_coupler, kBar.m_rocker};
  const double inertias[] = {kBar.i_crank, kBar.i_coupler, kBar.i_rocker};
  for (int k = 0; k < 3; ++k) {
    ir::Body b;
    b.name = kBarNames[k];
    b.parent = k == 1 ? 0 : -1;
    b.mass = masses[k];
    b.inertia = inertias[k];
    m.bodies.push_back(b);
  }
  return m;
}

// The closed state of the oracle at crank angle theta.
Eigen::VectorXd bar_state(double theta) {
  double phi, psi;
  kBar.angles(theta, phi, psi);
  return Eigen::Vector3d(theta, phi - theta, psi);
}

// The highest point of the potential over a turn of the crank: the unstable
// equilibrium (a scan, then Newton on dV/dtheta).
double top_angle() {
  double best = 0.0;
  for (int k = 0; k < 360; ++k) {
    const double theta = 2 * test::FourBar::kPi * k / 360;
    if (kBar.potential(theta) > kBar.potential(best)) best = theta;
  }
  for (int it = 0; it < 20; ++it) best -= kBar.slope(best) / kBar.curvature(best);
  return best;
}

double wrapped(double angle) { return std::remainder(angle, 2 * test::FourBar::kPi); }

class LoopSettledState : public ::testing::Test {
 protected:
  void SetUp() override { g_crank_torque = 0.0; }
  void TearDown() override { SetUp(); }
  const ir::Model ir_ = bar_ir();
  const mbfe_model_v1 kernels_ = bar_kernels();
  LoopPartitionedSystem system_{kernels_, body_inertias(ir_), rigid_coordinates(ir_)};
  // Its one mode at the lowest point (rad/s): V'' / m_eff.
  const double omega_ = std::sqrt(kBar.curvature(kBar.hanging_angle()) / kBar.effective_mass(kBar.hanging_angle()));
};

TEST_F(LoopSettledState, AFourBarReleasedNearItsTopSettlesWhereItsPotentialIsLeast) {
  const double hanging = kBar.hanging_angle();
  Eigen::VectorXd q = bar_state(top_angle() + 0.05), v = Eigen::VectorXd::Zero(3);
  ASSERT_TRUE(loop_settled_state(ir_, system_, omega_, omega_, q, v));
  const Eigen::VectorXd want = bar_state(hanging);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(wrapped(q[i] - want[i]), 0.0, kAngleTol) << kBarNames[i];
  EXPECT_EQ(v.norm(), 0.0);
}

TEST_F(LoopSettledState, AMotionThatNeverRestsLeavesTheStateAsItWas) {
  // Half as much again as the largest moment gravity exerts on the crank
  // (dV/dtheta over a turn): the crank turns for ever.
  double largest = 0.0;
  for (int k = 0; k < 360; ++k) largest = std::max(largest, std::abs(kBar.slope(2 * test::FourBar::kPi * k / 360)));
  g_crank_torque = 1.5 * largest;
  const Eigen::VectorXd q0 = bar_state(1.0), v0 = Eigen::VectorXd::Zero(3);
  Eigen::VectorXd q = q0, v = v0;
  EXPECT_FALSE(loop_settled_state(ir_, system_, omega_, omega_, q, v));
  EXPECT_EQ((q - q0).norm(), 0.0);
  EXPECT_EQ(v.norm(), 0.0);
}

TEST_F(LoopSettledState, ScalesThatAreNotScalesLeaveTheStateAsItWas) {
  const Eigen::VectorXd q0 = bar_state(kBar.hanging_angle());
  const double inf = std::numeric_limits<double>::infinity();
  // (omega_min = 0 is left to the test above, from an exact equilibrium: here,
  // undamped, the four-bar would not come to rest anyway.)
  for (const auto& [omega_min, omega_max] : {std::pair{omega_, 0.5 * omega_}, std::pair{omega_, inf}}) {
    Eigen::VectorXd q = q0, v = Eigen::VectorXd::Zero(3);
    EXPECT_FALSE(loop_settled_state(ir_, system_, omega_min, omega_max, q, v))
        << "omega_min " << omega_min << ", omega_max " << omega_max;
    EXPECT_EQ((q - q0).norm(), 0.0);
  }
}

}  // namespace
}  // namespace mbfe::runtime
