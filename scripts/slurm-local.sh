#!/usr/bin/env bash
# A one-node Slurm on this machine, for testing `mbfe sweep --slurm` against a
# real scheduler (docs/sweeps.md). Needs root and Debian's slurm-wlm and munge
# (MBFE_WITH_SLURM=1 scripts/install-deps.sh).
#
#   scripts/slurm-local.sh start DIR   writes DIR/slurm.conf (this host as controller
#                                      and compute node), starts munged, slurmctld and
#                                      slurmd with their state, pids and logs in DIR,
#                                      and waits until the node is idle
#   scripts/slurm-local.sh stop DIR    stops the daemons it started (by their pids)
#
# Clients then need SLURM_CONF=DIR/slurm.conf. A daemon that does not start is
# an error with its log: this script never pretends.
set -euo pipefail

action=${1:-}
dir=${2:-}
[[ -n $action && -n $dir ]] || { echo "usage: $0 start|stop DIR" >&2; exit 2; }

stop() {
  local name pid
  for name in slurmd slurmctld munged; do
    [[ -f $dir/$name.pid ]] || continue
    pid=$(cat "$dir/$name.pid")
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
    rm -f "$dir/$name.pid"
  done
}

fail() {
  echo "slurm-local: $1" >&2
  local log
  for log in "$dir"/*.log; do
    [[ -f $log ]] && { echo "--- $log (last lines)" >&2; tail -n 20 "$log" >&2; }
  done
  stop
  exit 1
}

if [[ $action == stop ]]; then
  stop
  echo "slurm-local: stopped"
  exit 0
fi
[[ $action == start ]] || { echo "usage: $0 start|stop DIR" >&2; exit 2; }
[[ $(id -u) == 0 ]] || { echo "slurm-local: needs root (it runs munged and the Slurm daemons)" >&2; exit 1; }
for tool in munged slurmctld slurmd sinfo sbatch; do
  command -v "$tool" >/dev/null ||
    { echo "slurm-local: no $tool (MBFE_WITH_SLURM=1 scripts/install-deps.sh)" >&2; exit 1; }
done

mkdir -p "$dir"/{state,spool,munge-key,munge-run}
chmod 0755 "$dir"
dir=$(cd "$dir" && pwd)
host=$(hostname -s)
cpus=$(nproc)

# munge: its own key (private) and socket (reachable by all) under DIR, run as
# the munge user, as Debian's service would.
chown munge:munge "$dir/munge-key" "$dir/munge-run"
chmod 0700 "$dir/munge-key"
chmod 0755 "$dir/munge-run"
if [[ ! -f $dir/munge-key/munge.key ]]; then
  dd if=/dev/urandom of="$dir/munge-key/munge.key" bs=1024 count=1 status=none
  chown munge:munge "$dir/munge-key/munge.key"
  chmod 0400 "$dir/munge-key/munge.key"
fi
socket=$dir/munge-run/munge.socket
runuser -u munge -- munged --key-file="$dir/munge-key/munge.key" --socket="$socket" \
  --pid-file="$dir/munge-run/munged.pid" --log-file="$dir/munge-run/munged.log" \
  --seed-file="$dir/munge-key/munged.seed" || fail "munged did not start"
cp "$dir/munge-run/munged.pid" "$dir/munged.pid"

cat >"$dir/slurm.conf" <<CONF
ClusterName=mbfe-local
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
SlurmctldPort=6817
SlurmdPort=6818
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
MpiDefault=none
SwitchType=switch/none
ReturnToService=2
SlurmdTimeout=30
InactiveLimit=0
MinJobAge=300
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$dir/slurm.conf

slurmctld -f "$SLURM_CONF" || fail "slurmctld did not start"
slurmd -f "$SLURM_CONF" || fail "slurmd did not start"
for _ in $(seq 100); do
  state=$(sinfo -h -N -o '%t' 2>/dev/null | head -n1 || true)
  [[ $state == idle ]] && { echo "slurm-local: node $host idle ($cpus CPUs); export SLURM_CONF=$SLURM_CONF"; exit 0; }
  sleep 0.2
done
fail "the node did not become idle in 20 s (state '${state:-none}')"
