#!/usr/bin/env python3
"""Writes dqskin's synthetic test rigs: small glTF 2.0 files, one behaviour each.

Usage: python3 scripts/testdata/make_rigs.py [OUTPUT_DIR]     (default: the repository's testdata/)

Every rig is one .gltf file with its buffer embedded as a base64 data: URI. The output is deterministic:
the same bytes on every run (sorted JSON keys, every float rounded to float32 before it is written, no
timestamps; scripts/testdata/gltf_builder.py writes the container).

Conventions every rig follows, so that tests can rely on them:
  * the rest pose of every joint is a pure translation by dyadic numbers, and the inverse bind matrix of
    each joint is the exact inverse of its rest world matrix: at the rest pose every joint matrix is the
    identity in exact arithmetic, and the skinned mesh is drawn at its bind positions;
  * the skinned mesh node is a root node without a transform, its skin lists every joint it uses;
  * weights are float, non-negative multiples of 1/256 at most, summing to exactly 1; unused influence
    slots hold joint 0 with weight 0;
  * every clip is LINEAR unless its name says otherwise, and starts at t = 0.
The table in testdata/README.md describes each rig.
"""

import math
import os
import struct
import sys
import zlib

from gltf_builder import ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER, UNSIGNED_BYTE, UNSIGNED_SHORT, Builder, f32


def snap(x):
    """Removes the rounding noise of trigonometry at exact angles (cos 90° = 6e-17 becomes 0)."""
    return 0.0 if abs(x) < 1e-12 else x


def quat_axis_angle(axis, degrees):
    """Unit quaternion (x, y, z, w) for a rotation of `degrees` about the unit `axis`."""
    half = math.radians(degrees) / 2
    s = math.sin(half)
    return [snap(axis[0] * s), snap(axis[1] * s), snap(axis[2] * s), snap(math.cos(half))]


