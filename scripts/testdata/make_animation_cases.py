#!/usr/bin/env python3
"""Writes the animation-channel test inputs of `dqskin`: duplicate channels and KHR_animation_pointer.

Usage:
  make_animation_cases.py cases OUTDIR TESTDATA
      From TESTDATA/twisted_cylinder.gltf (one clip, 'twist', one rotation channel on node 2):
        dup_identical.gltf    the channel repeated 14 times, each copy with a sampler and accessors of its
                              own holding the same bytes (what one exporter writes)
        dup_different.gltf    the channel and a second one for the same node and path whose keys are the
                              first's in reverse order
        dup_second_kept.gltf  the original with the second channel's keys in place of the first's: what
                              keeping the wrong channel would deform like
        pointer_ignored.gltf  a material and a camera animated by KHR_animation_pointer channels (in clip
                              'twist' beside its rotation, and alone in a second clip 'zoom')
  make_animation_cases.py pointer-copy IN OUT [--mesh-weights]
      IN (.gltf with data URIs only, or .glb) with every channel that targets a node rewritten as a
      KHR_animation_pointer channel ("/nodes/N/PATH"), the extension used and required; OUT is written the
      same way as IN (.gltf or .glb). With --mesh-weights, a weights channel of a node that draws a mesh no
      other node draws, and has no weights of its own, points at the mesh's weights ("/meshes/M/weights")
      instead: the same animation. Prints how many channels it rewrote; fails when it rewrote none.

Python 3 standard library only (and scripts/testdata/gltf_builder.py); the output is the same on every run.
"""

import base64
import copy
import json
import os
import struct
import sys

from gltf_builder import Builder, glb_parts, json_bytes, write_file

EXTENSION = "KHR_animation_pointer"
FLOAT = 5126
COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}
SIZES = {5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4}


