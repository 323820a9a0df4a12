#!/usr/bin/env bash
# A sweep on a real Slurm: a one-node cluster on localhost (munged, slurmctld, slurmd, all in a
# temporary folder, on ports of their own), the plan submitted as a job array with
# scripts/slurm/sweep.sbatch and `sbatch --wait`, collected, and every job's outputs compared
# byte for byte with a plain local `tumble sweep` of the same plan. Then one array task is
# cancelled in the middle of a job and the array resubmitted: only the missing job runs, the
# finished jobs' run.json stay untouched. Installs Debian's slurmctld, slurmd, slurm-client and
# munge if missing (as scripts/setup does); stops every daemon it started and removes its folder.
#
#   tests/cluster/slurm_sweep.sh TUMBLE_BINARY SOURCE_DIR
set -euo pipefail
tumble=$(realpath "$1")
source_dir=$(realpath "$2")
started=$(date +%s)
say() { echo "slurm_sweep: $* ($(($(date +%s) - started)) s)"; }
fail() { echo "slurm_sweep: FAIL: $*" >&2; exit 1; }

[ "$(id -u)" -eq 0 ] || fail "needs root: slurmd runs jobs as their user and munged as munge"
missing=()
for p in slurmctld slurmd slurm-client munge; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  say "installing ${missing[*]}"
  DEBIAN_FRONTEND=noninteractive apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

