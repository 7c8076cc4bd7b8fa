// The fixed joint rotation of the spatial derivation (rotation_rpy) against
// Eigen's product of axis rotations, and its quarter turns written exactly:
// the doubles nearest to k pi/2 give entries that are exactly 0, 1 or -1, so
// a URDF-style frame costs no operations, while any other angle keeps the
// decimal of its double's cosine and sine.
#include <gtest/gtest.h>
#include <ginac/ginac.h>

#include <Eigen/Geometry>
#include <cmath>

#include "generator/symbolic/spatial_vectors.h"

namespace mbfe::gen {
namespace {

// Entries of a rotation in [-1, 1]; a product of three rotations rounds a
// few times.
constexpr double kRotationTol = 1e-15;

Eigen::Matrix3d eigen_rpy(const ir::Vec3& rpy) {
  return (Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

double value(const GiNaC::ex& e) { return GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(e)).to_double(); }

TEST(SpatialVectors, RpyRotationIsRzRyRx) {
  const ir::Vec3 rpy{0.3, -1.1, 2.5};
  const Mat3x r = rotation_rpy(rpy);
  const Eigen::Matrix3d want = eigen_rpy(rpy);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(value(r.m[i][j]), want(i, j), kRotationTol) << i << ", " << j;
}

TEST(SpatialVectors, QuarterTurnsAreExact) {
  const double quarter = 1.5707963267948966, half = 3.141592653589793;
  for (const ir::Vec3& rpy : {ir::Vec3{quarter, 0, half}, ir::Vec3{-quarter, half, 0}, ir::Vec3{3 * quarter, -half, 0},
                              ir::Vec3{2 * half, quarter, -3 * quarter}, ir::Vec3{0, -quarter, 5 * quarter}}) {
    const Mat3x r = rotation_rpy(rpy);
    const Eigen::Matrix3d want = eigen_rpy(rpy);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        SCOPED_TRACE(std::to_string(rpy[0]) + " " + std::to_string(rpy[1]) + " " + std::to_string(rpy[2]));
        ASSERT_TRUE(GiNaC::is_a<GiNaC::numeric>(r.m[i][j]));
        const GiNaC::numeric entry = GiNaC::ex_to<GiNaC::numeric>(r.m[i][j]);
        EXPECT_TRUE(entry.is_integer()) << "entry " << i << ", " << j << " is " << entry;
        EXPECT_NEAR(entry.to_double(), want(i, j), kRotationTol) << i << ", " << j;
      }
  }
}

TEST(SpatialVectors, NearlyQuarterTurnsKeepTheirDecimals) {
  // 1.5708 is 3.7e-6 rad off a quarter turn: a real angle, kept as written.
  const Mat3x r = rotation_rpy({1.5708, 0, 0});
  EXPECT_EQ(r.m[1][1], GiNaC::ex(exact(std::cos(1.5708))));
  EXPECT_NE(r.m[1][1], GiNaC::ex(0));
  EXPECT_EQ(r.m[2][1], GiNaC::ex(exact(std::sin(1.5708))));
}

}  // namespace
}  // namespace mbfe::gen
