#!/usr/bin/env bash
# Pictures of the shipped coupled models' responses (docs/images/), made with
# `mbfe simulate` and `mbfe plot`:
#   docs/images/double_pendulum_beam_{deflection,force}.png  beam midspan deflection, slider force
#   docs/images/paper_platform_{deflection,force}.png        beams at the contacts, transverse contact forces
# Usage: scripts/coupled_pictures.sh [path/to/mbfe]   (default build/bin/mbfe)
set -euo pipefail
cd "$(dirname "$0")/.."
mbfe=${1:-build/bin/mbfe}
[[ -x $mbfe ]] || { echo "coupled_pictures: no $mbfe (run scripts/build.sh first)" >&2; exit 2; }
out=docs/images
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"

# Double pendulum on the beam: adjusted damping, RK4 at 1e-5 s (its limit ~2e-5 s), 1 s.
"$mbfe" simulate models/double_pendulum_beam.yaml --integrator rk4 --step 1e-5 --t-end 1 \
  --probe beam1@0.5 --out "$tmp/dpb.csv" --quiet
# mbfe plot draws one y axis: deflection (m) and force (N) go to two PNGs.
"$mbfe" plot "$tmp/dpb.csv" -o "$out/double_pendulum_beam_deflection.png" \
  --columns beam1@0.5 --title "double_pendulum_beam: beam midspan deflection (m), adjusted, RK4 h = 1e-5 s"
"$mbfe" plot "$tmp/dpb.csv" -o "$out/double_pendulum_beam_force.png" \
  --columns lambda_tip_slider --title "double_pendulum_beam: slider contact force lambda (N)"

# The paper's platform: adjusted damping, forward Euler at 1.4e-5 s (limit ~1.46e-5 s), 1 s.
"$mbfe" simulate models/paper_platform.yaml --integrator forward_euler --step 1.4e-5 --t-end 1 \
  --probe beam1@0.35,beam2@0.5 --out "$tmp/platform.csv" --quiet
"$mbfe" plot "$tmp/platform.csv" -o "$out/paper_platform_deflection.png" \
  --columns beam1@0.35,beam2@0.5 \
  --title "paper_platform: beam deflections at the pin (beam1@0.35) and at mid-beam2 (m), forward Euler h = 1.4e-5 s"
"$mbfe" plot "$tmp/platform.csv" -o "$out/paper_platform_force.png" \
  --columns lambda_arm_pin_2,lambda_cp2_slider \
  --title "paper_platform: transverse contact forces (N); the pin's axial force lambda_arm_pin_1 stays near the weight, 132 N"
echo "coupled_pictures: wrote $(ls "$out"/double_pendulum_beam_*.png "$out"/paper_platform_*.png | tr '\n' ' ')"
