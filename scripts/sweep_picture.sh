#!/usr/bin/env bash
# The speed sweep of the moving-mass bridge (models/sweeps/bridge_speeds.yaml,
# 31 speeds) run locally with `mbfe sweep`, and its picture:
#   docs/images/bridge_speeds.png   dynamic amplification of the midspan deflection against speed
# Usage: scripts/sweep_picture.sh [path/to/mbfe] [--jobs N]   (default build/bin/mbfe, every core)
set -euo pipefail
cd "$(dirname "$0")/.."
mbfe=${1:-build/bin/mbfe}
shift || true
[[ -x $mbfe ]] || { echo "sweep_picture: no $mbfe (run scripts/build.sh first)" >&2; exit 2; }
command -v gnuplot >/dev/null || { echo "sweep_picture: needs gnuplot (scripts/install-deps.sh)" >&2; exit 2; }
out=docs/images
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
"$mbfe" sweep models/sweeps/bridge_speeds.yaml --out "$tmp/speeds" "$@"

# DAF = (initial - lowest midspan deflection) / (P L^3 / 48 EI): the wheel's
# share of the peak, the deck's own static sag taken off; speed from the motion "v*t".
gnuplot <<GNUPLOT
set datafile separator ","
set terminal pngcairo size 1000,520 font ",11"
set output "$out/bridge_speeds.png"
set title "bridge\\\_speeds: the moving-mass bridge crossed at 31 speeds (mbfe sweep, 2 jobs)"
set grid
set key top left
set xlabel "speed v (m/s);  speed parameter alpha = v / (2 L f1) = v / 81.7 m/s"
set ylabel "dynamic amplification of the midspan deflection"
set y2label "largest tyre force (kN)"
set ytics nomirror
set y2tics
static = 9810.0*20.0**3/(48*2.1e7)
speed(s) = real(s[1:strstrt(s, "*") - 1])
plot "$tmp/speeds/summary.csv" using (speed(strcol(2))):((column("midspan_initial") - column("midspan_lowest"))/static) with linespoints lw 2 pt 7 title "DAF (moving mass, unilateral tyre)", \
     "$tmp/speeds/summary.csv" using (speed(strcol(2))):(column("tyre_force_max")/1000) axes x1y2 with linespoints lw 1 pt 6 title "largest tyre force"
GNUPLOT
echo "sweep_picture: wrote $out/bridge_speeds.png"
