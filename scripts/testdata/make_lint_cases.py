#!/usr/bin/env python3
"""Writes the rigs that `dqskin lint` is tested on beyond the bad-skin catalogue: legal rigs laid out as real
exporters lay them out, which must lint without a warning, and one defect per newer check.

    python3 scripts/testdata/make_lint_cases.py OUTDIR

Every rig is the same small character, modelled in T-pose in centimetres (hips at 100 cm, arms along ±x):
hips → spine → neck, and spine → shoulder → elbow → hand on each side, with a tube of 4-vertex rings along
every bone (each ring on one joint, or half on each at mid-bone), and a clip `wave` that bends the left
elbow (0°, 45°, 0° at 0, 0.5, 1 s) and turns the spine. What varies is where the exporter puts things:

- the armature node: scale 0.01 and a −90° turn about x (a Z-up rig in centimetres, as Blender imports an
  FBX file), or none;
- the skinned mesh node: a child of the armature (Blender) or its sibling at the root (FBX2glTF);
- bind space, the space POSITION is in: the armature's (centimetres; the joint matrices at rest are then
  the armature's transform) or the world's (metres; the inverse bind matrices then carry the ×100);
- the rest pose: the T-pose it was bound in, or arms down (shoulders turned 70°): glTF allows both, since
  the inverse bind matrices define the bind pose and the node transforms the rest pose (§3.7.3.1).

Legal (lint --werror exits 0): blender_armature_cm, blender_arms_down, fbx2gltf_armature_cm,
fbx2gltf_vertices_cm, arms_down_metres, three_skinned_nodes (three skinned mesh nodes under a moved node:
the notice glTF's ignored transform gets, once). Defects, one check each (docs/commands/lint.md):
ibm_not_affine, ibm_not_invertible, joint_zero_scale, joint_mirrored, joint_not_in_scene, blender_bone_moved.

Deterministic, byte for byte. Python 3 standard library only (and scripts/testdata/gltf_builder.py).
"""

import math
import os
import sys

from gltf_builder import ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER, UNSIGNED_BYTE, UNSIGNED_SHORT, Builder, f32

# ---- 4×4 matrices, row-major lists of rows ----------------------------------------------------------------


def mat_mul(a, b):
    return [[sum(a[r][k] * b[k][c] for k in range(4)) for c in range(4)] for r in range(4)]


def translation(t):
    return [[1, 0, 0, t[0]], [0, 1, 0, t[1]], [0, 0, 1, t[2]], [0, 0, 0, 1]]


def scaling(s):
    return [[s[0], 0, 0, 0], [0, s[1], 0, 0], [0, 0, s[2], 0], [0, 0, 0, 1]]


def quat(axis, degrees):
    """Unit quaternion (x, y, z, w) turning `degrees` about the unit vector `axis`."""
    h = math.radians(degrees) / 2
    return [axis[0] * math.sin(h), axis[1] * math.sin(h), axis[2] * math.sin(h), math.cos(h)]


def rotation(q):
    x, y, z, w = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w), 0],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w), 0],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y), 0],
            [0, 0, 0, 1]]


def trs(t=(0, 0, 0), q=(0, 0, 0, 1), s=(1, 1, 1)):
    return mat_mul(mat_mul(translation(t), rotation(q)), scaling(s))


def inverse(m):
    """Gauss-Jordan with partial pivoting; m must be invertible."""
    a = [list(map(float, m[r])) + [1.0 if c == r else 0.0 for c in range(4)] for r in range(4)]
    for c in range(4):
        p = max(range(c, 4), key=lambda r: abs(a[r][c]))
        a[c], a[p] = a[p], a[c]
        d = a[c][c]
        a[c] = [x / d for x in a[c]]
        for r in range(4):
            if r != c and a[r][c] != 0:
                f = a[r][c]
                a[r] = [x - f * y for x, y in zip(a[r], a[c])]
    return [row[4:] for row in a]


