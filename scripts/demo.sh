#!/usr/bin/env bash
# Quick start, command 1: install what is missing, build, run the main job.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
# The main job needs the tool only: no tests, no benchmarks (about half the build).
scripts/build.sh -DMBFE_BUILD_TESTS=OFF -DMBFE_BUILD_BENCHMARKS=OFF
scripts/install-python.sh
mkdir -p out
echo
echo "== The double pendulum: generated, compiled, simulated =="
build/bin/mbfe simulate models/double_pendulum.yaml --out out/double_pendulum.csv
build/bin/mbfe eval models/double_pendulum.yaml --q 0.3,0 --qd 0,0 --quiet
echo
echo "== The paper's beam (Section 7): Table 1 =="
build/bin/mbfe modal models/paper_beam.yaml
if build/bin/mbfe stability --help >/dev/null 2>&1; then
  echo
  echo "== Largest stable steps, original and with the modal adjustment of damping =="
  build/bin/mbfe stability models/paper_beam.yaml
fi
echo
echo "== A 1000 kg wheel crossing a 20 m bridge at 20 m/s, from Python =="
/usr/bin/python3 examples/python/bridge_crossing.py out
echo
echo "Results in out/. Next: README.md, 'build/bin/mbfe --help'."
