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

}  // namespace
}  // namespace mbfe::runtime