tmp=$(mktemp -d /tmp/tumble-slurm.XXXXXX)
chmod 755 "$tmp"  # munged (user munge) must reach its folder inside
cleanup() {
  local status=$?
  if [ -n "${SLURM_CONF:-}" ] && [ -f "$SLURM_CONF" ]; then scancel --quiet --full "${array_job:-0}" 2>/dev/null || true; fi
  for pid_file in "$tmp/slurmd.pid" "$tmp/slurmctld.pid" "$tmp/munge/munged.pid"; do
    [ -f "$pid_file" ] || continue
    pid=$(cat "$pid_file")
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
  if [ $status -ne 0 ]; then
    for log in "$tmp"/*.log "$tmp"/work/*.log; do
      [ -f "$log" ] && { echo "--- $log"; tail -n 30 "$log"; }
    done
  fi
  rm -rf "$tmp"
  exit $status
}
trap cleanup EXIT

# munged as user munge, on a socket of its own (a system munged, if any, is left alone).
mkdir -p "$tmp/munge"
cp /etc/munge/munge.key "$tmp/munge/munge.key" 2>/dev/null ||
  dd if=/dev/urandom of="$tmp/munge/munge.key" bs=1 count=1024 status=none
chown -R munge:munge "$tmp/munge"
chmod 700 "$tmp/munge"
chmod 400 "$tmp/munge/munge.key"
socket="$tmp/munge/munge.socket.2"
su -s /bin/sh munge -c "munged --key-file=$tmp/munge/munge.key --socket=$socket \
  --pid-file=$tmp/munge/munged.pid --log-file=$tmp/munge/munged.log \
  --seed-file=$tmp/munge/munged.seed --force"
for _ in $(seq 50); do [ -S "$socket" ] && break; sleep 0.1; done
[ -S "$socket" ] || fail "munged did not start"

# Ports of our own, so that another Slurm on this machine is not disturbed.
port=$((20000 + $$ % 20000))
host=$(hostname)
mkdir -p "$tmp/state" "$tmp/spool" "$tmp/work"
cat > "$tmp/slurm.conf" <<CONF
ClusterName=tumbletest
SlurmctldHost=$host
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
KillWait=20
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$tmp/slurm.conf"
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for _ in $(seq 100); do
  state=$(sinfo -h -n "$host" -o %t 2>/dev/null || true)
  [ "$state" = "idle" ] && break
  sleep 0.3
done
[ "$state" = "idle" ] || fail "the node is not idle (sinfo: '$state')"
say "one-node cluster up ($(nproc) CPUs, port $port)"

# Eight small render jobs: 160x120, 0.5 s clips and a still.
work="$tmp/work"
cat > "$work/drop.toml" <<'SCENE'
[simulation]
duration = 0.5
[floor]
[[body]]
name = "box"
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
position = [0.0, 2.0, 0.0]
SCENE
cat > "$work/plan.toml" <<'PLAN'
scene = "drop.toml"
command = "render"
args = ["--size", "160x120", "--still", "0.4", "--quiet"]
[grid]
"floor.restitution" = [0.3, 0.7]
[random]
count = 4
seed = 11
"body.box.orientation" = { choice = [{ axis = [1.0, 0.0, 0.0], degrees = 25.0 }, { axis = [0.0, 0.0, 1.0], degrees = 40.0 }] }
"body.box.angular_velocity" = { uniform = [[0.0, 0.0, 0.0], [1.0, 3.0, 1.0]] }
PLAN
cd "$work"
export TUMBLE="$tumble"
"$tumble" sweep plan.toml --out local --quiet
say "local sweep done"
sbatch --wait --array=0-3%2 --chdir="$work" --cpus-per-task=1 \
  "$source_dir/scripts/slurm/sweep.sbatch" plan.toml --out slurm >/dev/null
say "array job done"
"$tumble" sweep plan.toml --out slurm --collect >/dev/null || fail "--collect after the array job"
[ "$(ls -d slurm/job_* | wc -l)" -eq 8 ] || fail "expected 8 job folders"
for dir in local/job_*; do
  job=$(basename "$dir")
  for file in "$dir"/*; do
    name=$(basename "$file")
    [ "$name" = run.json ] && continue  # wall times and paths differ; its outputs are below
    cmp -s "$file" "slurm/$job/$name" || fail "$job/$name differs between Slurm and the local run"
  done
  [ "$(ls "$dir" | wc -l)" -eq "$(ls "slurm/$job" | wc -l)" ] || fail "$job: different files"
done
ls tumble-sweep-*_[0-3].log >/dev/null || fail "no log per array task"
say "all 8 jobs byte-identical to the local sweep; sweep.csv collected"

# Cancel a task in the middle of a job, then resubmit: job 5 (shard 1's last) is long.
cat > "$work/long.toml" <<'PLAN'
scene = "drop.toml"
command = "render"
args = ["--size", "160x120", "--quiet"]
[grid]
"simulation.duration" = [0.5, 0.5, 0.5, 0.5, 0.5, 300.0]
PLAN
array_job=$(sbatch --parsable --array=0-1 --chdir="$work" --cpus-per-task=1 \
  "$source_dir/scripts/slurm/sweep.sbatch" long.toml --out long)
for _ in $(seq 600); do
  [ -f long/job_00003/run.json ] && [ -f long/job_00005/scene.toml ] && break
  sleep 0.1
done
[ -f long/job_00005/scene.toml ] || fail "task 1 never reached job 5"
sleep 1  # well inside job 5 (18000 frames, about 10 s)
scancel --signal=TERM --full "${array_job}_1"
for _ in $(seq 300); do
  [ -z "$(squeue -h -j "$array_job" 2>/dev/null)" ] && break
  sleep 0.2
done
[ -z "$(squeue -h -j "$array_job")" ] || fail "the array job did not end"
[ ! -f long/job_00005/run.json ] || fail "the cancelled job 5 has a run.json"
[ ! -f long/job_00005/clip.mp4 ] || fail "the cancelled job 5 left a clip.mp4"
[ -z "$(find long -name '.*.partial')" ] || fail "a temporary file was left behind"
grep -q "interrupted" tumble-sweep-"${array_job}"_1.log || fail "task 1 was not interrupted"
if "$tumble" sweep long.toml --out long --collect >/dev/null 2>"$tmp/collect.err"; then
  fail "--collect found no missing job"
fi
grep -q "missing jobs (not run, interrupted or stale): 5$" "$tmp/collect.err" || fail "collect: $(cat "$tmp/collect.err")"
say "task 1 cancelled inside job 5: no run.json, collect names job 5"

before=$(for j in 0 1 2 3 4; do stat -c '%n %Y.%y' long/job_0000$j/run.json; sha256sum long/job_0000$j/run.json; done)
sbatch --wait --array=0-1 --chdir="$work" --cpus-per-task=1 \
  "$source_dir/scripts/slurm/sweep.sbatch" long.toml --out long >/dev/null
after=$(for j in 0 1 2 3 4; do stat -c '%n %Y.%y' long/job_0000$j/run.json; sha256sum long/job_0000$j/run.json; done)
[ "$before" = "$after" ] || fail "a finished job's run.json changed on resubmission"
"$tumble" sweep long.toml --out long --collect >/dev/null || fail "--collect after the resubmission"
logs=$(cat tumble-sweep-*.log)
echo "$logs" | grep -q "shard 0/2: 3 jobs, 0 ran, 3 skipped" || fail "shard 0 ran jobs again"
echo "$logs" | grep -q "shard 1/2: 3 jobs, 1 ran, 2 skipped" || fail "shard 1 did not run only job 5"
say "resubmission ran only job 5; the others' run.json untouched"
say "PASS"