def apply(m, p):
    return [sum(m[r][k] * (list(p) + [1.0])[k] for k in range(4)) for r in range(3)]


def column_major(m):
    return [m[r][c] for c in range(4) for r in range(4)]


def rotate_vector(q, v):
    return apply(rotation(q), v)


# ---- the character ----------------------------------------------------------------------------------------

# name, parent, bind position in the design space (Y up, centimetres)
JOINTS = [
    ("hips", -1, (0, 100, 0)),
    ("spine", 0, (0, 130, 0)),
    ("neck", 1, (0, 160, 0)),
    ("shoulder.L", 1, (20, 150, 0)),
    ("elbow.L", 3, (50, 150, 0)),
    ("hand.L", 4, (75, 150, 0)),
    ("shoulder.R", 1, (-20, 150, 0)),
    ("elbow.R", 6, (-50, 150, 0)),
    ("hand.R", 7, (-75, 150, 0)),
]
INDEX = {name: i for i, (name, _, _) in enumerate(JOINTS)}
Z_UP_TURN = quat((1, 0, 0), -90)  # the armature's turn that shows a Z-up rig upright in glTF's Y-up
RING = 3.0  # half the side of a bone's square tube, cm


class Character:
    def __init__(self, layout="blender", armature_scale=0.01, z_up=True, bind_space="armature", arms_down=False):
        self.layout = layout  # "blender": mesh node under the armature; "fbx": beside it
        self.armature_scale = armature_scale
        self.armature_turn = Z_UP_TURN if z_up else [0, 0, 0, 1]
        self.bind_space = bind_space  # "armature" (centimetres) or "world"
        self.arms_down = arms_down
        self.ibm_edits = {}  # joint index → function(row-major matrix) → matrix, applied to the stored one
        self.node_scale = {}  # joint index → rest scale
        self.scale_keys = None  # (joint index, [scale at 0, 0.5, 1 s])
        self.scene_has_armature = True
        self.skinned_nodes_under_moved_parent = 0  # > 0: that many skinned mesh nodes under a moved node

    def armature(self):
        s = self.armature_scale
        return trs(q=self.armature_turn, s=(s, s, s))

    def to_armature(self, v):
        """A design-space direction or position in the armature's space (undoing the armature's turn)."""
        q = self.armature_turn
        return rotate_vector([-q[0], -q[1], -q[2], q[3]], v)

    def bind_positions(self):
        return [self.to_armature(p) for _, _, p in JOINTS]

    def rest_rotation(self, name):
        """Arms down: the shoulders turned 70° about the design's z (front) axis, down from T-pose."""
        if not self.arms_down or not name.startswith("shoulder"):
            return [0, 0, 0, 1]
        return quat(self.to_armature((0, 0, 1)), -70 if name.endswith(".L") else 70)

    def build(self):
        g = Builder("dqskin scripts/testdata/make_lint_cases.py", indent=1)
        g.doc["scene"] = 0
        bind = self.bind_positions()
        bind_world = [translation(p) for p in bind]  # bind matrices in armature space (T-pose: no turns)
        to_bind_space = self.armature() if self.bind_space == "world" else trs()

        # The mesh: a square tube along each bone, rings at the parent (on it), mid-bone (half each) and
        # the joint (on it). Vertices in bind space.
        positions, joints, weights, indices = [], [], [], []
        for j, (_, parent, _) in enumerate(JOINTS):
            if parent < 0:
                continue
            a, b = bind[parent], bind[j]
            axis = [b[i] - a[i] for i in range(3)]
            length = math.sqrt(sum(x * x for x in axis))
            d = [x / length for x in axis]
            helper = (0, 0, 1) if abs(d[2]) < 0.9 else (1, 0, 0)
            u = [d[1] * helper[2] - d[2] * helper[1], d[2] * helper[0] - d[0] * helper[2], d[0] * helper[1] - d[1] * helper[0]]
            un = math.sqrt(sum(x * x for x in u))
            u = [x / un for x in u]
            v = [d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2], d[0] * u[1] - d[1] * u[0]]
            first = len(positions)
            for t, influence in ((0.0, [(parent, 1.0)]), (0.5, [(parent, 0.5), (j, 0.5)]), (1.0, [(j, 1.0)])):
                centre = [a[i] + t * axis[i] for i in range(3)]
                for cu, cv in ((1, 1), (-1, 1), (-1, -1), (1, -1)):
                    p = [centre[i] + RING * (cu * u[i] + cv * v[i]) for i in range(3)]
                    positions.append(tuple(f32(x) for x in apply(to_bind_space, p)))
                    pairs = influence + [(0, 0.0)] * (4 - len(influence))
                    joints.append([pj for pj, _ in pairs])
                    stored = [round(w * 255) for _, w in pairs]
                    stored[len(influence) - 1] += 255 - sum(stored)  # normalized bytes summing to exactly 255
                    weights.append(stored)
            for ring in range(2):
                for k in range(4):
                    p0 = first + 4 * ring + k
                    p1 = first + 4 * ring + (k + 1) % 4
                    indices += [p0, p1, p1 + 4, p0, p1 + 4, p0 + 4]
        attributes = {
            "POSITION": g.accessor(positions, "VEC3", target=ARRAY_BUFFER, with_bounds=True),
            "JOINTS_0": g.accessor(joints, "VEC4", UNSIGNED_BYTE, target=ARRAY_BUFFER),
            "WEIGHTS_0": g.accessor(weights, "VEC4", UNSIGNED_BYTE, target=ARRAY_BUFFER, normalized=True),
        }
        mesh = g.add("meshes", {"name": "body", "primitives": [{
            "attributes": attributes,
            "indices": g.accessor(indices, "SCALAR", UNSIGNED_SHORT, target=ELEMENT_ARRAY_BUFFER)}]})

        # Nodes: 0 the armature, 1… the joints (joint i is node i + 1), then the skinned mesh node(s).
        s = self.armature_scale
        armature = {"name": "Armature", "rotation": [f32(x) for x in self.armature_turn], "scale": [s, s, s]}
        if self.armature_turn == [0, 0, 0, 1]:
            del armature["rotation"]
        if s == 1:
            del armature["scale"]
        g.add("nodes", armature)
        for j, (name, parent, _) in enumerate(JOINTS):
            local = [bind[j][i] - (bind[parent][i] if parent >= 0 else 0) for i in range(3)]
            node = {"name": name, "translation": [f32(x) for x in local]}
            rest = self.rest_rotation(name)
            if rest != [0, 0, 0, 1]:
                node["rotation"] = [f32(x) for x in rest]
            if j in self.node_scale:
                node["scale"] = [f32(x) for x in self.node_scale[j]]
            children = [k + 1 for k, (_, p, _) in enumerate(JOINTS) if p == j]
            if children:
                node["children"] = children
            g.add("nodes", node)
        g.doc["nodes"][0]["children"] = [1]
        roots = [0] if self.scene_has_armature else []
        if self.skinned_nodes_under_moved_parent:
            holder = g.add("nodes", {"name": "characters", "translation": [0.0, 0.0, 1.0]})
            first = len(g.doc["nodes"])
            for k in range(self.skinned_nodes_under_moved_parent):
                g.add("nodes", {"name": "body%d" % k, "mesh": mesh, "skin": 0})
            g.doc["nodes"][holder]["children"] = list(range(first, len(g.doc["nodes"])))
            roots.append(holder)
        else:
            body = g.add("nodes", {"name": "body", "mesh": mesh, "skin": 0})
            if self.layout == "blender":
                g.doc["nodes"][0]["children"].append(body)
            else:
                roots.append(body)
        g.add("scenes", {"nodes": roots})

        # Inverse bind matrices: of the T-pose, from bind space to each joint's space.
        ibms = []
        for j in range(len(JOINTS)):
            m = inverse(mat_mul(to_bind_space, bind_world[j]))
            if j in self.ibm_edits:
                m = self.ibm_edits[j](m)
            ibms.append(column_major(m))
        g.add("skins", {"name": "Armature", "joints": [j + 1 for j in range(len(JOINTS))],
                        "inverseBindMatrices": g.accessor(ibms, "MAT4")})

        # The clip: the left elbow bends about the design's z, the spine turns about its y.
        times = g.accessor([0.0, 0.5, 1.0], "SCALAR", with_bounds=True)
        bend = self.to_armature((0, 0, 1))
        turn = self.to_armature((0, 1, 0))
        samplers = [
            {"input": times, "output": g.accessor([quat(bend, a) for a in (0, 45, 0)], "VEC4")},
            {"input": times, "output": g.accessor([quat(turn, a) for a in (0, 10, -10)], "VEC4")},
        ]
        channels = [{"sampler": 0, "target": {"node": INDEX["elbow.L"] + 1, "path": "rotation"}},
                    {"sampler": 1, "target": {"node": INDEX["spine"] + 1, "path": "rotation"}}]
        if self.scale_keys is not None:
            joint, keys = self.scale_keys
            samplers.append({"input": times, "output": g.accessor(keys, "VEC3")})
            channels.append({"sampler": 2, "target": {"node": joint + 1, "path": "scale"}})
        g.add("animations", {"name": "wave", "samplers": samplers, "channels": channels})
        return g


