// libFuzzer target over parse + validate + generate (see fuzz_entry.h).
// Built and run by scripts/fuzz.sh; not part of the CMake build. A crash it
// finds goes into tests/fuzz/regressions/, which the normal test suite replays
// (fuzz_regressions_test.cpp).
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  mbfe::fuzz::fuzz_one_input(data, size);  // unexpected exceptions escape: a crash
  return 0;
}
