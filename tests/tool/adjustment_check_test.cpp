// The step of `mbfe simulate --check-adjustment T` (tool/adjustment_check.h):
// at least 2000 steps over T and h omega <= 0.05 at the fastest frequency the
// adjusted run keeps, a whole fraction of the run's step; and that frequency
// read from a model's adjusted beams and contact springs.
#include "tool/adjustment_check.h"

#include <gtest/gtest.h>

#include <cmath>

namespace mbfe::tool {
namespace {

TEST(AdjustmentCheckStep, AtLeastTwoThousandStepsOverTheCheckedTime) {
  // No frequency to resolve: T / 2000 = 1.5e-4 s, 1e-3 s / 7 the first whole fraction below.
  EXPECT_DOUBLE_EQ(check_step(1e-3, 0.3, 0.0), 1e-3 / 7);
  // A frequency slower than the steps already resolve changes nothing.
  EXPECT_DOUBLE_EQ(check_step(1e-3, 0.3, 100.0), 1e-3 / 7);
}

TEST(AdjustmentCheckStep, ResolvesTheFastestFrequencyTheRunKeeps) {
  // 0.05 / 2000 rad/s = 2.5e-5 s: 1e-3 s / 40.
  EXPECT_DOUBLE_EQ(check_step(1e-3, 0.85, 2000.0), 1e-3 / 40);
  // 0.05 / 3000 = 1.667e-5 s: the run's step divided by 60.
  EXPECT_DOUBLE_EQ(check_step(1e-3, 0.85, 3000.0), 1e-3 / 60);
  // A run step already below both is kept.
  EXPECT_DOUBLE_EQ(check_step(1e-5, 0.85, 2000.0), 1e-5);
}

TEST(AdjustmentCheckStep, TheFrequencyIsTheLargestLimitOrContactBounce) {
  ir::Model model;
  model.bodies.resize(1);
  model.bodies[0].mass = 1500.0;  // kg
  ir::Contact wheel;
  wheel.type = ir::ContactType::kSliderSpring;
  wheel.body = 0;
  wheel.stiffness = 1e9;  // N/m: a bounce of sqrt(1e9 / 1500) = 816.5 rad/s
  model.contacts.push_back(wheel);
  EXPECT_DOUBLE_EQ(resolved_frequency(model, {{"deck", 500.0, false}}), std::sqrt(1e9 / 1500.0));
  EXPECT_DOUBLE_EQ(resolved_frequency(model, {{"deck", 2000.0, false}, {"slab", 3000.0, true}}), 3000.0);
  model.contacts[0].stiffness = 0.0;  // a Hertzian contact: no linear stiffness to read
  EXPECT_DOUBLE_EQ(resolved_frequency(model, {}), 0.0);
}

}  // namespace
}  // namespace mbfe::tool