class Gltf(Builder):
    """One rig's glTF document and its single buffer, with the parts rigs are made of. The JSON is indented
    (one space) so that a change to a rig reads as a diff."""

    def __init__(self):
        super().__init__("dqskin scripts/testdata/make_rigs.py", indent=1)
        self.doc["scene"] = 0

    # -- document parts -------------------------------------------------------------------------------

    def node(self, name, translation=None, rotation=None, scale=None, children=None, mesh=None, skin=None):
        n = {"name": name}
        if translation is not None:
            n["translation"] = [f32(x) for x in translation]
        if rotation is not None:
            n["rotation"] = [f32(x) for x in rotation]
        if scale is not None:
            n["scale"] = [f32(x) for x in scale]
        if children:
            n["children"] = list(children)
        if mesh is not None:
            n["mesh"] = mesh
        if skin is not None:
            n["skin"] = skin
        return self.add("nodes", n)

    def skinned_mesh(self, name, geometry, influence_sets, targets=None, default_weights=None, extra=None,
                     material=None):
        """geometry: dict with positions, normals, indices. influence_sets: list of (joints, weights)
        pairs, one per JOINTS_n/WEIGHTS_n set, each a per-vertex list of 4-tuples. targets: list of
        (position_deltas, normal_deltas). extra: {attribute: accessor index} added to the primitive.
        Returns the mesh index."""
        attributes = {
            "POSITION": self.accessor(geometry["positions"], "VEC3", target=ARRAY_BUFFER, with_bounds=True),
            "NORMAL": self.accessor(geometry["normals"], "VEC3", target=ARRAY_BUFFER),
        }
        for i, (joints, weights) in enumerate(influence_sets):
            joint_type = UNSIGNED_BYTE if max(max(j) for j in joints) < 256 else UNSIGNED_SHORT
            attributes["JOINTS_%d" % i] = self.accessor(joints, "VEC4", joint_type, target=ARRAY_BUFFER)
            attributes["WEIGHTS_%d" % i] = self.accessor(weights, "VEC4", target=ARRAY_BUFFER)
        attributes.update(extra or {})
        primitive = {
            "attributes": attributes,
            "indices": self.accessor(geometry["indices"], "SCALAR", UNSIGNED_SHORT, target=ELEMENT_ARRAY_BUFFER),
            "mode": 4,
        }
        if material is not None:
            primitive["material"] = material
        mesh = {"name": name, "primitives": [primitive]}
        if targets:
            primitive["targets"] = [
                {
                    "POSITION": self.accessor(dp, "VEC3", target=ARRAY_BUFFER, with_bounds=True),
                    "NORMAL": self.accessor(dn, "VEC3", target=ARRAY_BUFFER),
                }
                for dp, dn in targets
            ]
            mesh["weights"] = [f32(w) for w in default_weights]
        return self.add("meshes", mesh)

    def skin(self, name, joints, rest_world_translations):
        """A skin whose inverse bind matrices invert the joints' rest world matrices, which are the pure
        translations given (exactly representable, so the inverse is exact)."""
        ibms = []
        for t in rest_world_translations:
            # Column-major 4x4: translation by -t.
            ibms.append([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -t[0], -t[1], -t[2], 1])
            assert all(f32(x) == x for x in t), "rest translations must be exact in float32"
        return self.add(
            "skins",
            {
                "name": name,
                "joints": list(joints),
                "skeleton": joints[0],
                "inverseBindMatrices": self.accessor(ibms, "MAT4"),
            },
        )

    def animation(self, name, channels):
        """channels: list of (node, path, interpolation, times, values); values per key (a number or a
        tuple), for CUBICSPLINE already as in-tangent, value, out-tangent triples."""
        samplers, chans = [], []
        for node, path, interpolation, times, values in channels:
            element = {"translation": "VEC3", "rotation": "VEC4", "scale": "VEC3", "weights": "SCALAR"}[path]
            samplers.append(
                {
                    "input": self.accessor(times, "SCALAR", with_bounds=True),
                    "interpolation": interpolation,
                    "output": self.accessor(values, element),
                }
            )
            chans.append({"sampler": len(samplers) - 1, "target": {"node": node, "path": path}})
        self.add("animations", {"name": name, "channels": chans, "samplers": samplers})

    def png_texture(self, name, png, sampler):
        """An embedded PNG (its own bufferView) as image, sampler and texture; returns the texture index."""
        image = self.add("images", {"name": name, "bufferView": self.view(png), "mimeType": "image/png"})
        return self.add("textures", {"source": image, "sampler": self.add("samplers", sampler)})

    def material(self, name, base_color_factor=None, base_color_texture=None):
        pbr = {"metallicFactor": 0.0}
        if base_color_factor is not None:
            pbr["baseColorFactor"] = [f32(x) for x in base_color_factor]
        if base_color_texture is not None:
            pbr["baseColorTexture"] = {"index": base_color_texture}
        return self.add("materials", {"name": name, "pbrMetallicRoughness": pbr})

    def camera(self, name, projection):
        """projection: {"perspective": {...}} or {"orthographic": {...}}; returns the camera index."""
        (kind, values), = projection.items()
        return self.add("cameras", {"name": name, "type": kind, kind: {k: f32(v) for k, v in values.items()}})

    def scene(self, name, roots):
        self.add("scenes", {"name": name, "nodes": list(roots)})


# -- geometry -----------------------------------------------------------------------------------------


def tube(axis, radius, stations, around, center=(0.0, 0.0, 0.0)):
    """An open tube (side surface only) along +x or +y through `center`: one ring of `around` vertices
    at each station (coordinate along the axis). Returns positions, normals, indices and, per vertex, its
    station index. Triangles wind counter-clockwise seen from outside."""
    positions, normals, station_of = [], [], []
    for s, a in enumerate(stations):
        for k in range(around):
            angle = 2 * math.pi * k / around
            c, d = snap(math.cos(angle)), snap(math.sin(angle))
            if axis == "y":  # ring in the xz plane
                n = (c, 0.0, d)
                p = (center[0] + radius * c, a, center[2] + radius * d)
            else:  # axis x: ring in the yz plane
                n = (0.0, c, d)
                p = (a, center[1] + radius * c, center[2] + radius * d)
            positions.append(p)
            normals.append(n)
            station_of.append(s)
    indices = []
    for s in range(len(stations) - 1):
        for k in range(around):
            a0, a1 = s * around + k, s * around + (k + 1) % around
            b0, b1 = a0 + around, a1 + around
            for tri in ((a0, b0, a1), (a1, b0, b1)):
                indices.extend(orient(tri, positions, normals))
    return {"positions": positions, "normals": normals, "indices": indices, "station": station_of}


