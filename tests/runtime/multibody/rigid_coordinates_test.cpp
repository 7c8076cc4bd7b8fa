// The coordinate layout of a model's bodies (rigid_coordinates) and the
// operations on its unit quaternions: displace (q (+) dv), normalize_quaternions
// and quaternion_norm_error. Oracles: the layout of a tree of every joint type
// written out by hand; Hamilton's product, the exponential of a rotation
// vector and the rotation matrix of a quaternion written here; Rodrigues'
// formula for what a body-frame turn does to a body-fixed vector; central
// differences of a displacement against q' = 1/2 q (0, w); norms by hand.
#include "runtime/multibody/rigid_coordinates.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "ir/model.h"

namespace mbfe::runtime {
namespace {

constexpr double kPi = 3.14159265358979323846;
// The same products and sines of O(1) numbers computed in another order: a
// few units in the last place.
constexpr double kRoundOff = 1e-15;
// Central differences with step 1e-5 on exp(eps w / 2): truncation
// |w|^3 eps^2 / 48 ~ 1e-11, round-off 1e-16 / 1e-5 = 1e-11.
constexpr double kDifferenceTol = 1e-9;
constexpr double kDifferenceStep = 1e-5;

using Quat = std::array<double, 4>;  // (w, x, y, z)

// Hamilton's product a b.
Quat hamilton(const Quat& a, const Quat& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3], a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1], a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

// exp(r / 2): the unit quaternion of a turn by |r| rad about r / |r|.
Quat exp_half(const Eigen::Vector3d& r) {
  const double angle = r.norm();
  if (angle == 0.0) return {1.0, 0.0, 0.0, 0.0};
  const Eigen::Vector3d axis = r / angle;
  const double s = std::sin(angle / 2);
  return {std::cos(angle / 2), s * axis.x(), s * axis.y(), s * axis.z()};
}

// The rotation matrix of a unit quaternion (body frame to ground frame).
Eigen::Matrix3d rotation(const Quat& q) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  Eigen::Matrix3d R;
  R << 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),  //
      2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),   //
      2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y);
  return R;
}

// Rodrigues: the vector b turned by |r| rad about r / |r|.
Eigen::Vector3d rodrigues(const Eigen::Vector3d& r, const Eigen::Vector3d& b) {
  const double angle = r.norm();
  const Eigen::Vector3d k = r / angle;
  return b * std::cos(angle) + k.cross(b) * std::sin(angle) + k * k.dot(b) * (1 - std::cos(angle));
}

Quat unit(Quat q) {
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& e : q) e /= n;
  return q;
}

ir::Body body(const std::string& name, ir::JointType type) {
  ir::Body b;
  b.name = name;
  b.joint.type = type;
  b.mass = 1.0;
  return b;
}

// A spatial chain of every joint type: revolute, spherical, prismatic, free.
ir::Model every_joint() {
  ir::Model m;
  m.name = "every_joint";
  m.dimension = 3;
  m.bodies = {body("crank", ir::JointType::kRevolute), body("ball", ir::JointType::kSpherical),
              body("slider", ir::JointType::kPrismatic), body("float", ir::JointType::kFree)};
  for (int b = 1; b < 4; ++b) m.bodies[b].parent = b - 1;
  return m;
}

// Where every_joint's quaternions sit in q, and their angular velocities in v.
constexpr int kBallQ = 1, kFloatQ = 9, kBallW = 1, kFloatW = 8;

Quat quat_at(const std::vector<double>& q, int w) { return {q[w], q[w + 1], q[w + 2], q[w + 3]}; }
void set_quat(std::vector<double>& q, int w, const Quat& value) {
  for (int k = 0; k < 4; ++k) q[w + k] = value[k];
}

// The columns' units of what the coordinates measure (their `rate`-th derivative).
std::vector<std::string> units(const std::vector<ir::Quantity>& quantities, int rate) {
  std::vector<std::string> out;
  for (ir::Quantity q : quantities) out.push_back(ir::si_unit(q, rate));
  return out;
}

