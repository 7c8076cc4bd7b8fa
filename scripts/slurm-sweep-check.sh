#!/usr/bin/env bash
# The Slurm stage of .ci/run: a six-point sweep (tests/sweep/six_speeds.yaml)
# through a real one-node Slurm (scripts/slurm-local.sh), its summary compared
# with the same sweep run locally on two jobs. The cluster run's folder has a
# space, a % and a quote in its name: the scripts must quote every path for
# sbatch and for bash, and keep Slurm's %a apart from the folder's %. Needs
# root. Fails, with the
# reason, when the daemons do not start or the job does not finish in time:
# it never passes without having run the sweep on Slurm.
set -euo pipefail
cd "$(dirname "$0")/.."
MBFE_WITH_SLURM=1 scripts/install-deps.sh
[[ -x build/bin/mbfe ]] || scripts/build.sh
mbfe=$PWD/build/bin/mbfe
work=$(mktemp -d "${TMPDIR:-/tmp}/mbfe-slurm-XXXXXX")
chmod 0755 "$work"
trap 'scripts/slurm-local.sh stop "$work/slurm" >/dev/null 2>&1 || true' EXIT

scripts/slurm-local.sh start "$work/slurm"
export SLURM_CONF=$work/slurm/slurm.conf

"$mbfe" sweep tests/sweep/six_speeds.yaml --out "$work/local" --jobs 2 --quiet
cluster="$work/cluster of 50% \"load\""
"$mbfe" sweep tests/sweep/six_speeds.yaml --out "$cluster" --slurm --array-limit 2 --time 10:00 | tee "$work/submit.txt"
collect=$(sed -n 's/.* and collect job \([0-9]*\);.*/\1/p' "$work/submit.txt")
[[ -n $collect ]] || { echo "slurm-sweep-check: no collect job id in the submission" >&2; exit 1; }

# Wait for the collect job to leave the queue (10 minutes at most).
for _ in $(seq 600); do
  squeue -h -j "$collect" 2>/dev/null | grep -q . || break
  sleep 1
done
if squeue -h -j "$collect" 2>/dev/null | grep -q .; then
  echo "slurm-sweep-check: the collect job $collect is still queued after 10 minutes" >&2
  squeue >&2 || true
  exit 1
fi
[[ -f $cluster/summary.csv ]] || {
  echo "slurm-sweep-check: no summary from the cluster run; task logs:" >&2
  tail -n 5 "$cluster"/slurm/*.out >&2 || true
  exit 1
}
# One log per task, named by Slurm's %a, in the folder as named.
for i in 0 1 2 3 4 5; do
  [[ -f $cluster/slurm/point-$i.out ]] || { echo "slurm-sweep-check: no log $cluster/slurm/point-$i.out" >&2; exit 1; }
done

# The same rows but for the wall time (second to last column).
strip_wall() { awk -F, 'BEGIN { OFS = "," } { $(NF - 1) = ""; print }' "$1"; }
if ! diff <(strip_wall "$work/local/summary.csv") <(strip_wall "$cluster/summary.csv"); then
  echo "slurm-sweep-check: the Slurm summary differs from the local one" >&2
  exit 1
fi
echo "slurm-sweep-check: 6 points through Slurm, summary equal to the local --jobs 2 run"
