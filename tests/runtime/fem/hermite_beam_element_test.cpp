// The Hermite element alone: shape functions against their definition and
// finite differences, element matrices against energy identities.
#include <gtest/gtest.h>

#include <random>

#include "runtime/fem/hermite_beam_element.h"
#include "runtime/fem/hermite_shape.h"

namespace mbfe::runtime {
namespace {

// Central differences with h = 1e-5 on O(1) cubics: truncation ~h^2 = 1e-10,
// rounding ~eps/h = 2e-11.
constexpr double kFiniteDifferenceTol = 1e-8;
// Sums of a few O(1) products: a few ulps.
constexpr double kRoundoffTol = 1e-12;

TEST(HermiteShape, InterpolatesNodalValuesAndSlopes) {
  const double le = 0.37;
  const auto n0 = hermite::N(0.0, le);
  const auto n1 = hermite::N(1.0, le);
  const auto d0 = hermite::dN_ds(0.0, le);
  const auto d1 = hermite::dN_ds(1.0, le);
  for (int a = 0; a < 4; ++a) {
    EXPECT_NEAR(n0[a], a == 0 ? 1.0 : 0.0, kRoundoffTol) << a;
    EXPECT_NEAR(n1[a], a == 2 ? 1.0 : 0.0, kRoundoffTol) << a;
    EXPECT_NEAR(d0[a], a == 1 ? 1.0 : 0.0, kRoundoffTol) << a;
    EXPECT_NEAR(d1[a], a == 3 ? 1.0 : 0.0, kRoundoffTol) << a;
  }
}

TEST(HermiteShape, DerivativesMatchFiniteDifferences) {
  std::mt19937 rng(20240607);
  std::uniform_real_distribution<double> xi_dist(0.05, 0.95);
  const double le = 0.8;
  const double h = 1e-5;  // in s (m)
  for (int trial = 0; trial < 50; ++trial) {
    const double xi = xi_dist(rng);
    const double dxi = h / le;
    const hermite::Row4 fd1 = (hermite::N(xi + dxi, le) - hermite::N(xi - dxi, le)) / (2 * h);
    const hermite::Row4 fd2 = (hermite::dN_ds(xi + dxi, le) - hermite::dN_ds(xi - dxi, le)) / (2 * h);
    for (int a = 0; a < 4; ++a) {
      EXPECT_NEAR(hermite::dN_ds(xi, le)[a], fd1[a], kFiniteDifferenceTol) << "xi " << xi;
      EXPECT_NEAR(hermite::d2N_ds2(xi, le)[a], fd2[a], kFiniteDifferenceTol) << "xi " << xi;
    }
  }
}

TEST(HermiteElement, RigidMotionsStoreNoEnergyAndCarryTheElementMass) {
  const double le = 0.02, EI = 109.375, rhoA = 0.1965;
  const HermiteBeamElement e(le, EI, rhoA, ir::MassLumping::kConsistent);
  Eigen::Vector4d translation(1.0, 0.0, 1.0, 0.0);
  Eigen::Vector4d rotation(0.0, 1.0, le, 1.0);  // w = s about node 1
  const Eigen::MatrixXd K = e.stiffness();
  EXPECT_NEAR((K * translation).norm(), 0.0, kRoundoffTol * K.norm());
  EXPECT_NEAR((K * rotation).norm(), 0.0, kRoundoffTol * K.norm());
  // Kinetic energy of a unit translation: total mass.
  EXPECT_NEAR(translation.dot(e.mass() * translation), rhoA * le, kRoundoffTol);
  const HermiteBeamElement lumped(le, EI, rhoA, ir::MassLumping::kLumped);
  EXPECT_NEAR(translation.dot(lumped.mass() * translation), rhoA * le, kRoundoffTol);
  EXPECT_TRUE(lumped.mass().isDiagonal());
  EXPECT_GT(lumped.mass()(1, 1), 0.0);
}

TEST(HermiteElement, UniformLoadIsTheWorkOfTheShapeFunctions) {
  // p_a = integral q N_a ds, by 3-point Gauss (exact for cubics).
  const double le = 0.3, q = -2.5;
  const HermiteBeamElement e(le, 1.0, 1.0, ir::MassLumping::kConsistent);
  const double g = std::sqrt(0.6);
  const double xs[3] = {0.5 * (1 - g), 0.5, 0.5 * (1 + g)};
  const double ws[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};
  Eigen::Vector4d p = Eigen::Vector4d::Zero();
  for (int i = 0; i < 3; ++i) p += q * le * ws[i] * hermite::N(xs[i], le).transpose();
  EXPECT_NEAR((e.uniform_load(q) - p).norm(), 0.0, kRoundoffTol);
}

}  // namespace
}  // namespace mbfe::runtime