def textured_tube(radius, stations, around):
    """The y-axis tube of tube() with a UV seam: each ring has around + 1 vertices, the last one at the
    first one's position with u = 1. u goes once around (counter-clockwise seen from +y), v from 0 at
    the top station to 1 at the bottom one (glTF's v = 0 is the image's top row)."""
    positions, normals, uvs, station_of = [], [], [], []
    top, bottom = stations[-1], stations[0]
    for s, a in enumerate(stations):
        for k in range(around + 1):
            angle = 2 * math.pi * (k % around) / around
            c, d = snap(math.cos(angle)), snap(math.sin(angle))
            positions.append((radius * c, a, radius * d))
            normals.append((c, 0.0, d))
            uvs.append((k / around, (top - a) / (top - bottom)))
            station_of.append(s)
    ring = around + 1
    indices = []
    for s in range(len(stations) - 1):
        for k in range(around):
            a0, a1 = s * ring + k, s * ring + k + 1
            b0, b1 = a0 + ring, a1 + ring
            for tri in ((a0, b0, a1), (a1, b0, b1)):
                indices.extend(orient(tri, positions, normals))
    return {"positions": positions, "normals": normals, "indices": indices, "station": station_of, "uv": uvs}


def box_strip(length, half, columns):
    """A box along +x from 0 to `length` with a square cross-section of side 2·half, `columns` + 1
    rings of 4 corner vertices (no end caps). Normals point away from the axis (diagonals)."""
    positions, normals, station_of = [], [], []
    corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
    inv = 1 / math.sqrt(2)
    for c in range(columns + 1):
        x = length * c / columns
        for cy, cz in corners:
            positions.append((x, cy * half, cz * half))
            normals.append((0.0, cy * inv, cz * inv))
            station_of.append(c)
    indices = []
    for c in range(columns):
        for k in range(4):
            a0, a1 = c * 4 + k, c * 4 + (k + 1) % 4
            b0, b1 = a0 + 4, a1 + 4
            for tri in ((a0, b0, a1), (a1, b0, b1)):
                indices.extend(orient(tri, positions, normals))
    return {"positions": positions, "normals": normals, "indices": indices, "station": station_of}


def png_rgb(width, height, pixel):
    """A PNG (8-bit RGB) of pixel(x, y) -> (r, g, b), top row first. The image data is stored without
    compression (deflate level 0), so the bytes do not depend on the zlib version."""
    raw = b"".join(b"\x00" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))

    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 0)) + chunk(b"IEND", b"")


def orient(tri, positions, normals):
    """The triangle wound so that its face normal agrees with its vertices' normals."""
    p0, p1, p2 = (positions[i] for i in tri)
    e1 = [p1[i] - p0[i] for i in range(3)]
    e2 = [p2[i] - p0[i] for i in range(3)]
    face = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
    avg = [sum(normals[i][k] for i in tri) for k in range(3)]
    if sum(face[k] * avg[k] for k in range(3)) < 0:
        return (tri[0], tri[2], tri[1])
    return tri


def two_joint_weights(stations, station_of, blend_from, blend_to):
    """Per vertex (joints, weights) for a two-joint skin: joint 0 up to `blend_from`, joint 1 from
    `blend_to`, linear in between. The blend must put stations on multiples of 1/256."""
    joints, weights = [], []
    for s in station_of:
        a = stations[s]
        w1 = min(1.0, max(0.0, (a - blend_from) / (blend_to - blend_from)))
        assert abs(w1 * 256 - round(w1 * 256)) < 1e-9, "weights must be exact"
        w1 = round(w1 * 256) / 256
        w0 = 1.0 - w1
        if w1 == 0.0:
            joints.append((0, 0, 0, 0))
            weights.append((1.0, 0.0, 0.0, 0.0))
        elif w0 == 0.0:
            joints.append((1, 0, 0, 0))
            weights.append((1.0, 0.0, 0.0, 0.0))
        else:
            joints.append((0, 1, 0, 0))
            weights.append((w0, w1, 0.0, 0.0))
    return joints, weights


def hermite_key(value, tangent):
    """A CUBICSPLINE key: in-tangent, value, out-tangent (the same tangent on both sides)."""
    return [tuple(tangent), tuple(value), tuple(tangent)]


def flatten(keys):
    out = []
    for k in keys:
        out.extend(k)
    return out


# -- rigs -----------------------------------------------------------------------------------------------


