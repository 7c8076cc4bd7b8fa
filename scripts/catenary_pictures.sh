#!/usr/bin/env bash
# The picture of docs/catenary.md: the two-span pantograph-catenary model's
# contact force, adjusted (RK4 at 1e-3 s, the model's run) over original
# (generalized-alpha at 2e-4 s), and their difference, rows every 1 ms:
#   docs/images/catenary_adjusted_vs_original.png
# Usage: scripts/catenary_pictures.sh [path/to/mbfe]   (default build/bin/mbfe; about 20 s)
set -euo pipefail
cd "$(dirname "$0")/.."
mbfe=${1:-build/bin/mbfe}
[[ -x $mbfe ]] || { echo "catenary_pictures: no $mbfe (run scripts/build.sh first)" >&2; exit 2; }
command -v gnuplot >/dev/null || { echo "catenary_pictures: gnuplot is missing (Debian: gnuplot-nox)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
model=models/pantograph_catenary_2span.yaml
"$mbfe" simulate "$model" --every 1 --out "$tmp/adjusted.csv" --quiet
"$mbfe" simulate "$model" --adjust off --integrator generalized_alpha --step 2e-4 --every 5 \
  --out "$tmp/original.csv" --quiet
python3 - "$tmp" <<'PY'
import csv, sys
tmp = sys.argv[1]
def force(name):
    rows = list(csv.DictReader(open("%s/%s.csv" % (tmp, name))))
    return [(float(r["t"]), float(r["force_strip"])) for r in rows]
a, o = force("adjusted"), force("original")
assert len(a) == len(o), (len(a), len(o))
with open("%s/joined.dat" % tmp, "w") as f:
    for (t, fa), (t2, fo) in zip(a, o):
        assert abs(t - t2) < 1e-9, (t, t2)
        f.write("%.6f %.6f %.6f %.6f\n" % (t, fo, fa, fa - fo))
PY
gnuplot <<GP
set terminal pngcairo size 1100,700 font ",11"
set output "docs/images/catenary_adjusted_vs_original.png"
set multiplot layout 2,1 title "Two-span pantograph-catenary model, 300 km/h: contact force, adjusted against original"
set grid
set ylabel "contact force (N)"
set key top right
plot "$tmp/joined.dat" using 1:2 with lines lw 2 lc rgb "#1f77b4" title "original, generalized-alpha 2e-4 s", \
     "$tmp/joined.dat" using 1:3 with lines lw 1 lc rgb "#d62728" title "adjusted (cap 1500 rad/s), RK4 1e-3 s"
set ylabel "adjusted - original (N)"
set xlabel "t (s)"
plot "$tmp/joined.dat" using 1:4 with lines lw 1 lc rgb "#333333" notitle
unset multiplot
GP
echo "catenary_pictures: wrote docs/images/catenary_adjusted_vs_original.png"
