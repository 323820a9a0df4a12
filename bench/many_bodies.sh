#!/usr/bin/env bash
# Many bodies through `tumble simulate`, as issue 21 measures them against Bullet and MuJoCo: a
# pyramid of 1 m boxes standing (pyramid:N, N rows, 10 s), the same pyramid hit by a 50 kg ball
# (pyramid_hit:N, 5 s) and K spinning dice dropped from a lattice (dice:K, 10 s), all rk4 at
# dt = 0.002, friction 0.5, restitution 0; scenes from bench/many_bodies.py. A spec may end in
# @S to simulate S seconds instead (pyramid_hit:4@0.3). One row per scene: bodies, simulated and
# wall seconds (run.json's simulate stage, 60 Hz sampling included), steps/s, impacts, deepest
# overlap, largest energy gain across a contact, diagnostic codes, and for pyramids the largest
# displacement of any box from its start over the trajectory ("moved"); then the peers' figures.
# The default specs are the issue's full set and take long (tens of minutes or more).
#   bench/many_bodies.sh [path/to/tumble] [scene spec ...]
set -euo pipefail
cd "$(dirname "$0")/.."
tumble=${1:-build/release/tumble}
shift || true
specs=("$@")
[ ${#specs[@]} -gt 0 ] || specs=(pyramid:20 pyramid_hit:20 dice:10 dice:100 dice:1000)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

printf '%-22s %6s %8s %10s %10s %8s %10s %10s %10s %s\n' scene bodies "sim s" "wall s" \
  "steps/s" impacts "deepest m" "gain J" "moved m" diagnostics
for spec in "${specs[@]}"; do
  kind=${spec%%:*}
  rest=${spec#*:}
  count=${rest%%@*}
  args=()
  [ "$rest" != "$count" ] && args=(--duration "${rest#*@}")
  if [ "$kind" = "$spec" ] || ! [[ "$count" =~ ^[0-9]+$ ]]; then
    echo "many_bodies.sh: bad scene spec '$spec' (KIND:N[@SECONDS], KIND pyramid|pyramid_hit|dice)" >&2
    exit 2
  fi
  name=${spec//[:@]/_}
  scene="$work/$name.toml"
  bench/many_bodies.py "$kind" "$count" "${args[@]}" > "$scene"
  rc=0
  "$tumble" simulate "$scene" --out "$work/out_$name" --quiet 2> "$work/$name.err" || rc=$?
  if [ "$rc" -ne 0 ]; then
    printf '%-22s failed (exit %d): %s\n' "$spec" "$rc" "$(tr '\n' ' ' < "$work/$name.err")"
    continue
  fi
  python3 - "$spec" "$kind" "$work/out_$name" <<'EOF'
import csv, json, math, sys
spec, kind, out = sys.argv[1:]
r = json.load(open(f"{out}/run.json"))
p, c = r["physics"], r["counts"]
wall = r["wall_time"]["simulate_s"]
moved = "-"
if kind.startswith("pyramid"):
    start, far = {}, 0.0
    with open(f"{out}/trajectory.csv", newline="") as fh:
        for row in csv.DictReader(fh):
            if not row["body"].startswith("box_"):
                continue
            x = (float(row["x"]), float(row["y"]), float(row["z"]))
            x0 = start.setdefault(row["body"], x)
            far = max(far, math.dist(x, x0))
    moved = f"{far:.3g}"
codes = sorted({d["code"] for d in r["diagnostics"]})
print(f"{spec:<22} {len(r['bodies']):6d} {r['settings']['simulation']['duration_s']:8.3g}"
      f" {wall:10.4g} {c['steps'] / wall if wall > 0 else float('nan'):10.0f} {c['impacts']:8d}"
      f" {p['deepest_penetration_m']:10.3g} {p['max_contact_energy_gain_J']:10.3g} {moved:>10}"
      f" {','.join(codes) or '-'}")
EOF
done
cat <<'EOF'
peers (issue 21), wall s:
  pyramid 20 standing 10 s:  Bullet 3.24 2.1 s (sags 24 mm), MuJoCo 2.2 91 s (sags 3.6 mm)
  pyramid_hit 20, 5 s:       Bullet 0.88 s, MuJoCo 153 s
  dice 10 / 100 / 1000:      Bullet 0.036 / 0.57 / 10.4 s, MuJoCo 0.17 / 7.5 s / overflows at 0.44 s
EOF
