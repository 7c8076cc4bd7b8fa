// The search for the lowest omega_limit within a tolerance, on changes whose
// answer is known in closed form.
#include "runtime/simulation/limit_search.h"

#include <gtest/gtest.h>

namespace mbfe::runtime {
namespace {

constexpr LimitSearchResolution kFine{40, 40};

TEST(ReadableLimit, RoundsUpToFourSignificantDigits) {
  EXPECT_DOUBLE_EQ(readable_limit(459.41), 459.5);
  EXPECT_DOUBLE_EQ(readable_limit(1500.0), 1500.0);
  EXPECT_DOUBLE_EQ(readable_limit(0.012341), 0.01235);
}

TEST(LowestLimitWithin, AMonotoneChangeGivesItsCrossingRoundedUpToThePassingSide) {
  // change = 1/omega crosses 0.01 at omega = 100: the search ends just above
  // it, and 100 + epsilon reads as 100.1, which passes.
  const auto change = [](double omega) { return 1.0 / omega; };
  EXPECT_DOUBLE_EQ(lowest_limit_within(change, 0.01, 1e4, 1.0, kFine), 100.1);
}

TEST(LowestLimitWithin, AFailingBandAboveTheCrossingStopsTheSearchThere) {
  // Between 300 and 400 rad/s the change is too large (a mode's root beside
  // the contact's): every higher limit passes, so the answer is just above
  // 400, not the monotone part's 100.
  const auto change = [](double omega) { return omega >= 300.0 && omega <= 400.0 ? 1.0 : 1.0 / omega; };
  const double limit = lowest_limit_within(change, 0.01, 1e4, 1.0, kFine);
  EXPECT_GT(limit, 400.0);
  EXPECT_LE(limit, 400.1);
}

TEST(LowestLimitWithin, WhenEveryLimitPassesTheGridsBottomIsTheAnswer) {
  // The grid's last point is 2 up to the round-off of its powers, read up to
  // four digits: 2 or 2.001.
  const auto change = [](double) { return 0.0; };
  const double limit = lowest_limit_within(change, 0.01, 1e4, 2.0, kFine);
  EXPECT_GE(limit, 2.0 - 1e-12);
  EXPECT_LE(limit, 2.001 + 1e-12);
}

TEST(LowestLimitWithin, ACoarseSearchCallsTheChangeFewerTimesAndFindsTheSameCrossing) {
  int fine_calls = 0, coarse_calls = 0;
  const auto counted = [](int& calls) {
    return [&calls](double omega) {
      ++calls;
      return 1.0 / omega;
    };
  };
  const double fine = lowest_limit_within(counted(fine_calls), 0.01, 1e4, 1.0, kFine);
  const double coarse = lowest_limit_within(counted(coarse_calls), 0.01, 1e4, 1.0, LimitSearchResolution{10, 10});
  EXPECT_LT(coarse_calls, fine_calls);
  // 10 bisections of the grid ratio 10^0.1 leave it within 10^(0.1/1024) - 1 = 2.2e-4.
  EXPECT_NEAR(coarse, 100.0, 100.0 * 2.3e-4 + 0.1);
  EXPECT_DOUBLE_EQ(fine, 100.1);
}

}  // namespace
}  // namespace mbfe::runtime
