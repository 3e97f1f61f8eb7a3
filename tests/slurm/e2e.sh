#!/usr/bin/env bash
# End-to-end test of the render-farm recipe in examples/slurm on a real,
# one-node Slurm cluster started here: a 16-tile array and its dependent
# stitch job must give the single render's PNG byte for byte; then one task
# is made to fail, the stitch refuses naming the missing tile, the task is
# requeued and the stitch succeeds.
#
# Needs root (it installs Debian's slurm-wlm and munge and runs the daemons
# as root); anywhere else it prints a notice and exits 0 without testing.
# Every daemon it starts is stopped by its pid when it exits, failed or not.
#
# Usage: tests/slurm/e2e.sh [path/to/voxtrace]   (default: target/release/voxtrace)
set -euo pipefail
cd "$(dirname "$0")/../.."
repo=$(pwd)

if [ "$(id -u)" -ne 0 ]; then
  echo "SKIPPED: the Slurm end-to-end test needs root (to install slurm-wlm and munge and run slurmctld/slurmd); not run"
  exit 0
fi

started=$(date +%s)
voxtrace=$(realpath "${1:-${CARGO_TARGET_DIR:-target}/release/voxtrace}")
[ -x "$voxtrace" ] || { echo "no voxtrace binary at $voxtrace (cargo build --release -p voxtrace-cli)"; exit 1; }
timeout_s=${E2E_TIMEOUT:-60} # per wait for a job

if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
  echo "installing slurm-wlm and munge"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null
fi

