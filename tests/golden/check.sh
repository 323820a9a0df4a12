#!/usr/bin/env bash
# Renders a scene's golden stills afresh and compares them with the approved ones.
#   check.sh TUMBLE SCENE GOLDEN_DIR ACTUAL_DIR [--expect-difference] TIME...
# The actual stills and, on failure, the diff images stay in ACTUAL_DIR for a person to look at.
# With --expect-difference the comparison must fail (exit 1): the golden tests cannot pass
# vacuously.
set -euo pipefail
tumble=$1 scene=$2 golden=$3 actual=$4
shift 4
expect_difference=false
if [ "${1:-}" = --expect-difference ]; then expect_difference=true; shift; fi
stills=()
for t in "$@"; do stills+=(--still "$t"); done

rm -rf "$actual"
"$tumble" render "$scene" --no-mp4 --size 160x120 "${stills[@]}" --out "$actual" --quiet
rm -f "$actual/run.json"  # the folders compared hold the stills only
set +e
"$tumble" diff "$golden" "$actual" --max-delta 5 --max-fraction 0.001 --diff-out "$actual/diff"
status=$?
set -e
if $expect_difference; then
  [ "$status" -eq 1 ] || { echo "expected the comparison to fail (exit 1), got $status" >&2; exit 1; }
  exit 0
fi
[ "$status" -eq 0 ] || echo "actual and diff images: $actual" >&2
exit "$status"
