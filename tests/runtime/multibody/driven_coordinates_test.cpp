// Driven coordinates (driven_coordinates.h) on a hand-made three-coordinate
// ABI model whose coordinates 2 and 0 are driven, q_2 = a sin(w t) and
// q_0 = b t^2: the coordinates listed in model order with their mask, the
// motion read at t, and impose writing the motion's q and q' over the driven
// entries alone. eliminate_driven on a 3 x 3 M written here, against the
// reduced system solved by hand (Cramer's rule on M_ff q''_f = rhs_f -
// M_fd q''_d): the driven accelerations come out as prescribed, M stays
// symmetric positive definite, and the free rows of the original M q'' = rhs
// hold.
#include "runtime/multibody/driven_coordinates.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "runtime/abi/mbfe_model_abi.h"

namespace mbfe::runtime {
namespace {

// A 3 x 3 solve of O(1) entries, condition ~ 3, against Cramer's rule on
// accelerations up to ~10: a few roundings of values of that size.
constexpr double kSolveTol = 1e-13;

constexpr double kAmplitude = 0.05;  // m, a of q_2 = a sin(w t)
constexpr double kOmega = 12.0;      // rad/s, w
constexpr double kRamp = 0.8;        // rad/s^2, b of q_0 = b t^2

/// The motion of the driven coordinates (2, then 0) at t, as a generated model gives it.
void motion(double t, double* q, double* qd, double* qdd) {
  q[0] = kAmplitude * std::sin(kOmega * t);
  qd[0] = kAmplitude * kOmega * std::cos(kOmega * t);
  qdd[0] = -kAmplitude * kOmega * kOmega * std::sin(kOmega * t);
  q[1] = kRamp * t * t;
  qd[1] = 2 * kRamp * t;
  qdd[1] = 2 * kRamp;
}

const char* const kNames[] = {"crank", "arm", "slider"};
const int kDriven[] = {2, 0};

mbfe_model_v1 driven_model() {
  mbfe_model_v1 m{};
  m.abi_version = MBFE_MODEL_ABI_VERSION;
  m.model_name = "driven";
  m.num_coordinates = 3;
  m.coordinate_names = kNames;
  m.num_driven = 2;
  m.driven_coordinates = kDriven;
  m.motion = motion;
  return m;
}

/// An SPD mass matrix (kg, kg m, kg m^2) and a right-hand side (N, N m).
Eigen::Matrix3d mass_matrix() {
  Eigen::Matrix3d M;
  M << 4.0, 1.0, 0.5, 1.0, 3.0, -0.6, 0.5, -0.6, 2.0;
  return M;
}
Eigen::Vector3d right_hand_side() { return Eigen::Vector3d(1.2, -0.7, 0.4); }

TEST(DrivenCoordinates, ListsTheDrivenCoordinatesInModelOrder) {
  const mbfe_model_v1 model = driven_model();
  const DrivenCoordinates driven(model);
  EXPECT_FALSE(driven.empty());
  EXPECT_EQ(driven.count(), 2);
  EXPECT_EQ(driven.indices(), (std::vector<int>{2, 0}));
  EXPECT_EQ(driven.mask(), (std::vector<bool>{true, false, true}));
  EXPECT_TRUE(driven.is_driven(0));
  EXPECT_FALSE(driven.is_driven(1));
  EXPECT_TRUE(driven.is_driven(2));
  const DrivenCoordinates::Motion m = driven.make_motion();
  for (const Eigen::VectorXd* v : {&m.q, &m.qd, &m.qdd}) EXPECT_EQ(*v, Eigen::VectorXd::Zero(2));
}

TEST(DrivenCoordinates, TheMotionIsReadAtTAndImposedOnTheDrivenEntriesAlone) {
  const mbfe_model_v1 model = driven_model();
  const DrivenCoordinates driven(model);
  const double t = 0.37;
  // The model's own numbers, copied: exact.
  const double q2 = kAmplitude * std::sin(kOmega * t), qd2 = kAmplitude * kOmega * std::cos(kOmega * t);
  const double qdd2 = -kAmplitude * kOmega * kOmega * std::sin(kOmega * t);
  const double q0 = kRamp * t * t, qd0 = 2 * kRamp * t, qdd0 = 2 * kRamp;

  DrivenCoordinates::Motion m = driven.make_motion();
  driven.motion(t, m);
  EXPECT_EQ(m.q, Eigen::Vector2d(q2, q0));
  EXPECT_EQ(m.qd, Eigen::Vector2d(qd2, qd0));
  EXPECT_EQ(m.qdd, Eigen::Vector2d(qdd2, qdd0));

  // Rigid coordinates first, then (here) two beam coordinates: only 0 and 2 change.
  Eigen::VectorXd q(5), qd(5);
  q << 9.0, 8.0, 7.0, 6.0, 5.0;
  qd << -9.0, -8.0, -7.0, -6.0, -5.0;
  DrivenCoordinates::Motion scratch = driven.make_motion();
  driven.impose(t, q.data(), qd.data(), scratch);
  EXPECT_EQ(q, (Eigen::VectorXd(5) << q0, 8.0, q2, 6.0, 5.0).finished());
  EXPECT_EQ(qd, (Eigen::VectorXd(5) << qd0, -8.0, qd2, -6.0, -5.0).finished());
  EXPECT_EQ(scratch.qdd, Eigen::Vector2d(qdd2, qdd0));  // left for the caller
}

TEST(DrivenCoordinates, AModelWithoutDrivenJointsIsLeftAlone) {
  mbfe_model_v1 model = driven_model();
  model.num_driven = 0;
  model.driven_coordinates = nullptr;
  model.motion = nullptr;  // never called
  const DrivenCoordinates driven(model);
  EXPECT_TRUE(driven.empty());
  EXPECT_EQ(driven.count(), 0);
  EXPECT_EQ(driven.mask(), (std::vector<bool>{false, false, false}));
  Eigen::Vector3d q(1.0, 2.0, 3.0), qd(4.0, 5.0, 6.0);
  DrivenCoordinates::Motion scratch = driven.make_motion();
  driven.impose(0.5, q.data(), qd.data(), scratch);
  driven.motion(0.5, scratch);
  EXPECT_EQ(q, Eigen::Vector3d(1.0, 2.0, 3.0));
  EXPECT_EQ(qd, Eigen::Vector3d(4.0, 5.0, 6.0));
}

TEST(EliminateDriven, TheFreeAccelerationsSolveTheReducedSystem) {
  // Coordinate 1 driven at q''_1 = -a w^2 sin(w t).
  const double t = 0.3;
  const double qdd1 = -kAmplitude * kOmega * kOmega * std::sin(kOmega * t);
  const Eigen::Matrix3d M0 = mass_matrix();
  const Eigen::Vector3d rhs0 = right_hand_side();
  // By hand: M_ff = [4 0.5; 0.5 2] over (0, 2), M_fd = (1, -0.6), det 7.75.
  const double r0 = 1.2 - 1.0 * qdd1, r2 = 0.4 + 0.6 * qdd1;
  const double qdd0 = (2.0 * r0 - 0.5 * r2) / 7.75, qdd2 = (4.0 * r2 - 0.5 * r0) / 7.75;

  Eigen::MatrixXd M = M0;
  Eigen::VectorXd rhs = rhs0;
  eliminate_driven(M, rhs, {1}, Eigen::VectorXd::Constant(1, qdd1));
  Eigen::Matrix3d expected_M = M0;
  expected_M.row(1).setZero();
  expected_M.col(1).setZero();
  expected_M(1, 1) = 1.0;
  EXPECT_EQ(M, Eigen::MatrixXd(expected_M));
  EXPECT_NEAR(rhs[0], r0, kSolveTol);
  EXPECT_EQ(rhs[1], qdd1);
  EXPECT_NEAR(rhs[2], r2, kSolveTol);

  const Eigen::LLT<Eigen::MatrixXd> llt(M);
  ASSERT_EQ(llt.info(), Eigen::Success) << "no longer positive definite";
  const Eigen::VectorXd qdd = llt.solve(rhs);
  EXPECT_NEAR(qdd[0], qdd0, kSolveTol);
  EXPECT_NEAR(qdd[1], qdd1, kSolveTol);
  EXPECT_NEAR(qdd[2], qdd2, kSolveTol);
  // The free equations of the original system hold; the driven one's
  // residual is the force the drive exerts (not zero here).
  const Eigen::Vector3d residual = M0 * qdd - rhs0;
  EXPECT_NEAR(residual[0], 0.0, kSolveTol);
  EXPECT_NEAR(residual[2], 0.0, kSolveTol);
  EXPECT_GT(std::abs(residual[1]), 0.1);
}

TEST(EliminateDriven, TwoDrivenCoordinatesInTheMotionsOrder) {
  // Coordinates 2 and 0 driven, in that order, with the model's motion: the
  // one free coordinate solves M_11 q''_1 = rhs_1 - M_10 q''_0 - M_12 q''_2.
  const mbfe_model_v1 model = driven_model();
  const DrivenCoordinates driven(model);
  const double t = 0.61;
  DrivenCoordinates::Motion m = driven.make_motion();
  driven.motion(t, m);
  const double qdd2 = -kAmplitude * kOmega * kOmega * std::sin(kOmega * t), qdd0 = 2 * kRamp;
  const double qdd1 = (-0.7 - 1.0 * qdd0 - (-0.6) * qdd2) / 3.0;

  Eigen::MatrixXd M = mass_matrix();
  Eigen::VectorXd rhs = right_hand_side();
  eliminate_driven(M, rhs, driven.indices(), m.qdd);
  EXPECT_EQ(M, M.transpose());
  const Eigen::LLT<Eigen::MatrixXd> llt(M);
  ASSERT_EQ(llt.info(), Eigen::Success) << "no longer positive definite";
  const Eigen::VectorXd qdd = llt.solve(rhs);
  EXPECT_NEAR(qdd[0], qdd0, kSolveTol);
  EXPECT_NEAR(qdd[1], qdd1, kSolveTol);
  EXPECT_NEAR(qdd[2], qdd2, kSolveTol);
}

}  // namespace
}  // namespace mbfe::runtime
