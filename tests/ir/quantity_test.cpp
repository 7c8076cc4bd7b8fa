// The one rule for the units of coordinates and output columns: every
// quantity and time derivative against the units written out by hand, and
// what a joint's coordinate, its reaction and a beam DOF measure.
#include "ir/quantity.h"

#include <gtest/gtest.h>

namespace mbfe::ir {
namespace {

TEST(Quantity, SiUnitOfEveryQuantityAndRate) {
  EXPECT_EQ(si_unit(Quantity::kLength), "m");
  EXPECT_EQ(si_unit(Quantity::kLength, 1), "m/s");
  EXPECT_EQ(si_unit(Quantity::kLength, 2), "m/s^2");
  EXPECT_EQ(si_unit(Quantity::kAngle), "rad");
  EXPECT_EQ(si_unit(Quantity::kAngle, 1), "rad/s");
  EXPECT_EQ(si_unit(Quantity::kAngle, 2), "rad/s^2");
  EXPECT_EQ(si_unit(Quantity::kRatio), "1");
  EXPECT_EQ(si_unit(Quantity::kRatio, 1), "1/s");
  EXPECT_EQ(si_unit(Quantity::kRatio, 2), "1/s^2");
  EXPECT_EQ(si_unit(Quantity::kForce), "N");
  EXPECT_EQ(si_unit(Quantity::kMoment), "N m");
  EXPECT_EQ(si_unit(Quantity::kTime), "s");
}

TEST(Quantity, JointsAndBeamDofs) {
  EXPECT_EQ(joint_coordinate(JointType::kRevolute), Quantity::kAngle);
  EXPECT_EQ(joint_coordinate(JointType::kPrismatic), Quantity::kLength);
  EXPECT_EQ(joint_reaction(JointType::kRevolute), Quantity::kMoment);
  EXPECT_EQ(joint_reaction(JointType::kPrismatic), Quantity::kForce);
  // A slope w' = dw/ds is a length over a length.
  EXPECT_EQ(beam_dof(true), Quantity::kRatio);
  EXPECT_EQ(beam_dof(false), Quantity::kLength);
}

}  // namespace
}  // namespace mbfe::ir
