#!/usr/bin/env bash
# Measures what a chain of N bodies costs to generate and to compile, the two
# steps `mbfe simulate` runs for a model new to the solver cache: wall and CPU
# time and peak memory (/usr/bin/time -v) of `mbfe generate` and of the
# compiler on the generated source, with the flags the solver cache uses.
# Prints one Markdown table row per (N, points, flags); docs/performance.md,
# "Model size and compile time", holds the figures.
#
# Three chains (scripts/make_chain.py): `tip` has a named point on every link,
# as models/chain_N.yaml do, and every point gets a position kernel that walks
# the chain from the ground (code quadratic in N); `bare` has no points (linear);
# `worst` is about the most the parser's limits allow for N bodies: a point on
# every link (ParseLimits::max_points is one per body at the body limit) and a
# torque that is a 990-term sum (8,900 of the 10,000 expression nodes of
# ParseLimits::max_expression_nodes).
#
# Spatial models (dimension: 3; scripts/make_spatial_tree.py): `spatial` is a
# chain of revolute joints turning about z, y, x in turn with a point at the
# tip of every link; `free` a chain of free joints (6 coordinates a body, the
# most N bodies can have), a point on every link; `spatial_worst` about the
# most the limits of a spatial model allow for N bodies (ParseLimits::
# max_spatial_bodies, max_spatial_velocities): the `spatial` chain with its
# first N/5 joints free (at the 50-body limit, 10 free and 40 revolute
# joints: 100 velocity coordinates, the limit) and the 990-term torque on its
# last link.
#
# Usage: scripts/compile_cost.sh [N ...]           (default 50 100 200 300 500)
# Environment:
#   MBFE_COST_KINDS   which chains (default "bare tip worst"; also spatial,
#                     free, spatial_worst)
#   MBFE_COST_OPT     optimisation levels to compile at (default "-O3 -O1")
#   MBFE_COST_DIR     scratch folder (default build/compile-cost)
#   MBFE_COST_CPU_LIMIT CPU seconds after which a compile is stopped (default 1200;
#                     CPU time, not wall time: the machine may be shared)
set -euo pipefail
cd "$(dirname "$0")/.."
[[ -x build/bin/mbfe ]] || { echo "compile_cost: build/bin/mbfe missing (scripts/build.sh)" >&2; exit 1; }
sizes=("$@")
((${#sizes[@]})) || sizes=(50 100 200 300 500)
read -r -a levels <<<"${MBFE_COST_OPT:--O3 -O1}"
read -r -a kinds <<<"${MBFE_COST_KINDS:-bare tip worst}"
dir="${MBFE_COST_DIR:-build/compile-cost}"
cpu_limit="${MBFE_COST_CPU_LIMIT:-1200}"
compiler=$(sed -n 's/^#define MBFE_JIT_COMPILER "\(.*\)"$/\1/p' build/api/jit_config.h)
mkdir -p "$dir"

# "wall_s cpu_s peak_MB" from a /usr/bin/time -v log.
figures() {
  awk -F': ' '
    /Elapsed \(wall clock\)/ { n = split($2, p, ":"); w = 0; for (i = 1; i <= n; ++i) w = w * 60 + p[i] }
    /User time/ { u = $2 } /System time/ { s = $2 } /Maximum resident/ { m = $2 }
    END { printf "%.1f %.1f %.0f\n", w, u + s, m / 1024 }' "$1"
}

echo "| bodies | points | generate: CPU s, peak MB | source | flags | compile: wall s | CPU s | peak MB |"
echo "|---|---|---|---|---|---|---|---|"
for kind in "${kinds[@]}"; do
  for n in "${sizes[@]}"; do
    name="chain_$n"
    model="$dir/${kind}_$n.yaml"
    case "$kind" in
      spatial) name="spatial_chain_$n"; python3 scripts/make_spatial_tree.py chain "$n" -o "$model" ;;
      free) name="free_chain_$n"; python3 scripts/make_spatial_tree.py free "$n" -o "$model" ;;
      spatial_worst)
        name="spatial_chain_$n"
        python3 scripts/make_spatial_tree.py chain "$n" --free $((n / 5)) -o "$model"
        python3 -c "import sys; print('loads:\n  - {type: torque, body: link' + sys.argv[1] + ', value: [\\\"' +
                    ' + '.join('1.%02d*sin(%d.5*t + 0.%d)' % (j % 100, j, j % 10) for j in range(1, 991)) +
                    '\\\", 0, 0]}')" "$n" >>"$model"
        ;;
      bare) python3 scripts/make_chain.py "$n" /dev/stdout | sed '/^    points:/d' >"$model" ;;
      tip) python3 scripts/make_chain.py "$n" "$model" >/dev/null ;;
      worst)
        python3 scripts/make_chain.py "$n" /dev/stdout | sed '/^initial:/i loads:' >"$model"
        python3 -c "import sys; print('  - {type: torque, body: link' + sys.argv[1] + ', value: \\\"' +
                    ' + '.join('1.%02d*sin(%d.5*t + 0.%d)' % (j % 100, j, j % 10) for j in range(1, 991)) +
                    '\\\"}')" "$n" >"$model.loads"
        sed -i "/^loads:/r $model.loads" "$model"
        rm -f "$model.loads"
        ;;
    esac
    out="$dir/${kind}_$n"
    /usr/bin/time -v -o "$out.generate.time" build/bin/mbfe generate "$model" -o "$out" >/dev/null 2>&1
    read -r _ gen_cpu gen_mb < <(figures "$out.generate.time")
    source_file="$out/$name.cpp"
    kb=$(( $(stat -c %s "$source_file") / 1024 ))
    for opt in "${levels[@]}"; do
      status=0
      # The flags of the solver cache (api/jit_config.h.in), at each level.
      /usr/bin/time -v -o "$out$opt.time" bash -c 'ulimit -t "$1"; shift; exec "$@"' _ "$cpu_limit" \
        "$compiler" "$opt" -DNDEBUG -std=c++17 -shared -fPIC -DMBFE_SHARED_ENTRY -Iruntime/abi "$source_file" \
        -o "$out$opt.so" >/dev/null 2>&1 || status=$?
      read -r wall cpu mb < <(figures "$out$opt.time")
      note=""
      ((status == 0)) || note=" (stopped at the CPU limit of ${cpu_limit} s)"
      echo "| $n | $kind | $gen_cpu, $gen_mb | $kb KB | $opt | $wall$note | $cpu | $mb |"
      rm -f "$out$opt.so"
    done
  done
done
