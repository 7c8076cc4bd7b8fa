// The adjustment policies per mode (the operators they make are tested in
// tests/runtime/structure/).
#include <gtest/gtest.h>

#include <cmath>

#include "runtime/damping/modal_adjustment.h"

namespace mbfe::runtime {
namespace {

ir::Adjustment cap(double omega_limit, double zeta_min = 0.0) {
  ir::Adjustment a;
  a.present = true;
  a.policy = ir::AdjustmentPolicy::kCap;
  a.omega_limit = omega_limit;
  a.margin = 0.1;
  a.zeta_min = zeta_min;
  return a;
}

// A root of 1.37e5 1/s computed two ways: ~1e-11 relative.
constexpr double kRootTol = 1e-6;

TEST(Policies, CapFloorAndEq25PerMode) {
  // Modes: (omega, c, k). Mode 0 lightly damped; 1 overdamped below the
  // limit; 2 overdamped far above it.
  std::vector<ModalDynamics> modes{{100.0, 0.2, 1e4}, {2e4, 6e4, 4e8}, {9e5, 1.2e8, 8.1e11}};
  const AdjustedModes a = adjust_modes(modes, cap(1e5, 0.05));
  EXPECT_EQ(a.change[0], ModeChange::kFloored);
  EXPECT_DOUBLE_EQ(a.modes[0].c, 2 * 0.05 * 100.0);
  EXPECT_EQ(a.change[1], ModeChange::kKept);  // fastest root 6e4 - 4e8/6e4... < 1e5
  EXPECT_EQ(a.change[2], ModeChange::kAdjusted);
  EXPECT_DOUBLE_EQ(a.modes[2].k, 1e10);
  EXPECT_DOUBLE_EQ(a.modes[2].c, 2.1e5);
  EXPECT_NEAR(fastest_root(a.modes[2].c, a.modes[2].k), (1.05 + std::sqrt(1.05 * 1.05 - 1)) * 1e5, kRootTol);
  ir::Adjustment eq25 = cap(1e5);
  eq25.policy = ir::AdjustmentPolicy::kPaperEq25;
  const AdjustedModes b = adjust_modes(modes, eq25);
  EXPECT_EQ(b.change[1], ModeChange::kKept);
  EXPECT_DOUBLE_EQ(b.modes[2].c, 2.1 * 9e5);
  EXPECT_DOUBLE_EQ(b.modes[2].k, 8.1e11);
  ir::Adjustment bad = cap(0.0);
  EXPECT_THROW(adjust_modes(modes, bad), std::invalid_argument);
}

TEST(Policies, MassKeepsTheStiffnessAndPutsTheRootsWhereTheCapDoes) {
  std::vector<ModalDynamics> modes{{100.0, 0.2, 1e4}, {2e4, 6e4, 4e8}, {9e5, 1.2e8, 8.1e11}};
  ir::Adjustment mass = cap(1e5, 0.05);
  mass.policy = ir::AdjustmentPolicy::kMass;
  const AdjustedModes capped = adjust_modes(modes, cap(1e5, 0.05));
  const AdjustedModes a = adjust_modes(modes, mass);
  EXPECT_EQ(a.policy, ir::AdjustmentPolicy::kMass);
  EXPECT_EQ(a.change, capped.change);  // the cap's selection and the same floor
  EXPECT_EQ(a.adjusted, 1);
  EXPECT_FALSE(a.uniform);  // the cap's low-rank form of K and C does not apply
  EXPECT_DOUBLE_EQ(a.k_star, 1e10);
  EXPECT_DOUBLE_EQ(a.c_star, 2.1e5);
  // Kept and floored modes as the cap leaves them, with a unit modal mass.
  for (int j : {0, 1}) {
    EXPECT_EQ(a.modes[j].m, 1.0);
    EXPECT_EQ(a.modes[j].k, capped.modes[j].k);
    EXPECT_EQ(a.modes[j].c, capped.modes[j].c);
  }
  // The adjusted mode: stiffness kept, m = k / omega_l^2, c = m (2 + margin) omega_l.
  EXPECT_EQ(a.modes[2].k, 8.1e11);
  EXPECT_DOUBLE_EQ(a.modes[2].m, 8.1e11 / 1e10);
  EXPECT_DOUBLE_EQ(a.modes[2].c, 81.0 * 2.1e5);
  // Its roots (of m r^2 + c r + k) are the cap's, to round-off.
  const auto r_mass = modal_roots(a.modes[2]);
  const auto r_cap = modal_roots(capped.modes[2].c, capped.modes[2].k);
  constexpr double kRoundoffRel = 1e-14;  // two divisions apart
  EXPECT_NEAR(r_mass.first.real(), r_cap.first.real(), kRoundoffRel * std::abs(r_cap.first));
  EXPECT_NEAR(r_mass.second.real(), r_cap.second.real(), kRoundoffRel * std::abs(r_cap.second));
  EXPECT_NEAR(fastest_root(a.modes[2]), (1.05 + std::sqrt(1.05 * 1.05 - 1)) * 1e5, kRootTol);
  // Nothing above the limit: nothing changed, and the form stays uniform.
  mass.omega_limit = 1e9;  // above every fastest root (the last mode's: ~1.2e8)
  const AdjustedModes none = adjust_modes(modes, mass);
  EXPECT_EQ(none.adjusted, 0);
  EXPECT_TRUE(none.uniform);
}

TEST(Policies, TheFloorReadsTheModalMass) {
  // A mode with its own modal mass 4, k = 4e4 (omega 100), c = 8: a damping
  // ratio c / (2 sqrt(k m)) = 0.01, raised to 0.05: c = 2 0.05 sqrt(k m) = 40.
  const std::vector<ModalDynamics> modes{{100.0, 8.0, 4e4, 4.0}};
  const AdjustedModes a = adjust_modes(modes, cap(1e5, 0.05));
  ASSERT_EQ(a.change[0], ModeChange::kFloored);
  EXPECT_DOUBLE_EQ(a.modes[0].c, 40.0);
  const auto r = modal_roots(a.modes[0]);
  // A damping ratio from a root of a quadratic: round-off.
  constexpr double kRatioRoundOff = 1e-12;
  EXPECT_NEAR(-r.first.real() / std::abs(r.first), 0.05, kRatioRoundOff);
}

}  // namespace
}  // namespace mbfe::runtime