work=$(mktemp -d /tmp/voxtrace-slurm.XXXXXX)
chmod 755 "$work"
pids=()
cleanup() {
  local status=$?
  for pid in "${pids[@]}"; do
    kill "$pid" 2>/dev/null || true
  done
  for pid in "${pids[@]}"; do
    # Bounded: a daemon that ignores SIGTERM for 10 s is killed.
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
    kill -9 "$pid" 2>/dev/null || true
  done
  if [ "$status" -ne 0 ]; then
    echo "FAILED; the daemons' logs:"
    tail -n 20 "$work"/*.log 2>/dev/null || true
  fi
  rm -rf "$work"
  exit "$status"
}
trap cleanup EXIT
# A signal ends the script through exit, so that the EXIT trap runs.
trap 'exit 130' INT TERM

# Munge with its own key and socket, so that a munged the machine may run
# is left alone.
mkdir -m 700 "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
munged --foreground --force --key-file="$work/munge/munge.key" \
  --socket="$work/munge/munge.socket" --pid-file="$work/munge/munged.pid" \
  --seed-file="$work/munge/munged.seed" --log-file="$work/munged.log" 2>>"$work/munged.log" &
pids+=($!)

host=$(hostname -s)
cpus=$(nproc)
ctl_port=${E2E_SLURMCTLD_PORT:-16817}
node_port=${E2E_SLURMD_PORT:-16818}
mkdir -p "$work/state" "$work/spool" "$work/jobs"
export SLURM_CONF="$work/slurm.conf"
cat >"$SLURM_CONF" <<EOF
ClusterName=voxtrace-e2e
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctl_port
SlurmdPort=$node_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge/munge.socket
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
ReturnToService=2
SchedulerParameters=sched_interval=1
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=e2e Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF

for _ in $(seq 50); do [ -S "$work/munge/munge.socket" ] && break; sleep 0.1; done
# In the foreground (-D) so that $! is the daemon; they log to files.
slurmctld -D -i -f "$SLURM_CONF" 2>>"$work/slurmctld.log" &
pids+=($!)
slurmd -D -N "$host" -f "$SLURM_CONF" 2>>"$work/slurmd.log" &
pids+=($!)

deadline=$(($(date +%s) + timeout_s))
until sinfo -h -o %T 2>/dev/null | grep -qE '^(idle|mixed|allocated)'; do
  [ "$(date +%s)" -lt "$deadline" ] || { echo "the node did not come up"; sinfo || true; exit 1; }
  sleep 0.5
done
echo "slurm is up: $(sinfo -h -o '%P %D %T %c') (cpus per node)"

# The state of job (or array task) $1, or nothing once Slurm forgot it.
state() { scontrol show job "$1" -o 2>/dev/null | grep -o 'JobState=[A-Z_]*' | sort -u | cut -d= -f2 | tr '\n' ' '; }

# Waits until job $1 (all its tasks) has left the queue, within the timeout.
wait_done() {
  local deadline=$(($(date +%s) + timeout_s))
  while squeue -h -j "$1" -o %i 2>/dev/null | grep -q .; do
    if [ "$(date +%s)" -ge "$deadline" ]; then
      echo "job $1 still queued or running after ${timeout_s}s"; squeue || true; exit 1
    fi
    sleep 0.5
  done
}

cd "$work/jobs"
scene="--size 50 --seed 1 --width 320 --height 180 --position 60,90,45"
export VOXTRACE="$voxtrace" TILES=4x4 SCENE_ARGS="$scene"
"$voxtrace" $scene --threads 1 --out "$work/local.png"

echo "== 16 tiles and a dependent stitch"
export OUT_DIR="$work/jobs/parts" FRAME="$work/jobs/frame.png"
ids=$("$repo/examples/slurm/submit.sh" --array=0-15 --cpus-per-task=1)
array=$(echo "$ids" | sed -n 1p)
stitch_job=$(echo "$ids" | sed -n 2p)
echo "array job $array, stitch job $stitch_job"
wait_done "$array"
wait_done "$stitch_job"
[ "$(state "$stitch_job")" = "COMPLETED " ] || { echo "stitch job: $(state "$stitch_job")"; cat ./*.out; exit 1; }
cmp "$FRAME" "$work/local.png"
echo "the stitched frame equals the local render byte for byte ($(ls parts | wc -l) parts)"

echo "== a failed task, a refused stitch, a requeue"
# Task 5 fails while its poison file exists: a wrapper stands in for the
# binary (root writes through read-only directories, so no permission can
# make it fail).
cat >"$work/voxtrace-poisoned" <<EOF
#!/bin/sh
if [ -e "$work/poison-\$SLURM_ARRAY_TASK_ID" ]; then echo "poisoned task \$SLURM_ARRAY_TASK_ID" >&2; exit 1; fi
exec "$voxtrace" "\$@"
EOF
chmod +x "$work/voxtrace-poisoned"
touch "$work/poison-5"
export VOXTRACE="$work/voxtrace-poisoned" OUT_DIR="$work/jobs/parts2" FRAME="$work/jobs/frame2.png"
ids=$("$repo/examples/slurm/submit.sh" --array=0-15 --cpus-per-task=1)
array=$(echo "$ids" | sed -n 1p)
never=$(echo "$ids" | sed -n 2p)
# afterany here (the recipe uses afterok): this stitch must run to refuse.
refused=$(sbatch --parsable --dependency=afterany:"$array" --output=refused.out "$repo/examples/slurm/stitch.sbatch")
wait_done "$array"
wait_done "$refused"
wait_done "$never"
[ "$(state "${array}_5")" = "FAILED " ] || { echo "task 5: $(state "${array}_5")"; exit 1; }
[ "$(state "$never")" = "CANCELLED " ] || { echo "the recipe's afterok stitch: $(state "$never")"; exit 1; }
echo "task 5 failed; the recipe's afterok stitch was cancelled"
[ "$(state "$refused")" = "FAILED " ] || { echo "the stitch did not refuse: $(state "$refused")"; exit 1; }
grep -q '^error: missing 1 of the 16 tiles of the 4x4 grid (0 to 15): 5$' refused.out \
  || { echo "the stitch's refusal does not name tile 5:"; cat refused.out; exit 1; }
[ ! -e "$FRAME" ] || { echo "a refused stitch wrote $FRAME"; exit 1; }
echo "the stitch refused: $(cat refused.out)"

rm "$work/poison-5"
scontrol requeue "${array}_5"
# Slurm holds a requeued job until a begin time a while ahead; start now.
scontrol update JobId="${array}_5" StartTime=now
# afterok on the whole array can never be met once a task failed: the new
# stitch waits for the requeued task (the other 15 succeeded).
stitched=$(sbatch --parsable --dependency=afterok:"${array}_5" --output=stitched.out "$repo/examples/slurm/stitch.sbatch")
wait_done "$array"
wait_done "$stitched"
[ "$(state "$stitched")" = "COMPLETED " ] || { echo "stitch after the requeue: $(state "$stitched")"; cat stitched.out; exit 1; }
cmp "$FRAME" "$work/local.png"
echo "after requeueing task 5 the stitched frame equals the local render byte for byte"

echo "PASSED: Slurm end-to-end in $(($(date +%s) - started)) s"
