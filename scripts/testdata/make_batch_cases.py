#!/usr/bin/env python3
"""Writes the inputs of the tests that a batch of real files goes on (app/tests/batch_cases.cmake): files a
user feeds dqskin in bulk that today stop a batch, each made from one rig of testdata.

Usage: make_batch_cases.py OUTDIR RIG.gltf

RIG.gltf is a skinned, animated .gltf with one buffer as a data: URI (testdata/bending_arm.gltf). Written:
  rig.vrm, rig_b.vrm   the rig as a GLB named as VRM avatars are, with "extensionsUsed": ["VRMC_vrm"] and a
                       VRMC_vrm object, as the VRM add-on writes them (a .vrm is a GLB, VRM 1.0 §1); _b has
                       another VRM title, so the two files differ but their geometry does not
  rig_glb_no_extension the same GLB with no extension at all
  rig_gltf.dat         the rig's JSON .gltf under a name that says nothing
  no_skin.gltf         the rig without its skin (no "skin", no skins, no JOINTS_0/WEIGHTS_0): its mesh is
                       drawn as it is; the joints' animation moves nothing
  no_clips.gltf        the rig without its animation
  two_lengths.gltf     the rig's clip twice, stretched to 0.4 s ("short") and 2 s ("long"): at 30 fps frames
                       0..12 and 0..60
Only the Python standard library and scripts/testdata/gltf_builder.py are used; the output is the same on every run.
"""

import base64
import copy
import json
import os
import struct
import sys

from gltf_builder import Builder, write_file


def load_rig(path):
    """The rig's document and its one buffer, decoded from the data: URI."""
    with open(path, "rb") as f:
        doc = json.load(f)
    assert len(doc["buffers"]) == 1, "the rig must have one buffer"
    uri = doc["buffers"][0]["uri"]
    assert uri.startswith("data:") and ";base64," in uri, "the rig's buffer must be a base64 data: URI"
    return doc, bytearray(base64.b64decode(uri.split(",", 1)[1]))


def builder(doc, buffer):
    """A Builder of a copy of the rig (its JSON indented, as testdata's are)."""
    return Builder(doc=copy.deepcopy(doc), buffer=bytearray(buffer), indent=1)


def as_vrm(doc, buffer, title):
    """The rig marked as a VRM 1.0 avatar: the extension is used, not required (a viewer without VRM support
    still draws it), with the meta object every VRM file has."""
    b = builder(doc, buffer)
    b.doc["extensionsUsed"] = ["VRMC_vrm"]
    b.doc["extensions"] = {"VRMC_vrm": {"specVersion": "1.0", "meta": {
        "name": title, "version": "1", "authors": ["dqskin tests"], "licenseUrl": "https://vrm.dev/licenses/1.0/"}}}
    return b


def without_skin(doc, buffer):
    b = builder(doc, buffer)
    for node in b.doc["nodes"]:
        node.pop("skin", None)
    del b.doc["skins"]
    for mesh in b.doc["meshes"]:
        for primitive in mesh["primitives"]:
            for name in [n for n in primitive["attributes"] if n.startswith(("JOINTS_", "WEIGHTS_"))]:
                del primitive["attributes"][name]
    return b


def without_clips(doc, buffer):
    b = builder(doc, buffer)
    del b.doc["animations"]
    return b


def two_lengths(doc, buffer):
    """The rig's first clip as two clips of other lengths: its key times scaled to end at 0.4 s and 2 s."""
    b = builder(doc, buffer)
    clip = b.doc["animations"][0]
    times_accessor = b.doc["accessors"][clip["samplers"][0]["input"]]
    assert all(s["input"] == clip["samplers"][0]["input"] for s in clip["samplers"]), "one input accessor"
    end = times_accessor["max"][0]
    view = b.doc["bufferViews"][times_accessor["bufferView"]]
    start = view["byteOffset"] + times_accessor.get("byteOffset", 0)
    times = struct.unpack_from("<%df" % times_accessor["count"], buffer, start)
    clips = []
    for name, length in (("short", 0.4), ("long", 2.0)):
        scaled = b.accessor([t * length / end for t in times], "SCALAR", with_bounds=True)
        c = copy.deepcopy(clip)
        c["name"] = name
        for s in c["samplers"]:
            s["input"] = scaled
        clips.append(c)
    b.doc["animations"] = clips
    return b


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: make_batch_cases.py OUTDIR RIG.gltf")
    outdir, rig = sys.argv[1], sys.argv[2]
    os.makedirs(outdir, exist_ok=True)
    doc, buffer = load_rig(rig)
    as_vrm(doc, buffer, "rig").write_glb(os.path.join(outdir, "rig.vrm"))
    as_vrm(doc, buffer, "rig, second copy").write_glb(os.path.join(outdir, "rig_b.vrm"))
    builder(doc, buffer).write_glb(os.path.join(outdir, "rig_glb_no_extension"))
    builder(doc, buffer).write_gltf(os.path.join(outdir, "rig_gltf.dat"))
    without_skin(doc, buffer).write_gltf(os.path.join(outdir, "no_skin.gltf"))
    without_clips(doc, buffer).write_gltf(os.path.join(outdir, "no_clips.gltf"))
    two_lengths(doc, buffer).write_gltf(os.path.join(outdir, "two_lengths.gltf"))
    write_file(os.path.join(outdir, "done.txt"), b"make_batch_cases.py wrote this folder\n")
    print("make_batch_cases: 7 files in %s" % outdir)


if __name__ == "__main__":
    main()
