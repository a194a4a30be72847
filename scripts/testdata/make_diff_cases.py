#!/usr/bin/env python3
"""Makes the inputs of the geometry diff tests (app/tests/geometry_diff.cmake) from an existing glTF file.

Usage:
  make_diff_cases.py copy IN OUT
  make_diff_cases.py rotate-key IN OUT --joint NAME [--clip NAME|INDEX] [--key K] [--degrees D] [--axis x|y|z]
  make_diff_cases.py permute IN OUT [--seed S]
  make_diff_cases.py translate IN OUT --by X Y Z
  (every command also takes --external: a .gltf OUT gets its buffer in OUT's name with .bin, not embedded)

IN and OUT are .glb or .gltf (buffers embedded as data: URIs or in files beside it); OUT's extension chooses
the container. Every command reads IN and writes OUT through the same code, which joins all buffers into one
and embeds external images, so `copy` is "the same file without the change" that the other commands make:

  copy        the file rewritten, nothing else changed.
  rotate-key  ONE key of the rotation channel of node NAME (in clip NAME or INDEX; default the first clip
              that animates it) turned by D degrees (default 5) about the joint's local x, y or z axis
              (q' = q * axis-angle, renormalized): a defect of one joint at one time. K is the key's index
              (default the middle one). Float and normalized-integer outputs (KHR_mesh_quantization) are
              both handled; of a CUBICSPLINE key only the value turns, its tangents stay. When the output
              accessor's bytes are shared with another accessor, or the sampler with another channel, the
              channel gets a private copy first, so that only that key changes. Prints
              "clip <name> joint <name> key <K> t = <seconds> s".
  permute     the same surface in another order: in every mesh primitive the vertices (every attribute and
              morph target attribute) are permuted with a seeded random permutation, the indices remapped
              (a non-indexed primitive becomes indexed), each triangle's corners rotated (a,b,c)->(b,c,a)
              (the winding stays) and the triangles shuffled. New accessors per primitive (sparse ones
              become dense); POSITION gets its min/max from the new data.
  translate   every root node of every scene moved by (X, Y, Z) in its parent's (the scene's) frame; a
              root whose translation is animated has every key of that channel moved.

Refused, with a message: EXT_meshopt_compression (its bufferViews point into buffers that the joining would
move); permute also refuses KHR_draco_mesh_compression primitives.
Python 3 standard library only (and scripts/testdata/gltf_builder.py, for the container).
"""

import argparse
import base64
import json
import math
import os
import random
import struct
import sys
import urllib.parse

from gltf_builder import data_uri, glb_parts, json_bytes, write_file

BYTE, UNSIGNED_BYTE, SHORT, UNSIGNED_SHORT, UNSIGNED_INT, FLOAT = 5120, 5121, 5122, 5123, 5125, 5126
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
FORMAT = {BYTE: "b", UNSIGNED_BYTE: "B", SHORT: "h", UNSIGNED_SHORT: "H", UNSIGNED_INT: "I", FLOAT: "f"}
SIZE = {BYTE: 1, UNSIGNED_BYTE: 1, SHORT: 2, UNSIGNED_SHORT: 2, UNSIGNED_INT: 4, FLOAT: 4}
COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT2": 4, "MAT3": 9, "MAT4": 16}
# The largest value of each normalized integer type (glTF 2.0 §3.11: c / max, at least -1 for signed types).
NORM_MAX = {BYTE: 127, UNSIGNED_BYTE: 255, SHORT: 32767, UNSIGNED_SHORT: 65535}
IMAGE_TYPES = {".png": "image/png", ".jpg": "image/jpeg", ".jpeg": "image/jpeg", ".webp": "image/webp",
               ".ktx2": "image/ktx2"}


class CaseError(Exception):
    """What is wrong with the input or the request: printed as one line, exit status 2."""


# -- reading and writing ----------------------------------------------------------------------------------

