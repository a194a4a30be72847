#!/usr/bin/env python3
"""Writes testdata/socket_prop.gltf: a walking arm that holds a rigid prop, for --sockets and --root-motion.

Usage: python3 scripts/testdata/make_socket_rig.py [OUTPUT_DIR]     (default: the repository's testdata/)

The rig follows make_rigs.py's conventions (it reuses its parts): an arm along +x (tube, radius 0.4, x = 0
to 4) skinned to two joints, "body" at the origin and "hand" at x = 2, blended for 1.5 < x < 2.5; the
skinned mesh node is a root without a transform. The prop, "sword", is a box mesh that is not skinned: a
child node of "hand", placed by its own translation and rotation, so that its world transform is hand's
times its own at every frame. The clip "walk" (2 s, LINEAR, keys every 1/4 s) moves "body" along a curve on
the ground while it bobs up and down, turns it 120° about +Y and tilts it about its x axis (so that the
heading is not a rotation about +Y alone), and swings "hand" about z. Deterministic, byte for byte.
"""

import math
import os
import sys

from gltf_builder import ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER, UNSIGNED_SHORT, f32
from make_rigs import Gltf, quat_axis_angle, tube, two_joint_weights


def quat_mul(a, b):
    """The Hamilton product a · b of (x, y, z, w) quaternions: the rotation b, then a."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return [aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz]


def box(half):
    """A closed box centred on the origin with half-sizes `half`, 24 vertices (flat normals per face)."""
    positions, normals, indices = [], [], []
    for axis in range(3):
        for sign in (1.0, -1.0):
            u, v = (axis + 1) % 3, (axis + 2) % 3
            n = [0.0, 0.0, 0.0]
            n[axis] = sign
            base = len(positions)
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = sign * half[axis]
                p[u] = a * half[u]
                p[v] = b * half[v]
                positions.append(tuple(p))
                normals.append(tuple(n))
            quad = [(base, base + 1, base + 2), (base, base + 2, base + 3)]
            for tri in quad:
                indices.extend(tri if sign > 0 else (tri[0], tri[2], tri[1]))
    return positions, normals, indices


def socket_prop():
    g = Gltf()
    stations = [4.0 * i / 16 for i in range(17)]
    geo = tube("x", 0.4, stations, 16)
    joints, weights = two_joint_weights(stations, geo["station"], 1.5, 2.5)
    arm = g.skinned_mesh("arm", geo, [(joints, weights)])
    g.node("arm", mesh=arm, skin=0)                      # 0
    body = g.node("body", children=[2])                  # 1
    hand = g.node("hand", translation=(2.0, 0.0, 0.0), children=[3])  # 2
    positions, normals, indices = box((1.0, 0.0625, 0.125))
    sword_mesh = g.add("meshes", {"name": "sword", "primitives": [{
        "attributes": {
            "POSITION": g.accessor(positions, "VEC3", target=ARRAY_BUFFER, with_bounds=True),
            "NORMAL": g.accessor(normals, "VEC3", target=ARRAY_BUFFER),
        },
        "indices": g.accessor(indices, "SCALAR", UNSIGNED_SHORT, target=ELEMENT_ARRAY_BUFFER),
        "mode": 4,
    }]})
    g.node("sword", translation=(2.5, 0.25, 0.0), rotation=quat_axis_angle((1, 0, 0), 30.0), mesh=sword_mesh)  # 3
    g.skin("arm_skin", [body, hand], [(0.0, 0.0, 0.0), (2.0, 0.0, 0.0)])

    times = [0.25 * i for i in range(9)]  # 0 .. 2 s
    translation, rotation, swing = [], [], []
    for t in times:
        translation.append((1.5 * t, 0.125 * math.sin(2 * math.pi * t), 0.5 * t * t))
        heading = quat_axis_angle((0, 1, 0), 60.0 * t)
        tilt = quat_axis_angle((1, 0, 0), 10.0 * math.sin(math.pi * t))
        rotation.append(tuple(quat_mul(heading, tilt)))
        swing.append(tuple(quat_axis_angle((0, 0, 1), 45.0 * math.sin(math.pi * t))))
    g.animation("walk", [
        (body, "translation", "LINEAR", times, [tuple(f32(x) for x in v) for v in translation]),
        (body, "rotation", "LINEAR", times, rotation),
        (hand, "rotation", "LINEAR", times, swing),
    ])
    g.scene("scene", [0, body])
    return g


def main(argv):
    if len(argv) > 2 or (len(argv) == 2 and argv[1] in ("-h", "--help")):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    out = argv[1] if len(argv) == 2 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "testdata")
    os.makedirs(out, exist_ok=True)
    size = socket_prop().write_gltf(os.path.join(out, "socket_prop.gltf"))
    print("%-26s %7d bytes" % ("socket_prop.gltf", size))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
