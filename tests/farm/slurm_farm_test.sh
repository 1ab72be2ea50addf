#!/usr/bin/env bash
# End-to-end test of `spume farm slurm` on a real single-node Slurm cluster started here, on
# localhost, in a temporary folder (munged, slurmctld and slurmd; no accounting, no cgroups):
#   1. the simulation job and the render array (chunks of 1 frame, after it) render a tiny scene;
#      every frame must be byte-identical to a local `spume run`;
#   2. after cancelling a resubmitted array part way, submitting again renders only the missing
#      frames (counted by the `Saved:` lines of the array's logs) and the result is identical again;
#   3. when the simulation job fails, the array is cancelled without running.
# Exits 77 (ctest: skipped) when Slurm or munge is not installed.
# Usage: slurm_farm_test.sh SPUME_BINARY SCENE.json
set -euo pipefail

spume=$1
scene=$2
export PATH=$PATH:/usr/sbin  # the daemons live in sbin, often missing from a user's PATH
for program in munged slurmctld slurmd sbatch squeue scancel scontrol; do
  if ! command -v "$program" >/dev/null; then
    echo "SKIP: $program not found; install Debian's slurm-wlm and munge (listed in .ci/packages)"
    exit 77
  fi
done

work=$(mktemp -d /tmp/spume_slurm_test.XXXXXX)
pids=()
cleanup() {
  local status=$?
  # Daemons were started by this script only; stop them by their pids.
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  if [ -f "$work/munged.pid" ]; then
    munged_pid=$(cat "$work/munged.pid")
    kill "$munged_pid" 2>/dev/null || true
    # munged is not our child: wait for it (and any job step still writing logs) to go.
    for _ in $(seq 50); do kill -0 "$munged_pid" 2>/dev/null || break; sleep 0.1; done
  fi
  if [ $status -ne 0 ]; then
    echo "--- logs (test failed) ---"
    tail -n 20 "$work"/log/* "$work"/out/*/farm/logs/* 2>/dev/null || true
  fi
  # A job step that outlives the daemons can still be writing its log while the folder goes: try
  # again, and never let the clean-up decide the verdict.
  for _ in 1 2 3; do rm -rf "$work" 2>/dev/null && break; sleep 1; done
  exit $status
}
trap cleanup EXIT
fail() { echo "FAIL: $*"; exit 1; }

mkdir -p "$work/state" "$work/spool" "$work/log"
dd if=/dev/urandom of="$work/munge.key" bs=1 count=128 status=none
chmod 600 "$work/munge.key"

# Ports from the pid, so that two runs on one machine do not collide.
port=$((20000 + ($$ % 20000)))
cpus=$(slurmd -C | sed -n 's/.*CPUs=\([0-9]*\).*/\1/p' | head -1)
memory=$(slurmd -C | sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p' | head -1)
user=$(id -un)
cat >"$work/slurm.conf" <<EOF
ClusterName=spumetest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
AuthInfo=socket=$work/munge.socket
CryptoType=crypto/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
SchedulerParameters=sched_min_interval=0
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=farmtest Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$work/slurm.conf

# munged forks into the background and writes its pid file; -f lets it run as root.
munged -f --socket="$work/munge.socket" --key-file="$work/munge.key" --pid-file="$work/munged.pid" \
  --log-file="$work/log/munged.log" --seed-file="$work/munged.seed"
slurmctld -D -i -f "$work/slurm.conf" >"$work/log/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -N localhost -f "$work/slurm.conf" >"$work/log/slurmd.out" 2>&1 &
pids+=($!)
for _ in $(seq 100); do
  sinfo -h -o %t 2>/dev/null | grep -q idle && break
  sleep 0.2
done
sinfo -h -o %t | grep -q idle || fail "the Slurm node did not become idle"
echo "Slurm is up: 1 node, $cpus CPUs, port $port"

# The reference: the same scene rendered locally in one process.
"$spume" run "$scene" --out "$work/local" --quiet
frames=$(ls "$work/local"/*/frames/*.png | wc -l)
[ "$frames" -ge 4 ] || fail "the local render made $frames frames"

job_state() { scontrol show job "$1" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | sort -u | tr '\n' ' '; }
wait_for_jobs() {  # job ids; fails after 60 s
  for _ in $(seq 300); do
    [ -z "$(squeue -h -j "$(IFS=,; echo "$*")" 2>/dev/null)" ] && return 0
    sleep 0.2
  done
  squeue
  fail "jobs $* did not finish in 60 s"
}
submitted_id() { sed -n "s/^Submitted $1 job \([0-9]*\).*/\1/p" "$2"; }
compare_frames() {
  local local_dir=$(ls -d "$work/local"/*/frames) farm_dir=$(ls -d "$work/out"/*/frames)
  [ "$(ls "$farm_dir"/*.png | wc -l)" -eq "$frames" ] || fail "the farm made $(ls "$farm_dir"/*.png | wc -l) frames, not $frames"
  for f in "$local_dir"/*.png; do
    cmp "$f" "$farm_dir/$(basename "$f")" || fail "frame $(basename "$f") differs from the local render"
  done
}
saved_lines() { cat "$work/out"/*/farm/logs/render_"$1"_*.log | grep -c '^Saved: ' || true; }

# 1. Simulation job, then the array (one frame per task).
start=$(date +%s%N)
"$spume" farm slurm "$scene" --out "$work/out" --chunk 1 --partition farmtest --submit >"$work/submit1.txt"
cat "$work/submit1.txt"
simulation=$(submitted_id simulation "$work/submit1.txt")
array=$(submitted_id "render array" "$work/submit1.txt")
[ -n "$simulation" ] || fail "no simulation job was submitted for a fresh output folder"
[ -n "$array" ] || fail "no render array was submitted"
grep -q "dependency=afterok" "$work/out"/*/farm/submit.sh || fail "the array does not depend on the simulation"
wait_for_jobs "$simulation" "$array"
[ "$(job_state "$simulation")" = "COMPLETED " ] || fail "simulation job: $(job_state "$simulation")"
[ "$(job_state "$array")" = "COMPLETED " ] || fail "render array: $(job_state "$array")"
compare_frames
[ "$(saved_lines "$array")" -eq "$frames" ] || fail "the array saved $(saved_lines "$array") frames, not $frames"
echo "farm render: $frames frames byte-identical to the local render ($((($(date +%s%N) - start) / 1000000)) ms from submission)"

# 2. Remove all but the first two frames, resubmit with one task at a time, cancel the array once
#    it has saved a frame, then submit again: only the frames still missing are rendered.
farm_frames=$(ls -d "$work/out"/*/frames)
ls "$farm_frames"/*.png | tail -n +3 | xargs rm -f
"$spume" farm slurm "$scene" --out "$work/out" --chunk 1 --partition farmtest --max-running 1 --submit \
  >"$work/submit2.txt"
grep -q "^Submitted simulation" "$work/submit2.txt" && fail "a simulation job was submitted though the caches are current"
array=$(submitted_id "render array" "$work/submit2.txt")
for _ in $(seq 300); do
  [ "$(ls "$farm_frames"/*.png | wc -l)" -ge 3 ] && break
  sleep 0.1
done
scancel "$array"
wait_for_jobs "$array"
after_cancel=$(ls "$farm_frames"/*.png | wc -l)
echo "cancelled the array with $after_cancel of $frames frames on disk"
[ "$after_cancel" -lt "$frames" ] || fail "the array finished before it was cancelled; nothing left to resume"

"$spume" farm slurm "$scene" --out "$work/out" --chunk 1 --partition farmtest --submit >"$work/submit3.txt"
array=$(submitted_id "render array" "$work/submit3.txt")
wait_for_jobs "$array"
[ "$(job_state "$array")" = "COMPLETED " ] || fail "resumed render array: $(job_state "$array")"
rendered=$(saved_lines "$array")
[ "$rendered" -eq $((frames - after_cancel)) ] ||
  fail "the resumed array rendered $rendered frames; $((frames - after_cancel)) were missing"
compare_frames
echo "resume: rendered only the $rendered missing frames; all $frames byte-identical to the local render"

# 3. A failing simulation job: the array never runs (afterok), and is cancelled rather than left pending.
"$spume" farm slurm "$scene" --out "$work/failing" --chunk 4 --quiet >/dev/null
sed -i 's/^exec .*/exit 3/' "$work/failing"/*/farm/simulate.sbatch
bash "$work/failing"/*/farm/submit.sh >"$work/submit4.txt"
simulation=$(submitted_id simulation "$work/submit4.txt")
array=$(submitted_id "render array" "$work/submit4.txt")
wait_for_jobs "$simulation" "$array"
[ "$(job_state "$simulation")" = "FAILED " ] || fail "failing simulation job: $(job_state "$simulation")"
[ "$(job_state "$array")" = "CANCELLED " ] || fail "array after a failed simulation: $(job_state "$array")"
[ -z "$(ls "$work/failing"/*/frames/*.png 2>/dev/null)" ] || fail "frames were rendered after a failed simulation"
echo "failed simulation: the render array was cancelled without running"
echo "PASS"
