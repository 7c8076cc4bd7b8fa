#!/usr/bin/env bash
# Builds mbfe and its tests into build-asan/ with AddressSanitizer and
# UndefinedBehaviorSanitizer (-DMBFE_SANITIZE=ON) and runs the whole test suite
# under them. Any report fails the run (halt_on_error / abort_on_error).
# Solvers that `mbfe` compiles at run time inherit the sanitizer flags;
# GiNaC, CLN and yaml-cpp (Debian packages) are not instrumented.
#
# Environment:
#   MBFE_ASAN_BUILD_DIR   build folder (default build-asan)
#   MBFE_ASAN_GTEST_FILTER  extra gtest negative filter (default: none; see
#                         docs/robustness.md for what, if anything, is skipped)
#   MBFE_JOBS             parallel build/test jobs (default: nproc)
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir="${MBFE_ASAN_BUILD_DIR:-build-asan}"
jobs="${MBFE_JOBS:-$(nproc 2>/dev/null || echo 2)}"

# -O1: the optimisation level the sanitizer documentation recommends (usable
# stack traces, tests fast enough). -g1: line tables, all a report's stack
# trace needs, at three quarters of -g's compile time. No -DNDEBUG: Eigen's and
# our assertions stay on in this build, as a further check. Executables are
# linked without PIE: the sanitizers' metadata makes millions of relocations
# that a PIE applies at every start, about 0.4 s for each of the suite's
# nearly thousand test processes and each mbfe they run.
# Through ccache when it is there (scripts/ccache-launcher.sh): the next run
# in the same folder compiles only what changed.
source scripts/ccache-launcher.sh
cmake -S . -B "$build_dir" "${launcher[@]}" \
  -DMBFE_SANITIZE=ON \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1" \
  -DCMAKE_EXE_LINKER_FLAGS="-no-pie" \
  -DMBFE_BUILD_BENCHMARKS=OFF -DMBFE_BUILD_PYTHON=OFF >/dev/null
# The sanitizer settings hold for the build too: it runs the instrumented
# `mbfe generate` for the solvers of the test suite (mbfe_add_model).
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/support/lsan.supp:print_suppressions=0"
cmake --build "$build_dir" -j"$jobs" --target mbfe_cli mbfe_tests
export MBFE_CACHE_DIR="$PWD/$build_dir/test-cache"
# gtest_discover_tests sets MBFE_CACHE_DIR per test as well; the filter (if any)
# reaches every test process through GTEST_FILTER.
if [[ -n "${MBFE_ASAN_GTEST_FILTER:-}" ]]; then
  export GTEST_FILTER="-${MBFE_ASAN_GTEST_FILTER}"
fi
# The Python module is not built here: an instrumented extension needs the
# sanitizer runtime preloaded into the interpreter; the normal run tests it.
# downstream_cmake_project is left out: it builds a separate CMake project
# against this build's exported static libraries, and the instrumented ones
# need the consumer to link the sanitizer runtimes, which the build-tree
# package does not export. The normal run (scripts/test.sh) covers it.
# architecture_layers reads the sources only (no instrumented code runs): the
# normal run covers it too.
ctest --test-dir "$build_dir" --output-on-failure -j"$jobs" --timeout 1500 -E '^(downstream_cmake_project|architecture_layers)$'
