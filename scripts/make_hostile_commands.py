#!/usr/bin/env python3
"""Crafted inputs for the commands that came after the loader's hardening (app/tests/command_limits.cmake,
docs/SECURITY.md "Every command"): each made a command crash, hang, take memory past --max-memory, leak a
file's content or leave a half-written output; each class of problem is one small generated case here,
never a downloaded file.

    make_hostile_commands.py OUTDIR

writes one folder per command under OUTDIR (report/, lint/), deterministic, byte for byte. Python 3 standard
library only.
"""

import copy
import math
import os
import shutil
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_malformed as malformed  # noqa: E402  (the quad skinned to two joints, and its accessors)


def write(folder, name, data):
    path = os.path.join(folder, name)
    with open(path, "wb") as f:
        f.write(data)


def report_cases(folder):
    """dqskin report.

    clips_1000.gltf   the quad with its clip repeated 1,000 times (a 120 KB file): each clip's contact sheet
                      and the page that embeds them all took 5.7 GB whatever --max-memory said
    """
    a = malformed.base_asset()
    a.gltf["animations"] = [copy.deepcopy(a.gltf["animations"][0]) for _ in range(1000)]
    for i, animation in enumerate(a.gltf["animations"]):
        animation["name"] = "clip%d" % i
    write(folder, "clips_1000.gltf", a.gltf_bytes())


def unbacked(a, vertices):
    """Gives the quad `vertices` vertices, all at the origin and without weight: its POSITION, NORMAL,
    JOINTS_0 and WEIGHTS_0 accessors lose their bufferViews (glTF 2.0 §3.6.2.3: then they hold zeros)."""
    for accessor in (malformed.POSITION, malformed.NORMAL, malformed.JOINTS, malformed.WEIGHTS):
        entry = a.gltf["accessors"][accessor]
        del entry["bufferView"]
        entry["count"] = vertices
    a.gltf["accessors"][malformed.POSITION].update({"min": [0, 0, 0], "max": [0, 0, 0]})


def lint_cases(folder):
    """dqskin lint and lint --fix.

    chain_200k.gltf          the quad's skin with a chain of 200,000 more joints, each the child of the one
                             before (5.6 MB): lint walked from every joint to the root, and --fix from
                             every joint to the skeleton, which took minutes
    unweighted_50k.gltf      1,000,000 vertices without weight (accessors without a bufferView: all zeros)
                             and a skin of 50,000 joints side by side under one root (500 KB): --fix
                             compared every vertex with every joint to find its nearest, for minutes
    two_skins_one_mesh.gltf  the quad drawn twice, with the two-joint skin and with a three-joint one, its
                             vertex 3 on joint 2: --fix dropped the influence that the larger skin needs
    zero_rotation_keys.gltf  a LINEAR rotation channel whose middle key is (0, 0, 0, 0), and a second one,
                             on a node turned at rest, whose keys are all (0, 0, 0, 0): --fix wrote them
                             unchanged, and the fixed file was as invalid
    unweighted_4m.gltf       4,000,000 vertices without weight (3 KB): --fix writes 80 MB, long enough to
                             be stopped while it writes
    """
    a = malformed.base_asset()
    nodes = a.gltf["nodes"]
    start = len(nodes)
    chain = 200000
    nodes[1]["children"] = [2, start]
    nodes.extend({"children": [start + i + 1]} for i in range(chain - 1))
    nodes.append({"name": "deepest"})
    skin = a.gltf["skins"][0]
    skin["joints"] = [1, 2] + list(range(start, start + chain))
    del skin["inverseBindMatrices"]  # the identity: right for every chain joint (they rest at the origin)
    write(folder, "chain_200k.gltf", a.gltf_bytes())

    a = malformed.base_asset()
    nodes = a.gltf["nodes"]
    start = len(nodes)
    joints = 50000
    nodes[1]["children"] = [2] + list(range(start, start + joints))
    nodes.extend({} for _ in range(joints))
    skin = a.gltf["skins"][0]
    skin["joints"] = [1, 2] + list(range(start, start + joints))
    del skin["inverseBindMatrices"]
    unbacked(a, 1000000)
    write(folder, "unweighted_50k.gltf", a.gltf_bytes())

    a = malformed.base_asset()
    third = a.add("nodes", {"name": "third joint", "translation": [1, 0, 0]})
    a.gltf["nodes"][2]["children"] = [third]
    larger = a.add("nodes", {"name": "quad drawn by the larger skin", "mesh": 0, "skin": 1})
    a.gltf["scenes"][0]["nodes"].append(larger)
    # Inverse bind matrices (column-major) of joints resting at the origin, at y = 1 and at (1, 1, 0).
    ibm = b"".join(struct.pack("<16f", 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -x, -y, 0, 1)
                   for x, y in [(0, 0), (0, 1), (1, 1)])
    view = a.add_view(ibm)
    ibm3 = a.add("accessors", {"bufferView": view, "componentType": malformed.FLOAT, "count": 3, "type": "MAT4"})
    a.gltf["skins"].append({"name": "three joints", "joints": [1, 2, third], "inverseBindMatrices": ibm3})
    at = a.accessor_offset(malformed.JOINTS) + 3 * 4
    a.bin[at:at + 4] = bytes([1, 2, 0, 0])  # vertex 3: 0.25 on joint 1, 0.75 on joint 2 (the larger skin's)
    write(folder, "two_skins_one_mesh.gltf", a.gltf_bytes())

    a = malformed.base_asset()
    zero = struct.pack("<4f", 0, 0, 0, 0)
    s = math.sqrt(0.5)
    view = a.add_view(struct.pack("<4f", 0, 0, 0, 1) + zero + struct.pack("<4f", 0, 0, s, s))
    a.gltf["accessors"][malformed.ROTATIONS]["bufferView"] = view
    view = a.add_view(zero * 3)
    zeros = a.add("accessors", {"bufferView": view, "componentType": malformed.FLOAT, "count": 3, "type": "VEC4"})
    # A node beside the skeleton, turned at rest: what its all-zero channel's keys become.
    turned = a.add("nodes", {"name": "turned", "rotation": [0, 0, s, s]})
    a.gltf["scenes"][0]["nodes"].append(turned)
    animation = a.gltf["animations"][0]
    animation["samplers"].append({"input": malformed.TIMES, "output": zeros, "interpolation": "LINEAR"})
    animation["channels"].append({"sampler": 2, "target": {"node": turned, "path": "rotation"}})
    write(folder, "zero_rotation_keys.gltf", a.gltf_bytes())

    a = malformed.base_asset()
    unbacked(a, 4000000)
    write(folder, "unweighted_4m.gltf", a.gltf_bytes())


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make_hostile_commands.py OUTDIR")
    out = sys.argv[1]
    if os.path.exists(out):
        shutil.rmtree(out)
    for name, make in [("report", report_cases), ("lint", lint_cases)]:
        os.makedirs(os.path.join(out, name))
        make(os.path.join(out, name))


if __name__ == "__main__":
    main()
