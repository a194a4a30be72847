#!/usr/bin/env python3
"""Writes testdata/walk_run_legs.gltf: a pair of legs with a walk and a run, the crossfade tests' own
walking/running pair (lib/skin/crossfade_accuracy_test.cpp), so that they run without the shared models.

Usage: python3 scripts/testdata/make_walk_run.py [OUTPUT_DIR]     (default: the repository's testdata/)

The rig follows scripts/testdata/make_rigs.py's conventions (rest pose of pure dyadic translations, exact
inverse bind matrices, weights in multiples of 1/256 summing to 1, LINEAR clips from t = 0):
  * joints: pelvis at (0, 4, 0) (the root), hip_L and hip_R at x = ±0.5 below it, knee_L and knee_R 2 lower;
  * the mesh: a pelvis tube along +x at y = 4 (radius 0.3, all pelvis) and two leg tubes along +y from
    y = 0 to 4 at x = ±0.5 (radius 0.25, 12 around, a ring every 1/4): the knee's up to y = 1.5, the hip's
    from y = 2.5 (linear in between), and from y = 3.5 up the hip hands a quarter, then half, to the pelvis;
  * clips, 17 keys a cycle (every 1/16 of it), forward is +z, a positive angle about +x swings a leg back:
      walk (1 s):     hips ±25°, knees 4°..40°, the pelvis bobbing 0.04 and turning ±6° about +y;
      run (0.625 s):  hips −10° ± 45°, knees 10°..100°, the pelvis 0.2 lower, bobbing 0.12, leaning 12°
                      forward and turning ±10°.
    Both start with the left leg forward and the right back (the same phase at the same fraction of the
    cycle) but differ in amplitude, so a crossfade must bend every joint of the chain a different amount.
Deterministic (scripts/testdata/gltf_builder.py). Python 3 standard library only.
"""

import math
import os
import sys

from make_rigs import Gltf, quat_axis_angle, tube

KEYS = 17  # one cycle, first and last key equal
LEG_STATIONS = [0.25 * i for i in range(17)]  # y = 0 .. 4
PELVIS_STATIONS = [-0.75 + 0.25 * i for i in range(7)]  # x = -0.75 .. 0.75


def quat_mul(a, b):
    """Hamilton product of (x, y, z, w) quaternions: rotate by b, then by a."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return [aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz]


def leg_weights(heights, hip, knee, pelvis):
    """Per vertex (joints, weights) of one leg, as the module's docstring says; exact in 1/256."""
    joints, weights = [], []
    for y in heights:
        if y >= 3.5:
            w_pelvis = (y - 3.5)  # 0, 0.25, 0.5 at y = 3.5, 3.75, 4
            joints.append((hip, pelvis, 0, 0) if w_pelvis > 0 else (hip, 0, 0, 0))
            weights.append((1.0 - w_pelvis, w_pelvis, 0.0, 0.0))
        elif y >= 2.5:
            joints.append((hip, 0, 0, 0))
            weights.append((1.0, 0.0, 0.0, 0.0))
        elif y <= 1.5:
            joints.append((knee, 0, 0, 0))
            weights.append((1.0, 0.0, 0.0, 0.0))
        else:
            w_hip = y - 1.5  # 0.25, 0.5, 0.75
            joints.append((knee, hip, 0, 0))
            weights.append((1.0 - w_hip, w_hip, 0.0, 0.0))
    return joints, weights


def geometry():
    """The three tubes as one primitive, with their skin joints (indices into the skin's joint list:
    0 pelvis, 1 hip_L, 2 knee_L, 3 hip_R, 4 knee_R)."""
    parts = [
        (tube("x", 0.3, PELVIS_STATIONS, 12, center=(0.0, 4.0, 0.0)), None),
        (tube("y", 0.25, LEG_STATIONS, 12, center=(0.5, 0.0, 0.0)), (1, 2)),
        (tube("y", 0.25, LEG_STATIONS, 12, center=(-0.5, 0.0, 0.0)), (3, 4)),
    ]
    geo = {"positions": [], "normals": [], "indices": []}
    joints, weights = [], []
    for part, leg in parts:
        base = len(geo["positions"])
        geo["positions"] += part["positions"]
        geo["normals"] += part["normals"]
        geo["indices"] += [base + i for i in part["indices"]]
        if leg is None:
            joints += [(0, 0, 0, 0)] * len(part["positions"])
            weights += [(1.0, 0.0, 0.0, 0.0)] * len(part["positions"])
        else:
            j, w = leg_weights([p[1] for p in part["positions"]], leg[0], leg[1], 0)
            joints += j
            weights += w
    return geo, joints, weights


