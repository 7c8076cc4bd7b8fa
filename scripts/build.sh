#!/usr/bin/env bash
# Configures and builds mbfe into build/ (Release). Extra arguments go to cmake.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
# Through ccache when it is there: a second build of the same sources, such as
# `pip install .`'s own build folder (setup.py), compiles little.
source scripts/ccache-launcher.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "$@" >/dev/null
cmake --build build -j"$jobs"
