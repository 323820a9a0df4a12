#!/usr/bin/env bash
# Issue 21's rendering target: the 720p60 clip of the thousand dice within 1.5x ffmpeg's
# encode-only time of the same frames, memory reported. The dice are bench/many_bodies.py's, with
# --float (no gravity, collisions = "floor"): they spin where they were put, 0.5-3.2 m above the
# floor, every body moving in every frame, and the simulation costs seconds (the falling dice's
# pile is the physics' problem, not the renderer's). `tumble render` at 1280x720, 60 fps, beside
# ffmpeg encoding the same frames from raw RGB with the same codec settings (libx264 veryfast,
# CRF 23, yuv420p, 4 threads; as bench/e2e_render.sh). Prints the best of N runs of each, the
# ratio, tumble's stages (run.json, best run) and the peak resident memory of both
# (/usr/bin/time -v, Debian package `time`).
#   bench/many_bodies_render.sh [path/to/tumble] [dice] [seconds] [runs] [extra render options...]
set -euo pipefail
cd "$(dirname "$0")/.."
tumble=${1:-build/release/tumble}
count=${2:-1000}
duration=${3:-10}
runs=${4:-1}
shift 4 2>/dev/null || shift $#
extra=("$@")
[ -x /usr/bin/time ] || { echo "many_bodies_render.sh: needs /usr/bin/time (apt-get install time)" >&2; exit 3; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

scene="$work/dice.toml"
bench/many_bodies.py dice "$count" --float --duration "$duration" > "$scene"

# Runs the command under /usr/bin/time -v; sets wall_s and rss_kb.
timed() {
  /usr/bin/time -v -o "$work/time.txt" "$@"
  wall_s=$(awk -F': ' '/Elapsed \(wall clock\)/ { n = split($2, p, ":"); s = 0;
    for (i = 1; i <= n; i++) s = s * 60 + p[i]; printf "%.3f", s }' "$work/time.txt")
  rss_kb=$(awk -F': ' '/Maximum resident set size/ { print $2 }' "$work/time.txt")
}

best_s="" best_rss=0
for _ in $(seq "$runs"); do
  rm -rf "$work/run"
  timed "$tumble" render "$scene" --size 1280x720 --fps 60 --out "$work/run" --quiet "${extra[@]}"
  if [ -z "$best_s" ] || awk -v a="$wall_s" -v b="$best_s" 'BEGIN { exit !(a < b) }'; then
    best_s=$wall_s
    rm -rf "$work/tumble" && mv "$work/run" "$work/tumble"
  fi
  [ "$rss_kb" -gt "$best_rss" ] && best_rss=$rss_kb
done

# The same frames as raw RGB (decoded from tumble's clip; not timed).
ffmpeg -v error -i "$work/tumble/clip.mp4" -f rawvideo -pix_fmt rgb24 "$work/frames.rgb"
frames=$(( $(stat -c %s "$work/frames.rgb") / (1280 * 720 * 3) ))
ffmpeg_s="" ffmpeg_rss=0
for _ in $(seq "$runs"); do
  timed ffmpeg -v error -y -f rawvideo -pix_fmt rgb24 -s 1280x720 -r 60 -i "$work/frames.rgb" \
    -c:v libx264 -preset veryfast -crf 23 -threads 4 -pix_fmt yuv420p -colorspace bt709 \
    -color_primaries bt709 -color_trc bt709 -movflags +faststart "$work/ffmpeg.mp4"
  if [ -z "$ffmpeg_s" ] || awk -v a="$wall_s" -v b="$ffmpeg_s" 'BEGIN { exit !(a < b) }'; then
    ffmpeg_s=$wall_s
  fi
  [ "$rss_kb" -gt "$ffmpeg_rss" ] && ffmpeg_rss=$rss_kb
done

python3 - "$work/tumble/run.json" "$count" "$frames" "$best_s" "$best_rss" "$ffmpeg_s" \
  "$ffmpeg_rss" "${extra[*]:-}" <<'EOF'
import json, sys
report, count, frames, tumble_s, tumble_rss, ffmpeg_s, ffmpeg_rss, extra = sys.argv[1:]
r = json.load(open(report))
w = r["wall_time"]
frames, tumble_s, ffmpeg_s = int(frames), float(tumble_s), float(ffmpeg_s)
print(f"{count} floating dice, 1280x720, 60 fps, {frames} frames"
      f"{', options: ' + extra if extra else ''}")
print(f"{'what':<44} {'seconds':>8} {'ms/frame':>9} {'peak RSS MiB':>13}")
def row(what, s, rss=None):
    mib = f"{int(rss) / 1024:13.0f}" if rss is not None else ""
    print(f"{what:<44} {s:8.2f} {1000 * s / frames:9.1f} {mib}")
row("tumble render, wall", tumble_s, tumble_rss)
for stage in ("simulate_s", "framing_s", "render_s", "readback_s", "encode_s"):
    if stage in w:
        row(f"  {stage[:-2]} (run.json)", w[stage])
row(f"ffmpeg encode-only, same {frames} frames", ffmpeg_s, ffmpeg_rss)
print(f"{'ratio tumble / ffmpeg':<44} {tumble_s / ffmpeg_s:8.2f}  (target <= 1.5)")
c = r["counts"]
print(f"frames drawn: {c['frames'] - c.get('frames_reused', 0)}, reused unchanged:"
      f" {c.get('frames_reused', 0)}")
EOF
