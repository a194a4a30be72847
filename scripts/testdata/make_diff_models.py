#!/usr/bin/env python3
"""Writes the characters of the geometric diff's real-export tests (app/tests/geometry_diff_exports.cmake):
shapes that real files have and that the diff must compare by what they draw.

Usage:
  make_diff_models.py crumpled OUT    the character whose rest pose crumples the mesh
  make_diff_models.py unused OUT [--without]
                                      the character with vertices that no triangle uses (--without: the
                                      same character without them, what gltfpack makes of it)
  make_diff_models.py flat OUT [--normals split|none]
                                      the character flat shaded: every triangle its own three vertices
                                      with its face normal (split), or shared vertices without NORMAL,
                                      which glTF 2.0 §3.7.2.1 says a viewer draws with flat normals (none)
  make_diff_models.py all DIR         all of them into DIR: crumpled.glb, unused.glb, unused_without.glb,
                                      flat.glb and flat_no_normals.glb

OUT is a .glb or a .gltf (buffer embedded). The character: a tube along +y (radius 0.3, y = 0 .. 4, a ring
of 16 vertices every 1/8) on a chain of four joints at y = 0, 1, 2, 3; a vertex at height y follows joint
k with weight 1 − |y − k| (a hat; above y = 3 all joint 3), so every ring between joints blends two. Its
clip "wave" bends each joint about z by up to 20°, keyed every 0.5 s over 2 s (on the 30 Hz grid gltfpack resamples to). The inverse bind matrices
invert the joints' bind world matrices (translations by y = k).

  crumpled  the joints' nodes carry no transform: without the clip all four stand at the origin, each
            ring is moved down by its blend of bind heights and the tube folds into a unit-high crumple.
            The clip keys every joint's translation (0, 1, 0), as exporters that write the pose only in the
            animation do, so every frame of the clip is well posed.
  unused    after the tube's vertices, a second tube of the same shape 0.5 farther along +x, skinned like
            the first and used by no triangle (4,321 of an avatar's 9,986 vertices were such, dropped by
            gltfpack). --without leaves them out.
  flat      see above; the tube's positions, skin and clip are unchanged.

Deterministic (scripts/testdata/gltf_builder.py). Python 3 standard library only.
"""

import argparse
import math
import os
import sys

from gltf_builder import ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER, UNSIGNED_BYTE, UNSIGNED_SHORT
from make_rigs import Gltf, orient, quat_axis_angle, tube

JOINT_HEIGHTS = [0.0, 1.0, 2.0, 3.0]
STATIONS = [4.0 * i / 32 for i in range(33)]  # y = 0 .. 4 in steps of 1/8
AROUND = 16
RADIUS = 0.3
KEY_TIMES = [0.5 * i for i in range(5)]  # 0 .. 2 s, on the 30 Hz grid that gltfpack resamples to


def hat_weights(heights):
    """Per vertex (joints, weights): joint k with 1 − |y − k|, all of joint 3 above it (exact in 1/8)."""
    joints, weights = [], []
    for y in heights:
        if y >= JOINT_HEIGHTS[-1]:
            joints.append((3, 0, 0, 0))
            weights.append((1.0, 0.0, 0.0, 0.0))
            continue
        k = int(math.floor(y))
        w1 = y - k
        if w1 == 0.0:
            joints.append((k, 0, 0, 0))
            weights.append((1.0, 0.0, 0.0, 0.0))
        else:
            joints.append((k, k + 1, 0, 0))
            weights.append((1.0 - w1, w1, 0.0, 0.0))
    return joints, weights


def face_normal(a, b, c):
    e1 = [b[i] - a[i] for i in range(3)]
    e2 = [c[i] - a[i] for i in range(3)]
    n = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
    length = math.sqrt(sum(x * x for x in n))
    return tuple(x / length for x in n)


def flat_shaded(geo):
    """Every triangle of `geo` with three vertices of its own, each with the face normal."""
    positions, normals, heights, indices = [], [], [], []
    p = geo["positions"]
    for t in range(0, len(geo["indices"]), 3):
        tri = geo["indices"][t:t + 3]
        n = face_normal(*(p[i] for i in tri))
        for i in tri:
            indices.append(len(positions))
            positions.append(p[i])
            normals.append(n)
            heights.append(p[i][1])
    return {"positions": positions, "normals": normals, "indices": indices, "heights": heights}