# ---- the cases ------------------------------------------------------------------------------------------


def with_fourth_row(row):
    def edit(m):
        m = [list(r) for r in m]
        m[3] = list(row)
        return m
    return edit


def without_x(m):
    """The x column zeroed: the matrix cannot be inverted."""
    return [[0.0] + list(r[1:]) for r in m]


def moved_by(offset):
    def edit(m):
        return mat_mul(translation(offset), m)
    return edit


def cases():
    c = {}
    c["blender_armature_cm"] = Character("blender")
    c["blender_arms_down"] = Character("blender", arms_down=True)
    c["fbx2gltf_armature_cm"] = Character("fbx", bind_space="world")
    c["fbx2gltf_vertices_cm"] = Character("fbx")
    c["arms_down_metres"] = Character("fbx", armature_scale=1, z_up=False, arms_down=True)
    c["three_skinned_nodes"] = Character("fbx", armature_scale=1, z_up=False)
    c["three_skinned_nodes"].skinned_nodes_under_moved_parent = 3

    r = c["ibm_not_affine"] = Character("fbx", armature_scale=1, z_up=False)
    r.ibm_edits[INDEX["elbow.L"]] = with_fourth_row([0.0, 0.0, 0.0, 2.0])
    r = c["ibm_not_invertible"] = Character("fbx", armature_scale=1, z_up=False)
    r.ibm_edits[INDEX["elbow.L"]] = without_x
    r = c["joint_zero_scale"] = Character("fbx")
    r.scale_keys = (INDEX["hand.R"], [[1, 1, 1], [0.5, 0.5, 0.5], [0, 0, 0]])
    r = c["joint_mirrored"] = Character("fbx", armature_scale=1, z_up=False)
    r.node_scale[INDEX["hand.R"]] = [-1, 1, 1]
    r = c["joint_not_in_scene"] = Character("fbx")
    r.scene_has_armature = False
    # The left elbow's inverse bind matrix moved 5 cm along the arm, in a 0.01 armature: its bind
    # position is no longer where the shoulder and the bone put it.
    r = c["blender_bone_moved"] = Character("blender")
    r.ibm_edits[INDEX["elbow.L"]] = moved_by([-5.0, 0.0, 0.0])
    return c


def main(argv):
    if len(argv) != 2:
        sys.exit("usage: make_lint_cases.py OUTDIR")
    out = argv[1]
    os.makedirs(out, exist_ok=True)
    for name, rig in sorted(cases().items()):
        rig.build().write_gltf(os.path.join(out, name + ".gltf"))


if __name__ == "__main__":
    main(sys.argv)
