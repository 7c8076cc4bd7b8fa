#!/usr/bin/env bash
# Generation of spatial models, measured (docs/performance.md, "Spatial
# models"): the operations emitted for chains of 5 to 40 joints with the
# exponent of their growth fitted, and the CPU time (user + system) of the
# whole `mbfe generate` process for the chains and the 35-joint humanoid tree
# of scripts/make_spatial_tree.py.
#   scripts/spatial_generation_speed.sh [BUILD_DIR]     (default build)
set -euo pipefail
cd "$(dirname "$0")/.."
mbfe="${1:-build}/bin/mbfe"
[[ -x "$mbfe" ]] || { echo "no $mbfe: build first (scripts/build.sh)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

measure() {  # model name -> "cpu_seconds emitted executed fused_executed"
  local model=$1 name=$2
  local seconds
  seconds=$( { /usr/bin/time -f "%U %S" "$mbfe" generate "$model" -o "$work/$name" --quiet; } 2>&1 |
             awk '{printf "%.2f", $1 + $2}')
  local banner
  banner=$(grep -m1 "^// Operations per kernel" "$work/$name/$name.h")
  local total fused
  total=$(sed -E 's/.* total ([0-9]+)( \(([0-9]+) per call\))?;.*/\1 \3/' <<<"$banner")
  fused=$(sed -E 's/.*fused dynamics ([0-9]+)( \(([0-9]+) per call\))?\..*/\3/' <<<"$banner")
  echo "$seconds $total $fused"
}

echo "| model | joints | mbfe generate, CPU (s) | emitted M+F+Q | executed M+F+Q | executed fused |"
echo "|---|---|---|---|---|---|"
: >"$work/fit"
for n in 5 10 20 40; do
  python3 scripts/make_spatial_tree.py chain "$n" -o "$work/chain_$n.yaml"
  read -r seconds emitted executed fused <<<"$(measure "$work/chain_$n.yaml" "spatial_chain_$n")"
  echo "| chain | $n | $seconds | $emitted | ${executed:-$emitted} | $fused |"
  echo "$n $emitted" >>"$work/fit"
done
python3 scripts/make_spatial_tree.py humanoid -o "$work/humanoid.yaml"
read -r seconds emitted executed fused <<<"$(measure "$work/humanoid.yaml" humanoid_35)"
echo "| humanoid tree | 35 (40 velocities) | $seconds | $emitted | ${executed:-$emitted} | $fused |"
python3 - "$work/fit" <<'PY'
import math, sys
points = [tuple(map(float, line.split())) for line in open(sys.argv[1])]
xs = [math.log(n) for n, _ in points]
ys = [math.log(ops) for _, ops in points]
mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
print(f"\nEmitted operations of the chains: N^{slope:.2f} fitted over N = 5..40 (least squares on log N, log ops);")
print(f"from 20 to 40 joints x{points[3][1] / points[2][1]:.2f} (N^{math.log2(points[3][1] / points[2][1]):.2f}); "
      "per added joint: " + ", ".join(f"{(b[1] - a[1]) / (b[0] - a[0]):.0f}" for a, b in zip(points, points[1:]))
      + " (5-10, 10-20, 20-40).")
PY
