// Tensioned beams, elastic supports and point masses (the structural parts of
// a catenary), against closed forms:
//   - the geometric matrix is T int(N'^T N') ds, by composite Simpson
//     quadrature of the shape functions' slopes; the stiffness factor still factors K;
//   - a taut string (EI -> 0): omega_n = n pi / L sqrt(T / rho A);
//   - a pinned-pinned tensioned beam: omega_n = (n pi / L)^2 sqrt(EI / rho A)
//     sqrt(1 + T L^2 / (n^2 pi^2 EI)) (its modes are sines whatever T);
//   - a stiff beam on two end springs with lumped masses: the bounce mode
//     omega = sqrt(2 k / total mass), and the dampers in C on w only.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "runtime/damping/beam_model.h"
#include "runtime/fem/beam_element.h"
#include "runtime/fem/beam_system.h"
#include "runtime/fem/hermite_shape.h"
#include "tests/runtime/fem/beam_fixtures.h"

namespace mbfe::runtime {
namespace {

using test::kPi;

// A contact wire: 20 kN, 1.35 kg/m (copper, 150 mm^2), 10 m between pinned ends.
constexpr double kTension = 20000.0;
constexpr double kArea = 1.5e-4;
constexpr double kDensity = 9000.0;  // kg/m^3: 1.35 kg/m

ir::Beam wire(double E, double I, int elements, double tension) {
  ir::Beam b;
  b.name = "wire";
  b.length = 10.0;
  b.elements = elements;
  b.area = kArea;
  b.second_moment = I;
  b.youngs_modulus = E;
  b.density = kDensity;
  b.tension = tension;
  b.supports = {{0.0, ir::SupportType::kPinned, -1, {}}, {10.0, ir::SupportType::kPinned, -1, {}}};
  return b;
}

TEST(TensionedBeam, GeometricMatrixIsTheIntegralOfTheShapeSlopes) {
  const ir::Beam plain = wire(1.2e11, 1e-9, 10, 0.0);
  const ir::Beam taut = wire(1.2e11, 1e-9, 10, kTension);
  const auto e0 = make_beam_element(plain);
  const auto e1 = make_beam_element(taut);
  const double le = 1.0;
  // Independent quadrature: composite Simpson on the quartic integrand.
  Eigen::Matrix4d g = Eigen::Matrix4d::Zero();
  const int panels = 400;
  for (int i = 0; i <= panels; ++i) {
    const double xi = static_cast<double>(i) / panels;
    const double w = (i == 0 || i == panels) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    const Eigen::Matrix<double, 1, 4> d = hermite::dN_ds(xi, le);
    g += (w * le / (3.0 * panels)) * d.transpose() * d;
  }
  // Simpson is exact for the quartic up to round-off.
  constexpr double kQuadratureTol = 1e-9;
  const Eigen::MatrixXd geometric = e1->stiffness() - e0->stiffness();
  EXPECT_LT((geometric - kTension * g).norm(), kQuadratureTol * kTension * g.norm());
  // The factor still reproduces the stiffness (the sparse modal path factorises with it).
  const Eigen::MatrixXd f = e1->stiffness_factor();
  EXPECT_LT((f.transpose() * f - e1->stiffness()).norm(), 1e-10 * e1->stiffness().norm());
  // Rigid motions store no energy, with tension too.
  Eigen::Vector4d translate(1.0, 0.0, 1.0, 0.0), rotate(-0.5 * le, 1.0, 0.5 * le, 1.0);
  EXPECT_LT((e1->stiffness() * translate).norm(), 1e-9 * e1->stiffness().norm());
  EXPECT_GT((e1->stiffness() * rotate).norm(), 0.0);  // a rotation stretches a tensioned string
}

TEST(TensionedBeam, TautStringFrequencies) {
  // EI 1e-9 of the tension's T L^2 scale: bending adds (n pi)^2 EI / (T L^2) ~ 1e-9 relative.
  const BeamPart part = analyse_beam(wire(1.0, 1e-6, 200, kTension), {0.0, 0.0});
  const double c = std::sqrt(kTension / (kArea * kDensity));
  // 200 cubic elements: the n-th string mode is resolved to ~(n h / L)^4.
  constexpr double kStringTol = 1e-6;
  for (int n = 1; n <= 5; ++n) {
    const double exact = n * kPi / 10.0 * c;
    EXPECT_NEAR(part.basis.omega[n - 1], exact, kStringTol * exact) << "mode " << n;
  }
}

TEST(TensionedBeam, PinnedPinnedTensionedBeamFrequencies) {
  const double E = 1.2e11, I = 2.0e-9;  // a stiff wire: bending and tension of one order for n ~ 10
  const BeamPart part = analyse_beam(wire(E, I, 100, kTension), {0.0, 0.0});
  const double rhoA = kArea * kDensity;
  constexpr double kBeamTol = 1e-6;
  for (int n = 1; n <= 8; ++n) {
    const double k = n * kPi / 10.0;
    const double exact = k * k * std::sqrt(E * I / rhoA) * std::sqrt(1.0 + kTension / (k * k * E * I));
    EXPECT_NEAR(part.basis.omega[n - 1], exact, kBeamTol * exact) << "mode " << n;
  }
}

TEST(ElasticSupports, BounceModeOfAStiffBeamOnTwoSpringsWithMasses) {
  ir::Beam b = test::paper_beam(0.05, 10);  // a 50 mm square steel bar: bending modes ~1e3 rad/s and up
  const double k = 1000.0, c = 7.0, support_mass = 0.8, clamp = 0.3;
  b.rayleigh_alpha = b.rayleigh_beta = 0.0;
  b.supports = {{0.0, ir::SupportType::kSpring, -1, k, c, support_mass, {}},
                {1.0, ir::SupportType::kSpring, -1, k, c, support_mass, {}}};
  b.masses = {{0.5, clamp, -1, {}}};
  const BeamPart part = analyse_beam(b, {0.0, 0.0});
  const double total = b.density * b.area * b.length + 2 * support_mass + clamp;
  const double bounce = std::sqrt(2.0 * k / total);
  // The bounce mode couples to bending by (bounce / omega_bending)^2 ~ 1e-3 at most.
  constexpr double kBounceTol = 2e-3;
  EXPECT_NEAR(part.basis.omega[0], bounce, kBounceTol * bounce);
  // The supports' dampers are the whole C here (no Rayleigh): c on both end w's, nothing else.
  const BeamSystem& sys = part.system;
  const Eigen::MatrixXd C = Eigen::MatrixXd(sys.C);
  EXPECT_DOUBLE_EQ(C(sys.full_to_free[0], sys.full_to_free[0]), c);
  EXPECT_DOUBLE_EQ(C(sys.full_to_free[20], sys.full_to_free[20]), c);
  EXPECT_DOUBLE_EQ(C.cwiseAbs().sum(), 2.0 * c);
  // The masses sit on w: M's total translational mass is the beam's plus them.
  Eigen::VectorXd ones = Eigen::VectorXd::Zero(sys.M.rows());
  for (std::size_t i = 0; i < sys.full_to_free.size(); i += 2) ones[sys.full_to_free[i]] = 1.0;
  constexpr double kMassSumRoundOff = 1e-12;  // a sum of the mass matrix's entries, relative
  EXPECT_NEAR(ones.dot(sys.M * ones), total, kMassSumRoundOff * total);
}

}  // namespace
}  // namespace mbfe::runtime
