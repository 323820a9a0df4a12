#!/usr/bin/env bash
# End-to-end benchmark: `tumble render` of the default scene at 1280x720, 60 fps, 5 s (300
# frames), beside ffmpeg encoding the same 300 frames from raw RGB with the same codec settings
# (libx264 veryfast, CRF 23, yuv420p, 4 threads). Prints the best of N runs of each, and the ratio.
#   bench/e2e_render.sh [path/to/tumble] [runs]
set -euo pipefail
tumble=${1:-build/release/tumble}
runs=${2:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

now() { date +%s.%N; }
# Best wall time of $runs runs of the command.
best_of() {
  local best="" t t0
  for _ in $(seq "$runs"); do
    t0=$(now)
    "$@"
    t=$(awk -v a="$(now)" -v b="$t0" 'BEGIN { printf "%.3f", a - b }')
    best=$(awk -v t="$t" -v b="${best:-inf}" 'BEGIN { print (b == "inf" || t < b) ? t : b }')
  done
  echo "$best"
}
tumble_s=$(best_of "$tumble" render --duration 5 --size 1280x720 --fps 60 --out "$work/tumble" \
  --quiet)
# The reference the frame reuse is measured against: every frame drawn (same bytes out).
every_s=$(best_of "$tumble" render --duration 5 --size 1280x720 --fps 60 --out "$work/every" \
  --quiet --draw-every-frame)

# The same frames as raw RGB (decoded from tumble's clip; not timed).
ffmpeg -v error -i "$work/tumble/clip.mp4" -f rawvideo -pix_fmt rgb24 "$work/frames.rgb"
frames=$(( $(stat -c %s "$work/frames.rgb") / (1280 * 720 * 3) ))
ffmpeg_s=$(best_of ffmpeg -v error -y -f rawvideo -pix_fmt rgb24 -s 1280x720 -r 60 \
  -i "$work/frames.rgb" -c:v libx264 -preset veryfast -crf 23 -threads 4 -pix_fmt yuv420p \
  -colorspace bt709 -color_primaries bt709 -color_trc bt709 -movflags +faststart \
  "$work/ffmpeg.mp4")

stages=$(tr -d ' \n' < "$work/tumble/run.json" | grep -o '"wall_time":{[^}]*}')
printf '%-40s %8s\n' "what" "seconds"
printf '%-40s %8.2f\n' "tumble render (300 frames, 720p60)" "$tumble_s"
printf '%-40s %8.2f\n' "  the same, --draw-every-frame" "$every_s"
printf '%-40s %8.2f\n' "ffmpeg encode-only, same $frames frames" "$ffmpeg_s"
printf '%-40s %8.2f  (target <= 1.5)\n' "ratio tumble / ffmpeg" \
  "$(awk -v a="$tumble_s" -v b="$ffmpeg_s" 'BEGIN { print a / b }')"
echo "tumble stages (last run): $stages"
reused=$(tr -d ' \n' < "$work/tumble/run.json" | grep -o '"frames_reused":[0-9]*' | cut -d: -f2)
echo "frames drawn: $(( frames - reused )), reused unchanged: $reused (of $frames)"
