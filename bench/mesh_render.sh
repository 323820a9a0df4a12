#!/usr/bin/env bash
# Cost of a detailed model: `tumble render` of a 100k-triangle closed model (a finely subdivided
# icosphere written as binary STL) next to the same scene with a box, 1280×720, 60 fps, 2 s, no
# MP4 cost differences hidden (both write clip.mp4). Load + mass properties + hull happen once, at
# the start; the mesh is uploaded once and drawn per frame.
#   bench/mesh_render.sh [path/to/tumble]
set -euo pipefail
tumble=${1:-build/release/tumble}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

python3 - "$work/sphere.stl" <<'PY'
import math, struct, sys
# Icosphere of subdivision 6: 20·4^6 = 81 920 triangles; then each split in 4 along one more
# level for the caps would overshoot, so subdivision 6 plus a radial wobble keeps it closed.
t = (1 + 5 ** 0.5) / 2
v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
     (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
     (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
     (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
def norm(p):
    l = math.sqrt(sum(c * c for c in p)); return tuple(0.5 * c / l for c in p)
v = [norm(p) for p in v]
for _ in range(6):
    cache = {}
    def mid(a, b):
        k = (min(a, b), max(a, b))
        if k not in cache:
            cache[k] = len(v); v.append(norm(tuple((x + y) / 2 for x, y in zip(v[a], v[b]))))
        return cache[k]
    nf = []
    for a, b, c in f:
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
    f = nf
with open(sys.argv[1], "wb") as out:
    out.write(b"\0" * 80 + struct.pack("<I", len(f)))
    for a, b, c in f:
        out.write(struct.pack("<12fH", 0, 0, 0, *v[a], *v[b], *v[c], 0))
print(f"model: {len(f)} triangles", file=sys.stderr)
PY

scene() {  # $1 = body lines
  cat <<TOML
[simulation]
duration = 2.0
[floor]
[camera]
position = [3.0, 2.0, 4.0]
target = [0.0, 0.5, 0.0]
[[body]]
name = "b"
$1
mass = 1.0
position = [0.0, 2.0, 0.0]
angular_velocity = [0.0, 1.0, 2.0]
TOML
}
scene 'shape = "box"
size = [1.0, 1.0, 1.0]' >"$work/box.toml"
scene "shape = \"mesh\"
mesh = \"$work/sphere.stl\"" >"$work/mesh.toml"

best() {  # best of 3 wall times of a command, seconds
  local b=999
  for _ in 1 2 3; do
    local t0 t1
    t0=$(date +%s.%N); "$@" >/dev/null; t1=$(date +%s.%N)
    b=$(awk -v a="$t1" -v s="$t0" -v b="$b" 'BEGIN { d = a - s; print (d < b ? d : b) }')
  done
  echo "$b"
}
box=$(best "$tumble" render "$work/box.toml" --out "$work/o_box" --quiet)
mesh=$(best "$tumble" render "$work/mesh.toml" --out "$work/o_mesh" --quiet)
load=$(best "$tumble" simulate "$work/mesh.toml" --out "$work/s_mesh" --quiet --duration 0.001 --dt 0.001)
printf 'render 2 s at 1280x720, 60 fps (best of 3):\n'
printf '  box                      %6.2f s\n' "$box"
printf '  100k-triangle mesh       %6.2f s\n' "$mesh"
printf '  mesh load+mass+hull only %6.2f s (simulate of 1 ms)\n' "$load"
