#!/usr/bin/env bash
# Quick start, command 2: install what is missing, build, run every test.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh -DMBFE_BUILD_TESTS=ON -DMBFE_BUILD_BENCHMARKS=ON
scripts/install-python.sh
export MBFE_CACHE_DIR="$PWD/build/test-cache"
jobs=$(nproc 2>/dev/null || echo 2)
ctest --test-dir build --output-on-failure -j"$jobs"