def read_uri(uri, folder):
    """The bytes of a data: URI or of a file relative to `folder`."""
    if uri.startswith("data:"):
        header, _, payload = uri.partition(",")
        if not header.endswith(";base64"):
            raise CaseError("data: URI without base64 encoding")
        return base64.b64decode(payload)
    path = os.path.join(folder, urllib.parse.unquote(uri))
    try:
        with open(path, "rb") as f:
            return f.read()
    except OSError as e:
        raise CaseError("%s: %s" % (path, e.strerror))


class Model:
    """A glTF document whose buffers are joined into one: doc (the JSON, as a dict, its key order kept) and
    data (buffer 0's bytes). Every bufferView points into buffer 0, and every image is a bufferView."""

    def __init__(self, path):
        with open(path, "rb") as f:
            raw = f.read()
        folder = os.path.dirname(path)
        glb_bin = None
        if raw[:4] == b"glTF":
            magic, version, length = struct.unpack_from("<4sII", raw, 0)
            if version != 2 or length > len(raw):
                raise CaseError("not a glTF 2.0 binary")
            offset, chunks = 12, []
            while offset + 8 <= length:
                size, kind = struct.unpack_from("<I4s", raw, offset)
                chunks.append((kind, raw[offset + 8:offset + 8 + size]))
                offset += 8 + size
            if not chunks or chunks[0][0] != b"JSON":
                raise CaseError("the first chunk is not JSON")
            doc = json.loads(chunks[0][1])
            if len(chunks) > 1 and chunks[1][0] == b"BIN\0":
                glb_bin = chunks[1][1]
        else:
            doc = json.loads(raw)
        self.doc = doc
        used = doc.get("extensionsUsed", [])
        if "EXT_meshopt_compression" in used or "KHR_meshopt_compression" in used:
            raise CaseError("meshopt-compressed files are not supported (decompress it first)")

        buffers = []
        for i, b in enumerate(doc.get("buffers", [])):
            if "uri" in b:
                buffers.append(read_uri(b["uri"], folder))
            elif i == 0 and glb_bin is not None:
                buffers.append(glb_bin)
            else:
                raise CaseError("buffer %d has no data" % i)
            if len(buffers[-1]) < b["byteLength"]:
                raise CaseError("buffer %d is shorter than its byteLength" % i)

        # One buffer: every bufferView's bytes in order, each 8-byte aligned (more than any component needs).
        data = bytearray()
        for v in doc.get("bufferViews", []):
            if v.get("extensions"):
                raise CaseError("bufferView extensions (%s) are not supported" % ", ".join(v["extensions"]))
            start = v.get("byteOffset", 0)
            chunk = buffers[v["buffer"]][start:start + v["byteLength"]]
            data += b"\0" * (-len(data) % 8)
            v["buffer"], v["byteOffset"] = 0, len(data)
            data += chunk
        self.data = data
        views = doc.setdefault("bufferViews", [])
        for image in doc.get("images", []):
            if "uri" in image:
                uri = image.pop("uri")
                if uri.startswith("data:"):
                    mime = uri[5:].split(";")[0].split(",")[0]
                else:
                    mime = IMAGE_TYPES.get(os.path.splitext(urllib.parse.unquote(uri))[1].lower())
                image.setdefault("mimeType", mime or "image/png")
                image["bufferView"] = self.add_view(read_uri(uri, folder))
        if not views:
            del doc["bufferViews"]
        doc["buffers"] = [{"byteLength": 0}] if data or views else []
        if not doc["buffers"]:
            del doc["buffers"]

    def add_view(self, chunk, target=None, stride=None):
        """Appends `chunk` to buffer 0 as a new bufferView; returns its index."""
        self.data += b"\0" * (-len(self.data) % 8)
        view = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(chunk)}
        if stride is not None:
            view["byteStride"] = stride
        if target is not None:
            view["target"] = target
        self.data += chunk
        views = self.doc.setdefault("bufferViews", [])
        views.append(view)
        if "buffers" not in self.doc:
            self.doc["buffers"] = [{"byteLength": 0}]
        return len(views) - 1

    def write(self, path, external=False):
        self.data += b"\0" * (-len(self.data) % 4)
        doc = self.doc
        if doc.get("buffers"):
            doc["buffers"][0]["byteLength"] = len(self.data)
            doc["buffers"][0].pop("uri", None)
        if path.lower().endswith(".glb"):
            write_file(path, *glb_parts(json_bytes(doc, sort_keys=False), self.data))
            return
        if doc.get("buffers"):
            if external:
                name = os.path.splitext(os.path.basename(path))[0] + ".bin"
                write_file(os.path.join(os.path.dirname(path), name), self.data)
                doc["buffers"][0]["uri"] = urllib.parse.quote(name)
            else:
                doc["buffers"][0]["uri"] = data_uri(self.data)
        write_file(path, json_bytes(doc, sort_keys=False))

    # -- accessors ---------------------------------------------------------------------------------------

    def read(self, index):
        """Accessor `index`'s elements as a list of tuples of the stored numbers (integers stay integers,
        normalized or not), with sparse substitution applied."""
        a = self.doc["accessors"][index]
        n, ctype, count = COMPONENTS[a["type"]], a["componentType"], a["count"]
        fmt, size = "<%d%s" % (n, FORMAT[ctype]), n * SIZE[ctype]
        if "bufferView" in a:
            view = self.doc["bufferViews"][a["bufferView"]]
            stride = view.get("byteStride") or size
            base = view["byteOffset"] + a.get("byteOffset", 0)
            values = [struct.unpack_from(fmt, self.data, base + i * stride) for i in range(count)]
        else:
            values = [(0,) * n] * count
        sparse = a.get("sparse")
        if sparse:
            iv, vv = sparse["indices"], sparse["values"]
            ifmt = "<" + FORMAT[iv["componentType"]]
            ibase = self.doc["bufferViews"][iv["bufferView"]]["byteOffset"] + iv.get("byteOffset", 0)
            vbase = self.doc["bufferViews"][vv["bufferView"]]["byteOffset"] + vv.get("byteOffset", 0)
            for k in range(sparse["count"]):
                i = struct.unpack_from(ifmt, self.data, ibase + k * SIZE[iv["componentType"]])[0]
                values[i] = struct.unpack_from(fmt, self.data, vbase + k * size)
        return values

    def byte_ranges(self, index):
        """The [start, end) ranges of buffer 0 that accessor `index` reads."""
        a = self.doc["accessors"][index]
        views = self.doc["bufferViews"]
        size = COMPONENTS[a["type"]] * SIZE[a["componentType"]]
        ranges = []
        if "bufferView" in a and a["count"]:
            view = views[a["bufferView"]]
            stride = view.get("byteStride") or size
            start = view["byteOffset"] + a.get("byteOffset", 0)
            ranges.append((start, start + stride * (a["count"] - 1) + size))
        sparse = a.get("sparse")
        if sparse:
            for part, element in (("indices", SIZE[sparse["indices"].get("componentType", UNSIGNED_INT)]),
                                  ("values", size)):
                p = sparse[part]
                start = views[p["bufferView"]]["byteOffset"] + p.get("byteOffset", 0)
                ranges.append((start, start + element * sparse["count"]))
        return ranges

    def add_accessor(self, values, like, target=None, bounds=False):
        """A new dense accessor holding `values` (tuples of stored numbers) with the type, component type and
        normalization of accessor dict `like`, in its own bufferView; returns its index. Vertex attribute
        elements are padded to 4 bytes (glTF 2.0 §3.6.2.4) with a byteStride. bounds: min and max computed
        from the values; otherwise like's min/max are kept when it has them (the values are the same set)."""
        n, ctype = COMPONENTS[like["type"]], like["componentType"]
        size = n * SIZE[ctype]
        stride = size + (-size % 4) if target == ARRAY_BUFFER else size
        fmt = "<%d%s" % (n, FORMAT[ctype])
        chunk = bytearray(stride * len(values))
        for i, v in enumerate(values):
            struct.pack_into(fmt, chunk, i * stride, *v)
        accessor = {"bufferView": self.add_view(bytes(chunk), target, stride if stride != size else None),
                    "componentType": ctype, "count": len(values), "type": like["type"]}
        if like.get("normalized"):
            accessor["normalized"] = True
        if bounds:
            accessor["min"] = [min(v[c] for v in values) for c in range(n)]
            accessor["max"] = [max(v[c] for v in values) for c in range(n)]
        elif "min" in like and "max" in like and "sparse" not in like:
            accessor["min"], accessor["max"] = like["min"], like["max"]
        for key in ("name", "extras"):
            if key in like:
                accessor[key] = like[key]
        accessors = self.doc.setdefault("accessors", [])
        accessors.append(accessor)
        return len(accessors) - 1

    def write_element(self, index, i, element):
        """Overwrites element i of dense accessor `index` in place."""
        a = self.doc["accessors"][index]
        n, ctype = COMPONENTS[a["type"]], a["componentType"]
        view = self.doc["bufferViews"][a["bufferView"]]
        stride = view.get("byteStride") or n * SIZE[ctype]
        struct.pack_into("<%d%s" % (n, FORMAT[ctype]), self.data,
                         view["byteOffset"] + a.get("byteOffset", 0) + i * stride, *element)

    def refresh_bounds(self, index):
        """Recomputes accessor `index`'s min and max from its values, when it has them."""
        a = self.doc["accessors"][index]
        if "min" in a and "max" in a:
            values = self.read(index)
            a["min"] = [min(v[c] for v in values) for c in range(len(values[0]))]
            a["max"] = [max(v[c] for v in values) for c in range(len(values[0]))]

    # -- references ---------------------------------------------------------------------------------------

    def accessor_users(self):
        """Every place that names an accessor, as (container, key) pairs: container[key] is the index."""
        doc, users = self.doc, []
        for mesh in doc.get("meshes", []):
            for p in mesh["primitives"]:
                users += [(p["attributes"], k) for k in p["attributes"]]
                if "indices" in p:
                    users.append((p, "indices"))
                for t in p.get("targets", []):
                    users += [(t, k) for k in t]
        for skin in doc.get("skins", []):
            if "inverseBindMatrices" in skin:
                users.append((skin, "inverseBindMatrices"))
        for anim in doc.get("animations", []):
            for s in anim["samplers"]:
                users += [(s, "input"), (s, "output")]
        for node in doc.get("nodes", []):
            inst = node.get("extensions", {}).get("EXT_mesh_gpu_instancing")
            if inst:
                users += [(inst["attributes"], k) for k in inst["attributes"]]
        return users

    def drop_unused(self, candidates):
        """Removes the accessors in `candidates` that nothing names any more, then the bufferViews that only
        they used, and renumbers the rest."""
        users = self.accessor_users()
        named = {c[k] for c, k in users}
        accessors = self.doc.get("accessors", [])
        dead = {i for i in candidates if i not in named}
        if not dead:
            return
        views_of_dead = set()
        for i in dead:
            a = accessors[i]
            if "bufferView" in a:
                views_of_dead.add(a["bufferView"])
            for part in ("indices", "values"):
                if a.get("sparse"):
                    views_of_dead.add(a["sparse"][part]["bufferView"])
        new_index, kept = {}, []
        for i, a in enumerate(accessors):
            if i not in dead:
                new_index[i] = len(kept)
                kept.append(a)
        self.doc["accessors"] = kept
        for c, k in users:
            c[k] = new_index[c[k]]
        # bufferViews: named by accessors, sparse parts and images.
        view_users = []
        for a in kept:
            if "bufferView" in a:
                view_users.append((a, "bufferView"))
            if a.get("sparse"):
                view_users += [(a["sparse"]["indices"], "bufferView"), (a["sparse"]["values"], "bufferView")]
        for image in self.doc.get("images", []):
            if "bufferView" in image:
                view_users.append((image, "bufferView"))
        for mesh in self.doc.get("meshes", []):  # Draco's data, which only copy and rotate-key keep
            for p in mesh["primitives"]:
                draco = p.get("extensions", {}).get("KHR_draco_mesh_compression")
                if draco:
                    view_users.append((draco, "bufferView"))
        still = {c[k] for c, k in view_users}
        dead_views = {v for v in views_of_dead if v not in still}
        if not dead_views:
            return
        old_views, new_view, views = self.doc["bufferViews"], {}, []
        data = bytearray()
        for i, v in enumerate(old_views):  # repack, so that the dropped bytes leave the file too
            if i in dead_views:
                continue
            new_view[i] = len(views)
            chunk = self.data[v["byteOffset"]:v["byteOffset"] + v["byteLength"]]
            data += b"\0" * (-len(data) % 8)
            v["byteOffset"] = len(data)
            data += chunk
            views.append(v)
        self.doc["bufferViews"], self.data = views, data
        for c, k in view_users:
            c[k] = new_view[c[k]]


