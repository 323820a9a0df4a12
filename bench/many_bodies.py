#!/usr/bin/env python3
# Many-body benchmark scenes of issue 21, written as a tumble scene (TOML) on stdout, y up:
#   pyramid N      1 m cubes (1 kg) in N rows, row r = 0..N-1 holding N - r boxes exactly touching
#   pyramid_hit N  the pyramid and a 50 kg ball (r = 0.5 m) thrown at it at 10 m/s
#   dice K         K dice of 0.2 m (density 1000) on an n^3 lattice (n^3 >= K), 0.3 m apart,
#                  each tilted and spinning, dropped onto the floor
# Friction 0.5 and restitution 0 everywhere; rk4, dt = 0.002, 10 s (pyramid_hit: 5 s).
# --float: no gravity, and the bodies pass through each other (collisions = "floor"): the dice
# spin where they were put and never reach the floor, a rendering load whose simulation is cheap
# (bench/many_bodies_render.sh).
#   bench/many_bodies.py pyramid 20 [--duration S] [--dt S] [--float] > scene.toml
# Same arguments, same bytes: floats print with repr (shortest form that reads back exactly).
import argparse
import math
import sys

FRICTION = 0.5
RESTITUTION = 0.0


def f(x):
    """A float as TOML: repr, never an integer literal, never -0."""
    x = float(x) + 0.0
    return repr(x)


def vec(v):
    return "[" + ", ".join(f(c) for c in v) + "]"


def header(kind, count, duration, dt, floating=False):
    lines = [
        f"# bench/many_bodies.py {kind} {count}{' --float' if floating else ''} (issue 21)",
        "",
        "[simulation]",
        f"duration = {f(duration)}",
        f"dt = {f(dt)}",
        'integrator = "rk4"',
    ]
    if floating:
        lines += ["gravity = [0.0, 0.0, 0.0]", 'collisions = "floor"']
    return lines + [
        "",
        "[floor]",
        f"restitution = {f(RESTITUTION)}",
        f"friction = {f(FRICTION)}",
    ]


def body(name, shape_keys, position, orientation=None, velocity=None, angular_velocity=None):
    lines = ["", "[[body]]", f'name = "{name}"']
    lines += shape_keys
    lines.append(f"position = {vec(position)}")
    if orientation is not None:
        axis, degrees = orientation
        lines.append(f"orientation = {{ axis = {vec(axis)}, degrees = {f(degrees)} }}")
    if velocity is not None:
        lines.append(f"velocity = {vec(velocity)}")
    if angular_velocity is not None:
        lines.append(f"angular_velocity = {vec(angular_velocity)}")
    lines.append(f"friction = {f(FRICTION)}")
    lines.append(f"restitution = {f(RESTITUTION)}")
    return lines


def pyramid(n):
    cube = ['shape = "box"', "size = [1.0, 1.0, 1.0]", "mass = 1.0"]
    lines = []
    for r in range(n):
        row = n - r
        for i in range(row):
            x = i - (row - 1) / 2
            lines += body(f"box_{r}_{i}", cube, (x, 0.5 + r, 0.0))
    return lines


def pyramid_hit(n):
    # N/2 as real division (the formula); for even N it is the row index N/2 exactly.
    half = n / 2
    ball = ['shape = "sphere"', "radius = 0.5", "mass = 50.0"]
    return pyramid(n) + body(
        "ball", ball, (-(n - half) / 2 - 3, 0.5 + half, 0.0), velocity=(10.0, 0.0, 0.0)
    )


def dice(k_count):
    n = 1
    while n ** 3 < k_count:
        n += 1
    die = ['shape = "box"', "size = [0.2, 0.2, 0.2]", "density = 1000.0"]
    lines = []
    for k in range(k_count):
        i = k % n
        j = (k // n) % n
        l = k // (n * n)
        centre = (0.3 * (i - (n - 1) / 2), 0.5 + 0.3 * l, -0.3 * (j - (n - 1) / 2))
        theta = 0.1 + 0.06 * (k % 6)
        phi = 2.4 * k
        axis = (math.cos(phi), 0.0, -math.sin(phi))
        m = k + 1
        omega = (3 * math.sin(m), 3 * math.sin(3 * m), -3 * math.sin(2 * m))
        lines += body(f"die{k}", die, centre, orientation=(axis, math.degrees(theta)),
                      angular_velocity=omega)
    return lines


SCENES = {"pyramid": (pyramid, 10.0), "pyramid_hit": (pyramid_hit, 5.0), "dice": (dice, 10.0)}


def main():
    p = argparse.ArgumentParser(description="Write an issue-21 many-body scene (TOML) to stdout.")
    p.add_argument("kind", choices=sorted(SCENES))
    p.add_argument("count", type=int, help="pyramid rows N, or number of dice K")
    p.add_argument("--duration", type=float, help="simulated seconds (default 10, pyramid_hit 5)")
    p.add_argument("--dt", type=float, default=0.002, help="physics step (default 0.002)")
    p.add_argument("--float", action="store_true", dest="floating",
                   help="no gravity, bodies pass through each other (a cheap rendering load)")
    a = p.parse_args()
    if a.count < 1:
        p.error("count must be at least 1")
    make, default_duration = SCENES[a.kind]
    duration = default_duration if a.duration is None else a.duration
    if not (duration > 0 and math.isfinite(duration)) or not (a.dt > 0 and math.isfinite(a.dt)):
        p.error("--duration and --dt must be positive")
    lines = header(a.kind, a.count, duration, a.dt, a.floating) + make(a.count)
    sys.stdout.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
