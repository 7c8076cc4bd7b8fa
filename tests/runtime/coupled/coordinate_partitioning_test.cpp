// PartitionedSystem at one state of the slider pendulum on its beam (eqs
// (16)-(17)): the closed dependent coordinate puts the tip back on the beam
// (Phi = 0) and its rate satisfies the velocity constraint J q' = 0; the
// state keeps the independent coordinates given; and the independent
// accelerations are the augmented system's at the closed state (whose own
// oracle is augmented_system_test.cpp). The trajectories of both
// formulations, their energy and repartitioning are in coupled_system_test.cpp.
#include "runtime/coupled/coordinate_partitioning.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <random>

#include "runtime/coupled/augmented_system.h"
#include "tests/runtime/coupled/pendulum_on_beam.h"

namespace mbfe::runtime {
namespace {

using namespace pendulum_on_beam;

// The closure's tolerance (PartitionOptions::closure_tol).
constexpr double kClosureTol = 1e-10;  // m
// J q' of O(1) Jacobian entries times O(1) rates: round-off of the projection.
constexpr double kVelocityTol = 1e-12;  // m/s
// Accelerations from two saddle-point solves of one state: round-off of
// O(1e2) rad/s^2 values.
constexpr double kSameAccelerationTol = 1e-9;

TEST(CoordinatePartitioning, ClosesPositionsAndRatesAndMatchesTheAugmentedAccelerations) {
  const testing::TestBeam beam = make_beam(6, true);
  auto dyn = make_dynamics(*double_pendulum_beam_model(), beam);
  PartitionedSystem part(dyn);
  const int n = dyn->n(), nc = n - 2;

  // Off the constraint on purpose: the tip 1 mm above the bent beam, moving.
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd q = Eigen::VectorXd::NullaryExpr(n, [&]() { return 1e-4 * u(rng); });
  Eigen::VectorXd qd = Eigen::VectorXd::NullaryExpr(n, [&]() { return 1e-2 * u(rng); });
  q.head<2>() = pendulum_angles_for_tip(0.55) + Eigen::Vector2d(1e-3, 0.0);
  qd.head<2>() << 0.5, -0.2;

  const Eigen::VectorXd y = part.initial_state(0.0, q, qd);
  ASSERT_EQ(y.size(), 2 * (n - 1));  // one rigid coordinate is dependent
  Eigen::VectorXd qf, qdf;
  part.full_state(0.0, y, qf, qdf);
  const Partition& p = part.partition();
  ASSERT_EQ(p.dependent.size(), 1u);
  const int u_index = p.independent[0];
  EXPECT_EQ(qf[u_index], q[u_index]);                   // the independent angle as given
  EXPECT_EQ(qf.tail(nc), q.tail(nc));                   // the beam as given
  EXPECT_NE(qf[p.dependent[0]], q[p.dependent[0]]);     // the dependent one moved onto the beam

  ConstraintValues cv;
  dyn->constraints().evaluate(0.0, qf.data(), qf.data() + 2, nullptr, nullptr, cv);
  EXPECT_LT(cv.phi.cwiseAbs().maxCoeff(), kClosureTol);
  const Eigen::VectorXd jqd = cv.jb * qdf.head(2) + cv.jc_dense(nc) * qdf.tail(nc);
  EXPECT_LT(jqd.cwiseAbs().maxCoeff(), kVelocityTol);

  // The partitioned right-hand side against the augmented one at (qf, qdf).
  Eigen::VectorXd ydot;
  part.rhs(0.0, y, ydot);
  AugmentedSystem aug(make_dynamics(*double_pendulum_beam_model(), beam));
  Eigen::VectorXd ya(2 * n), yadot;
  ya << qf, qdf;
  aug.rhs(0.0, ya, yadot);
  const int nz = n - 1;
  EXPECT_NEAR(ydot[nz], yadot[n + u_index], kSameAccelerationTol * std::abs(yadot[n + u_index]));
  EXPECT_LT((ydot.tail(nc) - yadot.tail(nc)).cwiseAbs().maxCoeff(),
            kSameAccelerationTol * yadot.tail(nc).cwiseAbs().maxCoeff());
  EXPECT_EQ(ydot.head(nz), y.tail(nz));  // z' is the rate part of y
}

TEST(CoordinatePartitioning, WrongSizedStateIsRefused) {
  const testing::TestBeam beam = make_beam(4, false);
  PartitionedSystem part(make_dynamics(*double_pendulum_beam_model(), beam));
  Eigen::VectorXd ydot;
  EXPECT_THROW(part.rhs(0.0, Eigen::VectorXd::Zero(3), ydot), std::invalid_argument);
}

}  // namespace
}  // namespace mbfe::runtime
