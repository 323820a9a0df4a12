#!/usr/bin/env bash
# Renders a scene's golden pictures afresh and compares them with the approved ones.
#   check.sh TUMBLE SCENE GOLDEN_DIR ACTUAL_DIR [--expect-difference] [TIME...] [-- OPTION...]
# Each TIME is a --still; OPTIONs go to `tumble render` as they are (figures: --strobe N,
# --transparent, ...). Colour is compared by `tumble diff`; a golden with alpha (RGBA PNG) has
# its alpha channel compared the same way, extracted by the ffmpeg tool. The actual pictures and,
# on failure, the diff images stay in ACTUAL_DIR for a person to look at. With
# --expect-difference the comparison must fail (exit 1): the golden tests cannot pass vacuously.
set -euo pipefail
tumble=$1 scene=$2 golden=$3 actual=$4
shift 4
expect_difference=false
if [ "${1:-}" = --expect-difference ]; then expect_difference=true; shift; fi
stills=()
while [ $# -gt 0 ] && [ "$1" != -- ]; do stills+=(--still "$1"); shift; done
[ "${1:-}" = -- ] && shift
options=("$@")

rm -rf "$actual"
"$tumble" render "$scene" --no-mp4 --size 160x120 "${stills[@]}" "${options[@]}" --out "$actual" \
  --quiet
rm -f "$actual/run.json"  # the folders compared hold the pictures only
tolerance=(--max-delta 5 --max-fraction 0.001)
set +e
"$tumble" diff "$golden" "$actual" "${tolerance[@]}" --diff-out "$actual/diff"
status=$?
set -e

# Alpha: PNG colour type 6 (byte 25 of the file) is RGBA.
for png in "$golden"/*.png; do
  [ "$(od -An -tu1 -j25 -N1 "$png" | tr -d ' ')" = 6 ] || continue
  name=$(basename "$png")
  mkdir -p "$actual/alpha/golden" "$actual/alpha/actual"
  for side in golden actual; do
    source_png=$golden/$name
    [ $side = actual ] && source_png=$actual/$name
    [ -f "$source_png" ] || continue
    ffmpeg -v error -y -i "$source_png" -vf alphaextract "$actual/alpha/$side/$name"
  done
done
if [ -d "$actual/alpha" ] && [ "$status" -eq 0 ]; then
  set +e
  "$tumble" diff "$actual/alpha/golden" "$actual/alpha/actual" "${tolerance[@]}" \
    --diff-out "$actual/alpha/diff"
  status=$?
  set -e
fi

if $expect_difference; then
  [ "$status" -eq 1 ] || { echo "expected the comparison to fail (exit 1), got $status" >&2; exit 1; }
  exit 0
fi
[ "$status" -eq 0 ] || echo "actual and diff images: $actual" >&2
exit "$status"