def twisted_cylinder(textured=False):
    """Candy wrapper: the child joint twists the upper half of a cylinder 180° about its own axis.
    textured gives textured_cylinder()'s surface."""
    g = Gltf()
    stations = [4.0 * i / 32 for i in range(33)]  # y = 0 .. 4 in steps of 1/8
    geo = textured_tube(0.5, stations, 24) if textured else tube("y", 0.5, stations, 24)
    joints, weights = two_joint_weights(stations, geo["station"], 1.0, 3.0)  # 50/50 at y = 2
    extra, material = None, None
    if textured:
        orange, cream = (230, 120, 40), (245, 235, 215)
        # 8 squares around and 8 up the 64x64 image; the first column of squares is blue, to mark u = 0.
        png = png_rgb(64, 64, lambda x, y: (40, 90, 200) if x < 8 and (y // 8) % 2 == 0 else
                      orange if (x // 8 + y // 8) % 2 == 0 else cream)
        texture = g.png_texture("checker", png, {"magFilter": 9728, "minFilter": 9987, "wrapS": 10497, "wrapT": 33071})
        material = g.material("checker", base_color_factor=(1.0, 1.0, 1.0, 1.0), base_color_texture=texture)
        # COLOR_0: white at the bottom to a light green at the top, in 1/255 steps.
        colors = [(255, 255, round(255 - 60 * p[1] / 4.0), 255) for p in geo["positions"]]
        extra = {
            "TEXCOORD_0": g.accessor(geo["uv"], "VEC2", target=ARRAY_BUFFER),
            "COLOR_0": g.accessor(colors, "VEC4", UNSIGNED_BYTE, target=ARRAY_BUFFER, normalized=True),
        }
    mesh = g.skinned_mesh("cylinder", geo, [(joints, weights)], extra=extra, material=material)
    g.node("cylinder", mesh=mesh, skin=0)
    root = g.node("root", children=[2])
    child = g.node("child", translation=(0.0, 2.0, 0.0))
    g.skin("cylinder_skin", [root, child], [(0.0, 0.0, 0.0), (0.0, 2.0, 0.0)])
    times = [0.0, 0.25, 0.5, 0.75, 1.0]
    g.animation("twist", [(child, "rotation", "LINEAR", times,
                           [tuple(quat_axis_angle((0, 1, 0), 45.0 * i)) for i in range(5)])])
    g.scene("scene", [0, root])
    return g


def bending_arm(with_cameras=False):
    """An arm along +x: shoulder at x = 0, elbow at x = 2; the elbow bends 90° about z. with_cameras adds
    camera_dolly()'s cameras."""
    g = Gltf()
    stations = [4.0 * i / 16 for i in range(17)]  # x = 0 .. 4 in steps of 1/4
    geo = tube("x", 0.4, stations, 16)
    joints, weights = two_joint_weights(stations, geo["station"], 1.5, 2.5)
    mesh = g.skinned_mesh("arm", geo, [(joints, weights)])
    g.node("arm", mesh=mesh, skin=0)
    shoulder = g.node("shoulder", children=[2])
    elbow = g.node("elbow", translation=(2.0, 0.0, 0.0))
    g.skin("arm_skin", [shoulder, elbow], [(0.0, 0.0, 0.0), (2.0, 0.0, 0.0)])
    times = [0.0, 0.5, 1.0]
    channels = [(elbow, "rotation", "LINEAR", times, [tuple(quat_axis_angle((0, 0, 1), a)) for a in (0.0, 45.0, 90.0)])]
    roots = [0, shoulder]
    if with_cameras:
        dolly_cam = g.camera("dolly", {"perspective": {"yfov": 0.6, "aspectRatio": 1.5, "znear": 0.1}})
        top_cam = g.camera("top", {"orthographic": {"xmag": 3.0, "ymag": 2.0, "znear": 0.5, "zfar": 20.0}})
        dolly = g.node("dolly", translation=(1.0, 1.0, 9.0))
        g.doc["nodes"][dolly]["camera"] = dolly_cam
        top = g.node("top", translation=(2.0, 8.0, 0.0), rotation=quat_axis_angle((1, 0, 0), -90.0))
        g.doc["nodes"][top]["camera"] = top_cam
        channels += [
            (dolly, "translation", "LINEAR", times, [(1.0, 1.0, 9.0), (2.0, 1.0, 8.0), (3.0, 1.0, 7.0)]),
            (dolly, "rotation", "LINEAR", times, [tuple(quat_axis_angle((0, 1, 0), a)) for a in (0.0, 5.0, 10.0)]),
        ]
        roots += [dolly, top]
    g.animation("bend", channels)
    g.scene("scene", roots)
    return g


def camera_dolly():
    """The bending arm seen by two glTF cameras: `dolly`, a perspective camera (yfov 0.6, aspect ratio
    1.5, no zfar, so an infinite projection) that moves along +x and turns during the clip, and `top`, a
    static orthographic camera (xmag 3, ymag 2) looking straight down."""
    return bending_arm(with_cameras=True)


def textured_cylinder():
    """The twisting cylinder with a surface the renderer can show the twist on: a checker base color
    texture (an embedded PNG through TEXCOORD_0, with a UV seam), a baseColorFactor and a COLOR_0 gradient
    (normalized unsigned bytes), which glTF multiplies."""
    return twisted_cylinder(textured=True)


def scaled_joint_rig(clip, scale_keys, rotation_keys):
    """A column along +y: a static base joint at y = 0 and a joint at y = 2 whose scale (and rotation,
    when given) animate; vertices below y = 1.5 follow the base, above y = 2.5 the scaled joint."""
    g = Gltf()
    stations = [4.0 * i / 16 for i in range(17)]
    geo = tube("y", 0.5, stations, 16)
    joints, weights = two_joint_weights(stations, geo["station"], 1.5, 2.5)
    mesh = g.skinned_mesh("column", geo, [(joints, weights)])
    g.node("column", mesh=mesh, skin=0)
    base = g.node("base", children=[2])
    top = g.node("scaled", translation=(0.0, 2.0, 0.0))
    g.skin("column_skin", [base, top], [(0.0, 0.0, 0.0), (0.0, 2.0, 0.0)])
    times = [0.0, 1.0]
    channels = [(top, "scale", "LINEAR", times, [tuple(s) for s in scale_keys])]
    if rotation_keys:
        channels.append((top, "rotation", "LINEAR", times, [tuple(q) for q in rotation_keys]))
    g.animation(clip, channels)
    g.scene("scene", [0, base])
    return g


def uniform_scale():
    return scaled_joint_rig("grow", [(1.0, 1.0, 1.0), (2.0, 2.0, 2.0)], None)


def nonuniform_scale():
    # Scale (1,1,1) -> (2,0.5,1) and, so that the rigid part is not the identity, a 30° turn about z.
    return scaled_joint_rig("squash", [(1.0, 1.0, 1.0), (2.0, 0.5, 1.0)],
                            [quat_axis_angle((0, 0, 1), 0.0), quat_axis_angle((0, 0, 1), 30.0)])


def eight_influences():
    """A box along +x over a chain of 8 joints (x = 0, 0.5, .. 3.5). Vertices from x = 1 on have 8
    non-zero weights, joints 0-3 in JOINTS_0/WEIGHTS_0 and joints 4-7 in JOINTS_1/WEIGHTS_1; vertices
    before x = 1 have weight on joints 0-3 only (their second set is all zero)."""
    g = Gltf()
    columns = 16
    geo = box_strip(4.0, 0.25, columns)
    joint_x = [0.5 * j for j in range(8)]
    j0, w0, j1, w1 = [], [], [], []
    for s in geo["station"]:
        x = 4.0 * s / columns
        used = range(8) if x >= 1.0 else range(4)
        raw = {j: math.exp(-((x - joint_x[j]) / 1.25) ** 2) + 0.05 for j in used}
        total = sum(raw.values())
        # Integer parts of 256, each at least 1, the largest absorbing the rounding: exact and summing to 1.
        parts = {j: max(1, int(round(256 * raw[j] / total))) for j in used}
        biggest = max(used, key=lambda j: (parts[j], -j))
        parts[biggest] += 256 - sum(parts.values())
        w = [parts.get(j, 0) / 256 for j in range(8)]
        j0.append((0, 1, 2, 3))
        w0.append(tuple(w[0:4]))
        if x >= 1.0:
            j1.append((4, 5, 6, 7))
            w1.append(tuple(w[4:8]))
        else:
            j1.append((0, 0, 0, 0))
            w1.append((0.0, 0.0, 0.0, 0.0))
    mesh = g.skinned_mesh("strip", geo, [(j0, w0), (j1, w1)])
    g.node("strip", mesh=mesh, skin=0)
    chain = []
    for j in range(8):
        chain.append(g.node("bone%d" % j, translation=None if j == 0 else (0.5, 0.0, 0.0),
                            children=[2 + j] if j < 7 else None))
    g.skin("chain_skin", chain, [(x, 0.0, 0.0) for x in joint_x])
    times = [0.25 * i for i in range(5)]
    channels = []
    for j in range(8):
        angles = [20.0 * math.sin(2 * math.pi * (t - j / 8)) for t in times]
        channels.append((chain[j], "rotation", "LINEAR", times, [tuple(quat_axis_angle((0, 0, 1), a)) for a in angles]))
    g.animation("wave", channels)
    g.scene("scene", [0, chain[0]])
    return g


def interpolation_modes():
    """One skinned cylinder, two clips: "cubic" (CUBICSPLINE rotation and translation of the child
    joint, non-zero tangents) and "step" (STEP rotation)."""
    g = Gltf()
    stations = [2.0 * i / 8 for i in range(9)]  # y = 0 .. 2 in steps of 1/4
    geo = tube("y", 0.25, stations, 12)
    joints, weights = two_joint_weights(stations, geo["station"], 0.75, 1.25)
    mesh = g.skinned_mesh("cylinder", geo, [(joints, weights)])
    g.node("cylinder", mesh=mesh, skin=0)
    root = g.node("root", children=[2])
    child = g.node("child", translation=(0.0, 1.0, 0.0))
    g.skin("cylinder_skin", [root, child], [(0.0, 0.0, 0.0), (0.0, 1.0, 0.0)])
    times = [0.0, 0.5, 1.0]
    rot = [quat_axis_angle((0, 0, 1), a) for a in (0.0, 45.0, 90.0)]
    # Tangents: the slerp's dq/dt = 0.5 * (0, 0, ω, 0) * q at ω = π/2 rad/s (90°/s about z), scaled by
    # 1.5, 0.5 and 1 at the three keys, so that between keys the curve is not the slerp.
    rot_tangents = []
    for q, wobble in zip(rot, (1.5, 0.5, 1.0)):
        x, y, z, w = q
        half = 0.5 * (math.pi / 2) * wobble
        rot_tangents.append((snap(-half * y), snap(half * x), snap(half * w), snap(-half * z)))
    cubic_rotation = flatten(hermite_key(v, t) for v, t in zip(rot, rot_tangents))
    tr = [(0.0, 1.0, 0.0), (0.25, 1.25, 0.0), (0.0, 1.0, 0.5)]
    tr_tangents = [(1.0, 0.0, 0.0), (0.0, 0.5, 1.0), (-1.0, 0.0, 0.0)]
    cubic_translation = flatten(hermite_key(v, t) for v, t in zip(tr, tr_tangents))
    g.animation("cubic", [(child, "rotation", "CUBICSPLINE", times, cubic_rotation),
                          (child, "translation", "CUBICSPLINE", times, cubic_translation)])
    g.animation("step", [(child, "rotation", "STEP", times,
                          [tuple(quat_axis_angle((1, 0, 0), a)) for a in (0.0, 60.0, 20.0)])])
    g.scene("scene", [0, root])
    return g


def morph_skin():
    """A skinned cylinder with 2 morph targets (POSITION and NORMAL deltas), default weights [0.5, 0];
    the clip "morph" animates the weights and the child joint's rotation."""
    g = Gltf()
    stations = [2.0 * i / 8 for i in range(9)]  # y = 0 .. 2
    geo = tube("y", 0.25, stations, 12)
    joints, weights = two_joint_weights(stations, geo["station"], 0.75, 1.25)
    # Target 0: a bulge, radial, largest at mid height; its normals lean down. Target 1: the top shifts
    # along x; its normals lean towards +x.
    d0p, d0n, d1p, d1n = [], [], [], []
    for (px, py, pz), (nx, ny, nz) in zip(geo["positions"], geo["normals"]):
        bulge = 0.25 * math.sin(math.pi * py / 2)
        d0p.append((nx * bulge, 0.0, nz * bulge))
        d0n.append((0.0, -0.25 * math.cos(math.pi * py / 2), 0.0))
        d1p.append((0.25 * py / 2, 0.0, 0.0))
        d1n.append((0.125, 0.0, 0.0))
    mesh = g.skinned_mesh("cylinder", geo, [(joints, weights)], targets=[(d0p, d0n), (d1p, d1n)],
                          default_weights=[0.5, 0.0])
    g.node("cylinder", mesh=mesh, skin=0)
    root = g.node("root", children=[2])
    child = g.node("child", translation=(0.0, 1.0, 0.0))
    g.skin("cylinder_skin", [root, child], [(0.0, 0.0, 0.0), (0.0, 1.0, 0.0)])
    times = [0.0, 0.5, 1.0]
    g.animation("morph", [
        (0, "weights", "LINEAR", times, [0.5, 0.0, 1.0, 0.5, 0.25, 1.0]),
        (child, "rotation", "LINEAR", times, [tuple(quat_axis_angle((1, 0, 0), a)) for a in (0.0, 30.0, 60.0)]),
    ])
    g.scene("scene", [0, root])
    return g


def two_skins():
    """Two skinned cylinders, each with its own two-joint skin: A at x = -1 (its child bends about z),
    B at x = +1 (its child bends about x). One clip "sway" moves both."""
    g = Gltf()
    stations = [2.0 * i / 8 for i in range(9)]
    geo_a = tube("y", 0.25, stations, 12, center=(-1.0, 0.0, 0.0))
    geo_b = tube("y", 0.25, stations, 12, center=(1.0, 0.0, 0.0))
    ja, wa = two_joint_weights(stations, geo_a["station"], 0.75, 1.25)
    jb, wb = two_joint_weights(stations, geo_b["station"], 0.75, 1.25)
    mesh_a = g.skinned_mesh("cylinder_a", geo_a, [(ja, wa)])
    mesh_b = g.skinned_mesh("cylinder_b", geo_b, [(jb, wb)])
    g.node("cylinder_a", mesh=mesh_a, skin=0)  # node 0
    g.node("cylinder_b", mesh=mesh_b, skin=1)  # node 1
    root_a = g.node("root_a", translation=(-1.0, 0.0, 0.0), children=[3])  # node 2
    child_a = g.node("child_a", translation=(0.0, 1.0, 0.0))  # node 3
    root_b = g.node("root_b", translation=(1.0, 0.0, 0.0), children=[5])  # node 4
    child_b = g.node("child_b", translation=(0.0, 1.0, 0.0))  # node 5
    g.skin("skin_a", [root_a, child_a], [(-1.0, 0.0, 0.0), (-1.0, 1.0, 0.0)])
    g.skin("skin_b", [root_b, child_b], [(1.0, 0.0, 0.0), (1.0, 1.0, 0.0)])
    times = [0.0, 0.5, 1.0]
    g.animation("sway", [
        (child_a, "rotation", "LINEAR", times, [tuple(quat_axis_angle((0, 0, 1), a)) for a in (0.0, 30.0, 60.0)]),
        (child_b, "rotation", "LINEAR", times, [tuple(quat_axis_angle((1, 0, 0), a)) for a in (0.0, -45.0, -90.0)]),
        (root_b, "translation", "LINEAR", times, [(1.0, 0.0, 0.0), (1.0, 0.5, 0.0), (1.0, 0.0, 0.0)]),
    ])
    g.scene("scene", [0, 1, root_a, root_b])
    return g


RIGS = {
    "twisted_cylinder.gltf": twisted_cylinder,
    "bending_arm.gltf": bending_arm,
    "uniform_scale.gltf": uniform_scale,
    "nonuniform_scale.gltf": nonuniform_scale,
    "eight_influences.gltf": eight_influences,
    "interpolation_modes.gltf": interpolation_modes,
    "morph_skin.gltf": morph_skin,
    "two_skins.gltf": two_skins,
    "textured_cylinder.gltf": textured_cylinder,
    "camera_dolly.gltf": camera_dolly,
}


def main(argv):
    if len(argv) > 2 or (len(argv) == 2 and argv[1] in ("-h", "--help")):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    out = argv[1] if len(argv) == 2 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "testdata")
    os.makedirs(out, exist_ok=True)
    for name, make in RIGS.items():
        size = make().write_gltf(os.path.join(out, name))
        print("%-26s %7d bytes" % (name, size))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
