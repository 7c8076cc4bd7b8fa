#!/usr/bin/env bash
# The HSLM sweep of the 20 m bridge (models/sweeps/hslm_20m.yaml: HSLM-A1..A10
# at 57 speeds, 570 runs of moving forces) run locally with `mbfe sweep`, and
# its picture:
#   docs/images/hslm_20m.png   peak midspan deck acceleration against speed, one curve per train
# About 95 s on two cores (docs/performance.md, "The HSLM sweep").
# Usage: scripts/hslm_picture.sh [path/to/mbfe] [--jobs N]   (default build/bin/mbfe, every core)
set -euo pipefail
cd "$(dirname "$0")/.."
mbfe=${1:-build/bin/mbfe}
shift || true
[[ -x $mbfe ]] || { echo "hslm_picture: no $mbfe (run scripts/build.sh first)" >&2; exit 2; }
command -v gnuplot >/dev/null || { echo "hslm_picture: needs gnuplot (scripts/install-deps.sh)" >&2; exit 2; }
out=docs/images
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
"$mbfe" sweep models/sweeps/hslm_20m.yaml --out "$tmp/hslm" "$@"

gnuplot <<GNUPLOT
set datafile separator ","
set linetype 9 lc rgb "#8c564b"
set linetype 10 lc rgb "#7f7f7f"
set terminal pngcairo size 1000,560 font ",11"
set output "$out/hslm_20m.png"
set title "20 m simply supported deck (f1 = 4.02 Hz, 15 t/m, 1 % damping) under HSLM-A1..A10 (mbfe sweep, 570 runs)"
set grid
set key top left maxrows 5
set xlabel "speed (km/h)"
set ylabel "peak midspan deck acceleration, low-pass 36.2 Hz (m/s^2)"
set xrange [180:432]
set yrange [0:*]
set arrow from 180,3.5 to 432,3.5 nohead lw 2 dt 2 lc rgb "black"
set label "EN 1990 A2, ballasted track: 3.5 m/s^2" at 330,1.8
train(n, s) = strcol(2) eq sprintf("A%d", n) ? s : 1/0
plot for [n=1:10] "$tmp/hslm/summary.csv" using (train(n, column(3)*3.6)):(column("acc_max")) with linespoints lw 1.5 pt 7 ps 0.5 title sprintf("HSLM-A%d", n)
GNUPLOT
echo "hslm_picture: wrote $out/hslm_20m.png"