def clip(name, period, hip_mean, hip_swing, knee_mean, knee_swing, height, bob, lean, turn, nodes):
    """One gait cycle's channels. At key phase φ = 2πk/16: the left hip at hip_mean − hip_swing·sin φ (forward
    first), the right hip at hip_mean + hip_swing·sin φ, the knees at knee_mean ∓ knee_swing·cos φ; the pelvis
    at height + bob·cos 2φ, turned turn·sin φ about +y after leaning `lean` about +x."""
    pelvis, hip_l, knee_l, hip_r, knee_r = nodes
    times = [period * k / (KEYS - 1) for k in range(KEYS)]
    phases = [2 * math.pi * k / (KEYS - 1) for k in range(KEYS)]
    x_axis, y_axis = (1, 0, 0), (0, 1, 0)

    def about_x(degrees):
        return [tuple(quat_axis_angle(x_axis, d)) for d in degrees]

    hip_left = [hip_mean - hip_swing * math.sin(f) for f in phases]   # φ = 0..π/2: the left leg swings forward
    hip_right = [hip_mean + hip_swing * math.sin(f) for f in phases]
    knee_left = [knee_mean - knee_swing * math.cos(f) for f in phases]
    knee_right = [knee_mean + knee_swing * math.cos(f) for f in phases]
    pelvis_t = [(0.0, height + bob * math.cos(2 * f), 0.0) for f in phases]
    pelvis_r = [tuple(quat_mul(quat_axis_angle(y_axis, turn * math.sin(f)), quat_axis_angle(x_axis, lean))) for f in phases]
    return (name, [
        (pelvis, "translation", "LINEAR", times, pelvis_t),
        (pelvis, "rotation", "LINEAR", times, pelvis_r),
        (hip_l, "rotation", "LINEAR", times, about_x(hip_left)),
        (knee_l, "rotation", "LINEAR", times, about_x(knee_left)),
        (hip_r, "rotation", "LINEAR", times, about_x(hip_right)),
        (knee_r, "rotation", "LINEAR", times, about_x(knee_right)),
    ])


def walk_run_legs():
    g = Gltf()
    g.doc["asset"]["generator"] = "dqskin scripts/testdata/make_walk_run.py"
    geo, joints, weights = geometry()
    mesh = g.skinned_mesh("legs", geo, [(joints, weights)])
    g.node("legs", mesh=mesh, skin=0)
    pelvis = g.node("pelvis", translation=(0.0, 4.0, 0.0), children=[2, 4])
    hip_l = g.node("hip_L", translation=(0.5, 0.0, 0.0), children=[3])
    knee_l = g.node("knee_L", translation=(0.0, -2.0, 0.0))
    hip_r = g.node("hip_R", translation=(-0.5, 0.0, 0.0), children=[5])
    knee_r = g.node("knee_R", translation=(0.0, -2.0, 0.0))
    nodes = (pelvis, hip_l, knee_l, hip_r, knee_r)
    g.skin("legs_skin", list(nodes), [(0.0, 4.0, 0.0), (0.5, 4.0, 0.0), (0.5, 2.0, 0.0), (-0.5, 4.0, 0.0), (-0.5, 2.0, 0.0)])
    g.animation(*clip("walk", 1.0, 0.0, 25.0, 22.0, 18.0, 4.0, 0.04, 0.0, 6.0, nodes))
    g.animation(*clip("run", 0.625, -10.0, 45.0, 55.0, 45.0, 3.8, 0.12, 12.0, 10.0, nodes))
    g.scene("scene", [0, pelvis])
    return g


def main(argv):
    if len(argv) > 2 or (len(argv) == 2 and argv[1] in ("-h", "--help")):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    out = argv[1] if len(argv) == 2 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "testdata")
    os.makedirs(out, exist_ok=True)
    size = walk_run_legs().write_gltf(os.path.join(out, "walk_run_legs.gltf"))
    print("%-26s %7d bytes" % ("walk_run_legs.gltf", size))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
