// The thread budget (runtime/platform/thread_budget.h): MBFE_THREADS limits
// the cores a process may use, never raises them, and a malformed value is
// no limit.
#include <gtest/gtest.h>

#include "runtime/platform/thread_budget.h"

namespace mbfe::runtime {
namespace {

TEST(ThreadBudget, TheEnvironmentLimitsTheCoresAndAMalformedValueDoesNot) {
  EXPECT_EQ(thread_budget(2, nullptr), 2u);
  EXPECT_EQ(thread_budget(2, "1"), 1u);
  EXPECT_EQ(thread_budget(2, "2"), 2u);
  EXPECT_EQ(thread_budget(2, "16"), 2u) << "a limit above the cores does not raise them";
  EXPECT_EQ(thread_budget(64, "3"), 3u);
  for (const char* bad : {"", "0", "-1", "+2", " 2", "2 ", "2x", "two", "1.5", "99999999999999999999999"})
    EXPECT_EQ(thread_budget(4, bad), 4u) << "MBFE_THREADS='" << bad << "'";
  EXPECT_EQ(thread_budget(0, nullptr), 1u) << "at least one";
  EXPECT_GE(thread_budget(), 1u);
}

}  // namespace
}  // namespace mbfe::runtime
