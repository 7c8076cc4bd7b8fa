#include "runtime/coupled/structure_lanes.h"

#include <chrono>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace mbfe::runtime {

namespace {

// How long a side spins before it sleeps: longer than the gaps between the
// lanes' handovers in a run (an evaluation's serial part, the rest of a time
// step and its report), so that a run seldom pays a sleep and a wake-up;
// short enough to cost little when the other side has really gone. Spinning
// yields the core now and then, so that on a busy host (a sweep's processes)
// it gives way to the thread it waits for.
constexpr std::chrono::microseconds kSpin{500};
constexpr int kPausesPerCheck = 64;

void pause() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#else
  std::this_thread::yield();
#endif
}

/// Spins until done() or kSpin has passed; true if done().
template <class Done>
bool spin_until(Done done) {
  const auto end = std::chrono::steady_clock::now() + kSpin;
  for (int checks = 0;; ++checks) {
    for (int i = 0; i < kPausesPerCheck; ++i) {
      if (done()) return true;
      pause();
    }
    if (std::chrono::steady_clock::now() > end) return done();
    if (checks % 64 == 63) std::this_thread::yield();
  }
}

}  // namespace

StructureLanes::StructureLanes(bool threaded) {
  if (threaded) worker_ = std::thread([this]() { serve(); });
}

StructureLanes::~StructureLanes() {
  if (!worker_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_.store(true);
  }
  wake_.notify_one();
  worker_.join();
}

void StructureLanes::run_erased(int count, Call call, void* work) {
  if (!worker_.joinable() || count < 2) {
    for (int i = 0; i < count; ++i) call(work, i);
    return;
  }
  call_ = call;
  work_ = work;
  count_ = count;
  const unsigned long generation = posted_.load(std::memory_order_relaxed) + 1;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    posted_.store(generation, std::memory_order_release);
  }
  wake_.notify_one();
  std::exception_ptr mine;
  try {
    for (int i = 0; i < count; i += 2) call(work, i);
  } catch (...) {
    mine = std::current_exception();
  }
  if (!spin_until([&]() { return finished_.load(std::memory_order_acquire) == generation; })) {
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [&]() { return finished_.load(std::memory_order_acquire) == generation; });
  }
  std::exception_ptr theirs = failure_;
  failure_ = nullptr;
  if (mine) std::rethrow_exception(mine);
  if (theirs) std::rethrow_exception(theirs);
}

void StructureLanes::serve() {
  unsigned long seen = 0;
  for (;;) {
    const auto waiting = [&]() { return !stop_.load() && posted_.load(std::memory_order_acquire) == seen; };
    if (!spin_until([&]() { return !waiting(); })) {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&]() { return !waiting(); });
    }
    if (stop_.load()) return;
    seen = posted_.load(std::memory_order_acquire);
    std::exception_ptr failure;
    try {
      for (int i = 1; i < count_; i += 2) call_(work_, i);
    } catch (...) {
      failure = std::current_exception();
    }
    failure_ = failure;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      finished_.store(seen, std::memory_order_release);
    }
    done_.notify_one();
  }
}

}  // namespace mbfe::runtime