// A state of every_joint with unit quaternions that are not the identity.
std::vector<double> every_joint_state() {
  std::vector<double> q = {0.3, 0, 0, 0, 0, -0.7, 1.5, -2.0, 0.25, 0, 0, 0, 0};
  set_quat(q, kBallQ, unit({0.8, -0.3, 0.4, 0.2}));
  set_quat(q, kFloatQ, unit({-0.1, 0.6, 0.5, -0.7}));
  return q;
}

TEST(RigidCoordinates, LayoutOfEveryJointTypeIsTheHandWrittenOne) {
  const RigidCoordinates c = rigid_coordinates(every_joint());
  // q: crank | ball (w x y z) | slider | float x y z | float (w x y z).
  // v: crank | ball wx wy wz | slider | float vx vy vz | float wx wy wz.
  EXPECT_EQ(c.nq, 13);
  EXPECT_EQ(c.nv, 11);
  EXPECT_TRUE(c.has_quaternions());
  EXPECT_EQ(c.quaternions, (std::vector<int>{kBallQ, kFloatQ}));
  EXPECT_EQ(c.rate_of, (std::vector<int>{0, -1, -1, -1, 5, 6, 7, 8, -1, -1, -1}));
  EXPECT_EQ(c.rotation_of, (std::vector<int>{-1, 1, 1, 1, -1, -1, -1, -1, 9, 9, 9}));
  EXPECT_EQ(c.rotation_axis, (std::vector<int>{-1, 0, 1, 2, -1, -1, -1, -1, 0, 1, 2}));
  EXPECT_EQ(c.position_columns,
            (std::vector<std::string>{"crank", "ball_qw", "ball_qx", "ball_qy", "ball_qz", "slider", "float_x",
                                      "float_y", "float_z", "float_qw", "float_qx", "float_qy", "float_qz"}));
  EXPECT_EQ(c.velocity_columns,
            (std::vector<std::string>{"crank_dot", "ball_wx", "ball_wy", "ball_wz", "slider_dot", "float_vx",
                                      "float_vy", "float_vz", "float_wx", "float_wy", "float_wz"}));
  EXPECT_EQ(units(c.position_quantity, 0),
            (std::vector<std::string>{"rad", "1", "1", "1", "1", "m", "m", "m", "m", "1", "1", "1", "1"}));
  EXPECT_EQ(units(c.velocity_quantity, 1), (std::vector<std::string>{"rad/s", "rad/s", "rad/s", "rad/s", "m/s", "m/s",
                                                                     "m/s", "m/s", "rad/s", "rad/s", "rad/s"}));
  EXPECT_EQ(c.velocity_body, (std::vector<int>{0, 1, 1, 1, 2, 3, 3, 3, 3, 3, 3}));
}

TEST(RigidCoordinates, APlanarModelIsOneCoordinateOfEachPerBodyAndDisplacesByAddition) {
  ir::Model m;
  m.bodies = {body("arm", ir::JointType::kRevolute), body("carriage", ir::JointType::kPrismatic)};
  m.bodies[1].parent = 0;
  const RigidCoordinates c = rigid_coordinates(m);
  EXPECT_EQ(c.nq, 2);
  EXPECT_EQ(c.nv, 2);
  EXPECT_FALSE(c.has_quaternions());
  EXPECT_EQ(c.rate_of, (std::vector<int>{0, 1}));
  EXPECT_EQ(c.velocity_columns, (std::vector<std::string>{"arm_dot", "carriage_dot"}));
  EXPECT_EQ(units(c.position_quantity, 0), (std::vector<std::string>{"rad", "m"}));
  EXPECT_EQ(units(c.velocity_quantity, 1), (std::vector<std::string>{"rad/s", "m/s"}));
  double q[2] = {0.75, -2.5};
  displace(c, q, Eigen::Vector2d(0.125, 0.5));
  EXPECT_EQ(q[0], 0.875);  // sums exact in binary
  EXPECT_EQ(q[1], -2.0);
  EXPECT_EQ(quaternion_norm_error(c, q), 0.0);
}

