#!/usr/bin/env python3
"""Writes the catalogue of bad skins that `dqskin lint` is tested on: one problem per file, plus a clean one.

Usage: python3 scripts/testdata/make_bad_skins.py [OUTPUT_DIR]     (default: the repository's testdata/bad_skins/)

Every file is the same small rig with one thing broken, so that each lint check can be seen to find its
problem and nothing else: a strip of quads along +x (x = 0 … 4.5, y = 0 and 1; vertex 2c + row sits at
column c), a chain of ten joints at x = 0, 0.5, … 4.5 (each a child of the previous, rest pose a pure
translation, inverse bind matrices their exact inverses), every vertex of column c bound with weight 1 to
joint c, and a clip `bend` turning joint 1 about z (LINEAR, keys at 0, 0.5, 1 s: 0°, 20°, 40°). The output
is deterministic (scripts/testdata/gltf_builder.py writes the container). The list of files and the check each one
shows is CATALOGUE below and in testdata/README.md; app/tests/lint.cmake reads the same list.
"""

import math
import os
import sys

from gltf_builder import (ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER, FLOAT, UNSIGNED_BYTE, UNSIGNED_SHORT, Builder,
                          f32)

COLUMNS = 10  # joints and columns of vertices
STEP = 0.5


def quat_z(degrees):
    half = math.radians(degrees) / 2
    return [0.0, 0.0, math.sin(half), math.cos(half)]


