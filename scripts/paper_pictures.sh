#!/usr/bin/env bash
# Regenerates the pictures of README.md and docs/ for the rigid models and the
# paper's beam: docs/images/{double_pendulum,paper_beam_midspan,paper_beam_spectrum}.png
set -euo pipefail
cd "$(dirname "$0")/.."
[[ -x build/bin/mbfe ]] || scripts/build.sh
mbfe=build/bin/mbfe
out=docs/images
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"

$mbfe simulate models/double_pendulum.yaml --t-end 5 --quiet --out "$tmp/pendulum.csv"
$mbfe plot "$tmp/pendulum.csv" -o "$out/double_pendulum.png" --columns link1,link2 \
  --title "double pendulum: joint angles [rad], RK4, h = 1e-3 s"

# The paper's result: the adjusted beam under forward Euler at 1.4e-5 s (the
# original needs 1.5e-8 s, about 1000 times smaller).
$mbfe simulate models/paper_beam.yaml --integrator forward_euler --step 1.4e-5 --t-end 1 \
  --probe beam1@0.5 --quiet --out "$tmp/midspan.csv"
$mbfe plot "$tmp/midspan.csv" -o "$out/paper_beam_midspan.png" --columns beam1@0.5 \
  --title "paper beam, adjusted damping: midspan deflection [m], forward Euler, h = 1.4e-5 s"

$mbfe modal models/paper_beam.yaml --plot "$out/paper_beam_spectrum.png" --step 1.4e-5 >/dev/null
echo "wrote $out/double_pendulum.png $out/paper_beam_midspan.png $out/paper_beam_spectrum.png"
