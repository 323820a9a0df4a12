#!/usr/bin/env bash
# Speed against accuracy on every example scene: `tumble study` of each assets/scenes/*.toml (every
# integrator × dt, adaptive × tolerance, defaults otherwise), then one table of accuracy per cost:
# per scene and integrator, the cheapest run that cannot be told from the reference (pixel error
# < 0.5 px), its derivative evaluations and error, and the most accurate trusted run; per scene
# the study's wall time, the reference and the recommendation.
#   bench/study_examples.sh [path/to/tumble] [out-dir] [more study options, e.g. --jobs 1]
# Without out-dir the studies go to a temporary folder, removed at the end.
set -euo pipefail
tumble=${1:-build/release/tumble}
here=$(cd "$(dirname "$0")/.." && pwd)
if [[ $# -ge 2 ]]; then
  work=$2
  mkdir -p "$work"
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi
shift $(( $# < 2 ? $# : 2 ))

now() { date +%s.%N; }

printf '%-26s %-17s %-18s %10s %10s %10s\n' "scene" "integrator" "cheapest < 0.5 px" \
  "evals" "error m" "best m"
for scene in "$here"/assets/scenes/*.toml; do
  stem=$(basename "$scene" .toml)
  t0=$(now)
  "$tumble" study "$scene" --out "$work/$stem" --quiet "$@"
  wall=$(awk -v a="$(now)" -v b="$t0" 'BEGIN { printf "%.2f", a - b }')
  # Columns by name, so the table survives new columns in study.csv.
  awk -F, -v stem="$stem" '
    NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    $col["status"] != "ok" { next }
    {
      name = $col["integrator"]
      if (!(name in seen)) { seen[name] = 1; order[++n] = name }
      setting = $col["tolerance"] != "" ? "tol=" $col["tolerance"] : sprintf("dt=%.4g", $col["dt"])
      if ($col["indistinguishable"] == "true" &&
          (!(name in cheap) || $col["evaluations"] + 0 < cheap_evals[name])) {
        cheap[name] = setting; cheap_evals[name] = $col["evaluations"] + 0
        cheap_error[name] = $col["error"] + 0
      }
      if ($col["trusted"] == "true" && (!(name in best) || $col["error"] + 0 < best[name]))
        best[name] = $col["error"] + 0
    }
    END {
      for (k = 1; k <= n; ++k) {
        name = order[k]
        printf "%-26s %-17s %-18s %10s %10s %10s\n", (k == 1 ? stem : ""), name,
          (name in cheap ? cheap[name] : "none"),
          (name in cheap ? cheap_evals[name] : "-"),
          (name in cheap ? sprintf("%.2g", cheap_error[name]) : "-"),
          (name in best ? sprintf("%.2g", best[name]) : "-")
      }
    }' "$work/$stem/study.csv"
  reference=$(sed -n 's/^\*\*Exact\*\*.*/exact/p; s/^\*\*Numeric\*\*: \([^,]*\),.*/\1/p' \
    "$work/$stem/study.md")
  recommended=$(grep -A2 '^## Recommendation' "$work/$stem/study.md" | grep -o '^\*\*[^*]*\*\*' |
                tr -d '*' || true)
  printf '%-26s study %s s; reference %s; recommended: %s\n\n' "" "$wall" "$reference" \
    "${recommended:-none}"
done
