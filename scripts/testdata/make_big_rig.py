#!/usr/bin/env python3
"""Writes a large synthetic skinned character as one glTF 2.0 binary (.glb), for benchmarks.

Usage: python3 scripts/testdata/make_big_rig.py OUT.glb [--vertices N] [--joints J] [--seconds S]
       (defaults: 1000000 vertices, 64 joints, 4 seconds)

The character is one long open tube along +y, skinned to a chain of J joints, with one LINEAR clip of S
seconds that bends and twists the chain (each joint turns about an axis that sweeps around the chain).
Python 3 standard library only (and scripts/testdata/gltf_builder.py); about a million vertices take a few seconds.

The output is deterministic: the same bytes on every run (sorted JSON keys, every float rounded to float32
before it is written or bounded, no timestamps). It follows the conventions of scripts/testdata/make_rigs.py:
  * every joint's rest pose is a pure translation by dyadic numbers and its inverse bind matrix is the
    exact inverse of its rest world matrix (at the rest pose every joint matrix is the identity);
  * the skinned mesh node is a root node without a transform, its skin lists every joint;
  * each vertex has 4 influences on distinct joints (fewer when J < 4; unused slots hold joint 0 with
    weight 0), weights are positive multiples of 1/4096 summing to exactly 1;
  * POSITION has min/max; indices are UNSIGNED_INT; JOINTS_0 is UNSIGNED_BYTE (UNSIGNED_SHORT past 256
    joints).
The tube has a seam: the first and last vertex of every ring coincide, with texture u = 0 and u = 1.
"""

import argparse
import math
import sys
import time
from array import array

from gltf_builder import (ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER, FLOAT, UNSIGNED_BYTE, UNSIGNED_INT, UNSIGNED_SHORT,
                          Builder, f32)

SEGMENT = 0.25  # rest length of every bone (dyadic: joint positions are exact in float32)
RADIUS = 0.375  # tube radius
KEYS_PER_SECOND = 10
WEIGHT_UNITS = 4096  # weights are multiples of 1/WEIGHT_UNITS


def snap(x):
    """Removes the rounding noise of trigonometry at exact angles (cos 90° = 6e-17 becomes 0)."""
    return 0.0 if abs(x) < 1e-12 else x


def tube_layout(vertices):
    """(around, rings): vertices around a ring (before the seam copy) and rings along the tube, so that
    rings · (around + 1) is about `vertices`."""
    around = max(8, min(256, int(round(math.sqrt(vertices / 16.0)))))
    rings = max(2, int(round(vertices / (around + 1))))
    return around, rings


def ring_influences(c, joints):
    """The 4 (or fewer) joints nearest to c (a position along the chain in bone units, bone j centred
    on c = j) and their weights: a Gaussian falloff, renormalized and quantized to positive multiples
    of 1/WEIGHT_UNITS summing to exactly 1. Always 4 slots; unused ones hold joint 0, weight 0."""
    count = min(4, joints)
    start = min(max(int(math.floor(c)) - 1, 0), joints - count)
    chosen = list(range(start, start + count))
    raw = [math.exp(-(((c - j) / 0.9) ** 2)) for j in chosen]
    total = sum(raw)
    units = [max(1, int(round(w / total * WEIGHT_UNITS))) for w in raw]
    largest = units.index(max(units))
    units[largest] += WEIGHT_UNITS - sum(units)
    assert all(u > 0 for u in units) and sum(units) == WEIGHT_UNITS
    weights = [u / WEIGHT_UNITS for u in units]
    while len(chosen) < 4:
        chosen.append(0)
        weights.append(0.0)
    return chosen, weights


def quat_axis_angle(axis, radians):
    length = math.sqrt(sum(a * a for a in axis))
    s = math.sin(radians / 2) / length
    return [axis[0] * s, axis[1] * s, axis[2] * s, math.cos(radians / 2)]


