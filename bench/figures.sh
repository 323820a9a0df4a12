#!/usr/bin/env bash
# What the documentation figures cost: `--strobe 12` at 1280x720 beside a single still, and
# `--gif` / `--webp` for the default clip (4 s, 60 fps) beside the MP4, at 1280x720 and at the
# README size 480x270. Prints the best wall time of N runs, the stage that does the work
# (run.json's wall_time) and the file size.
#   bench/figures.sh [path/to/tumble] [runs]
set -euo pipefail
tumble=${1:-build/release/tumble}
runs=${2:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

now() { date +%s.%N; }
# best_of NAME ARGS...: runs `tumble render ARGS --out $work/NAME` $runs times, prints the best.
best_of() {
  local name=$1 best="" t0 t
  shift
  for _ in $(seq "$runs"); do
    t0=$(now)
    "$tumble" render "$@" --out "$work/$name" --quiet
    t=$(awk -v a="$(now)" -v b="$t0" 'BEGIN { printf "%.3f", a - b }')
    best=$(awk -v t="$t" -v b="${best:-inf}" 'BEGIN { print (b == "inf" || t < b) ? t : b }')
  done
  echo "$best"
}
stage() {  # stage NAME KEY: a wall_time entry of the last run's run.json
  tr -d ' \n' < "$work/$1/run.json" | grep -o "\"$2\":[0-9.e-]*" | cut -d: -f2 |
    awk '{ printf "%.3f", $1 }'
}
size() { stat -c %s "$work/$1/$2"; }
row() { printf '%-46s %8s %10s %10s\n' "$@"; }

row "what" "wall s" "stage s" "bytes"
still=$(best_of still --no-mp4 --size 1280x720 --still 4)
row "one still at 4 s, 1280x720" "$still" "$(stage still render_s)" "$(size still still_4.png)"
strobe=$(best_of strobe --no-mp4 --size 1280x720 --strobe 12)
row "--strobe 12, 1280x720 (render_s: its draw)" "$strobe" "$(stage strobe render_s)" \
  "$(size strobe strobe.png)"
row "  strobe PNG (png_s, level 9)" "" "$(stage strobe png_s)" ""

for size in 1280x720 480x270; do
  mp4=$(best_of "mp4-$size" --size "$size")
  row "default clip $size: MP4 (encode_s)" "$mp4" "$(stage "mp4-$size" encode_s)" \
    "$(size "mp4-$size" clip.mp4)"
  gif=$(best_of "gif-$size" --size "$size" --no-mp4 --gif)
  row "default clip $size: --gif --no-mp4 (gif_s)" "$gif" "$(stage "gif-$size" gif_s)" \
    "$(size "gif-$size" clip.gif)"
  webp=$(best_of "webp-$size" --size "$size" --no-mp4 --webp)
  row "default clip $size: --webp --no-mp4 (webp_s)" "$webp" "$(stage "webp-$size" webp_s)" \
    "$(size "webp-$size" clip.webp)"
done
