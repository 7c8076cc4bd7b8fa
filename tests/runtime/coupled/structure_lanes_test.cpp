// StructureLanes (runtime/coupled/structure_lanes.h): every item runs once,
// on one thread or two, many times over (a run hands work over four times a
// step), and an item's exception reaches the caller from either side.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "runtime/coupled/structure_lanes.h"

namespace mbfe::runtime {
namespace {

// Enough handovers that a lost wake-up or a race on the posted work would
// show as a hang or a miscount.
constexpr int kRounds = 5000;

TEST(StructureLanes, EveryItemRunsOnceARoundOnOneThreadOrTwo) {
  for (const bool threaded : {false, true}) {
    StructureLanes lanes(threaded);
    EXPECT_EQ(lanes.threaded(), threaded);
    for (const int count : {0, 1, 2, 3, 5}) {
      std::vector<int> runs(static_cast<std::size_t>(count), 0);
      std::vector<std::thread::id> where(static_cast<std::size_t>(count));
      auto work = [&](int i) {
        ++runs[static_cast<std::size_t>(i)];
        where[static_cast<std::size_t>(i)] = std::this_thread::get_id();
      };
      for (int round = 0; round < kRounds; ++round) lanes.run(count, work);
      for (int i = 0; i < count; ++i) {
        EXPECT_EQ(runs[static_cast<std::size_t>(i)], kRounds) << "item " << i << " of " << count;
        // The caller takes the even items; the worker the odd ones.
        const bool on_caller = where[static_cast<std::size_t>(i)] == std::this_thread::get_id();
        EXPECT_EQ(on_caller, !threaded || count < 2 || i % 2 == 0) << "item " << i << " of " << count;
      }
    }
  }
}

TEST(StructureLanes, AnItemsExceptionReachesTheCallerFromEitherSide) {
  StructureLanes lanes(true);
  for (const int failing : {0, 1}) {
    auto work = [&](int i) {
      if (i == failing) throw std::runtime_error("item " + std::to_string(i));
    };
    try {
      lanes.run(2, work);
      ADD_FAILURE() << "no exception from item " << failing;
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "item " + std::to_string(failing));
    }
    // The lanes still work afterwards.
    std::atomic<int> runs{0};
    auto count = [&](int) { ++runs; };
    lanes.run(2, count);
    EXPECT_EQ(runs, 2);
  }
}

}  // namespace
}  // namespace mbfe::runtime