def read_model(path):
    """(document, buffer 0's bytes or None, is_glb). A .gltf's buffers must be data: URIs."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] == b"glTF":
        json_length = struct.unpack_from("<I", data, 12)[0]
        doc = json.loads(data[20:20 + json_length])
        rest = 20 + json_length
        binary = None
        if rest + 8 <= len(data):
            bin_length = struct.unpack_from("<I", data, rest)[0]
            binary = bytearray(data[rest + 8:rest + 8 + bin_length])
        return doc, binary, True
    doc = json.loads(data)
    buffers = doc.get("buffers", [])
    binary = None
    if buffers:
        uri = buffers[0].get("uri", "")
        if not uri.startswith("data:"):
            sys.exit("make_animation_cases: %s: buffer 0 is not a data: URI" % path)
        binary = bytearray(base64.b64decode(uri.split(",", 1)[1]))
    return doc, binary, False


def write_model(path, doc, binary, glb):
    if glb:
        write_file(path, *glb_parts(json_bytes(doc, sort_keys=False), binary or b""))
    else:
        if binary is not None:
            doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bytes(binary)).decode()
            doc["buffers"][0]["byteLength"] = len(binary)
        write_file(path, json_bytes(doc, indent=1, sort_keys=False))


def accessor_bytes(doc, binary, index):
    """The bytes of a tightly packed accessor (animation data is)."""
    a = doc["accessors"][index]
    view = doc["bufferViews"][a["bufferView"]]
    start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
    size = COMPONENTS[a["type"]] * SIZES[a["componentType"]]
    assert view.get("byteStride", size) == size
    return bytes(binary[start:start + a["count"] * size])


def copy_accessor(b, index, data=None):
    """A new accessor with the same fields as `index`, in a new bufferView holding `data` (default: the
    same bytes)."""
    a = copy.deepcopy(b.doc["accessors"][index])
    a["bufferView"] = b.view(accessor_bytes(b.doc, b.buffer, index) if data is None else data)
    a.pop("byteOffset", None)
    return b.add("accessors", a)


def add_channel(b, animation, node, path, sampler, output=None):
    """A channel for node/path in `animation` with a new sampler like `sampler` (its keys copied into
    accessors of their own; `output` replaces the output's bytes)."""
    s = animation["samplers"][sampler]
    new_sampler = {"input": copy_accessor(b, s["input"]), "output": copy_accessor(b, s["output"], output)}
    if "interpolation" in s:
        new_sampler["interpolation"] = s["interpolation"]
    animation["samplers"].append(new_sampler)
    animation["channels"].append({"sampler": len(animation["samplers"]) - 1, "target": {"node": node, "path": path}})


def reversed_keys(doc, binary, accessor):
    a = doc["accessors"][accessor]
    size = COMPONENTS[a["type"]] * SIZES[a["componentType"]]
    data = accessor_bytes(doc, binary, accessor)
    return b"".join(data[k * size:(k + 1) * size] for k in reversed(range(a["count"])))


def float_accessor(b, values, element_type, bounds=False):
    a = {"bufferView": b.view(struct.pack("<%df" % len(values), *values)), "componentType": FLOAT,
         "count": len(values) // COMPONENTS[element_type], "type": element_type}
    if bounds:
        a["min"], a["max"] = [min(values)], [max(values)]
    return b.add("accessors", a)


def pointer_channel(sampler, pointer):
    return {"sampler": sampler, "target": {"path": "pointer", "extensions": {EXTENSION: {"pointer": pointer}}}}


def cases(outdir, testdata):
    os.makedirs(outdir, exist_ok=True)
    source = os.path.join(testdata, "twisted_cylinder.gltf")
    doc, binary, _ = read_model(source)
    (channel,) = doc["animations"][0]["channels"]
    node, path, sampler = channel["target"]["node"], channel["target"]["path"], channel["sampler"]
    output = doc["animations"][0]["samplers"][sampler]["output"]

    b = Builder(doc=copy.deepcopy(doc), buffer=bytearray(binary), sort_keys=False)
    for _ in range(14):
        add_channel(b, b.doc["animations"][0], node, path, sampler)
    write_model(os.path.join(outdir, "dup_identical.gltf"), b.doc, b.buffer, False)

    different = reversed_keys(doc, binary, output)
    assert different != accessor_bytes(doc, binary, output)
    b = Builder(doc=copy.deepcopy(doc), buffer=bytearray(binary), sort_keys=False)
    add_channel(b, b.doc["animations"][0], node, path, sampler, different)
    write_model(os.path.join(outdir, "dup_different.gltf"), b.doc, b.buffer, False)

    b = Builder(doc=copy.deepcopy(doc), buffer=bytearray(binary), sort_keys=False)
    b.doc["animations"][0]["samplers"][sampler]["output"] = copy_accessor(b, output, different)
    write_model(os.path.join(outdir, "dup_second_kept.gltf"), b.doc, b.buffer, False)

    # A material's base color and a camera's field of view: glTF properties dqskin does not deform.
    b = Builder(doc=copy.deepcopy(doc), buffer=bytearray(binary), sort_keys=False)
    d = b.doc
    d["materials"] = [{"name": "paint", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1]}}]
    for mesh in d["meshes"]:
        for primitive in mesh["primitives"]:
            primitive["material"] = 0
    d["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}]
    d["nodes"].append({"name": "camera", "camera": 0, "translation": [0, 1, 6]})
    d["scenes"][d.get("scene", 0)]["nodes"].append(len(d["nodes"]) - 1)
    times = float_accessor(b, [0.0, 1.0], "SCALAR", bounds=True)
    colors = float_accessor(b, [1, 1, 1, 1, 1, 0, 0, 1], "VEC4")
    fovs = float_accessor(b, [0.8, 0.4], "SCALAR")
    twist = d["animations"][0]
    twist["samplers"] += [{"input": times, "output": colors}, {"input": times, "output": fovs}]
    twist["channels"] += [pointer_channel(len(twist["samplers"]) - 2, "/materials/0/pbrMetallicRoughness/baseColorFactor"),
                          pointer_channel(len(twist["samplers"]) - 1, "/cameras/0/perspective/yfov")]
    d["animations"].append({"name": "zoom", "samplers": [{"input": times, "output": fovs}],
                            "channels": [pointer_channel(0, "/cameras/0/perspective/yfov")]})
    d["extensionsUsed"] = [EXTENSION]
    write_model(os.path.join(outdir, "pointer_ignored.gltf"), d, b.buffer, False)
    print("make_animation_cases: 4 cases in %s" % outdir)


def pointer_copy(source, target, mesh_weights):
    with open(source, "rb") as f:
        glb = f.read(4) == b"glTF"
    if glb:
        doc, binary, _ = read_model(source)
    else:  # the JSON is rewritten, the data URIs kept as they are
        with open(source, "rb") as f:
            doc, binary = json.load(f), None
        for item in doc.get("buffers", []) + doc.get("images", []):
            if "uri" in item and not item["uri"].startswith("data:"):
                sys.exit("make_animation_cases: %s: %s is an external file" % (source, item["uri"]))
    nodes = doc.get("nodes", [])
    drawn_by = {}
    for n, node in enumerate(nodes):
        if "mesh" in node:
            drawn_by.setdefault(node["mesh"], []).append(n)
    rewritten = 0
    for animation in doc.get("animations", []):
        for channel in animation.get("channels", []):
            t = channel.get("target", {})
            if "node" not in t:
                continue
            node = t.pop("node")
            pointer = "/nodes/%d/%s" % (node, t["path"])
            mesh = nodes[node].get("mesh")
            if (mesh_weights and t["path"] == "weights" and "weights" not in nodes[node]
                    and drawn_by.get(mesh) == [node]):
                pointer = "/meshes/%d/weights" % mesh
            t["path"] = "pointer"
            t.setdefault("extensions", {})[EXTENSION] = {"pointer": pointer}
            rewritten += 1
    if rewritten == 0:
        sys.exit("make_animation_cases: %s has no channel to rewrite" % source)
    for key in ("extensionsUsed", "extensionsRequired"):
        if EXTENSION not in doc.setdefault(key, []):
            doc[key].append(EXTENSION)
    write_model(target, doc, binary, glb)
    print("make_animation_cases: %d channels rewritten" % rewritten)


def main():
    args = sys.argv[1:]
    if len(args) == 3 and args[0] == "cases":
        cases(args[1], args[2])
    elif len(args) in (3, 4) and args[0] == "pointer-copy" and args[3:] in ([], ["--mesh-weights"]):
        pointer_copy(args[1], args[2], args[3:] == ["--mesh-weights"])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
