// The choice of dependent rigid coordinates: the largest pivots of J_b, the
// smallest singular value of the chosen J_v against its closed form for 2 x 2,
// the constraint scale against the norms it bounds, and the singular cases
// (a rank-deficient J_b named by its contact, more rows than coordinates).
#include "runtime/coupled/partition_choice.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "runtime/errors/multibody_errors.h"
#include "tests/runtime/coupled/pendulum_on_beam.h"

namespace mbfe::runtime {
namespace {

using namespace pendulum_on_beam;

// Singular values of 2 x 2 matrices with O(1) entries: round-off.
constexpr double kSingularValueTol = 1e-14;

/// Smallest singular value of a 2 x 2 matrix: sqrt of the smaller root of
/// s^4 - tr(A^T A) s^2 + det(A)^2 = 0.
double closed_form_sigma_min(const Eigen::Matrix2d& a) {
  const double tr = a.squaredNorm(), det = a.determinant();
  return std::sqrt(0.5 * (tr - std::sqrt(tr * tr - 4.0 * det * det)));
}

ConstraintValues values(const Eigen::MatrixXd& jb) {
  ConstraintValues cv;
  cv.jb = jb;
  return cv;
}

TEST(PartitionChoice, DependentCoordinatesAreTheLargestPivots) {
  const testing::TestBeam beam = make_beam(4, false);
  auto dyn = make_dynamics(*double_pendulum_beam_pin_model(), beam);
  // Column 2 is the largest; orthogonal to it, column 1 keeps 2 and column 0
  // 1e-3: the dependent pair is {1, 2}.
  Eigen::MatrixXd jb(2, 3);
  jb << 1e-3, 2.0, 0.0,  //
      0.0, 0.1, 5.0;
  double smin = 0.0;
  const Partition p = choose_partition(dyn->constraints(), values(jb), 0.0, &smin);
  EXPECT_EQ(p.dependent, (std::vector<int>{1, 2}));
  EXPECT_EQ(p.independent, (std::vector<int>{0}));
  Eigen::Matrix2d jv;
  jv << 2.0, 0.0, 0.1, 5.0;
  EXPECT_NEAR(smin, closed_form_sigma_min(jv), kSingularValueTol);
  EXPECT_NEAR(sigma_min(jv), closed_form_sigma_min(jv), kSingularValueTol);
}

TEST(PartitionChoice, OneRowPicksItsLargestEntry) {
  const testing::TestBeam beam = make_beam(4, false);
  auto dyn = make_dynamics(*double_pendulum_beam_model(), beam);
  Eigen::MatrixXd jb(1, 2);
  jb << 0.3, -4.0;
  double smin = 0.0;
  const Partition p = choose_partition(dyn->constraints(), values(jb), 0.0, &smin);
  EXPECT_EQ(p.dependent, (std::vector<int>{1}));
  EXPECT_EQ(p.independent, (std::vector<int>{0}));
  EXPECT_NEAR(smin, 4.0, kSingularValueTol);
  // The scale is sigma_max(J_b) = |row| here, or the largest |J_e| if above it.
  ConstraintValues cv = values(jb);
  EXPECT_NEAR(constraint_scale(cv), std::hypot(0.3, 4.0), kSingularValueTol);
  cv.je.resize(1, 4);
  cv.je << 0.0, 7.0, -9.0, 1.0;
  EXPECT_EQ(constraint_scale(cv), 9.0);
}

TEST(PartitionChoice, NoRowsLeaveEveryCoordinateIndependent) {
  const testing::TestBeam beam = make_beam(4, false);
  auto dyn = make_dynamics(*double_pendulum_beam_model(), beam);
  double smin = 0.0;
  const Partition p = choose_partition(dyn->constraints(), values(Eigen::MatrixXd(0, 3)), 0.0, &smin);
  EXPECT_TRUE(p.dependent.empty());
  EXPECT_EQ(p.independent, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(smin, 1.0);
  EXPECT_EQ(sigma_min(Eigen::MatrixXd(0, 0)), 1.0);
}

TEST(PartitionChoice, RankDeficientJacobianNamesTheContact) {
  const testing::TestBeam beam = make_beam(4, false);
  auto dyn = make_dynamics(*double_pendulum_beam_pin_model(), beam);
  Eigen::MatrixXd jb(2, 2);
  jb << 1.0, 2.0,  //
      2.0, 4.0;    // rank 1: a dead point
  try {
    choose_partition(dyn->constraints(), values(jb), 0.25, nullptr);
    FAIL() << "a singular J_b was partitioned";
  } catch (const SingularConstraintError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("tip_pin"), std::string::npos) << what;
    EXPECT_NE(what.find("t = 0.25"), std::string::npos) << what;
  }
  // A rank defect of 1e-10, above the threshold (1e-13 of the scale), is not one.
  jb(1, 1) = 4.0 + 1e-10;
  EXPECT_NO_THROW(choose_partition(dyn->constraints(), values(jb), 0.25, nullptr));
}

TEST(PartitionChoice, MoreRowsThanRigidCoordinatesAreRefused) {
  const testing::TestBeam beam = make_beam(4, false);
  auto dyn = make_dynamics(*double_pendulum_beam_pin_model(), beam);
  EXPECT_THROW(choose_partition(dyn->constraints(), values(Eigen::MatrixXd::Identity(3, 2)), 0.0, nullptr),
               SingularConstraintError);
}

}  // namespace
}  // namespace mbfe::runtime