# -- numbers ------------------------------------------------------------------------------------------------

def decode(element, accessor):
    """Stored numbers → floats (normalized integers divided by their type's maximum, at least -1)."""
    if not accessor.get("normalized"):
        return [float(x) for x in element]
    m = NORM_MAX[accessor["componentType"]]
    return [max(x / m, -1.0) for x in element]


def encode(values, accessor):
    """Floats → stored numbers of the accessor's type (rounded to float32, or to the nearest integer step)."""
    ctype = accessor["componentType"]
    if ctype == FLOAT:
        return tuple(struct.unpack("<f", struct.pack("<f", v))[0] for v in values)
    if not accessor.get("normalized"):
        raise CaseError("accessor with non-normalized integers cannot hold these values")
    m = NORM_MAX[ctype]
    low = 0 if ctype in (UNSIGNED_BYTE, UNSIGNED_SHORT) else -m
    return tuple(min(max(int(round(v * m)), low), m) for v in values)


def quat_mul(a, b):
    """Hamilton product of quaternions given as (x, y, z, w)."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz)


# -- commands -----------------------------------------------------------------------------------------------

def find_node(model, name):
    matches = [i for i, n in enumerate(model.doc.get("nodes", [])) if n.get("name") == name]
    if not matches:
        raise CaseError("no node is named %r" % name)
    if len(matches) > 1:
        raise CaseError("%d nodes are named %r" % (len(matches), name))
    return matches[0]


def private_output(model, anim, channel):
    """Makes channel's sampler and its output accessor the channel's own (copies where another channel shares
    the sampler, another sampler the accessor, or another accessor its bytes); returns the sampler."""
    sampler = anim["samplers"][channel["sampler"]]
    if sum(1 for c in anim["channels"] if c["sampler"] == channel["sampler"]) > 1:
        anim["samplers"].append(dict(sampler))
        channel["sampler"] = len(anim["samplers"]) - 1
        sampler = anim["samplers"][-1]
    out = sampler["output"]
    users = sum(1 for a in model.doc["animations"] for s in a["samplers"] if s["output"] == out)
    ranges = model.byte_ranges(out)
    shared_bytes = any(s < e2 and s2 < e
                       for j in range(len(model.doc["accessors"])) if j != out
                       for s2, e2 in model.byte_ranges(j) for s, e in ranges)
    if users > 1 or shared_bytes or "sparse" in model.doc["accessors"][out] or \
            "bufferView" not in model.doc["accessors"][out]:
        like = model.doc["accessors"][out]
        sampler["output"] = model.add_accessor(model.read(out), like)
        model.drop_unused([out])  # only when nothing else names it
    return sampler


def cmd_rotate_key(model, args):
    doc = model.doc
    node = find_node(model, args.joint)
    animations = doc.get("animations", [])

    def channel_of(anim):
        found = [c for c in anim["channels"] if c["target"].get("node") == node and c["target"]["path"] == "rotation"]
        return found[0] if found else None

    if args.clip is None:
        candidates = [i for i, a in enumerate(animations) if channel_of(a)]
        if not candidates:
            raise CaseError("no clip animates the rotation of %r" % args.joint)
        clip = candidates[0]
    elif args.clip.isdigit():
        clip = int(args.clip)
        if clip >= len(animations):
            raise CaseError("clip %d: the file has %d clips" % (clip, len(animations)))
    else:
        named = [i for i, a in enumerate(animations) if a.get("name") == args.clip]
        if len(named) != 1:
            raise CaseError("%d clips are named %r" % (len(named), args.clip))
        clip = named[0]
    anim = animations[clip]
    channel = channel_of(anim)
    if channel is None:
        raise CaseError("clip %s does not animate the rotation of %r" % (anim.get("name", clip), args.joint))
    sampler = private_output(model, anim, channel)
    times = model.read(sampler["input"])
    key = len(times) // 2 if args.key is None else args.key
    if not 0 <= key < len(times):
        raise CaseError("key %d: the channel has %d keys" % (key, len(times)))
    out_accessor = doc["accessors"][sampler["output"]]
    # CUBICSPLINE stores (in-tangent, value, out-tangent) per key: the value is the middle one.
    element = key * 3 + 1 if sampler.get("interpolation") == "CUBICSPLINE" else key
    q = decode(model.read(sampler["output"])[element], out_accessor)
    half = math.radians(args.degrees) / 2
    axis = {"x": (1, 0, 0), "y": (0, 1, 0), "z": (0, 0, 1)}[args.axis]
    turn = tuple(c * math.sin(half) for c in axis) + (math.cos(half),)
    r = quat_mul(q, turn)
    norm = math.sqrt(sum(c * c for c in r))
    model.write_element(sampler["output"], element, encode([c / norm for c in r], out_accessor))
    model.refresh_bounds(sampler["output"])
    # An unnamed clip is called what dqskin calls it (lib/load/load.cpp): "animation<index>".
    name = anim.get("name") or "animation%d" % clip
    print("clip %s joint %s key %d t = %.9g s" % (name, args.joint, key, times[key][0]))


def cmd_permute(model, args):
    rng = random.Random(args.seed)
    doc = model.doc
    replaced = set()
    for mesh in doc.get("meshes", []):
        for p in mesh["primitives"]:
            if "KHR_draco_mesh_compression" in p.get("extensions", {}):
                raise CaseError("Draco-compressed primitives are not supported (decompress the file first)")
            attrs = p["attributes"]
            if "POSITION" not in attrs:
                raise CaseError("a primitive has no POSITION")
            n = doc["accessors"][attrs["POSITION"]]["count"]
            order = list(range(n))  # new vertex i is old vertex order[i]
            rng.shuffle(order)
            new_of = [0] * n
            for new, old in enumerate(order):
                new_of[old] = new

            def permuted(semantic, index):
                like = doc["accessors"][index]
                values = model.read(index)
                if len(values) != n:
                    raise CaseError("attribute %s has %d elements, POSITION %d" % (semantic, len(values), n))
                replaced.add(index)
                return model.add_accessor([values[old] for old in order], like, ARRAY_BUFFER,
                                          bounds=(semantic == "POSITION"))

            for semantic in list(attrs):
                attrs[semantic] = permuted(semantic, attrs[semantic])
            for target in p.get("targets", []):
                for semantic in list(target):
                    target[semantic] = permuted(semantic, target[semantic])

            if "indices" in p:
                replaced.add(p["indices"])
                indices = [v[0] for v in model.read(p["indices"])]
            else:
                indices = list(range(n))
            remapped = [new_of[i] for i in indices]
            if p.get("mode", 4) == 4:
                if len(remapped) % 3:
                    raise CaseError("a triangle list of %d indices" % len(remapped))
                triangles = [(remapped[i + 1], remapped[i + 2], remapped[i])
                             for i in range(0, len(remapped), 3)]
                rng.shuffle(triangles)
                remapped = [i for t in triangles for i in t]
            ctype = UNSIGNED_SHORT if n <= 65535 else UNSIGNED_INT  # 65535 itself is the restart value
            p["indices"] = model.add_accessor([(i,) for i in remapped],
                                              {"type": "SCALAR", "componentType": ctype}, ELEMENT_ARRAY_BUFFER)
    model.drop_unused(replaced)


def cmd_translate(model, args):
    doc = model.doc
    nodes = doc.get("nodes", [])
    children = {c for n in nodes for c in n.get("children", [])}
    roots = sorted({r for s in doc.get("scenes", []) for r in s.get("nodes", [])} |
                   {i for i in range(len(nodes)) if i not in children})
    by, moved_nodes = args.by, []
    for r in roots:
        node = nodes[r]
        if "skin" in node and not node.get("children"):
            continue  # a skinned mesh's node transform moves nothing (glTF 2.0 §3.7.3.3); its joints do
        moved_nodes.append(node.get("name", str(r)))
        if "matrix" in node:  # column-major: the translation is elements 12..14
            node["matrix"] = [v + by[i - 12] if 12 <= i < 15 else v for i, v in enumerate(node["matrix"])]
            continue
        t = node.get("translation", [0.0, 0.0, 0.0])
        node["translation"] = [t[i] + by[i] for i in range(3)]
        for anim in doc.get("animations", []):
            for channel in anim["channels"]:
                if channel["target"].get("node") == r and channel["target"]["path"] == "translation":
                    sampler = private_output(model, anim, channel)
                    acc = doc["accessors"][sampler["output"]]
                    values = model.read(sampler["output"])
                    tangent = sampler.get("interpolation") == "CUBICSPLINE"
                    moved = []
                    for i, v in enumerate(values):
                        if tangent and i % 3 != 1:
                            moved.append(v)  # tangents are derivatives: a constant offset leaves them
                        else:
                            moved.append(encode([x + by[c] for c, x in enumerate(decode(v, acc))], acc))
                    for i, v in enumerate(moved):
                        model.write_element(sampler["output"], i, v)
                    model.refresh_bounds(sampler["output"])
    if not moved_nodes:
        raise CaseError("no root node to move")
    print("moved %s by %g %g %g" % (", ".join(moved_nodes), *by))


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    commands = parser.add_subparsers(dest="command", required=True)

    def command(name, **kw):
        p = commands.add_parser(name, **kw)
        p.add_argument("input")
        p.add_argument("output")
        p.add_argument("--external", action="store_true",
                       help="a .gltf output gets its buffer in a .bin file beside it, not embedded")
        return p

    command("copy", help="rewrite the file unchanged")
    p = command("rotate-key", help="turn one rotation key of one joint")
    p.add_argument("--joint", required=True, help="name of the animated node")
    p.add_argument("--clip", help="animation name or index (default: the first that animates the joint)")
    p.add_argument("--key", type=int, help="index of the key (default: the middle one)")
    p.add_argument("--degrees", type=float, default=5.0)
    p.add_argument("--axis", choices="xyz", default="x")
    p = command("permute", help="reorder vertices and triangles")
    p.add_argument("--seed", type=int, default=1)
    p = command("translate", help="move the root nodes")
    p.add_argument("--by", type=float, nargs=3, required=True, metavar=("X", "Y", "Z"))
    args = parser.parse_args(argv)
    if os.path.abspath(args.input) == os.path.abspath(args.output):
        parser.error("OUT must differ from IN")
    try:
        model = Model(args.input)
        {"copy": lambda m, a: None, "rotate-key": cmd_rotate_key, "permute": cmd_permute,
         "translate": cmd_translate}[args.command](model, args)
        model.write(args.output, args.external)
    except CaseError as e:
        print("make_diff_cases: %s: %s" % (args.input, e), file=sys.stderr)
        return 2
    except (OSError, ValueError, KeyError, IndexError, struct.error) as e:
        print("make_diff_cases: %s: cannot read it: %s" % (args.input, e), file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
