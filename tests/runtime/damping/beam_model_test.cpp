// The beams of a model analysed (runtime/damping/beam_model.h): a simply
// supported Euler-Bernoulli beam's modes against the closed form
// omega_n = (n pi / L)^2 sqrt(EI / rho A), its Rayleigh modal damping against
// alpha + beta omega^2, and the threaded analysis of several large beams
// against the same beams analysed one by one, bit for bit.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <string>

#include "ir/model.h"
#include "runtime/damping/beam_model.h"

namespace mbfe::runtime {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kSpan = 10.0;         // m
constexpr double kYoungsModulus = 1e11;  // Pa
constexpr double kDensity = 8900.0;      // kg/m^3
constexpr double kArea = 1e-4;           // m^2
constexpr double kSecondMoment = 2e-7;   // m^4: EI = 2e4 N m^2

// The Hermite element with consistent mass overestimates omega_n by
// (k h)^4 / 1440 relative, k = n pi / L, to leading order (Rayleigh-Ritz: from
// above); the higher orders add less than a tenth of it for the lowest five
// modes of 40 elements (mode 5: 1.65e-5 against 1.65e-5 predicted).
constexpr double kLeadingTermMargin = 1.1;
// Two lowest modes of a beam, same closed form, different meshes: both
// within 1e-6 of it.
constexpr double kDiscretisationTol = 1e-6;
// c_j = alpha + beta omega_j^2 evaluated again here: a few ulps of omega^2.
constexpr double kRoundOff = 1e-12;

ir::Beam simply_supported(const std::string& name, int elements) {
  ir::Beam b;
  b.name = name;
  b.length = kSpan;
  b.elements = elements;
  b.area = kArea;
  b.second_moment = kSecondMoment;
  b.youngs_modulus = kYoungsModulus;
  b.density = kDensity;
  b.rayleigh_alpha = 0.3;
  b.rayleigh_beta = 2e-5;
  b.supports = {{0.0, ir::SupportType::kPinned, -1, {}}, {kSpan, ir::SupportType::kPinned, -1, {}}};
  return b;
}

TEST(BeamModel, ModesOfASimplySupportedBeamAreTheClosedForm) {
  const ir::Beam beam = simply_supported("deck", 40);
  const BeamPart part = analyse_beam(beam, {0.0, -9.81});
  ASSERT_TRUE(part.dense);
  ASSERT_TRUE(part.basis.complete);
  // 41 nodes, two DOFs each, the two end deflections held.
  ASSERT_EQ(part.basis.omega.size(), 2 * 41 - 2);
  const double speed = std::sqrt(kYoungsModulus * kSecondMoment / (kDensity * kArea));
  const double h = kSpan / 40;
  for (int n = 1; n <= 5; ++n) {
    const double closed = std::pow(n * kPi / kSpan, 2) * speed;
    const double leading = std::pow(n * kPi / kSpan * h, 4) / 1440.0;
    const double excess = part.basis.omega[n - 1] / closed - 1.0;
    EXPECT_GT(excess, 0.0) << "mode " << n << ": a Ritz approximation lies above";
    EXPECT_LT(excess, kLeadingTermMargin * leading) << "mode " << n;
  }

  ASSERT_EQ(part.original.size(), static_cast<std::size_t>(part.basis.omega.size()));
  for (std::size_t j = 0; j < part.original.size(); ++j) {
    const double w = part.basis.omega[static_cast<Eigen::Index>(j)];
    const double c = beam.rayleigh_alpha + beam.rayleigh_beta * w * w;
    EXPECT_NEAR(part.original[j].c, c, kRoundOff * c) << "mode " << j + 1;
    EXPECT_NEAR(part.original[j].k, w * w, kRoundOff * w * w) << "mode " << j + 1;
    EXPECT_EQ(part.original[j].m, 1.0);
  }
  // Without an adjustment block the adjusted modes are the original ones.
  EXPECT_FALSE(part.has_adjustment);
  ASSERT_EQ(part.adjusted.modes.size(), part.original.size());
  for (std::size_t j = 0; j < part.original.size(); ++j) {
    EXPECT_EQ(part.adjusted.modes[j].k, part.original[j].k);
    EXPECT_EQ(part.adjusted.modes[j].c, part.original[j].c);
  }
}

TEST(BeamModel, ThreadedAnalysisIsTheSerialOneBitForBit) {
  // Three beams above the dense limit: analyse_beams takes them on threads
  // (when the machine has more than one core); analyse_beam one by one is
  // the serial reference.
  ir::Model model;
  model.gravity = {0.0, -9.81};
  model.beams = {simply_supported("a", 30), simply_supported("b", 36), simply_supported("c", 24)};
  model.beams[1].second_moment = 3e-7;
  BeamAnalysisOptions options;
  options.dense_limit = 20;
  options.sparse_modes = 6;
  const BeamModel all = analyse_beams(model, options);
  ASSERT_EQ(all.beams.size(), 3u);
  int offset = 0;
  for (std::size_t k = 0; k < model.beams.size(); ++k) {
    const BeamPart alone = analyse_beam(model.beams[k], model.gravity, options);
    const BeamPart& part = all.beams[k];
    EXPECT_FALSE(part.dense);
    EXPECT_EQ(part.system.name, model.beams[k].name);
    EXPECT_EQ(part.offset, offset) << "beam " << k;
    offset += static_cast<int>(part.system.M.rows());
    ASSERT_EQ(part.basis.omega.size(), 6) << "beam " << k;
    EXPECT_TRUE(part.basis.omega == alone.basis.omega) << "beam " << k;
    EXPECT_TRUE(part.basis.phi == alone.basis.phi) << "beam " << k;
    ASSERT_EQ(part.original.size(), alone.original.size());
    for (std::size_t j = 0; j < part.original.size(); ++j) {
      EXPECT_EQ(part.original[j].c, alone.original[j].c) << "beam " << k << " mode " << j;
      EXPECT_EQ(part.original[j].k, alone.original[j].k) << "beam " << k << " mode " << j;
    }
  }
  EXPECT_EQ(all.dof, offset);
  // Beam b is stiffer: its lowest mode is sqrt(1.5) times beam a's.
  EXPECT_NEAR(all.beams[1].basis.omega[0] / all.beams[0].basis.omega[0], std::sqrt(1.5), kDiscretisationTol);
}

}  // namespace
}  // namespace mbfe::runtime