def body_geometry(kind, without, normals):
    """The character's surface: positions, normals (None: no NORMAL), heights (for the weights), indices."""
    geo = tube("y", RADIUS, STATIONS, AROUND)
    geo["indices"] = [i for tri in zip(*[iter(geo["indices"])] * 3) for i in orient(tri, geo["positions"], geo["normals"])]
    geo["heights"] = [p[1] for p in geo["positions"]]
    if kind == "unused" and not without:
        # The second tube's vertices follow the first's in the same accessors; no index names them.
        geo["positions"] = geo["positions"] + [(x + 0.5, y, z) for x, y, z in geo["positions"]]
        geo["normals"] = geo["normals"] + geo["normals"]
        geo["heights"] = geo["heights"] + geo["heights"]
    if kind == "flat":
        if normals == "split":
            geo = flat_shaded(geo)
        else:  # shared vertices without NORMAL: the viewer flat shades them
            geo["normals"] = None
    return geo


def character(kind, without=False, normals="split"):
    g = Gltf()
    geo = body_geometry(kind, without, normals)
    joints, weights = hat_weights(geo["heights"])
    attributes = {"POSITION": g.accessor(geo["positions"], "VEC3", target=ARRAY_BUFFER, with_bounds=True)}
    if geo["normals"] is not None:
        attributes["NORMAL"] = g.accessor(geo["normals"], "VEC3", target=ARRAY_BUFFER)
    attributes["JOINTS_0"] = g.accessor(joints, "VEC4", UNSIGNED_BYTE, target=ARRAY_BUFFER)
    attributes["WEIGHTS_0"] = g.accessor(weights, "VEC4", target=ARRAY_BUFFER)
    primitive = {"attributes": attributes, "mode": 4,
                 "indices": g.accessor(geo["indices"], "SCALAR", UNSIGNED_SHORT, target=ELEMENT_ARRAY_BUFFER)}
    mesh = g.add("meshes", {"name": "body", "primitives": [primitive]})
    g.node("body", mesh=mesh, skin=0)

    # Nodes 1..4: the joint chain. Crumpled: no transforms on the nodes, the clip carries them.
    crumpled = kind == "crumpled"
    chain = []
    for k in range(len(JOINT_HEIGHTS)):
        child = [2 + k] if k + 1 < len(JOINT_HEIGHTS) else None
        translation = None if crumpled or k == 0 else (0.0, 1.0, 0.0)
        chain.append(g.node("joint%d" % k, translation=translation, children=child))
    g.skin("body_skin", chain, [(0.0, h, 0.0) for h in JOINT_HEIGHTS])
    channels = []
    for k, node in enumerate(chain):
        amplitude = 20.0 * (1 if k % 2 == 0 else -1)
        keys = [tuple(quat_axis_angle((0, 0, 1), amplitude * math.sin(math.pi * t))) for t in KEY_TIMES]
        channels.append((node, "rotation", "LINEAR", KEY_TIMES, keys))
        if crumpled and k > 0:
            channels.append((node, "translation", "LINEAR", [0.0, 2.0], [(0.0, 1.0, 0.0), (0.0, 1.0, 0.0)]))
    g.animation("wave", channels)
    g.scene("scene", [0, chain[0]])
    return g


# What `all DIR` writes: file name, then character()'s arguments.
MODELS = [
    ("crumpled.glb", ("crumpled",)),
    ("unused.glb", ("unused",)),
    ("unused_without.glb", ("unused", True)),
    ("flat.glb", ("flat", False, "split")),
    ("flat_no_normals.glb", ("flat", False, "none")),
]


def write(g, path):
    if os.path.splitext(path)[1].lower() == ".glb":
        g.write_glb(path)
    else:
        g.write_gltf(path)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    commands = parser.add_subparsers(dest="command", required=True)
    commands.add_parser("crumpled").add_argument("out")
    unused = commands.add_parser("unused")
    unused.add_argument("out")
    unused.add_argument("--without", action="store_true")
    flat = commands.add_parser("flat")
    flat.add_argument("out")
    flat.add_argument("--normals", choices=("split", "none"), default="split")
    commands.add_parser("all").add_argument("dir")
    args = parser.parse_args(argv[1:])
    if args.command == "all":
        os.makedirs(args.dir, exist_ok=True)
        for name, arguments in MODELS:
            write(character(*arguments), os.path.join(args.dir, name))
        return 0
    write(character(args.command, without=getattr(args, "without", False), normals=getattr(args, "normals", "split")),
          args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
