#!/usr/bin/env bash
# A real one-node Slurm cluster on localhost (Debian's slurm-wlm + munge): submits a 3-task job
# array of a small impact sweep and its dependent merge job with the script `pdamp slurm`
# writes, waits (with a time limit), compares the merged sweep.csv and strobe.csv with a local
# single-process run byte for byte, and stops the daemons it started.
#
# Usage: tests/slurm/one_node.sh PATH/TO/pdamp
# Needs root (the daemons run as root here) and slurmctld, slurmd, munged, sbatch on PATH.
# Missing pieces: prints why and exits 0 (skipped, loudly); a failed check exits 1.
set -uo pipefail
PDAMP=$(realpath "${1:?usage: one_node.sh PATH/TO/pdamp}")
HERE=$(cd "$(dirname "$0")/../.." && pwd)
skip() { echo "!!! SLURM TEST SKIPPED: $*" >&2; exit 0; }
fail() { echo "!!! SLURM TEST FAILED: $*" >&2; exit 1; }
for cmd in slurmctld slurmd munged sbatch scontrol; do
  command -v "$cmd" >/dev/null 2>&1 || skip "$cmd not found (apt-get install slurm-wlm munge)"
done
[ "$(id -u)" = 0 ] || skip "needs root to start munged, slurmctld and slurmd"

WORK=$(mktemp -d /tmp/pdamp-slurm.XXXXXX)
PIDS=()
cleanup() {
  for pid in "${PIDS[@]}"; do kill "$pid" 2>/dev/null; done
  sleep 1
  for pid in "${PIDS[@]}"; do kill -9 "$pid" 2>/dev/null; done
  [ -n "${KEEP:-}" ] || rm -rf "$WORK"
}
trap cleanup EXIT

# munge: a fresh key and socket in WORK
mkdir -p "$WORK/munge"
dd if=/dev/urandom of="$WORK/munge/munge.key" bs=1024 count=1 status=none
chmod 700 "$WORK/munge"; chmod 400 "$WORK/munge/munge.key"
munged --force -F --key-file="$WORK/munge/munge.key" --socket="$WORK/munge/munge.socket" \
  --pid-file="$WORK/munge/munged.pid" --log-file="$WORK/munge/munged.log" \
  --seed-file="$WORK/munge/munged.seed" >"$WORK/munge/munged.stdout" 2>&1 &
PIDS+=($!)
for _ in $(seq 50); do [ -S "$WORK/munge/munge.socket" ] && break; sleep 0.1; done
[ -S "$WORK/munge/munge.socket" ] || fail "munged did not start ($(cat "$WORK/munge/munged.log" 2>/dev/null))"

HOST=$(hostname -s)
CPUS=$(nproc)
mkdir -p "$WORK/state" "$WORK/spool"
export SLURM_CONF="$WORK/slurm.conf"
cat > "$SLURM_CONF" <<CONF
ClusterName=pdamptest
SlurmctldHost=$HOST(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$WORK/munge/munge.socket
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool
SlurmctldPidFile=$WORK/slurmctld.pid
SlurmdPidFile=$WORK/slurmd.pid
SlurmctldLogFile=$WORK/slurmctld.log
SlurmdLogFile=$WORK/slurmd.log
SlurmctldPort=16817
SlurmdPort=16818
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
MinJobAge=600
NodeName=$HOST NodeAddr=127.0.0.1 CPUs=$CPUS RealMemory=4000 State=UNKNOWN
PartitionName=debug Nodes=$HOST Default=YES MaxTime=INFINITE State=UP
CONF
slurmctld -D -i -f "$SLURM_CONF" >"$WORK/slurmctld.stdout" 2>&1 &
PIDS+=($!)
slurmd -D -f "$SLURM_CONF" >"$WORK/slurmd.stdout" 2>&1 &
PIDS+=($!)
up=""
for _ in $(seq 60); do
  if scontrol show node "$HOST" 2>/dev/null | grep -Eq "State=(IDLE|MIXED)"; then up=1; break; fi
  sleep 1
done
if [ -z "$up" ]; then
  tail -5 "$WORK/slurmctld.log" "$WORK/slurmd.log" >&2
  KEEP=1; fail "the node did not come up (logs above; kept in $WORK)"
fi
echo "slurm: slurmctld and slurmd up on $HOST ($CPUS CPUs), munge socket $WORK/munge/munge.socket"

SCENE="$HERE/data/scenes/thesis_b_impact.toml"
SWEEP=(--set run.periods=100 --set damper.restitution=0.8 --vary excitation.frequency=2:28:2 --no-analysis)
"$PDAMP" slurm "$SCENE" "${SWEEP[@]}" --out "$WORK/cluster" --shards 3 --parallel 3 \
  --cpus-per-task 1 --job-name pdamp-ci --pdamp "$PDAMP" --script "$WORK/submit.sh" \
  || fail "pdamp slurm did not write the script"
grep -E "^#SBATCH --(array|time|mem)=" "$WORK/submit.sh" | sort -u
submitted=$(bash "$WORK/submit.sh") || fail "submission failed: $submitted"
echo "$submitted"
ARRAY=$(echo "$submitted" | sed -n 's/^array job \([0-9]*\).*/\1/p')
MERGE=$(echo "$submitted" | sed -n 's/.*merge job \([0-9]*\).*/\1/p')
[ -n "$ARRAY" ] && [ -n "$MERGE" ] || fail "no job ids in: $submitted"

state() { scontrol show job "$1" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -1; }
deadline=$((SECONDS + 300))
while :; do
  s=$(state "$MERGE")
  case "$s" in COMPLETED|FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY) break ;; esac
  [ $SECONDS -lt $deadline ] || { scontrol show job "$ARRAY" >&2; fail "merge job $MERGE still $s after 300 s"; }
  sleep 2
done
echo "array job $ARRAY tasks:"
scontrol show job "$ARRAY" | grep -E "JobId=|JobState=" | paste - - | sed 's/^ */  /'
echo "merge job $MERGE: $(state "$MERGE")"
[ "$(state "$MERGE")" = COMPLETED ] || { cat "$WORK"/cluster/slurm-*.out >&2; fail "merge job $MERGE ended $(state "$MERGE")"; }
cat "$WORK"/cluster/slurm-merge-*.out

"$PDAMP" sweep "$SCENE" "${SWEEP[@]}" --out "$WORK/local" >/dev/null || fail "local sweep failed"
for f in sweep.csv strobe.csv; do
  if cmp "$WORK/local/$f" "$WORK/cluster/$f"; then
    echo "byte comparison: $f identical ($(wc -c < "$WORK/local/$f") bytes, $(($(wc -l < "$WORK/local/$f") - 1)) rows) between the 3-task Slurm array + merge and a local run"
  else
    fail "$f differs between the Slurm run and the local run"
  fi
done
echo "slurm test: OK (stopping the daemons started here: pids ${PIDS[*]})"
