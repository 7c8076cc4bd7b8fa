// The running surface a slider rides on: the offset reaches the generated
// kernels through the element's DOFs, so the Hermite interpolation of those
// DOFs must give the profile's value, slope and curvature at s exactly; a
// table is the linear interpolation of its rows; a spectrum profile's table
// follows its harmonic sum; camber: static is the closed-form sag of a
// simply supported beam under its own weight.
#include "runtime/fem/running_surface.h"

#include <gtest/gtest.h>

#include <cmath>

#include "frontend/expression_parser.h"
#include "runtime/fem/hermite_shape.h"
#include "tests/runtime/fem/beam_fixtures.h"

namespace mbfe::runtime {
namespace {

constexpr double kExactTol = 1e-13;  // m: round-off on millimetre offsets
constexpr double kSlopeRoundOff = 1e-12;  // rad: a difference of millimetre offsets over a 0.5 m row spacing

ir::BeamProfile expression_profile(const std::string& text) {
  ir::BeamProfile p;
  p.kind = ir::ProfileKind::kExpression;
  p.expression = frontend::parse_expression(text, "test.yaml", ir::SourceLoc{1, 1}, "profile.expression", "s");
  return p;
}

TEST(RunningSurface, ElementDofsCarryTheProfilesValueSlopeAndCurvatureAtS) {
  const RunningSurface surface(expression_profile("0.002*sin(2*pi*s/25) + 1e-4*s"), 30.0, 30, {});
  const double le = 1.0;
  for (double s : {0.0, 0.4, 12.7, 29.99}) {
    const int e = std::min(29, static_cast<int>(s / le));
    const double s0 = e * le;
    double qe[4] = {1e-3, -2e-4, 3e-3, 5e-4};  // some deflection of the beam itself
    const Eigen::Vector4d before = Eigen::Map<Eigen::Vector4d>(qe);
    surface.add_to_element(e, s, s0, le, qe);
    const Eigen::Vector4d after = Eigen::Map<Eigen::Vector4d>(qe);
    const double xi = (s - s0) / le;
    const Jet r = surface.profile(s);
    EXPECT_NEAR(hermite::N(xi, le) * (after - before), r.value, kExactTol);
    // Slope and curvature from the element DOFs: the shape functions'
    // derivatives scale the round-off by their sizes (a hundred and a
    // thousand times, with a margin, on 1 m elements).
    constexpr double kSlopeTol = 1e2 * kExactTol;
    constexpr double kCurvatureTol = 1e3 * kExactTol;
    EXPECT_NEAR(hermite::dN_ds(xi, le) * (after - before), r.d1, kSlopeTol);
    EXPECT_NEAR(hermite::d2N_ds2(xi, le) * (after - before), r.d2, kCurvatureTol);
  }
}

TEST(RunningSurface, TableIsTheLinearInterpolationOfTheExpressionItWasSampledFrom) {
  const ir::BeamProfile exact = expression_profile("0.002*sin(2*pi*s/25)");
  ir::BeamProfile table;
  table.kind = ir::ProfileKind::kTable;
  const double h = 0.5;
  for (int k = 0; k <= 60; ++k) {
    table.table_s.push_back(k * h);
    table.table_offset.push_back(exact.expression.evaluate(k * h));
  }
  const RunningSurface from_table(table, 30.0, 30, {}), from_expression(exact, 30.0, 30, {});
  // At the rows: the same value. Between them: within the linear
  // interpolation's bound h^2 / 8 max |r''| = 0.25 / 8 * 0.002 (2 pi / 25)^2.
  const double bound = h * h / 8 * 0.002 * std::pow(2 * test::kPi / 25, 2);
  constexpr double kBoundMargin = 1.0001;  // the bound widened by 1e-4 of it: the round-off of its terms
  for (int k = 0; k < 60; ++k) {
    const double s = k * h;
    EXPECT_NEAR(from_table.profile(s).value, from_expression.profile(s).value, kExactTol);
    const double mid = s + h / 2;
    const double linear = 0.5 * (table.table_offset[k] + table.table_offset[k + 1]);
    EXPECT_NEAR(from_table.profile(mid).value, linear, kExactTol);
    EXPECT_NEAR(from_table.profile(mid).value, from_expression.profile(mid).value, bound * kBoundMargin);
    EXPECT_NEAR(from_table.profile(mid).d1, (table.table_offset[k + 1] - table.table_offset[k]) / h, kSlopeRoundOff);
  }
}

TEST(RunningSurface, RefusesATableWhoseSDoesNotIncrease) {
  ir::BeamProfile table;
  table.kind = ir::ProfileKind::kTable;
  table.table_s = {0.0, 1.0, 1.0};
  table.table_offset = {0.0, 0.0, 0.0};
  EXPECT_THROW(RunningSurface(table, 1.0, 1, {}), std::invalid_argument);
}

TEST(RunningSurface, TabulatedSpectrumProfileFollowsItsHarmonicSum) {
  ir::BeamProfile p;
  p.kind = ir::ProfileKind::kSpectrum;
  p.spectrum = ir::TrackSpectrum::kFra;
  p.spectrum_class = 5;
  p.wavelength_min = 1.0;
  p.wavelength_max = 80.0;
  p.seed = 7;
  const RunningSurface surface(p, 30.0, 30, {});
  const HarmonicProfile sum = spectrum_profile(p.spectrum, 5, 1.0, 80.0, 30.0, 7);
  // Cubic Hermite on a grid of lambda_min / 32: relative error (h omega)^4 / 384
  // at the shortest wavelength, 4e-6 of its amplitude; against the profile's
  // rms (about 1 mm), 1e-8 m, and a slope error of the order h^3 omega^4.
  constexpr double kValueTol = 1e-8;   // m
  constexpr double kSlopeTol = 1e-6;   // rad
  double rms = 0.0;
  for (int k = 0; k <= 3000; ++k) {
    const double s = 0.01 * k + 0.0037;
    double r, dr, ddr;
    sum.evaluate(s, r, dr, ddr);
    const Jet j = surface.profile(s);
    EXPECT_NEAR(j.value, r, kValueTol) << "s = " << s;
    EXPECT_NEAR(j.d1, dr, kSlopeTol) << "s = " << s;
    rms += r * r / 3001;
  }
  EXPECT_GT(std::sqrt(rms), 1e-4);  // a profile, not zeros
}

TEST(RunningSurface, StaticCamberIsTheSagOfASimplySupportedBeamUnderItsOwnWeight) {
  ir::Beam beam = test::paper_beam(0.005, 20);
  beam.profile.camber_static = true;
  const ir::Vec2 gravity{0.0, -9.81};
  const std::optional<RunningSurface> surface = running_surface(beam, gravity);
  ASSERT_TRUE(surface.has_value());
  // w(x) = q x (L^3 - 2 L x^2 + x^3) / (24 EI), q = rho A g downwards (w < 0):
  // the Hermite element with consistent loads is exact at the nodes.
  const double q = -beam.density * beam.area * 9.81, L = beam.length, EI = test::bending_stiffness(beam);
  const double sag = 5 * std::abs(q) * std::pow(L, 4) / (384 * EI);
  // At the nodes: a static solve of 40 DOF against the closed form, round-off
  // times the stiffness's conditioning, relative to the midspan sag.
  constexpr double kNodalRel = 1e-9;
  // Between nodes the cubic interpolates the quartic: within 1e-3 of the sag.
  constexpr double kInterpolationRel = 1e-3;
  for (int node = 0; node <= 20; ++node) {
    const double x = node * L / 20;
    const double w = q * x * (L * L * L - 2 * L * x * x + x * x * x) / (24 * EI);
    EXPECT_NEAR(surface->camber()[2 * node], w, kNodalRel * sag) << "node " << node;
    EXPECT_NEAR(surface->offset(x), -w, kNodalRel * sag) << "node " << node;
  }
  const double x = 0.525;
  EXPECT_NEAR(surface->offset(x), -q * x * (L * L * L - 2 * L * x * x + x * x * x) / (24 * EI), kInterpolationRel * sag);
  // Point loads are live loads, not dead weight: they leave the camber alone.
  ir::Beam loaded = beam;
  loaded.loads.push_back({});
  loaded.loads.back().at = 0.5;
  loaded.loads.back().value = ir::Expression::number(-1e4);
  // The same solve with the same load: equal but for a last bit (m).
  constexpr double kSameSolveTol = 1e-15;
  EXPECT_NEAR(running_surface(loaded, gravity)->camber()[20], surface->camber()[20], kSameSolveTol);
  // A beam no support holds has no own-weight sag to take out.
  ir::Beam hung = beam;
  hung.supports.clear();
  EXPECT_THROW(running_surface(hung, gravity), std::invalid_argument);
}

}  // namespace
}  // namespace mbfe::runtime
