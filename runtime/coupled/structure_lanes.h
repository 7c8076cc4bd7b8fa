// Work on independent structures of one evaluation, on two threads: the two
// wires of a catenary are independent blocks between the coupling forces
// (docs/performance.md, "Both cores in a step"). The caller takes the even
// items, a worker thread kept for the run the odd ones; each item writes its
// own structure's workspace, so the result is the same bits on one lane or
// two. Handing work over allocates nothing.
#pragma once

#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace mbfe::runtime {

class StructureLanes {
 public:
  /// @param threaded false: every item runs on the caller's thread.
  explicit StructureLanes(bool threaded);
  ~StructureLanes();
  StructureLanes(const StructureLanes&) = delete;
  StructureLanes& operator=(const StructureLanes&) = delete;

  bool threaded() const { return worker_.joinable(); }

  /// Calls work(i) for every i in [0, count) and returns when all have; an
  /// item's exception is rethrown (the caller's side's before the worker's).
  template <class Work>
  void run(int count, Work& work) {
    run_erased(count, [](void* w, int i) { (*static_cast<Work*>(w))(i); }, &work);
  }

 private:
  using Call = void (*)(void*, int);
  void run_erased(int count, Call call, void* work);
  void serve();

  // Each side waits for the other by spinning a while first (an
  // evaluation's serial part between two handovers is shorter than a sleep
  // and a wake-up), then on the condition variable.
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  // The work posted to the worker, and the generation it belongs to (the
  // work is written before posted_ is raised, read after it is seen).
  Call call_ = nullptr;
  void* work_ = nullptr;
  int count_ = 0;
  std::atomic<unsigned long> posted_{0}, finished_{0};
  std::atomic<bool> stop_{false};
  std::exception_ptr failure_;
  std::thread worker_;
};

}  // namespace mbfe::runtime
