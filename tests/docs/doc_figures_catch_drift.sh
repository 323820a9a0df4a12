#!/usr/bin/env bash
# scripts/doc-figures itself: a quoted figure within its tolerance passes, one beyond it fails
# naming the file, the line, the quote and the measurement, --write puts the measured value in,
# and a marker naming no measurement is an error. On a committed figure file (no rendering), so
# it costs nothing.
#   doc_figures_catch_drift.sh SOURCE_DIR
set -euo pipefail
script=$1/scripts/doc-figures
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
bytes=$(stat -c %s "$1/docs/figures/side_view.webp")
kb=$(( (bytes + 500) / 1000 ))

fail() { echo "FAIL: $*" >&2; exit 1; }

# Within 10 %: current.
printf 'The WebP is %d kB<!--figure:file_side_view.webp-->.\n' "$(( kb * 105 / 100 ))" > "$work/ok.md"
"$script" --doc "$work/ok.md" > "$work/out" || fail "a figure within 10 % was reported: $(cat "$work/out")"

# 30 % off: drifted, exit 1, the place and both values named.
printf 'Intro.\nThe WebP is %d kB<!--figure:file_side_view.webp-->.\n' "$(( kb * 13 / 10 ))" > "$work/off.md"
if "$script" --doc "$work/off.md" > "$work/out"; then fail "a figure 30 % off passed"; fi
grep -q "off.md:2: file_side_view.webp is quoted as $(( kb * 13 / 10 )) kB but measures $kb kB" "$work/out" ||
  fail "the drift is not named: $(cat "$work/out")"

# --write puts the measured value in; then it is current.
"$script" --doc "$work/off.md" --write > /dev/null
grep -q "The WebP is $kb kB<!--figure:file_side_view.webp-->." "$work/off.md" ||
  fail "--write did not update the quote: $(cat "$work/off.md")"
"$script" --doc "$work/off.md" > /dev/null || fail "the written figure is not current"

# A marker naming no measurement.
printf 'A 3 kB<!--figure:no_such_figure--> file.\n' > "$work/unknown.md"
if "$script" --doc "$work/unknown.md" 2> "$work/err"; then fail "an unknown figure passed"; fi
grep -q "no_such_figure" "$work/err" || fail "the unknown figure is not named: $(cat "$work/err")"
echo "doc-figures: drift caught, --write fixes it, unknown names refused"
