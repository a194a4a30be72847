#!/usr/bin/env python3
"""Writes the many-influence rigs: vertices with more than 8 joints, as real exports carry them.

Usage: python3 scripts/testdata/make_influence_cases.py OUTPUT_DIR

  twelve_influences.gltf       a box strip over a chain of 12 joints; every vertex has 12 joints with
                               weight, in JOINTS_0..JOINTS_2 / WEIGHTS_0..WEIGHTS_2
  twenty_influences.gltf       the same over 20 joints, in JOINTS_0..JOINTS_4 (what one real export has)
  twenty_influences_top4.gltf  twenty_influences with only each vertex's 4 largest weights kept (ties to
                               the lower joint), renormalized in double and stored as float32, in that order
                               in JOINTS_0/WEIGHTS_0: what `--max-influences 4` and `lint --fix
                               --max-influences 4` make of twenty_influences, value for value
  twenty_influences_top12.gltf the same with 12 kept (JOINTS_0..JOINTS_2)

The weights fall off along the chain (a Gaussian of the distance to the joint) over a floor, so that the
small ones together carry about a third of each vertex: dropping them moves the surface by a large share
of the strip's size, which tests measure to prove that every influence is used. The joints rotate about z
in a travelling wave (and the last third about x as well), so that far joints turn more than 180° from
near ones at some frames: DQS must flip each influence to the heaviest's hemisphere.

The rigs follow scripts/testdata/make_rigs.py's conventions (rest pose of pure dyadic translations, exact inverse
bind matrices, float weights, LINEAR clips from t = 0), except that the weights are float32 values that
sum to 1 within float rounding rather than multiples of 1/256 (eight bits cannot hold 20 useful weights).
Only the Python standard library is used; the output is the same on every run.
"""

import math
import os
import sys

from gltf_builder import f32
from make_rigs import Gltf, box_strip, quat_axis_angle


def quat_mul(a, b):
    """The Hamilton product a·b of quaternions (x, y, z, w): rotation b, then a."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz)


def chain_weights(x, joint_x, spread, floor):
    """Every joint's float32 weight at x: exp(-((x - xj) / spread)²) + floor, divided by the sum."""
    raw = [math.exp(-((x - xj) / spread) ** 2) + floor for xj in joint_x]
    total = sum(raw)
    return [f32(r / total) for r in raw]


def top_weights(weights, keep):
    """The `keep` largest (joint, weight) pairs (ties to the lower joint), renormalized as the loader does:
    summed in double in that order, each divided by the sum and rounded to float32."""
    ranked = sorted(range(len(weights)), key=lambda j: (-weights[j], j))[:keep]
    total = 0.0
    for j in ranked:  # left to right, as the loader (Python's sum() may compensate)
        total += weights[j]
    return [(j, f32(weights[j] / total)) for j in ranked]


def sets_of(per_vertex):
    """Per-vertex lists of (joint, weight) as JOINTS_n/WEIGHTS_n sets of 4 (zero-weight joint 0 pads)."""
    count = (max(len(v) for v in per_vertex) + 3) // 4
    sets = []
    for s in range(count):
        joints, weights = [], []
        for v in per_vertex:
            part = v[4 * s:4 * s + 4] + [(0, 0.0)] * (4 - len(v[4 * s:4 * s + 4]))
            joints.append(tuple(j for j, _ in part))
            weights.append(tuple(w for _, w in part))
        sets.append((joints, weights))
    return sets


def chain_rig(count, keep=None):
    """A box along +x, 0.25 per joint, over a chain of `count` joints 0.25 apart; `keep`: only each
    vertex's `keep` largest weights."""
    g = Gltf()
    g.doc["asset"]["generator"] = "dqskin scripts/testdata/make_influence_cases.py"
    length = 0.25 * count
    columns = 2 * count
    geo = box_strip(length, 0.125, columns)
    joint_x = [0.25 * j for j in range(count)]
    per_vertex = []
    for station in geo["station"]:
        x = length * station / columns
        w = chain_weights(x, joint_x, 0.6, 0.02)
        per_vertex.append(top_weights(w, keep) if keep else list(enumerate(w)))
    mesh = g.skinned_mesh("strip", geo, sets_of(per_vertex))
    g.node("strip", mesh=mesh, skin=0)
    chain = []
    for j in range(count):
        chain.append(g.node("bone%d" % j, translation=None if j == 0 else (0.25, 0.0, 0.0),
                            children=[2 + j] if j + 1 < count else None))
    g.skin("chain_skin", chain, [(x, 0.0, 0.0) for x in joint_x])
    times = [0.125 * i for i in range(9)]
    channels = []
    for j in range(count):
        keys = []
        for t in times:
            q = quat_axis_angle((0, 0, 1), 16.0 * math.sin(2 * math.pi * (t - j / count)))
            if 3 * j >= 2 * count:
                q = quat_mul(q, quat_axis_angle((1, 0, 0), 40.0 * math.sin(math.pi * t)))
            keys.append(tuple(q))
        channels.append((chain[j], "rotation", "LINEAR", times, keys))
    g.animation("wave", channels)
    g.scene("scene", [0, chain[0]])
    return g


CASES = {
    "twelve_influences.gltf": lambda: chain_rig(12),
    "twenty_influences.gltf": lambda: chain_rig(20),
    "twenty_influences_top4.gltf": lambda: chain_rig(20, keep=4),
    "twenty_influences_top12.gltf": lambda: chain_rig(20, keep=12),
}


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    os.makedirs(argv[1], exist_ok=True)
    for name, make in CASES.items():
        size = make().write_gltf(os.path.join(argv[1], name))
        print("%-28s %7d bytes" % (name, size))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
