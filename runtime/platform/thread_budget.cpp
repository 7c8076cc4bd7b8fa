#include "runtime/platform/thread_budget.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <thread>

#if defined(__linux__)
#include <sched.h>
#endif

namespace mbfe::runtime {

namespace {

unsigned cores_of_this_process() {
#if defined(__linux__)
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) == 0) {
    const int count = CPU_COUNT(&set);
    if (count > 0) return static_cast<unsigned>(count);
  }
#endif
  return std::max(1u, std::thread::hardware_concurrency());
}

}  // namespace

unsigned thread_budget(unsigned cores, const char* limit) {
  cores = std::max(1u, cores);
  if (limit == nullptr || *limit < '1' || *limit > '9') return cores;
  char* end = nullptr;
  errno = 0;
  const unsigned long value = std::strtoul(limit, &end, 10);
  if (errno != 0 || *end != '\0' || value == 0) return cores;
  return value < cores ? static_cast<unsigned>(value) : cores;
}

unsigned thread_budget() {
  static const unsigned budget = thread_budget(cores_of_this_process(), std::getenv("MBFE_THREADS"));
  return budget;
}

}  // namespace mbfe::runtime