class Rig:
    """The rig's parts as plain lists, edited by each case before build() writes them."""

    def __init__(self):
        self.vertices = 2 * COLUMNS
        # Influence sets: per set, per vertex, (joints 4-tuple, weights 4-tuple).
        self.sets = [[([v // 2, 0, 0, 0], [1.0, 0.0, 0.0, 0.0]) for v in range(self.vertices)]]
        self.weight_type = FLOAT
        self.joint_parent = [i - 1 for i in range(COLUMNS)]  # -1: a root
        self.joint_translation = [[0.0 if i == 0 else STEP, 0.0, 0.0] for i in range(COLUMNS)]
        self.joint_scale = [None] * COLUMNS
        self.extra_joints = []  # (name, parent joint or -1, translation): appended to the skin
        self.ibm_offsets = {}  # joint -> added to its inverse bind matrix's translation
        self.skeleton = None
        self.rotation_keys = [quat_z(0), quat_z(20), quat_z(40)]
        self.scale_keys = None  # (joint, [scale at 0, 0.5, 1 s])
        self.cubic = False  # CUBICSPLINE rotation keys, each tangent a tenth of its key (so a sign shows)

    def rest_world(self, parent, translation, scale):
        """World translation and scale of a joint from its parent's (no rotations at rest)."""
        pt, ps = parent
        return ([pt[i] + ps[i] * translation[i] for i in range(3)], [ps[i] * (scale or [1, 1, 1])[i] for i in range(3)])

    def build(self):
        g = Builder("dqskin scripts/testdata/make_bad_skins.py", indent=1)
        g.doc["scene"] = 0
        positions = [(STEP * (v // 2), float(v % 2), 0.0) for v in range(self.vertices)]
        normals = [(0.0, 0.0, 1.0)] * self.vertices
        indices = []
        for c in range(COLUMNS - 1):
            a, b = 2 * c, 2 * c + 2
            indices += [a, b, a + 1, a + 1, b, b + 1]
        attributes = {
            "POSITION": g.accessor(positions, "VEC3", target=ARRAY_BUFFER, with_bounds=True),
            "NORMAL": g.accessor(normals, "VEC3", target=ARRAY_BUFFER),
        }
        scale = {FLOAT: 1, UNSIGNED_BYTE: 255, UNSIGNED_SHORT: 65535}[self.weight_type]
        for n, influence in enumerate(self.sets):
            joints = [j for j, _ in influence]
            weights = [[w * scale if self.weight_type == FLOAT else round(w * scale) for w in ws] for _, ws in influence]
            attributes["JOINTS_%d" % n] = g.accessor(joints, "VEC4", UNSIGNED_BYTE, target=ARRAY_BUFFER)
            attributes["WEIGHTS_%d" % n] = g.accessor(weights, "VEC4", self.weight_type, target=ARRAY_BUFFER,
                                                      normalized=self.weight_type != FLOAT)
        mesh = g.add("meshes", {"name": "strip", "primitives": [{
            "attributes": attributes,
            "indices": g.accessor(indices, "SCALAR", UNSIGNED_BYTE, target=ELEMENT_ARRAY_BUFFER)}]})

        # Joints: the chain, then the extras. Node i + 1 is joint i (node 0 is the mesh node).
        joints = [(("joint%d" % i), self.joint_parent[i], self.joint_translation[i], self.joint_scale[i])
                  for i in range(COLUMNS)]
        joints += [(name, parent, translation, None) for name, parent, translation in self.extra_joints]
        world = []
        for name, parent, translation, s in joints:
            base = ([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]) if parent < 0 else world[parent]
            world.append(self.rest_world(base, translation, s))
        g.add("nodes", {"name": "strip", "mesh": mesh, "skin": 0})
        for i, (name, parent, translation, s) in enumerate(joints):
            node = {"name": name, "translation": [f32(x) for x in translation]}
            if s is not None:
                node["scale"] = [f32(x) for x in s]
            children = [k + 1 for k, j in enumerate(joints) if j[1] == i]
            if children:
                node["children"] = children
            g.add("nodes", node)
        roots = [0] + [i + 1 for i, j in enumerate(joints) if j[1] < 0]
        g.add("scenes", {"nodes": roots})

        ibms = []
        for i, (t, s) in enumerate(world):
            off = self.ibm_offsets.get(i, [0.0, 0.0, 0.0])
            # inverse of T·S: S⁻¹ and −S⁻¹ t, column-major
            inv = [1.0 / s[0], 1.0 / s[1], 1.0 / s[2]]
            ibms.append([inv[0], 0, 0, 0, 0, inv[1], 0, 0, 0, 0, inv[2], 0,
                         -inv[0] * t[0] + off[0], -inv[1] * t[1] + off[1], -inv[2] * t[2] + off[2], 1])
        skin = {"name": "chain", "joints": [i + 1 for i in range(len(joints))],
                "inverseBindMatrices": g.accessor(ibms, "MAT4")}
        if self.skeleton is not None:
            skin["skeleton"] = self.skeleton + 1
        g.add("skins", skin)

        times = g.accessor([0.0, 0.5, 1.0], "SCALAR", with_bounds=True)
        if self.cubic:
            keys = []
            for q in self.rotation_keys:
                tangent = [0.1 * x for x in q]
                keys += [tangent, q, tangent]
            samplers = [{"input": times, "output": g.accessor(keys, "VEC4"), "interpolation": "CUBICSPLINE"}]
        else:
            samplers = [{"input": times, "output": g.accessor(self.rotation_keys, "VEC4"), "interpolation": "LINEAR"}]
        channels = [{"sampler": 0, "target": {"node": 2, "path": "rotation"}}]
        if self.scale_keys is not None:
            joint, keys = self.scale_keys
            samplers.append({"input": times, "output": g.accessor(keys, "VEC3"), "interpolation": "LINEAR"})
            channels.append({"sampler": 1, "target": {"node": joint + 1, "path": "scale"}})
        g.add("animations", {"name": "bend", "samplers": samplers, "channels": channels})
        return g


def set_vertex(rig, v, pairs):
    """Vertex v's influences: (joint, weight) pairs, four per set, sets added (all zero) as needed."""
    while len(rig.sets) * 4 < len(pairs):
        rig.sets.append([([0, 0, 0, 0], [0.0, 0.0, 0.0, 0.0]) for _ in range(rig.vertices)])
    for n in range(len(rig.sets)):
        chunk = pairs[4 * n:4 * n + 4]
        chunk += [(0, 0.0)] * (4 - len(chunk))
        rig.sets[n][v] = ([j for j, _ in chunk], [w for _, w in chunk])


def weights_sum_float(r):
    set_vertex(r, 6, [(3, 0.5), (4, 0.25)])


def weights_sum_ubyte(r):
    r.weight_type = UNSIGNED_BYTE
    set_vertex(r, 10, [(5, 200 / 255), (6, 30 / 255)])


def weights_sum_ushort(r):
    r.weight_type = UNSIGNED_SHORT
    set_vertex(r, 10, [(5, 60000 / 65535), (6, 10000 / 65535)])


def five_influences(r):
    set_vertex(r, 8, [(4, 0.25), (5, 0.25), (3, 0.25), (6, 0.125), (7, 0.125)])


def nine_influences(r):
    set_vertex(r, 8, [(j, 0.125) for j in range(7)] + [(7, 0.0625), (8, 0.0625)])


def zero_weight_vertex(r):
    set_vertex(r, 7, [])


def negative_weight(r):
    set_vertex(r, 9, [(4, 1.25), (5, -0.25)])


def duplicate_joint(r):
    set_vertex(r, 11, [(5, 0.5), (5, 0.5)])


def joint_out_of_range(r):
    set_vertex(r, 13, [(6, 0.75), (12, 0.25)])


def unused_joint(r):
    r.extra_joints.append(("spare", 0, [0.0, 1.0, 0.0]))


def no_common_root(r):
    # A joint at joint 9's place but in a tree of its own, used by vertex 19.
    r.extra_joints.append(("detached", -1, [STEP * (COLUMNS - 1), 0.0, 0.0]))
    set_vertex(r, 19, [(COLUMNS, 1.0)])


def skeleton_not_root(r):
    r.skeleton = 5


def wrong_inverse_bind(r):
    r.ibm_offsets[4] = [0.25, 0.0, 0.0]


def nonuniform_scaled_joint(r):
    r.scale_keys = (6, [[1.0, 1.0, 1.0], [1.25, 0.75, 1.0], [1.5, 0.5, 1.0]])


def uniform_scaled_joint(r):
    r.scale_keys = (6, [[1.0, 1.0, 1.0], [1.25, 1.25, 1.25], [1.5, 1.5, 1.5]])


def non_orthonormal_ibm(r):
    # The last joint scaled by 0.5 at rest: its inverse bind matrix scales by 2, and the joint matrix is
    # still the identity at rest.
    r.joint_scale[COLUMNS - 1] = [0.5, 0.5, 0.5]


def non_unit_rotation_keys(r):
    r.rotation_keys[1] = [x * 1.25 for x in quat_z(20)]


def hemisphere_flip_keys(r):
    r.rotation_keys[1] = [-x for x in quat_z(20)]


def hemisphere_flip_cubic(r):
    r.cubic = True
    r.rotation_keys[1] = [-x for x in quat_z(20)]


# file name -> (how the rig is broken, the lint check that must find it; None for the clean file)
CATALOGUE = {
    "clean.gltf": (None, None),
    "weights_sum_float.gltf": (weights_sum_float, "weight-sum"),
    "weights_sum_ubyte.gltf": (weights_sum_ubyte, "weight-sum"),
    "weights_sum_ushort.gltf": (weights_sum_ushort, "weight-sum"),
    "five_influences.gltf": (five_influences, "too-many-influences"),
    "nine_influences.gltf": (nine_influences, "over-8-influences"),
    "zero_weight_vertex.gltf": (zero_weight_vertex, "zero-weight-vertex"),
    "negative_weight.gltf": (negative_weight, "negative-weight"),
    "duplicate_joint.gltf": (duplicate_joint, "duplicate-joint"),
    "joint_out_of_range.gltf": (joint_out_of_range, "joint-out-of-range"),
    "unused_joint.gltf": (unused_joint, "unused-joint"),
    "no_common_root.gltf": (no_common_root, "no-common-root"),
    "skeleton_not_root.gltf": (skeleton_not_root, "skeleton-not-root"),
    "wrong_inverse_bind.gltf": (wrong_inverse_bind, "inverse-bind-mismatch"),
    "nonuniform_scaled_joint.gltf": (nonuniform_scaled_joint, "joint-nonuniform-scale"),
    "uniform_scaled_joint.gltf": (uniform_scaled_joint, "joint-uniform-scale"),
    # Legal: the joint matrix is the identity, so nothing deforms differently (lint once warned about it).
    "non_orthonormal_ibm.gltf": (non_orthonormal_ibm, None),
    "non_unit_rotation_keys.gltf": (non_unit_rotation_keys, "rotation-not-unit"),
    "hemisphere_flip_keys.gltf": (hemisphere_flip_keys, "hemisphere-flip"),
    "hemisphere_flip_cubic.gltf": (hemisphere_flip_cubic, "hemisphere-flip"),
}


def main(argv):
    if len(argv) > 2 or (len(argv) == 2 and argv[1] in ("-h", "--help")):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    out = argv[1] if len(argv) == 2 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "testdata",
                                                      "bad_skins")
    os.makedirs(out, exist_ok=True)
    for name, (breaks, check) in CATALOGUE.items():
        rig = Rig()
        if breaks:
            breaks(rig)
        size = rig.build().write_gltf(os.path.join(out, name))
        print("%-30s %6d bytes  %s" % (name, size, check or "clean"))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