def build(vertices, joints, seconds):
    around, rings = tube_layout(vertices)
    columns = around + 1  # the seam column repeats the first one, with u = 1
    length = joints * SEGMENT
    g = Builder("dqskin scripts/testdata/make_big_rig.py")

    # Ring templates: xz and normals of one ring; y and v per ring.
    ring_xyz, ring_normal, ring_u = array("f"), array("f"), array("f")
    for k in range(columns):
        angle = 2 * math.pi * (k % around) / around
        c, d = snap(math.cos(angle)), snap(math.sin(angle))
        ring_xyz.extend((RADIUS * c, 0.0, RADIUS * d))
        ring_normal.extend((c, 0.0, d))
        ring_u.extend((k / around, 0.0))

    positions, texcoords = array("f"), array("f")
    joint_code = "B" if joints <= 256 else "H"
    joint_data, weight_data = array(joint_code), array("f")
    for s in range(rings):
        y = length * s / (rings - 1)
        ring = array("f", ring_xyz)
        ring[1::3] = array("f", [y]) * columns
        positions += ring
        uv = array("f", ring_u)
        uv[1::2] = array("f", [1.0 - s / (rings - 1)]) * columns  # v down the texture, glTF convention
        texcoords += uv
        chosen, weights = ring_influences(y / SEGMENT - 0.5, joints)
        joint_data += array(joint_code, chosen) * columns
        weight_data += array("f", weights) * columns
    normals = ring_normal * rings

    # Two triangles per quad, counter-clockwise seen from outside: (a0, b0, a1) and (a1, b0, b1) where b
    # is the next ring up (+y) and 1 the next column (angle increasing from +x towards +z).
    pattern = []
    for k in range(around):
        a0, a1, b0, b1 = k, k + 1, k + columns, k + 1 + columns
        pattern.extend((a0, b0, a1, a1, b0, b1))
    indices = array("I")
    for s in range(rings - 1):
        base = s * columns
        indices.extend([i + base for i in pattern])

    g.doc["materials"] = [
        {
            "name": "skin",
            "pbrMetallicRoughness": {
                "baseColorFactor": [f32(0.8), f32(0.45), f32(0.3), 1.0],
                "metallicFactor": 0.0,
                "roughnessFactor": f32(0.6),
            },
        }
    ]
    attributes = {
        "POSITION": g.accessor(positions, "VEC3", FLOAT, ARRAY_BUFFER, with_bounds=True),
        "NORMAL": g.accessor(normals, "VEC3", FLOAT, ARRAY_BUFFER),
        "TEXCOORD_0": g.accessor(texcoords, "VEC2", FLOAT, ARRAY_BUFFER),
        "JOINTS_0": g.accessor(joint_data, "VEC4", UNSIGNED_BYTE if joint_code == "B" else UNSIGNED_SHORT, ARRAY_BUFFER),
        "WEIGHTS_0": g.accessor(weight_data, "VEC4", FLOAT, ARRAY_BUFFER),
    }
    primitive = {
        "attributes": attributes,
        "indices": g.accessor(indices, "SCALAR", UNSIGNED_INT, ELEMENT_ARRAY_BUFFER),
        "material": 0,
        "mode": 4,
    }
    g.doc["meshes"] = [{"name": "tube", "primitives": [primitive]}]

    # The chain: joint 0 at the origin, each next one SEGMENT further up +y.
    nodes = []
    for j in range(joints):
        node = {"name": "joint_%03d" % j}
        if j > 0:
            node["translation"] = [0.0, SEGMENT, 0.0]
        if j + 1 < joints:
            node["children"] = [j + 1]
        nodes.append(node)
    nodes.append({"name": "character", "mesh": 0, "skin": 0})
    g.doc["nodes"] = nodes
    g.doc["scenes"] = [{"name": "big_rig", "nodes": [0, joints]}]
    g.doc["scene"] = 0

    ibm = array("f")
    for j in range(joints):  # column-major: translation by minus the rest world position (0, j·SEGMENT, 0)
        ibm.extend((1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -j * SEGMENT, 0, 1))
    g.doc["skins"] = [
        {
            "name": "chain",
            "joints": list(range(joints)),
            "skeleton": 0,
            "inverseBindMatrices": g.accessor(ibm, "MAT4", FLOAT),
        }
    ]

    # The clip: every joint turns about an axis that sweeps around the chain (with a twist component
    # along it) by an angle that travels along the chain as a wave; it loops (last key = first key).
    keys = max(1, int(round(seconds * KEYS_PER_SECOND)))
    times = array("f", [seconds * k / keys for k in range(keys + 1)])
    amplitude = math.radians(max(2.0, min(25.0, 480.0 / joints)))
    time_accessor = g.accessor(times, "SCALAR", FLOAT, with_bounds=True)
    samplers, channels = [], []
    for j in range(joints):
        rotations = array("f")
        for k in range(keys + 1):
            phase = 2 * math.pi * k / keys
            sweep = 0.5 * j + phase
            axis = (math.cos(sweep), 0.35 + 0.25 * math.sin(0.7 * j - phase), math.sin(sweep))
            rotations.extend(quat_axis_angle(axis, amplitude * math.sin(phase + 0.35 * j)))
        samplers.append({"input": time_accessor, "interpolation": "LINEAR",
                         "output": g.accessor(rotations, "VEC4", FLOAT)})
        channels.append({"sampler": j, "target": {"node": j, "path": "rotation"}})
    g.doc["animations"] = [{"name": "bend_twist", "channels": channels, "samplers": samplers}]

    stats = {"vertices": rings * columns, "triangles": len(indices) // 3, "around": around, "rings": rings}
    return g, stats


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out", metavar="OUT.glb")
    parser.add_argument("--vertices", type=int, default=1000000, help="about how many vertices (default 1000000)")
    parser.add_argument("--joints", type=int, default=64, help="joints in the chain (default 64)")
    parser.add_argument("--seconds", type=float, default=4.0, help="length of the clip (default 4)")
    args = parser.parse_args(argv)
    if args.vertices < 18:
        parser.error("--vertices must be at least 18")
    if not 1 <= args.joints <= 65535:
        parser.error("--joints must be 1 to 65535")
    if not (args.seconds > 0 and math.isfinite(args.seconds)):
        parser.error("--seconds must be positive")
    start = time.monotonic()
    g, stats = build(args.vertices, args.joints, args.seconds)
    size = g.write_glb(args.out)
    print(
        "%s: %d vertices (%d rings of %d+1), %d triangles, %d joints, %g s clip, %.1f MB in %.1f s"
        % (args.out, stats["vertices"], stats["rings"], stats["around"], stats["triangles"], args.joints,
           args.seconds, size / 1e6, time.monotonic() - start),
        file=sys.stderr,
    )
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
