#!/usr/bin/env bash
# Regenerates docs/accuracy-vs-cost-coupled.md (the tables between its
# markers, the machine line) and docs/images/accuracy_vs_cost_coupled.png.
#
#   scripts/coupled_accuracy_vs_cost.sh
#
# Configures the study build folder build-study (-DMBFE_BUILD_STUDIES=ON, which
# also wants SUNDIALS for the beam study: installed through install-deps.sh),
# builds the study and runs it (about 2 minutes on 2 cores: the references are
# 800,000 implicit steps of the platform and 120,000 RK4 steps of the bridge).
# Then the policies' study, scripts/adjustment_error_study.sh (about 20 minutes
# more): `cap` beside `mass` on the 30 m railway bridge, the platform, the
# moving mass and the two-span catenary, each contact's force on its own row,
# into the same document's "adjustment-errors" tables.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
doc=docs/accuracy-vs-cost-coupled.md
png=docs/images/accuracy_vs_cost_coupled.png

MBFE_WITH_SUNDIALS=1 scripts/install-deps.sh
cmake -S . -B build-study -DCMAKE_BUILD_TYPE=Release -DMBFE_BUILD_STUDIES=ON -DMBFE_BUILD_TESTS=OFF >/dev/null
cmake --build build-study -j"${MBFE_JOBS:-2}" --target coupled_accuracy_study

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
build-study/bin/coupled_accuracy_study --markdown "$out/table.md" --csv-dir "$out" 2> >(tee "$out/log.txt" >&2)

cpu=$(lscpu | sed -n 's/^Model name:[[:space:]]*//p' | head -1)
{
  echo "Machine: ${cpu}, $(nproc) cores; $(g++ --version | head -1); load average at the end of the run: $(cut -d' ' -f1-3 /proc/loadavg); $(date -u +%Y-%m-%d)."
  echo
  cat "$out/table.md"
} > "$out/block.md"

python3 - "$doc" "$out/block.md" <<'PY'
import sys
doc, block = sys.argv[1], open(sys.argv[2]).read()
text = open(doc).read()
begin, end = "<!-- tables:begin (scripts/coupled_accuracy_vs_cost.sh) -->", "<!-- tables:end -->"
i, j = text.index(begin) + len(begin), text.index(end)
open(doc, "w").write(text[:i] + "\n" + block + text[j:])
PY

mkdir -p docs/images
# Error against wall time, one panel per model and class: the generalized-alpha
# curve (original model) and the adjusted explicit runs (points).
{
  cat <<GP
set terminal pngcairo size 1500,1100 font ",10" noenhanced
set output "${root}/${png}"
set datafile separator ","
set logscale xy
set format y "%.0e"
set format x "%g"
set xlabel "wall time (s)"
set ylabel "error / peak"
set grid
set key bottom left font ",8" opaque box
set multiplot layout 3,4
GP
  first=1
  for tag in paper_platform paper_platform_nofloor bridge_moving_mass; do
    case $tag in
      paper_platform) title="platform, zeta_min 0.05";;
      paper_platform_nofloor) title="platform, zeta_min 0";;
      bridge_moving_mass) title="moving-mass bridge";;
    esac
    # adjusted.csv: run,h,wall,rigid,w,slope,force; curve.csv: h,wall,rigid,w,slope,force
    for c in "3 rigid" "4 w" "5 slope" "6 force"; do
      set -- $c
      a=$(( $1 + 1 ))
      if [[ $first == 1 ]]; then echo "set key"; first=0; else echo "unset key"; fi
      # One clause per adjusted run the model has (an empty one would make gnuplot warn).
      line="\"${out}/${tag}_curve.csv\" every ::1 using 2:$1 with linespoints lw 2 pt 7 lc rgb \"#1f77b4\" title \"original + generalized-alpha\""
      if grep -q '^forward_euler,' "${out}/${tag}_adjusted.csv"; then
        line+=", \"${out}/${tag}_adjusted.csv\" every ::1 using 3:(strcol(1) eq \"forward_euler\" ? \$$a : 1/0) with points pt 9 ps 2 lc rgb \"#d62728\" title \"adjusted + forward Euler at its limit\""
      fi
      if grep -q '^rk4,' "${out}/${tag}_adjusted.csv"; then
        line+=", \"${out}/${tag}_adjusted.csv\" every ::1 using 3:(strcol(1) eq \"rk4\" ? \$$a : 1/0) with points pt 5 ps 1.6 lc rgb \"#2ca02c\" title \"adjusted + RK4 at its limit\""
      fi
      echo "set title \"${title}: $2\""
      echo "plot ${line}"
    done
  done
  echo "unset multiplot"
} > "$out/plot.gp"
gnuplot "$out/plot.gp"
echo "coupled_accuracy_vs_cost: wrote ${doc} (tables) and ${png}"
scripts/adjustment_error_study.sh
