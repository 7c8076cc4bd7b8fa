#!/usr/bin/env bash
# Regenerates docs/accuracy-vs-cost.md (the table between its markers, the
# machine line) and docs/images/accuracy_vs_cost.png.
#
#   scripts/accuracy_vs_cost.sh [--a-t-end T]   (extra arguments go to the study)
#
# Installs SUNDIALS (Debian libsundials-dev) through install-deps.sh, configures
# a separate build folder build-study with -DMBFE_BUILD_STUDIES=ON, builds the
# study and runs it (about 1-2 minutes: the original beam with forward Euler at
# 1.5e-8 is 66.7 million steps). MBFE_JOBS (default 2) sets the build jobs.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
doc=docs/accuracy-vs-cost.md
png=docs/images/accuracy_vs_cost.png

MBFE_WITH_SUNDIALS=1 scripts/install-deps.sh
cmake -S . -B build-study -DCMAKE_BUILD_TYPE=Release -DMBFE_BUILD_STUDIES=ON -DMBFE_BUILD_TESTS=OFF >/dev/null
cmake --build build-study -j"${MBFE_JOBS:-2}" --target accuracy_vs_cost_study

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
build-study/bin/accuracy_vs_cost_study --markdown "$out/table.md" --csv-dir "$out" "$@" 2> >(tee "$out/log.txt" >&2)

cpu=$(lscpu | sed -n 's/^Model name:[[:space:]]*//p' | head -1)
cores=$(nproc)
load=$(cut -d' ' -f1-3 /proc/loadavg)
{
  echo "Machine: ${cpu}, ${cores} cores; $(g++ --version | head -1); SUNDIALS $(sed -n 's/#define SUNDIALS_VERSION "\(.*\)"/\1/p' /usr/include/sundials/sundials_config.h); load average at the end of the run: ${load}; $(date -u +%Y-%m-%d)."
  echo
  cat "$out/table.md"
} > "$out/block.md"

# Replace the text between the markers of the doc.
python3 - "$doc" "$out/block.md" <<'PY'
import sys
doc, block = sys.argv[1], open(sys.argv[2]).read()
text = open(doc).read()
begin, end = "<!-- table:begin (scripts/accuracy_vs_cost.sh) -->", "<!-- table:end -->"
i, j = text.index(begin) + len(begin), text.index(end)
open(doc, "w").write(text[:i] + "\n" + block + text[j:])
PY

mkdir -p docs/images
gnuplot <<GP
set terminal pngcairo size 1200,1000 font ",11" noenhanced
set output "${root}/${png}"
set datafile separator ","
set multiplot layout 2,1
set title "Paper beam, midspan deflection under gravity + 10 N stepped on at t = 0"
set xlabel "t (s)"
set ylabel "w(0.5 m) (mm)"
set key outside below
set grid
plot "${out}/reference.csv" every ::1 using 1:(\$2*1e3) with lines lw 3 lc rgb "black" title "exact, original model", \
     "${out}/b_adjusted_floor_fe.csv" every ::1 using 1:(\$2*1e3) with lines lw 1.5 lc rgb "#d62728" title "(b) adjusted, zeta_min 0.05, forward Euler 1.4e-5", \
     "${out}/b_adjusted_nofloor_fe.csv" every ::1 using 1:(\$2*1e3) with lines lw 1.5 lc rgb "#1f77b4" title "(b) adjusted, no floor, forward Euler 1.4e-5", \
     "${out}/d_adjusted_nofloor_rk4.csv" every ::1 using 1:(\$2*1e3) with lines lw 1.5 dt 2 lc rgb "#2ca02c" title "(d) adjusted, no floor, RK4 2e-5"
set title "Error against the exact original model (|w - w_exact|, m; log scale)"
set logscale y
set format y "10^{%L}"
set yrange [1e-10:1e-1]
set ylabel "|error| (m)"
set key outside below
plot "${out}/err_b_floor.csv" every ::1 using 1:2 with lines lw 1.5 lc rgb "#d62728" title "(b) zeta_min 0.05, forward Euler", \
     "${out}/err_b_nofloor.csv" every ::1 using 1:2 with lines lw 1.5 lc rgb "#1f77b4" title "(b) no floor, forward Euler", \
     "${out}/err_d_floor.csv" every ::1 using 1:2 with lines lw 1 dt 2 lc rgb "#ff7f0e" title "(d) zeta_min 0.05, RK4", \
     "${out}/err_d_nofloor.csv" every ::1 using 1:2 with lines lw 1.5 lc rgb "#2ca02c" title "(d) no floor, RK4"
unset multiplot
GP
echo "accuracy_vs_cost: wrote ${doc} (table) and ${png}"
