#!/usr/bin/env bash
# Awake contact through `tumble simulate`, as issue 10 measures it against MuJoCo and Bullet:
# rk4, dt = 1e-5, a body that keeps moving on the floor so contact forces are solved in every
# derivative evaluation. Three scenes: a unit box spinning (and drifting) on a face of a
# frictionless floor, the same box sliding with friction mu = 0.5 (it slides for 0.68 s: the
# run is kept shorter than that), and the chamfered die mesh spinning on a hull face. Prints
# steps per second from run.json's simulate stage (sampling at 60 Hz included), best of N runs.
#   bench/awake_contact.sh [path/to/tumble] [steps] [runs]
set -euo pipefail
cd "$(dirname "$0")/.."
tumble=${1:-build/release/tumble}
steps=${2:-1000000}
runs=${3:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

body_box='shape = "box"
size = [1.0, 1.0, 1.0]'
body_die="shape = \"mesh\"
mesh = \"$PWD/assets/meshes/die.obj\""

scene() {  # name friction body-keys velocity
  cat > "$work/$1.toml" <<EOF
[simulation]
dt = 1e-5
integrator = "rk4"
[floor]
friction = $2
[[body]]
name = "body"
$3
mass = 1.0
position = [0.0, 0.5, 0.0]
velocity = $4
angular_velocity = [0.0, 5.0, 0.0]
EOF
}
scene spinning_box 0.0 "$body_box" "[0.3, 0.0, 0.1]"
scene sliding_box 0.5 "$body_box" "[3.0, 0.0, 1.5]"
scene spinning_die 0.0 "$body_die" "[0.3, 0.0, 0.1]"

printf '%-40s %12s %12s\n' "scene (rk4, dt = 1e-5)" "steps" "steps/s"
for name in spinning_box sliding_box spinning_die; do
  n=$steps
  # The sliding box stops after 0.68 s (68 000 steps): time its sliding only.
  [ "$name" = sliding_box ] && n=$(( steps < 60000 ? steps : 60000 ))
  duration=$(awk -v n="$n" 'BEGIN { printf "%.5f", n * 1e-5 }')
  best=""
  for _ in $(seq "$runs"); do
    "$tumble" simulate "$work/$name.toml" --duration "$duration" --out "$work/out_$name" --quiet
    t=$(tr -d ' \n' < "$work/out_$name/run.json" | grep -o '"simulate_s":[0-9.e+-]*' | cut -d: -f2)
    best=$(awk -v t="$t" -v b="${best:-inf}" 'BEGIN { print (b == "inf" || t < b) ? t : b }')
  done
  printf '%-40s %12d %12.0f\n' "$name" "$n" "$(awk -v n="$n" -v t="$best" 'BEGIN { print n / t }')"
done
echo "targets (issue 10): spinning box >= 1 000 000 steps/s (MuJoCo 2.2 RK4 100 000, Bullet 3.24 550 000)"