TEST(RigidCoordinates, DisplaceTurnsEachQuaternionByItsOwnRotationVectorOnTheRight) {
  const RigidCoordinates c = rigid_coordinates(every_joint());
  const std::vector<double> q0 = every_joint_state();
  Eigen::VectorXd dv(11);
  dv << 0.1, 0.3, -0.2, 0.5, -0.05, 0.01, 0.02, -0.03, -1.1, 0.4, 2.0;
  std::vector<double> q = q0;
  displace(c, q.data(), dv);
  // Plain coordinates: q + dv at the entries they are the rates of.
  EXPECT_NEAR(q[0], q0[0] + dv[0], kRoundOff);
  EXPECT_NEAR(q[5], q0[5] + dv[4], kRoundOff);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(q[6 + k], q0[6 + k] + dv[5 + k], kRoundOff);
  // Quaternions: quat exp(r / 2), each with the angular velocity entries of its body.
  const Quat ball = hamilton(quat_at(q0, kBallQ), exp_half(dv.segment<3>(kBallW)));
  const Quat floating = hamilton(quat_at(q0, kFloatQ), exp_half(dv.segment<3>(kFloatW)));
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(q[kBallQ + k], ball[k], kRoundOff) << "ball entry " << k;
    EXPECT_NEAR(q[kFloatQ + k], floating[k], kRoundOff) << "float entry " << k;
  }
}

TEST(RigidCoordinates, DisplaceTurnsTheBodyAboutItsOwnAxes) {
  // Independent of the product above: a body-fixed vector b lands at
  // R(q) Rodrigues(r, b), the turn r taken in the body frame.
  const RigidCoordinates c = rigid_coordinates(every_joint());
  const std::vector<double> q0 = every_joint_state();
  const Eigen::Vector3d r(0.7, -0.4, 0.9), b(0.2, -1.0, 0.5);
  Eigen::VectorXd dv = Eigen::VectorXd::Zero(11);
  dv.segment<3>(kFloatW) = r;
  std::vector<double> q = q0;
  displace(c, q.data(), dv);
  const Eigen::Vector3d got = rotation(quat_at(q, kFloatQ)) * b;
  const Eigen::Vector3d want = rotation(quat_at(q0, kFloatQ)) * rodrigues(r, b);
  EXPECT_LT((got - want).cwiseAbs().maxCoeff(), kRoundOff);
  // Only the float turned.
  for (int k = 0; k < 4; ++k) EXPECT_EQ(q[kBallQ + k], q0[kBallQ + k]);
}

TEST(RigidCoordinates, DisplaceByZeroRotationLeavesTheQuaternionExactly) {
  const RigidCoordinates c = rigid_coordinates(every_joint());
  const std::vector<double> q0 = every_joint_state();
  std::vector<double> q = q0;
  displace(c, q.data(), Eigen::VectorXd::Zero(11));
  for (int i = 0; i < c.nq; ++i) EXPECT_EQ(q[i], q0[i]) << "entry " << i;
}

TEST(RigidCoordinates, DisplaceKeepsUnitNormAndAFullTurnFlipsTheSign) {
  const RigidCoordinates c = rigid_coordinates(every_joint());
  const std::vector<double> q0 = every_joint_state();
  // A large turn stays on the unit sphere.
  Eigen::VectorXd dv = Eigen::VectorXd::Zero(11);
  dv.segment<3>(kBallW) = Eigen::Vector3d(2.0, -1.5, 1.0);
  std::vector<double> q = q0;
  displace(c, q.data(), dv);
  EXPECT_LT(quaternion_norm_error(c, q.data()), kRoundOff);
  // 2 pi about any axis: exp(pi n) = -1, so the quaternion becomes -q (the same rotation).
  dv.setZero();
  dv.segment<3>(kFloatW) = 2 * kPi * Eigen::Vector3d(0.6, 0.0, -0.8);
  q = q0;
  displace(c, q.data(), dv);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(q[kFloatQ + k], -q0[kFloatQ + k], kRoundOff);
}

TEST(RigidCoordinates, TwoTurnsAboutOneAxisAddUp) {
  const RigidCoordinates c = rigid_coordinates(every_joint());
  const std::vector<double> q0 = every_joint_state();
  const Eigen::Vector3d n = Eigen::Vector3d(1.0, 2.0, -2.0) / 3.0;
  Eigen::VectorXd a = Eigen::VectorXd::Zero(11), b = a;
  a.segment<3>(kBallW) = 0.4 * n;
  b.segment<3>(kBallW) = 1.3 * n;
  std::vector<double> twice = q0, once = q0;
  displace(c, twice.data(), a);
  displace(c, twice.data(), b);
  displace(c, once.data(), a + b);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(twice[kBallQ + k], once[kBallQ + k], kRoundOff);
}

