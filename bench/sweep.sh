#!/usr/bin/env bash
# Sweep throughput: 100 jobs of the default scene (random tilt and spin), each a 2-s clip at
# 320x240 (MP4 + a still), three ways: `tumble sweep` in one process (one EGL context for every
# job), a shell loop calling `tumble render` once per job on the same effective scenes, and two
# shards in parallel (`--shard 0/2` and `--shard 1/2`). Prints clips per second for each, checks
# that all three wrote the same clip bytes, and prints the start-up costs the one process saves.
#   bench/sweep.sh [path/to/tumble] [jobs]
set -euo pipefail
tumble=$(realpath "${1:-build/release/tumble}")
jobs=${2:-100}
source_dir=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cat > "$work/plan.toml" <<PLAN
scene = "$source_dir/assets/scenes/default.toml"
command = "render"
args = ["--size", "320x240", "--duration", "2", "--still", "1.0", "--quiet"]
[random]
count = $jobs
seed = 2024
"body.box.orientation.degrees" = { uniform = [0.0, 90.0] }
"body.box.angular_velocity" = { uniform = [[-2.0, -2.0, -2.0], [2.0, 2.0, 2.0]] }
PLAN
cd "$work"
now() { date +%s.%N; }
rate() { awk -v n="$jobs" -v a="$2" -v b="$1" 'BEGIN { printf "%.2f clips/s (%.1f s)", n / (a - b), a - b }'; }

t0=$(now)
"$tumble" sweep plan.toml --out one --quiet
t1=$(now)
one=$(rate "$t0" "$t1")

t0=$(now)
for dir in one/job_*; do
  "$tumble" render "$dir/scene.toml" --size 320x240 --duration 2 --still 1.0 --quiet \
    --out "loop/$(basename "$dir")"
done
t1=$(now)
loop=$(rate "$t0" "$t1")

t0=$(now)
"$tumble" sweep plan.toml --out shards --shard 0/2 --quiet &
"$tumble" sweep plan.toml --out shards --shard 1/2 --quiet &
wait
t1=$(now)
shards=$(rate "$t0" "$t1")

for dir in one/job_*; do
  job=$(basename "$dir")
  cmp -s "$dir/clip.mp4" "loop/$job/clip.mp4" || { echo "loop: $job/clip.mp4 differs" >&2; exit 1; }
  cmp -s "$dir/clip.mp4" "shards/$job/clip.mp4" || { echo "shards: $job/clip.mp4 differs" >&2; exit 1; }
done

# Where the loop's time goes: a process that only starts and renders no frame, and the wall
# time of one job as the sweep's run.json reports it (its first job pays the driver's start-up).
t0=$(now)
for _ in $(seq 10); do "$tumble" render "one/job_00000/scene.toml" --size 320x240 --duration 0.02 \
  --fps 50 --no-mp4 --still 0 --quiet --out startup; done
t1=$(now)
startup=$(awk -v a="$t1" -v b="$t0" 'BEGIN { printf "%.0f", (a - b) * 100 }')
first=$(python3 -c "import json;print(round(json.load(open('one/job_00000/run.json'))['wall_time']['total_s']*1000))")
rest=$(python3 -c "
import json,glob
t=[json.load(open(f))['wall_time']['total_s'] for f in sorted(glob.glob('one/job_*/run.json'))[1:]]
print(round(1000*sum(t)/len(t)))")

echo "tumble sweep, $jobs jobs (320x240, 2-s clips, MP4 + still), $(nproc) cores:"
echo "  one process (one EGL context):  $one"
echo "  shell loop of tumble render:    $loop"
echo "  2 shards in parallel:           $shards"
echo "  a tumble render that draws one still and no clip: $startup ms per process"
echo "  a job inside the sweep: $first ms the first (driver start-up), $rest ms each after"
echo "  clips byte-identical in all three"
