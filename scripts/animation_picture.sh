#!/usr/bin/env bash
# One frame of the two-axle vehicle's animation (docs/animation.md), rendered
# off screen with VTK: docs/images/bridge_two_axle_frame.png. Needs
# python3-vtk9 and xvfb (scripts/install-deps.sh).
# Usage: scripts/animation_picture.sh [path/to/mbfe]   (default build/bin/mbfe)
set -euo pipefail
cd "$(dirname "$0")/.."
mbfe=${1:-build/bin/mbfe}
[[ -x $mbfe ]] || { echo "animation_picture: no $mbfe (run scripts/build.sh first)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$mbfe" simulate models/bridge_two_axle_vehicle.yaml --out "$tmp/truck.csv" --vtk "$tmp/vtk" --vtk-scale 50 \
  --vtk-frames 81 --quiet
xvfb-run -a /usr/bin/python3 scripts/render_frame.py "$tmp/vtk/frames/frame_000040.vtp" \
  docs/images/bridge_two_axle_frame.png