TEST(RigidCoordinates, DisplaceToFirstOrderIsHalfTheQuaternionTimesTheAngularVelocity) {
  // d/de (q (+) e v) at e = 0 by central differences against q' = G(q) v:
  // v itself for plain coordinates, 1/2 quat (0, w) for a quaternion.
  const RigidCoordinates c = rigid_coordinates(every_joint());
  const std::vector<double> q0 = every_joint_state();
  Eigen::VectorXd v(11);
  v << 0.7, -1.2, 0.4, 2.1, 0.3, -0.6, 1.1, 0.2, 0.9, -1.7, 0.5;
  const double e = kDifferenceStep;
  std::vector<double> plus = q0, minus = q0;
  displace(c, plus.data(), e * v);
  displace(c, minus.data(), -e * v);
  std::vector<double> want(13, 0.0);
  for (int i = 0; i < 11; ++i)
    if (c.rate_of[i] >= 0) want[c.rate_of[i]] = v[i];
  for (const auto& [w, at] : {std::pair{kBallQ, kBallW}, std::pair{kFloatQ, kFloatW}}) {
    const Quat rate = hamilton(quat_at(q0, w), {0.0, v[at], v[at + 1], v[at + 2]});
    for (int k = 0; k < 4; ++k) want[w + k] = 0.5 * rate[k];
  }
  for (int i = 0; i < 13; ++i) EXPECT_NEAR((plus[i] - minus[i]) / (2 * e), want[i], kDifferenceTol) << "entry " << i;
}

TEST(RigidCoordinates, NormalizingScalesEachQuaternionToUnitLengthAndNothingElse) {
  const RigidCoordinates c = rigid_coordinates(every_joint());
  std::vector<double> q = {0.3, 1.2, 0.0, -0.9, 0.0, -0.7, 1.5, -2.0, 0.25, 0.36, 0.0, 0.48, 0.0};
  // The ball's quaternion has norm 1.5, the float's 0.6.
  EXPECT_NEAR(quaternion_norm_error(c, q.data()), 0.5, kRoundOff);
  const std::vector<double> before = q;
  normalize_quaternions(c, q.data());
  const std::vector<double> want = {0.3, 0.8, 0.0, -0.6, 0.0, -0.7, 1.5, -2.0, 0.25, 0.6, 0.0, 0.8, 0.0};
  for (int i = 0; i < 13; ++i) EXPECT_NEAR(q[i], want[i], kRoundOff) << "entry " << i;
  for (int i : {0, 5, 6, 7, 8}) EXPECT_EQ(q[i], before[i]) << "plain entry " << i;
  EXPECT_LT(quaternion_norm_error(c, q.data()), kRoundOff);
}

TEST(RigidCoordinates, NormErrorIsTheLargestOverTheQuaternions) {
  const RigidCoordinates c = rigid_coordinates(every_joint());
  std::vector<double> q = every_joint_state();
  for (int k = 0; k < 4; ++k) q[kBallQ + k] *= 0.9;    // | |q| - 1 | = 0.1
  for (int k = 0; k < 4; ++k) q[kFloatQ + k] *= 1.02;  // 0.02
  EXPECT_NEAR(quaternion_norm_error(c, q.data()), 0.1, kRoundOff);
}

TEST(RigidCoordinates, AZeroQuaternionIsLeftAlone) {
  // Left for the kernels to fail on, not turned into NaN here.
  const RigidCoordinates c = rigid_coordinates(every_joint());
  std::vector<double> q = every_joint_state();
  const Quat ball = quat_at(q, kBallQ);
  set_quat(q, kFloatQ, {0.0, 0.0, 0.0, 0.0});
  normalize_quaternions(c, q.data());
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(q[kFloatQ + k], 0.0);
    EXPECT_NEAR(q[kBallQ + k], ball[k], kRoundOff);
  }
  EXPECT_EQ(quaternion_norm_error(c, q.data()), 1.0);
}

}  // namespace
}  // namespace mbfe::runtime
