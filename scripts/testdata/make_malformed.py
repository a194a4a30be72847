#!/usr/bin/env python3
"""Writes the catalogue of malformed glTF inputs that `dqskin info` must reject.

Usage: make_malformed.py OUTDIR

Starts from one small, valid, skinned and animated asset (4 vertices, 2 triangles, NORMAL,
JOINTS_0/WEIGHTS_0, a 2-joint skin with inverseBindMatrices, one clip animating a joint's translation and
rotation) written three ways: valid.gltf (base64 data-URI buffer), valid.glb, valid_external.gltf + .bin.
Every other file breaks exactly one thing. OUTDIR/cases.txt has one line per broken file:

    <file name> TAB <regex>

where the regex (CMake syntax: no \\d, no {n}, no ';') must match the start of the one-line message that
`dqskin info` prints after "dqskin: <path>: ". OUTDIR/valid.txt lists the files that must load: the
three above and valid_deep_hierarchy.gltf (a 200000-node chain that must load within the test timeout).
OUTDIR/undeformable.txt has the same form for files that parse as glTF but cannot be deformed: `info` and
`lint` describe them (the reason under "cannot be deformed", an error of lint), `bake` refuses them in one
line matching the regex. The tests run with OUTDIR/cwd as the current directory (one case checks that a buffer there is ignored).
The last group of cases are inputs the loader mishandles today: their expectations are the correct
behaviour. Only the Python standard library is used (and scripts/testdata/gltf_builder.py); the output is the same on
every run.
"""

import base64
import copy
import json
import math
import os
import shutil
import struct
import sys

from gltf_builder import Builder, data_uri, json_bytes

# glTF constants (glTF 2.0 §5.1.3, §5.24.4).
BYTE, UBYTE, SHORT, USHORT, UINT, FLOAT = 5120, 5121, 5122, 5123, 5125, 5126
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963


class Asset(Builder):
    """A glTF document (dict) and its one binary buffer (bytearray), edited together. Its JSON keeps the
    document's key order (compact, not sorted): some cases edit the text where a key is."""

    def __init__(self, gltf, binary):
        super().__init__(doc=gltf, buffer=binary, sort_keys=False)

    # The names the cases use for Builder's doc and buffer.
    gltf = property(lambda self: self.doc)
    bin = property(lambda self: self.buffer)

    def copy(self):
        return Asset(copy.deepcopy(self.gltf), bytearray(self.bin))

    def add_view(self, data, target=None, stride=None):
        """Builder.view, keeping buffer 0's byteLength right in the document: cases copy it as it is."""
        view = self.view(data, target, stride)
        self.gltf["buffers"][0]["byteLength"] = len(self.bin)
        return view

    def accessor_offset(self, index):
        """Byte offset in the buffer of accessor `index`'s element 0."""
        a = self.gltf["accessors"][index]
        return self.gltf["bufferViews"][a["bufferView"]]["byteOffset"] + a.get("byteOffset", 0)


def floats(values):
    return struct.pack("<%df" % len(values), *values)


def base_asset():
    """The valid asset: a quad skinned to two joints, one clip on the second joint."""
    positions = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)]
    normals = [(0, 0, 1)] * 4
    joints = [(0, 1, 0, 0), (0, 1, 0, 0), (1, 0, 0, 0), (1, 0, 0, 0)]
    weights = [(0.75, 0.25, 0, 0), (0.5, 0.5, 0, 0), (1, 0, 0, 0), (0.25, 0.75, 0, 0)]
    indices = [0, 1, 2, 2, 1, 3]
    # Column-major inverse bind matrices: identity, and translation by (0, -1, 0) (joint 1 rests at y = 1).
    ibm = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
           1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1]
    times = [0.0, 0.5, 1.0]
    translations = [(0, 1, 0), (0.5, 1, 0), (0, 1, 0)]
    s = math.sqrt(0.5)
    rotations = [(0, 0, 0, 1), (0, 0, s, s), (0, 0, 0, 1)]

    a = Asset({
        "asset": {"version": "2.0", "generator": "dqskin scripts/testdata/make_malformed.py"},
        "scene": 0,
        "scenes": [{"name": "scene", "nodes": [0, 1]}],
        "nodes": [
            {"name": "skinned quad", "mesh": 0, "skin": 0},
            {"name": "root joint", "children": [2]},
            {"name": "tip joint", "translation": [0, 1, 0]},
        ],
        "meshes": [{"name": "quad", "primitives": [{
            "attributes": {"POSITION": 0, "NORMAL": 1, "JOINTS_0": 2, "WEIGHTS_0": 3},
            "indices": 4}]}],
        "skins": [{"name": "two joints", "joints": [1, 2], "inverseBindMatrices": 5, "skeleton": 1}],
        "animations": [{"name": "wave",
                        "samplers": [{"input": 6, "output": 7, "interpolation": "LINEAR"},
                                     {"input": 6, "output": 8, "interpolation": "LINEAR"}],
                        "channels": [{"sampler": 0, "target": {"node": 2, "path": "translation"}},
                                     {"sampler": 1, "target": {"node": 2, "path": "rotation"}}]}],
        "buffers": [{"byteLength": 0}],
        "bufferViews": [],
        "accessors": [],
    }, bytearray())

    def attribute(data, type_, ctype, count, **extra):
        view = a.add_view(data, ARRAY_BUFFER)
        return a.add("accessors", dict({"bufferView": view, "componentType": ctype, "count": count, "type": type_},
                                       **extra))

    flat = lambda rows: [x for row in rows for x in row]
    attribute(floats(flat(positions)), "VEC3", FLOAT, 4, min=[0, 0, 0], max=[1, 1, 0])
    attribute(floats(flat(normals)), "VEC3", FLOAT, 4)
    attribute(bytes(flat(joints)), "VEC4", UBYTE, 4)
    attribute(floats(flat(weights)), "VEC4", FLOAT, 4)
    view = a.add_view(struct.pack("<6H", *indices), ELEMENT_ARRAY_BUFFER)
    a.add("accessors", {"bufferView": view, "componentType": USHORT, "count": 6, "type": "SCALAR"})
    for data, type_, count, extra in [(floats(ibm), "MAT4", 2, {}),
                                      (floats(times), "SCALAR", 3, {"min": [0.0], "max": [1.0]}),
                                      (floats(flat(translations)), "VEC3", 3, {}),
                                      (floats(flat(rotations)), "VEC4", 3, {})]:
        view = a.add_view(data)
        a.add("accessors", dict({"bufferView": view, "componentType": FLOAT, "count": count, "type": type_}, **extra))
    return a


# Accessor indices of the base asset.
POSITION, NORMAL, JOINTS, WEIGHTS, INDICES, IBM, TIMES, TRANSLATIONS, ROTATIONS = range(9)


def to_json(gltf):
    """A document as an Asset writes it (compact, in its own key order), for a case that edits a copy."""
    return json_bytes(gltf, sort_keys=False)


class Catalogue:
    def __init__(self, outdir):
        self.outdir = outdir
        self.cases = []  # (file name, regex)
        self.valid = []
        self.warnings = []  # (file name, regex): loads (exit 0), and `info` lists a warning matching regex
        # (file name, regex): parses as glTF, so `info` describes it (exit 0) listing a reason matching regex
        # under "cannot be deformed", `lint` reports it as an error, and `bake` refuses it in one line.
        self.undeformable = []

    def write(self, name, data):
        with open(os.path.join(self.outdir, name), "wb") as f:
            f.write(data)

    def case(self, name, data, regex):
        """A file that must fail with one line matching regex; data None: the caller made the file."""
        assert "\t" not in regex and ";" not in regex and "\n" not in regex, name
        assert regex.count("[") == regex.count("]"), name  # CMake lists keep ';' inside brackets
        stem = os.path.splitext(name)[0]
        assert stem not in [os.path.splitext(c[0])[0] for c in self.cases + self.warnings + self.undeformable], name
        if data is not None:
            self.write(name, data)
        self.cases.append((name, regex))

    def warning(self, name, a, regex):
        """A .gltf that must load, with a warning matching regex (appearance that is dropped)."""
        assert "\t" not in regex and ";" not in regex and "\n" not in regex, name
        assert name not in [os.path.splitext(c[0])[0] for c in self.cases + self.warnings], name
        self.write(name + ".gltf", a.gltf_bytes())
        self.warnings.append((name + ".gltf", regex))

    def undeformable_gltf(self, name, a, regex):
        """A .gltf that info and lint read and the deforming commands refuse, with one line matching regex."""
        assert "\t" not in regex and ";" not in regex and "\n" not in regex, name
        assert regex.count("[") == regex.count("]"), name
        others = self.cases + self.warnings + self.undeformable
        assert name not in [os.path.splitext(c[0])[0] for c in others], name
        self.write(name + ".gltf", a.gltf_bytes())
        self.undeformable.append((name + ".gltf", regex))

    def gltf(self, name, a, regex):
        self.case(name + ".gltf", a.gltf_bytes(), regex)

    def external(self, name, a, regex, bin_data=None, uri=None):
        """A .gltf whose buffer is the file `uri` (default name.bin, written with bin_data or the buffer)."""
        g = a.document(uri if uri is not None else name + ".bin")
        if uri is None:
            self.write(name + ".bin", bytes(a.bin) if bin_data is None else bin_data)
        self.case(name + ".gltf", to_json(g), regex)

    def finish(self):
        with open(os.path.join(self.outdir, "cases.txt"), "w") as f:
            for name, regex in self.cases:
                f.write("%s\t%s\n" % (name, regex))
        with open(os.path.join(self.outdir, "valid.txt"), "w") as f:
            for name in self.valid:
                f.write(name + "\n")
        with open(os.path.join(self.outdir, "warnings.txt"), "w") as f:
            for name, regex in self.warnings:
                f.write("%s\t%s\n" % (name, regex))
        with open(os.path.join(self.outdir, "undeformable.txt"), "w") as f:
            for name, regex in self.undeformable:
                f.write("%s\t%s\n" % (name, regex))


def regex_escape(text):
    """text as a CMake regex that matches it. ';' (CMake's list separator) and square brackets (CMake keeps
    the ';' inside them, so an unbalanced one joins list elements) are matched by '.'; the rest literally."""
    return "".join("\\" + c if c in "(){}.*+?^$|\\" else "." if c in ";[]" else c for c in text)


def set_path(gltf, path, value):
    """gltf[path[0]][path[1]]... = value, creating objects (and one-element arrays) on the way."""
    node = gltf
    for key, following in zip(path, path[1:]):
        if isinstance(node, dict) and key not in node:
            node[key] = [] if isinstance(following, int) else {}
        if isinstance(node, list):
            while len(node) <= key:
                node.append([] if isinstance(following, int) else {})
        node = node[key]
    if isinstance(node, list):
        while len(node) <= path[-1]:
            node.append(None)
    node[path[-1]] = value


def json_text(value):
    """A value as dqskin's messages print it (nlohmann::json::dump): 2.0 keeps its fraction."""
    return json.dumps(value, separators=(",", ":"))


class Bad:
    """What a case writes (`set`, an object holding the bad value) and the bad value its message shows."""

    def __init__(self, set_, shown):
        self.set = set_
        self.shown = shown


INDEX = "an index (an integer from 0 to 2147483647)"
OFFSET = "an integer of at least 0"
COUNT = "an integer of at least 1"


def schema_value_cases(cat, base):
    """One case per rule of lib/load/schema_values.cpp: a value that glTF 2.0's schema forbids and that
    tinygltf would read past (a fraction, a negative number, an index beyond 32 bits that it truncates, a
    string, a value not in the enum). Structure, geometry, skins and animation fail the input with a line
    naming the value; appearance loads with a warning saying what happens instead."""
    def sparse(field, value):
        """A sparse object whose `field` is `value`, and that value (what the message shows)."""
        s = {"count": 1, "indices": {"bufferView": 4, "componentType": USHORT}, "values": {"bufferView": 0}}
        set_path(s, field, value)
        return Bad(s, value)
    # (case name, where, value, message owner and property, what it must be)
    errors = [
        ("scene", ["scene"], 4.5, "scene", INDEX),
        ("scene_node", ["scenes", 0, "nodes", 1], -1, "scene 0: nodes[1]", INDEX),
        ("node_child", ["nodes", 1, "children", 0], 2.0, "node 1: children[0]", INDEX),
        # 2^32 + 0: tinygltf's int truncation would read mesh 0.
        ("node_mesh", ["nodes", 0, "mesh"], 4294967296, "node 0: mesh", INDEX),
        ("node_skin", ["nodes", 0, "skin"], "0", "node 0: skin", INDEX),
        ("attribute", ["meshes", 0, "primitives", 0, "attributes", "NORMAL"], -1,
         "mesh 0 primitive 0: attributes.NORMAL", INDEX),
        ("indices", ["meshes", 0, "primitives", 0, "indices"], 4.5, "mesh 0 primitive 0: indices", INDEX),
        ("mode", ["meshes", 0, "primitives", 0, "mode"], 7, "mesh 0 primitive 0: mode", "an integer from 0 to 6"),
        ("morph_target", ["meshes", 0, "primitives", 0, "targets", 0, "POSITION"], -3,
         "mesh 0 primitive 0: targets[0].POSITION", INDEX),
        # 2^32 + 5: truncated, it would name the real inverseBindMatrices accessor.
        ("inverse_bind_matrices", ["skins", 0, "inverseBindMatrices"], 4294967301, "skin 0: inverseBindMatrices", INDEX),
        ("skeleton", ["skins", 0, "skeleton"], -1, "skin 0: skeleton", INDEX),
        ("joint", ["skins", 0, "joints", 1], 2.5, "skin 0: joints[1]", INDEX),
        ("channel_sampler", ["animations", 0, "channels", 0, "sampler"], -1, "animation 0 channel 0: sampler", INDEX),
        ("channel_node", ["animations", 0, "channels", 1, "target", "node"], 2.0,
         "animation 0 channel 1: target.node", INDEX),
        ("sampler_input", ["animations", 0, "samplers", 0, "input"], -6, "animation 0 sampler 0: input", INDEX),
        ("sampler_output", ["animations", 0, "samplers", 1, "output"], 4294967303, "animation 0 sampler 1: output", INDEX),
        ("accessor_buffer_view", ["accessors", 0, "bufferView"], -1, "accessor 0: bufferView", INDEX),
        ("accessor_byte_offset_minus_12", ["accessors", 0, "byteOffset"], -12, "accessor 0: byteOffset", OFFSET),
        ("accessor_byte_offset_4_5", ["accessors", 0, "byteOffset"], 4.5, "accessor 0: byteOffset", OFFSET),
        ("accessor_component_type", ["accessors", 0, "componentType"], 5126.5, "accessor 0: componentType",
         "one of 5120, 5121, 5122, 5123, 5125, 5126"),
        ("accessor_count", ["accessors", 0, "count"], -4, "accessor 0: count", COUNT),
        ("accessor_normalized", ["accessors", 3, "normalized"], "yes", "accessor 3: normalized", "true or false"),
        ("sparse_count", ["accessors", 0, "sparse"], sparse(["count"], 0), "accessor 0: sparse.count", COUNT),
        ("sparse_indices_view", ["accessors", 0, "sparse"], sparse(["indices", "bufferView"], -1),
         "accessor 0: sparse.indices.bufferView", INDEX),
        ("sparse_indices_offset", ["accessors", 0, "sparse"], sparse(["indices", "byteOffset"], -4),
         "accessor 0: sparse.indices.byteOffset", OFFSET),
        ("sparse_indices_type", ["accessors", 0, "sparse"], sparse(["indices", "componentType"], FLOAT),
         "accessor 0: sparse.indices.componentType", "one of 5121, 5123, 5125"),
        ("sparse_values_view", ["accessors", 0, "sparse"], sparse(["values", "bufferView"], 1.5),
         "accessor 0: sparse.values.bufferView", INDEX),
        ("sparse_values_offset", ["accessors", 0, "sparse"], sparse(["values", "byteOffset"], -8),
         "accessor 0: sparse.values.byteOffset", OFFSET),
        ("view_buffer", ["bufferViews", 0, "buffer"], -1, "bufferView 0: buffer", INDEX),
        ("view_byte_offset", ["bufferViews", 0, "byteOffset"], -4, "bufferView 0: byteOffset", OFFSET),
        ("view_byte_length", ["bufferViews", 0, "byteLength"], 0, "bufferView 0: byteLength", COUNT),
        ("view_byte_stride_minus_12", ["bufferViews", 0, "byteStride"], -12, "bufferView 0: byteStride",
         "a multiple of 4 from 4 to 252"),
        ("view_byte_stride_14", ["bufferViews", 0, "byteStride"], 14, "bufferView 0: byteStride",
         "a multiple of 4 from 4 to 252"),
        ("view_target", ["bufferViews", 0, "target"], 34964, "bufferView 0: target", "one of 34962, 34963"),
        ("image_buffer_view", ["images", 0], Bad({"bufferView": -2, "mimeType": "image/png"}, -2), "image 0: bufferView",
         INDEX),
    ]
    for name, where, value, what, want in errors:
        a = base.copy()
        bad = value if isinstance(value, Bad) else Bad(value, value)
        set_path(a.gltf, where, bad.set)
        cat.gltf("value_" + name, a, regex_escape("%s %s must be %s" % (what, json_text(bad.shown), want)) + "$")
    # Asset.gltf_bytes() writes the buffer's true byteLength; this case replaces it in the text.
    text = base.gltf_bytes().replace(b'"buffers":[{"byteLength":%d' % len(base.bin), b'"buffers":[{"byteLength":-1', 1)
    assert b'"byteLength":-1' in text
    cat.case("value_buffer_byte_length.gltf", text, regex_escape("buffer 0: byteLength -1 must be " + COUNT) + "$")

    appearance = {
        "materials": [{"pbrMetallicRoughness": {}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{}],
        "images": [{"uri": "data:image/png;base64,iVBORw0KGgo=", "mimeType": "image/png"}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.1}}],
    }
    # (case name, where, value, message, consequence)
    warnings = [
        ("node_camera", ["nodes", 0, "camera"], 0.5, "node 0: camera", "the node has no camera"),
        ("node_light", ["nodes", 0, "extensions", "KHR_lights_punctual", "light"], -1,
         "node 0: extensions.KHR_lights_punctual.light", "the node has no light"),
        ("primitive_material", ["meshes", 0, "primitives", 0, "material"], -1, "mesh 0 primitive 0: material",
         "the default material is used"),
        ("variant_material", ["meshes", 0, "primitives", 0, "extensions", "KHR_materials_variants", "mappings", 0],
         Bad({"material": 1.5, "variants": [0]}, 1.5),
         "mesh 0 primitive 0: extensions.KHR_materials_variants.mappings[0].material", "the mapping is ignored"),
        ("variant_variant", ["meshes", 0, "primitives", 0, "extensions", "KHR_materials_variants", "mappings", 0],
         Bad({"material": 0, "variants": [-1]}, -1),
         "mesh 0 primitive 0: extensions.KHR_materials_variants.mappings[0].variants[0]", "the mapping is ignored"),
        ("texture_index", ["materials", 0, "pbrMetallicRoughness", "baseColorTexture"], Bad({"index": -1}, -1),
         "material 0: pbrMetallicRoughness.baseColorTexture.index", "it is drawn without that texture"),
        ("texture_tex_coord", ["materials", 0, "normalTexture"], Bad({"index": 0, "texCoord": 4.5}, 4.5),
         "material 0: normalTexture.texCoord", "it is drawn without that texture"),
        ("texture_transform_tex_coord", ["materials", 0, "emissiveTexture"],
         Bad({"index": 0, "extensions": {"KHR_texture_transform": {"texCoord": -1}}}, -1),
         "material 0: emissiveTexture.extensions.KHR_texture_transform.texCoord", "the transform is ignored"),
        ("extension_texture_index", ["materials", 0, "extensions", "KHR_materials_clearcoat", "clearcoatTexture"],
         Bad({"index": 2.5}, 2.5), "material 0: extensions.KHR_materials_clearcoat.clearcoatTexture.index",
         "it is drawn without that texture"),
        ("texture_source", ["textures", 0, "source"], -1, "texture 0: source", "textures using it are not drawn"),
        ("texture_sampler", ["textures", 0, "sampler"], 2.5, "texture 0: sampler", "the default sampler is used"),
        ("texture_extension_source", ["textures", 0, "extensions", "EXT_texture_webp", "source"], -1,
         "texture 0: extensions.EXT_texture_webp.source", "the extension's image is ignored"),
        ("sampler_mag_filter", ["samplers", 0, "magFilter"], 9728.5, "sampler 0: magFilter",
         "one of 9728, 9729", "the default is used"),
        ("sampler_min_filter", ["samplers", 0, "minFilter"], 1, "sampler 0: minFilter",
         "one of 9728, 9729, 9984, 9985, 9986, 9987", "the default is used"),
        ("sampler_wrap_s", ["samplers", 0, "wrapS"], 0, "sampler 0: wrapS", "one of 33071, 33648, 10497", "REPEAT is used"),
        ("sampler_wrap_t", ["samplers", 0, "wrapT"], "REPEAT", "sampler 0: wrapT", "one of 33071, 33648, 10497",
         "REPEAT is used"),
    ]
    for entry in warnings:
        name, where, value, what = entry[:4]
        want, consequence = (entry[4], entry[5]) if len(entry) == 6 else (INDEX, entry[4])
        a = base.copy()
        a.gltf.update(copy.deepcopy(appearance))
        bad = value if isinstance(value, Bad) else Bad(value, value)
        set_path(a.gltf, where, bad.set)
        cat.warning("value_" + name, a, regex_escape("%s %s must be %s; %s" % (what, json_text(bad.shown), want, consequence)))


def hostile_cases(cat, base, glb, outdir):
    """Files made to attack a loader: reading outside the model's folder, nesting that overflows a
    recursive parser's stack, small files that decode to gigabytes, GLB headers whose sizes underflow,
    text that breaks a terminal line, inputs that are not regular files."""
    # ---- The resource root: external files only from inside the model's folder -----------------------
    outside = "leads outside the model's folder.*dqskin does not read it$"
    for name, uri in [("parent", "../" * 8 + "etc/passwd"),
                      ("percent_encoded", "..%2F" * 8 + "etc%2Fpasswd"),
                      ("percent_encoded_dots", "%2E%2E/" * 8 + "etc/passwd"),
                      ("inside_then_out", "sub/../../" + "../" * 8 + "etc/passwd")]:
        cat.external("buffer_uri_traversal_" + name, base, r"buffer 0 uri '" + regex_escape(uri) + "' " + outside,
                     uri=uri)
    cat.external("buffer_uri_absolute", base, r"buffer 0 uri '/etc/passwd' is an absolute path", uri="/etc/passwd")
    cat.external("buffer_uri_file_scheme", base, r"buffer 0 uri 'file:///etc/passwd' has a scheme",
                 uri="file:///etc/passwd")
    os.symlink("/etc/passwd", os.path.join(outdir, "link_to_passwd.bin"))
    cat.external("buffer_uri_symlink_outside", base,
                 r"buffer 0 uri 'link_to_passwd\.bin' leads outside the model's folder \(to /etc/passwd\)",
                 uri="link_to_passwd.bin")
    os.mkfifo(os.path.join(outdir, "a_fifo.bin"))
    cat.external("buffer_uri_fifo", base, r"buffer 0 uri 'a_fifo\.bin' is a FIFO, not a regular file", uri="a_fifo.bin")
    os.symlink("/dev/zero", os.path.join(outdir, "link_to_dev_zero.bin"))
    cat.external("buffer_uri_symlink_to_device", base, r"buffer 0 uri 'link_to_dev_zero\.bin' leads outside",
                 uri="link_to_dev_zero.bin")
    # An image is appearance: one that leaves the root is not read, with a warning, and the file loads.
    for name, uri, regex in [("traversal", "../" * 8 + "etc/passwd", "leads outside the model's folder"),
                             ("absolute", "/etc/passwd", "is an absolute path"),
                             ("scheme", "https://example.com/t.png", "has a scheme"),
                             ("symlink_outside", "link_to_passwd.bin", "leads outside the model's folder")]:
        g = copy.deepcopy(base.gltf)
        g["images"] = [{"uri": uri}]
        cat.warning("image_uri_" + name, Asset(g, base.bin),
                    r"image 0 uri '" + regex_escape(uri) + "' " + regex + ".*. textures using it are not drawn")

    # ---- Nesting: tinygltf recurses once per level (20000 levels crashed it) -----------------------------
    for depth, fails in [(20000, True), (129, True), (100, False)]:
        g = copy.deepcopy(base.gltf)
        g["asset"]["extras"] = "NESTING"
        text = Asset(g, base.bin).gltf_bytes().replace(b'"NESTING"', b"[" * depth + b"]" * depth)
        if fails:
            cat.case("json_nested_%d_deep.gltf" % depth, text,
                     r"its JSON nests arrays and objects more than 128 deep \(at byte [0-9]+\)$")
        else:
            cat.write("valid_json_nested_%d_deep.gltf" % depth, text)
            cat.valid.append("valid_json_nested_%d_deep.gltf" % depth)
    # Brackets inside strings are not nesting.
    g = copy.deepcopy(base.gltf)
    g["asset"]["copyright"] = "[" * 5000 + "{" * 5000
    cat.write("valid_brackets_in_strings.gltf", Asset(g, base.bin).gltf_bytes())
    cat.valid.append("valid_brackets_in_strings.gltf")

    # ---- Memory in proportion to the file: 3000 primitives share one 1.2 MB accessor (a 1.3 MB file) -------
    a = base.copy()
    count = 100000
    view = a.add_view(bytes(12 * count), ARRAY_BUFFER)
    shared = a.add("accessors", {"bufferView": view, "componentType": FLOAT, "count": count, "type": "VEC3",
                             "min": [0, 0, 0], "max": [0, 0, 0]})
    a.gltf["meshes"].append({"primitives": [{"attributes": {"POSITION": shared}}] * 3000})
    a.gltf["nodes"].append({"mesh": 1})
    a.gltf["scenes"][0]["nodes"].append(len(a.gltf["nodes"]) - 1)
    cat.case("shared_accessor_3000_primitives.glb", a.glb_bytes(),
             r"loading it needs about [0-9.]+ GiB \([0-9.]+ GiB decoded by 30[0-9][0-9] accessor reads, .*\), "
             r"more than --max-memory 2\.00 GiB$")

    # ---- GLB headers whose length is below the 20 bytes of the headers ----------------------------------
    def patched(data, offset, fmt, value):
        d = bytearray(data)
        struct.pack_into(fmt, d, offset, value)
        return bytes(d)
    # A JSON chunk whose length is not a multiple of 4: tinygltf reads the next chunk's header at the
    # unpadded offset.
    cat.case("glb_json_chunk_not_padded.glb", patched(glb, 12, "<I", struct.unpack_from("<I", glb, 12)[0] - 1),
             r"GLB JSON chunk of [0-9]+ bytes is not padded to a multiple of 4$")
    for length in (0, 12, 19):
        cat.case("glb_header_length_%d.glb" % length, patched(glb, 8, "<I", length),
                 r"GLB header gives a length of %d bytes, less than its headers \(20\)$" % length)

    # ---- One clean line: control characters and bytes that are not UTF-8 are escaped ---------------------
    g = copy.deepcopy(base.gltf)
    g["extensionsUsed"] = g["extensionsRequired"] = ["KHR_\x1b[31mevil\nsecond line"]
    cat.case("required_extension_with_escape_and_newline.gltf", Asset(g, base.bin).gltf_bytes(),
             r"requires extension KHR_\\x1b.31mevil\\nsecond line, which dqskin does not support$")
    cat.case("not_utf8.gltf", b'{"asset":{"version":"2.0"},"x":\xff\xfe}', r".*last read: .*\\xff")
    # Found by the fuzzer: a version string with a newline, quoted by the message.
    cat.case("asset_version_with_newline.gltf", b'{"asset":{"version":"2\\n"}}',
             r"asset\.version is 2\\n, but dqskin reads glTF 2\.x$")

    # ---- Inputs that are not regular files: never waited on, never read forever ---------------------------
    os.mkfifo(os.path.join(outdir, "fifo_input.gltf"))
    cat.case("fifo_input.gltf", None, r"is a FIFO, not a regular file$")
    os.symlink("/dev/zero", os.path.join(outdir, "dev_zero_input.glb"))
    cat.case("dev_zero_input.glb", None, r"is a device, not a regular file$")
    os.makedirs(os.path.join(outdir, "folder_input.gltf"))
    cat.case("folder_input.gltf", None, r"is a folder, not a regular file$")


def job_inputs(base, folder):
    """Inputs for the command-line tests of bake, render and diff (app/tests/hardening.cmake): files that load
    but fail a job half-way on the landed code, or that need more than `info` to show a problem.

    huge_skin.gltf        a skin of 70000 joints: its bone texture is wider than any GPU's
    long_names.gltf       two animations named with 254 bytes: the second folder's name gets a suffix
    endless_clip.gltf     a clip whose last key is at 1e30 s
    still_clip.gltf       a clip of one key at 0 s: one frame at any fps
    many_instances.gltf   1000 nodes drawing one mesh of 20000 points: 2e7 vertices a frame
    big_textures.gltf     ten images whose PNG headers declare 8192 x 8192 pixels (2.5 GiB decoded)
    models/shared_texture.gltf and textures/checker.png
                          a model whose image is in a sibling folder (--resource-root)
    truncated_texture.gltf    a model whose PNG texture is cut short
    truncated.png, good.png   a PNG cut short, and a whole one
    fifo.png, zero.png        a FIFO, and a symbolic link to /dev/zero, named as images
    "line\nbreak\x1bc.gltf"   a valid file whose name holds a newline and an escape sequence
    image_traversal.gltf  a textured quad whose image uri is ../../../../../../../../etc/passwd
    """
    os.makedirs(folder)
    os.mkfifo(os.path.join(folder, "fifo.png"))
    os.symlink("/dev/zero", os.path.join(folder, "zero.png"))
    write_file(folder, "line\nbreak\x1bc.gltf", base.gltf_bytes())

    a = base.copy()
    joints = 70000
    first = len(a.gltf["nodes"])
    a.gltf["nodes"][1]["children"] = [2] + list(range(first, first + joints - 2))
    a.gltf["nodes"] += [{} for _ in range(joints - 2)]
    a.gltf["skins"][0]["joints"] = [1, 2] + list(range(first, first + joints - 2))
    del a.gltf["skins"][0]["inverseBindMatrices"]
    write_file(folder, "huge_skin.gltf", a.gltf_bytes())

    a = base.copy()
    a.gltf["animations"].append(copy.deepcopy(a.gltf["animations"][0]))
    for animation in a.gltf["animations"]:
        animation["name"] = "a" * 254
    write_file(folder, "long_names.gltf", a.gltf_bytes())

    a = base.copy()
    struct.pack_into("<f", a.bin, a.accessor_offset(TIMES) + 8, 1e30)
    a.gltf["accessors"][TIMES]["max"] = [1e30]
    write_file(folder, "endless_clip.gltf", a.gltf_bytes())

    a = base.copy()
    for accessor in (TIMES, TRANSLATIONS, ROTATIONS):
        a.gltf["accessors"][accessor]["count"] = 1
    a.gltf["accessors"][TIMES]["max"] = [0.0]
    write_file(folder, "still_clip.gltf", a.gltf_bytes())

    a = base.copy()
    points = 20000
    view = a.add_view(bytes(12 * points), ARRAY_BUFFER)
    accessor = a.add("accessors", {"bufferView": view, "componentType": FLOAT, "count": points, "type": "VEC3",
                               "min": [0, 0, 0], "max": [0, 0, 0]})
    a.gltf["meshes"].append({"primitives": [{"attributes": {"POSITION": accessor}, "mode": 0}]})
    first = len(a.gltf["nodes"])
    a.gltf["nodes"] += [{"mesh": 1} for _ in range(1000)]
    a.gltf["scenes"][0]["nodes"] += list(range(first, first + 1000))
    write_file(folder, "many_instances.gltf", a.gltf_bytes())

    png = tiny_png(8, 8)
    os.makedirs(os.path.join(folder, "models"))
    os.makedirs(os.path.join(folder, "textures"))
    write_file(folder, "textures/checker.png", png)
    write_file(folder, "good.png", png)
    write_file(folder, "truncated.png", png[:len(png) - 20])
    a = textured(base, {"uri": "../textures/checker.png"})
    write_file(folder, "models/shared_texture.gltf", a.gltf_bytes())
    write_file(folder, "image_traversal.gltf", textured(base, {"uri": "../" * 8 + "etc/passwd"}).gltf_bytes())
    image_view = a.add_view(png[:len(png) - 20])
    a = textured(a, {"bufferView": image_view, "mimeType": "image/png"})
    write_file(folder, "truncated_texture.gltf", a.gltf_bytes())

    header_only = png[:33]  # the signature and IHDR, which then declares 8192 x 8192
    header_only = header_only[:16] + struct.pack(">II", 8192, 8192) + header_only[24:]
    a = textured(base, {"uri": data_uri(header_only, "image/png")})
    a.gltf["images"] *= 10
    a.gltf["textures"] = [{"source": i} for i in range(10)]
    write_file(folder, "big_textures.gltf", a.gltf_bytes())


def tiny_png(width, height):
    """An RGB PNG of a checker pattern (only the standard library: zlib and CRC-32)."""
    import zlib

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    rows = b"".join(b"\x00" + b"".join(b"\xff\xff\xff" if (x + y) % 2 else b"\x20\x40\x80" for x in range(width))
                    for y in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def textured(base, image):
    """A copy of base whose quad has TEXCOORD_0 and a material with a base color texture from `image`."""
    a = base.copy()
    uv = a.add_view(floats([0, 0, 1, 0, 0, 1, 1, 1]), ARRAY_BUFFER)
    uv_accessor = a.add("accessors", {"bufferView": uv, "componentType": FLOAT, "count": 4, "type": "VEC2"})
    primitive = a.gltf["meshes"][0]["primitives"][0]
    primitive["attributes"]["TEXCOORD_0"] = uv_accessor
    primitive["material"] = 0
    a.gltf["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    a.gltf["textures"] = [{"source": 0}]
    a.gltf["images"] = [image]
    return a


def write_file(folder, name, data):
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data)


def edit(base, change):
    """A copy of base with change(asset) applied."""
    a = base.copy()
    change(a)
    return a


def meshopt_attributes(data, stride):
    """data compressed as an EXT_meshopt_compression ATTRIBUTES stream (the extension's Appendix A, mode 0),
    every group of 16 byte deltas stored whole (header bits 3): larger than meshoptimizer's encoder makes
    it, and as valid."""
    count = len(data) // stride
    assert count * stride == len(data) and stride % 4 == 0
    block = min((8192 // stride) & ~15, 256)
    out = bytearray([0xA0])
    last = bytearray(data[0:stride])  # the baseline: the first element, stored in the tail
    for start in range(0, count, block):
        n = min(block, count - start)
        groups = (n + 15) // 16
        for k in range(stride):
            header = bytearray((groups + 3) // 4)
            body = bytearray()
            previous = last[k]
            for g in range(groups):
                header[g // 4] |= 3 << (g % 4 * 2)
                for i in range(g * 16, g * 16 + 16):
                    delta = 0  # elements past the block's end: ignored by the decoder
                    if i < n:
                        value = data[(start + i) * stride + k]
                        delta = (value - previous) & 0xFF
                        previous = value
                    body.append((~(delta << 1) if delta & 0x80 else delta << 1) & 0xFF)
            out += header + body
        last = bytearray(data[(start + n - 1) * stride:(start + n) * stride])
    out += bytes(max(32 - stride, 0)) + bytes(data[0:stride])
    return bytes(out)


def meshopt_asset(base, fallback_flag=True):
    """base with every buffer view compressed (ATTRIBUTES, stride: the accessor's element size, else 4)
    into buffer 0, the BIN chunk; the views' uncompressed layout in buffer 1, a fallback without data, as
    gltfpack writes it."""
    a = base.copy()
    g = a.gltf
    sizes = {}
    for acc in g["accessors"]:
        size = {BYTE: 1, UBYTE: 1, SHORT: 2, USHORT: 2}.get(acc["componentType"], 4)
        sizes[acc["bufferView"]] = size * {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}[acc["type"]]
    packed = bytearray()
    fallback_length = 0
    for i, view in enumerate(g["bufferViews"]):
        data = bytes(a.bin[view.get("byteOffset", 0):view.get("byteOffset", 0) + view["byteLength"]])
        stride = sizes[i] if sizes[i] % 4 == 0 else 4
        stream = meshopt_attributes(data, stride)
        packed += bytes(-len(packed) % 4)
        view["extensions"] = {"EXT_meshopt_compression": {
            "buffer": 0, "byteOffset": len(packed), "byteLength": len(stream), "byteStride": stride,
            "count": len(data) // stride, "mode": "ATTRIBUTES"}}
        packed += stream
        fallback_length += -fallback_length % 4
        view["buffer"] = 1
        view["byteOffset"] = fallback_length
        fallback_length += len(data)
    fallback = {"byteLength": fallback_length}
    if fallback_flag:
        fallback["extensions"] = {"EXT_meshopt_compression": {"fallback": True}}
    g["buffers"] = [{"byteLength": 0}, fallback]
    g["extensionsUsed"] = ["EXT_meshopt_compression"]
    g["extensionsRequired"] = ["EXT_meshopt_compression"]
    return Asset(g, packed)


def meshopt_cases(cat, base):
    """EXT_meshopt_compression: two valid files (buffer 1 a fallback with and without the flag: tinygltf
    alone copies the BIN chunk into any GLB buffer without uri) and one broken thing each."""
    cat.write("valid_meshopt.glb", meshopt_asset(base).glb_bytes())
    cat.write("valid_meshopt_placeholder.glb", meshopt_asset(base, fallback_flag=False).glb_bytes())
    cat.valid += ["valid_meshopt.glb", "valid_meshopt_placeholder.glb"]
    ext = lambda a, view: a.gltf["bufferViews"][view]["extensions"]["EXT_meshopt_compression"]
    prefix = "bufferView %d: EXT_meshopt_compression "

    def case(name, change, message):
        a = meshopt_asset(base)
        change(a)
        cat.case("meshopt_%s.glb" % name, a.glb_bytes(), regex_escape(message))

    def truncated(a):
        ext(a, POSITION)["byteLength"] -= 20
    case("truncated", truncated, prefix % POSITION + "data is malformed (ATTRIBUTES decoder error")

    def header(a):
        a.bin[ext(a, POSITION)["byteOffset"]] = 0x50
    case("header_byte", header, prefix % POSITION + "data is malformed (header byte 0x50 does not start ATTRIBUTES data")

    def wrong_mode(a):  # the index view (12 bytes, stride 4) declared as an index sequence
        ext(a, INDICES)["mode"] = "INDICES"
    case("wrong_mode", wrong_mode, prefix % INDICES + "data is malformed (header byte 0xa0 does not start INDICES data")

    def count(a):
        ext(a, POSITION)["count"] = 3
    case("count_mismatch", count, prefix % POSITION + "holds 3 elements of 12 bytes, but the view's byteLength is 48")

    def bad_filter(a):
        ext(a, POSITION)["filter"] = "OCTAHEDRAL"
    case("filter_stride", bad_filter, prefix % POSITION + "filter OCTAHEDRAL does not allow byteStride 12 (4 or 8)")

    def odd_stride(a):
        ext(a, POSITION)["byteStride"] = 6
        ext(a, POSITION)["count"] = 8
    case("stride_6", odd_stride, prefix % POSITION + "byteStride 6 must be a multiple of 4 (up to 256) in ATTRIBUTES mode")

    def unknown_filter(a):
        ext(a, NORMAL)["filter"] = "ZIGZAG"
    case("unknown_filter", unknown_filter, 'bufferView %d: EXT_meshopt_compression.filter "ZIGZAG" must be' % NORMAL)

    def past_buffer(a):
        ext(a, NORMAL)["byteOffset"] = 1 << 20
    case("past_buffer", past_buffer, prefix % NORMAL + "data (offset 1048576")

    def uncompressed_in_fallback(a):
        del a.gltf["bufferViews"][WEIGHTS]["extensions"]
    case("uncompressed_view_in_fallback", uncompressed_in_fallback,
         "bufferView %d: buffer 1 has no data (an EXT_meshopt_compression fallback" % WEIGHTS)

    def source_is_fallback(a):
        ext(a, JOINTS)["buffer"] = 1
    case("source_is_fallback", source_is_fallback, prefix % JOINTS + "buffer 1 has no data")


# The base asset's quad (POSITION, NORMAL, JOINTS_0, WEIGHTS_0 with unique ids 0-3 in that order, the two
# triangles 0 1 2 and 2 1 3) as a KHR_draco_mesh_compression stream: made once with libdraco 1.5.5's
# draco::Encoder (MESH_SEQUENTIAL_ENCODING, no quantization, so the values decode exactly; JOINTS_0 as
# DT_UINT8, the others as DT_FLOAT32), from a draco::Mesh built with AddFace and AddAttribute, and written
# here as base64 so that this script needs no Draco. Its layout (Draco bitstream 2.2): "DRACO", version 2 2,
# encoder type 1 (mesh), method 0 (sequential), flags 0 0; then the connectivity: varints faces (2) and
# points (4) at offsets 11 and 12, method 1 (raw) and the six indices as bytes; then the attributes.
DRACO_QUAD = base64.b64decode(
    "RFJBQ08CAgEAAAACBAEAAQICAQMBBAAJAwAAAQkDAAEEAgQAAgQJBAADAAABAAAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAA"
    "AIA/AAAAAAAAgD8AAIA/AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAACAPwAAAAAAAAAAAACAPwAAAAAAAAAAAACAPwABAQACAwFA"
    "AQACAwAAAAABAAAAAABAPwAAgD4AAAAAAAAAAAAAAD8AAAA/AAAAAAAAAAAAAIA/AAAAAAAAAAAAAAAAAACAPgAAQD8AAAAAAAAA"
    "AA==")
DRACO_FACES_OFFSET = 11


def varint(value):
    """value as Draco writes an unsigned varint: 7 bits a byte, low bits first, the high bit set on all
    bytes but the last."""
    out = bytearray()
    while True:
        out.append((value & 0x7F) | (0x80 if value > 0x7F else 0))
        value >>= 7
        if not value:
            return bytes(out)


def draco_asset(base, stream=DRACO_QUAD):
    """base with the quad's primitive KHR_draco_mesh_compression-compressed: its attribute and index
    accessors keep count and type but lose their bufferView (as gltf-transform writes them), the stream is
    the last view of buffer 0, and the other accessors' views are as they were, renumbered."""
    a = base.copy()
    g = a.gltf
    old_views, old_bin = g["bufferViews"], bytes(a.bin)
    g["bufferViews"] = []
    del a.bin[:]
    for i, acc in enumerate(g["accessors"]):
        v = old_views[acc.pop("bufferView")]
        if i <= INDICES:
            continue
        start = v.get("byteOffset", 0)
        acc["bufferView"] = a.add_view(old_bin[start:start + v["byteLength"]], v.get("target"))
    primitive = g["meshes"][0]["primitives"][0]
    primitive["extensions"] = {"KHR_draco_mesh_compression": {
        "bufferView": a.add_view(stream),
        "attributes": {"POSITION": 0, "NORMAL": 1, "JOINTS_0": 2, "WEIGHTS_0": 3}}}
    a.pad()
    g["buffers"][0]["byteLength"] = len(a.bin)
    g["extensionsUsed"] = ["KHR_draco_mesh_compression"]
    g["extensionsRequired"] = ["KHR_draco_mesh_compression"]
    return a


def draco_cases(cat, base):
    """KHR_draco_mesh_compression: one valid file and one broken thing each."""
    cat.write("valid_draco.glb", draco_asset(base).glb_bytes())
    cat.valid.append("valid_draco.glb")
    ext = lambda a: a.gltf["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]
    prefix = "mesh 0 primitive 0: KHR_draco_mesh_compression "

    def case(name, change, message, stream=DRACO_QUAD):
        a = draco_asset(base, stream)
        change(a)
        cat.case("draco_%s.glb" % name, a.glb_bytes(), regex_escape(message))

    def view_bytes(a):
        v = a.gltf["bufferViews"][ext(a)["bufferView"]]
        return v["byteOffset"], v["byteLength"]

    def garbage(a):  # not a Draco stream at all
        at, n = view_bytes(a)
        a.bin[at:at + n] = bytes((k * 131 + 7) & 0xFF for k in range(n))
    case("garbage", garbage, prefix + "data is malformed (")

    def truncated(a):
        a.gltf["bufferViews"][ext(a)["bufferView"]]["byteLength"] = len(DRACO_QUAD) // 2
    case("truncated", truncated, prefix + "data is malformed (")

    def unknown_id(a):
        ext(a)["attributes"]["WEIGHTS_0"] = 7
    case("unknown_unique_id", unknown_id, prefix + "attribute WEIGHTS_0: unique id 7 is not in the compressed data")

    def count(a):
        a.gltf["accessors"][POSITION]["count"] = 5
    case("count_mismatch", count,
         prefix + "attribute POSITION: accessor %d has count 5, the compressed data 4 points" % POSITION)

    def lines(a):
        a.gltf["meshes"][0]["primitives"][0]["mode"] = 1
    case("mode_lines", lines, prefix + "is on a primitive of mode 1; dqskin decodes triangle lists (mode 4)")

    def view_out_of_range(a):
        ext(a)["bufferView"] = 99
    case("view_out_of_range", view_out_of_range, prefix + "bufferView 99 does not exist")

    # An edgebreaker stream (method 1, traversal 0) whose connectivity header claims 1431655765 triangles
    # and as many vertices and symbols, which passes libdraco's own checks of those counts: libdraco would
    # allocate its corner table for them (17 GB, past the tests' 4 GiB cap) before it reads a symbol. The
    # loader refuses the count first.
    faces = 0x55555555
    huge = (DRACO_QUAD[:8] + bytes([1]) + DRACO_QUAD[9:DRACO_FACES_OFFSET] + bytes([0]) + varint(faces) + varint(faces) +
            bytes([0]) + varint(faces) + varint(0) + bytes(64))
    case("huge_face_count", lambda a: None,
         prefix + "indices: accessor %d has count 6, the compressed data %d triangles (%d indices)" % (INDICES, faces, 3 * faces),
         stream=huge)


MARKER = ".written-by-make_malformed"


def animation_channel_cases(cat, base):
    """Channels that repeat a target, and KHR_animation_pointer channels (glTF 2.0 §3.11 and the extension's
    README): a pointer must be a JSON pointer (RFC 6901) to a property the asset defines, its node or mesh
    must exist, its output must have the type of the ordinary channel it stands for, and the channel must
    not also name a node. Repeats with the same keys, and pointers to properties dqskin does not deform,
    load with one warning per animation."""
    def pointer(channel, value, sampler=None, keep_node=False):
        def f(a):
            ch = a.gltf["animations"][0]["channels"][channel]
            if not keep_node:
                ch["target"].pop("node", None)
            ch["target"]["path"] = "pointer"
            if value is not None:
                ch["target"]["extensions"] = {"KHR_animation_pointer": {"pointer": value}}
            if sampler is not None:
                ch["sampler"] = sampler
            a.gltf["extensionsUsed"] = ["KHR_animation_pointer"]
        return f
    for name, change, regex in [
        ("pointer_node_missing", pointer(0, "/nodes/30/translation"),
         r"animation 0 channel 0: pointer '/nodes/30/translation' names node 30, which does not exist$"),
        ("pointer_mesh_missing", pointer(0, "/meshes/7/weights"),
         r"animation 0 channel 0: pointer '/meshes/7/weights' names mesh 7, which does not exist$"),
        ("pointer_not_a_json_pointer", pointer(0, "nodes/2/translation"),
         r"animation 0 channel 0: pointer 'nodes/2/translation' does not start with '/'$"),
        ("pointer_bad_escape", pointer(0, "/nodes/2/transl~ation"),
         r"animation 0 channel 0: pointer '/nodes/2/transl~ation' has '~' not followed by 0 or 1$"),
        ("pointer_index_leading_zero", pointer(0, "/nodes/02/translation"),
         r"animation 0 channel 0: pointer '/nodes/02/translation' names node '02', which is not an array index$"),
        ("pointer_without_extension", pointer(0, None),
         r"animation 0 channel 0: path 'pointer' without a KHR_animation_pointer pointer string$"),
        ("pointer_with_node", pointer(0, "/nodes/2/translation", keep_node=True),
         r"animation 0 channel 0: has a target node and path 'pointer'"),
        ("pointer_wrong_output_type", pointer(0, "/nodes/2/translation", sampler=1),
         r"animation 0 sampler 1 output \(accessor 8\): has type VEC4, which is not allowed here$"),
        ("pointer_mesh_weights_without_targets", pointer(0, "/meshes/0/weights"),
         r"animation 0 channel 0: animates weights of a mesh without morph targets$"),
    ]:
        cat.gltf(name, edit(base, change), regex)

    def f(a):
        a.gltf["nodes"][2] = {"name": "tip joint", "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 1]}
        pointer(0, "/nodes/2/translation")(a)
        pointer(1, "/nodes/2/rotation")(a)
    cat.undeformable_gltf("pointer_animates_matrix_node", edit(base, f),
                          r"animation 0 channel 0: animates node 2, which has a matrix \(.*3\.11 forbids it\)$")

    # A repeat with the same keys, as an ordinary channel and as a pointer: loaded, one warning.
    def f(a):
        a.gltf["animations"][0]["channels"].append(copy.deepcopy(a.gltf["animations"][0]["channels"][0]))
    cat.warning("two_channels_same_target", edit(base, f),
                r"animation 0 'wave': 1 duplicate channel \(the same node, path and keys as an earlier channel\) is ignored")
    def f(a):
        a.gltf["animations"][0]["channels"].append(copy.deepcopy(a.gltf["animations"][0]["channels"][1]))
        a.gltf["animations"][0]["channels"][2]["target"] = {"node": 2, "path": "rotation"}
        pointer(2, "/nodes/2/rotation")(a)
    cat.warning("pointer_repeats_channel", edit(base, f),
                r"animation 0 'wave': 1 duplicate channel \(the same node, path and keys as an earlier channel\) is ignored")
    # A pointer to a material's color: not deformation, so ignored with a warning that lists it.
    def f(a):
        a.gltf["materials"] = [{"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1]}}]
        a.gltf["animations"][0]["channels"].append(copy.deepcopy(a.gltf["animations"][0]["channels"][1]))
        pointer(2, "/materials/0/pbrMetallicRoughness/baseColorFactor")(a)
    cat.warning("pointer_to_material", edit(base, f),
                r"animation 0 'wave': 1 KHR_animation_pointer channel animating what dqskin does not deform is "
                r"ignored: '/materials/0/pbrMetallicRoughness/baseColorFactor'")
    # Seven such pointers, the first 200 bytes long: the warning quotes five, each cut at 80 bytes.
    def f(a):
        a.gltf["materials"] = [{"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1]}}]
        channels = a.gltf["animations"][0]["channels"]
        for k in range(7):
            channels.append(copy.deepcopy(channels[1]))
            pointer(len(channels) - 1, "/extras/" + "x" * 192 if k == 0 else "/materials/0/extras/%d" % k)(a)
    cat.warning("pointer_many_ignored", edit(base, f),
                r"animation 0 'wave': 7 KHR_animation_pointer channels animating what dqskin does not deform are "
                r"ignored: '/extras/x+[.][.][.]', '/materials/0/extras/1', '/materials/0/extras/2', "
                r"'/materials/0/extras/3', '/materials/0/extras/4' and 2 more")
    # Both channels as pointers, the extension required: a file dqskin reads.
    def f(a):
        pointer(0, "/nodes/2/translation")(a)
        pointer(1, "/nodes/2/rotation")(a)
        a.gltf["extensionsRequired"] = ["KHR_animation_pointer"]
    cat.write("valid_animation_pointer.gltf", edit(base, f).gltf_bytes())
    cat.valid.append("valid_animation_pointer.gltf")
def texture_extension_cases(cat, base):
    """Textures whose image an extension holds (docs/commands/render.md): they load, with one warning when
    the extension's image cannot be drawn."""
    def with_textures(textures, used, required=()):
        a = base.copy()
        a.gltf.update(copy.deepcopy({
            "textures": textures,
            "images": [{"uri": "data:image/png;base64,iVBORw0KGgo=", "mimeType": "image/png"},
                       {"uri": "data:application/octet-stream;base64,q0tUWCAyMLsNChoK", "mimeType": "image/ktx2"}],
        }))
        a.gltf["extensionsUsed"] = list(used)
        if required:
            a.gltf["extensionsRequired"] = list(required)
        return a
    # EXT_texture_webp naming an image that does not exist: the core source is drawn.
    cat.warning("texture_webp_image_missing",
                with_textures([{"source": 0, "extensions": {"EXT_texture_webp": {"source": 5}}}], ["EXT_texture_webp"]),
                regex_escape("texture 0: EXT_texture_webp source 5 does not exist") + ". its core source is used")
    # KHR_texture_basisu without a PNG or JPEG fallback (so required): drawn with the material's factors.
    basisu = ["KHR_texture_basisu"]
    cat.warning("texture_basisu_without_fallback",
                with_textures([{"extensions": {"KHR_texture_basisu": {"source": 1}}}], basisu, basisu),
                regex_escape("texture 0 has only a KTX2 image (KHR_texture_basisu), which dqskin does not decode, "
                             "and no PNG or JPEG fallback") + ". materials using it are drawn with their factors")
def undeformable_cases(cat, base):
    """Files that parse as glTF but cannot be deformed: info and lint describe them, bake refuses."""
    # A skinned mesh node whose primitive has no JOINTS_0/WEIGHTS_0 (§3.7.3: a skinned primitive needs
    # them). A viewer draws the primitive unskinned.
    def f(a):
        attributes = a.gltf["meshes"][0]["primitives"][0]["attributes"]
        del attributes["JOINTS_0"]
        del attributes["WEIGHTS_0"]
    cat.undeformable_gltf("skinned_primitive_without_joints", edit(base, f),
                          r"node 0: is skinned, but mesh 0 primitive 0 has no JOINTS_0/WEIGHTS_0$")


def influence_set_cases(cat, base):
    """JOINTS_n/WEIGHTS_n sets past the first two (glTF 2.0 §3.7.3.3: any number of sets, numbered from 0
    without gaps, §3.7.2.1). dqskin reads up to 8 sets (32 influences per vertex) and refuses more, so
    that attribute names alone cannot make it decode gigabytes; the extra sets reuse the base's JOINTS_0
    and WEIGHTS_0 accessors, which have the right shape and count."""
    def sets(names):
        def f(a):
            attributes = a.gltf["meshes"][0]["primitives"][0]["attributes"]
            for n in names:
                attributes["JOINTS_%s" % n] = JOINTS
                attributes["WEIGHTS_%s" % n] = WEIGHTS
        return f
    prefix = r"mesh 0 primitive 0: "
    cat.gltf("influence_set_gap", edit(base, sets([2])),
             prefix + r"has JOINTS_2 or WEIGHTS_2 but not JOINTS_1 or WEIGHTS_1 \(sets are numbered from 0 without gaps\)$")
    cat.gltf("influence_sets_past_cap", edit(base, sets(range(1, 9))),
             prefix + r"has JOINTS_8/WEIGHTS_8: more than 32 influences per vertex \(8 sets\), which dqskin does not read$")
    cat.gltf("influence_set_index_huge", edit(base, sets([999999999])),
             prefix + r"has JOINTS_999999999/WEIGHTS_999999999: more than 32 influences per vertex")

    def joints_without_weights(a):
        sets([1, 2, 3])(a)
        del a.gltf["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_3"]
    cat.gltf("joints_3_without_weights_3", edit(base, joints_without_weights), prefix + r"has JOINTS_3 without WEIGHTS_3$")
    # Eight sets, the most dqskin reads: they load (the same four influences eight times over).
    cat.write("valid_eight_influence_sets.gltf", edit(base, sets(range(1, 8))).gltf_bytes())
    cat.valid.append("valid_eight_influence_sets.gltf")


def main():
    if len(sys.argv) == 2 and sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        return
    # An option is never a folder: "--help" once became one, full of cases.
    if len(sys.argv) != 2 or sys.argv[1].startswith("-"):
        sys.exit("usage: make_malformed.py OUTDIR")
    outdir = sys.argv[1]
    if os.path.isdir(outdir) and os.listdir(outdir):
        # Only ever delete a folder that an earlier run wrote (its marker is written first, so a run that
        # failed half-way is recognised too).
        if not os.path.isfile(os.path.join(outdir, MARKER)) and not os.path.isfile(os.path.join(outdir, "cases.txt")):
            sys.exit("make_malformed: %s is not empty and holds no %s; not touching it" % (outdir, MARKER))
        shutil.rmtree(outdir)
    os.makedirs(outdir, exist_ok=True)
    open(os.path.join(outdir, MARKER), "w").close()
    cat = Catalogue(outdir)
    base = base_asset()

    # ---- The valid files ------------------------------------------------------------------------
    cat.write("valid.gltf", base.gltf_bytes())
    cat.write("valid.glb", base.glb_bytes())
    cat.write("valid_external.gltf", to_json(base.document("valid_external.bin")))
    cat.write("valid_external.bin", bytes(base.bin))
    cat.valid += ["valid.gltf", "valid.glb", "valid_external.gltf"]

    # ---- Files that are not glTF at all ---------------------------------------------------------
    cat.case("empty.gltf", b"", r"the file is empty$")
    cat.case("not_json.gltf", b"This is a text file, not JSON.\n",
             r"is not a glTF file: it starts with 'This is a text file, not'$")
    # What users download by mistake: an HTML error page or a ZIP archive under a .glb name. One line says
    # what the file looks like, never the JSON parser's "invalid literal".
    cat.case("html_page_named.glb", b"<!DOCTYPE html>\n<html><head><title>404 Not Found</title></head></html>\n",
             r"is not a glTF file: it starts with '<!DOCTYPE html>'$")
    cat.case("zip_archive_named.glb", b"PK\x03\x04\x14\x00\x00\x00\x08\x00" + bytes(20),
             r"is not a glTF file: it is a ZIP archive$")
    cat.case("png_image_named.gltf", b"\x89PNG\r\n\x1a\n" + bytes(24), r"is not a glTF file: it is a PNG image$")
    cat.case("json_not_gltf.gltf", b'{"hello": "world"}', r".*asset")
    # tinygltf's message says the asset object is missing; it is there, without "version".
    cat.case("asset_without_version.gltf", b'{"asset": {"generator": "nobody"}}', r'.*(version|"asset")')
    cat.case("json_array.gltf", b"[1, 2, 3]", r"is not a glTF file: it starts with '\[1, 2, 3\]'$")
    valid_json = base.gltf_bytes()
    cat.case("truncated_json.gltf", valid_json[: len(valid_json) // 2], r".*(parse error|JSON)")
    cat.case("truncated_json_one_byte.gltf", valid_json[:-1], r".*(parse error|JSON)")

    # ---- GLB container (glTF 2.0 §4.4) ----------------------------------------------------------
    glb = base.glb_bytes()
    json_length = struct.unpack_from("<I", glb, 12)[0]
    bin_chunk = 20 + json_length  # offset of the BIN chunk header
    for label, cut in [("in_header", 7), ("after_header", 12), ("in_json_chunk_header", 16),
                       ("in_json", 20 + json_length // 2), ("before_bin_chunk", bin_chunk),
                       ("in_bin_chunk_header", bin_chunk + 4), ("in_bin", bin_chunk + 8 + len(base.bin) // 2),
                       ("last_byte", len(glb) - 1)]:
        # The header's length field is left as it was: the file is simply cut short.
        cat.case("glb_truncated_%s.glb" % label, glb[:cut], r".*([Tt]oo short|[Ii]nvalid glTF binary|truncated|length|size)")

    def patched(data, offset, fmt, value):
        d = bytearray(data)
        struct.pack_into(fmt, d, offset, value)
        return bytes(d)

    cat.case("glb_wrong_magic.glb", patched(glb, 0, "<I", 0x46546C68), r".*(parse error|JSON)")
    cat.case("glb_length_past_end.glb", patched(glb, 8, "<I", len(glb) + 100), r".*(length|size|[Ii]nvalid)")
    cat.case("glb_length_too_small.glb", patched(glb, 8, "<I", 20), r".*(length|size|[Ii]nvalid)")
    cat.case("glb_json_chunk_past_end.glb", patched(glb, 12, "<I", len(glb)), r".*(length|size|[Ii]nvalid|chunk)")
    cat.case("glb_json_chunk_huge.glb", patched(glb, 12, "<I", 0xFFFFFFF0), r".*(length|size|[Ii]nvalid|chunk)")
    cat.case("glb_json_chunk_wrong_type.glb", patched(glb, 16, "<I", 0x12345678), r".*([Ii]nvalid glTF binary|JSON|chunk|type)")
    cat.case("glb_bin_chunk_past_end.glb", patched(glb, bin_chunk, "<I", len(base.bin) + 64),
             r".*(length|size|[Ii]nvalid|chunk|BIN)")
    cat.case("glb_bin_chunk_smaller_than_buffer.glb", patched(glb, bin_chunk, "<I", 16),
             r".*(length|size|[Ii]nvalid|chunk|BIN|buffer)")
    cat.case("glb_json_is_garbage.glb", base.glb_bytes(b"\x01\x02not json at all"), r".*(parse error|JSON)")

    # ---- Buffers ----------------------------------------------------------------------------------
    cat.external("external_bin_missing", base, r".*(external_bin_missing\.bin|No such file|[Ff]ile)",
                 uri="external_bin_missing.bin")
    cat.external("external_bin_short", base, r".*(size|length|short|[Ff]ile)", bin_data=bytes(base.bin[:100]))
    os.makedirs(os.path.join(outdir, "a_directory.bin"))
    cat.external("buffer_uri_directory", base, r".*(a_directory\.bin|regular|[Ff]ile)", uri="a_directory.bin")
    cat.external("buffer_uri_dev_zero", base, r".*(/dev/zero|regular|[Ff]ile)", uri="/dev/zero")
    cat.external("buffer_uri_dev_zero_relative", base, r".*(dev/zero|regular|[Ff]ile)",
                 uri="../" * 32 + "dev/zero")
    g = copy.deepcopy(base.gltf)
    g["buffers"][0]["uri"] = "data:application/octet-stream;base64,!!!!not*base64!!!!"
    cat.case("data_uri_not_base64.gltf", to_json(g), r".*(decode|base64|uri|URI)")
    g = copy.deepcopy(base.gltf)
    g["buffers"][0]["uri"] = data_uri(base.bin[:64])
    g["buffers"][0]["byteLength"] = len(base.bin)
    cat.case("data_uri_wrong_length.gltf", to_json(g), r".*(decode|base64|uri|URI|length|size)")

    # ---- Buffer views and accessors (§3.6) ---------------------------------------------------------
    def f(a):
        a.gltf["accessors"][POSITION]["byteOffset"] = 12
    cat.gltf("accessor_past_buffer_view", edit(base, f),
             r"mesh 0 primitive 0 POSITION \(accessor 0\): 4 elements of 12 bytes \(stride 12, offset 12\) "
             r"do not fit in bufferView 0 \(48 bytes\)")

    def f(a):
        a.gltf["bufferViews"][8]["byteLength"] = 4096
    cat.gltf("buffer_view_past_buffer", edit(base, f),
             r".*bufferView 8 \(offset [0-9]+, length 4096\) runs past the end of buffer 0")

    def f(a):
        a.gltf["bufferViews"][0]["byteStride"] = 8
    cat.gltf("byte_stride_smaller_than_element", edit(base, f),
             r".*byteStride 8, but elements are 12 bytes")

    def f(a):
        a.gltf["accessors"][POSITION]["count"] = 0
    cat.gltf("accessor_count_zero", edit(base, f), r"accessor 0: count 0 must be an integer of at least 1")

    def f(a):
        a.gltf["accessors"][POSITION] = {"componentType": FLOAT, "count": 4000000000, "type": "VEC3"}
    cat.gltf("accessor_count_4e9_unbacked", edit(base, f),
             r"loading it needs about [0-9.]+ GiB \(.*\), more than --max-memory 2.00 GiB")

    def f(a):
        a.gltf["accessors"][POSITION]["bufferView"] = 42
    cat.gltf("accessor_buffer_view_missing", edit(base, f), r".*bufferView 42 does not exist")

    def f(a):
        a.gltf["bufferViews"][0]["buffer"] = 3
    cat.gltf("buffer_view_buffer_missing", edit(base, f), r".*(buffer 3|buffer).*does not exist")

    def f(a):
        a.gltf["accessors"][POSITION]["componentType"] = 5130  # GL_DOUBLE: not in glTF
    cat.gltf("accessor_component_type_double", edit(base, f), r".*(componentType|component type).*(5130|not allowed|invalid|unknown)")

    def sparse(indices_fmt, indices, values, count=None):
        def f(a):
            iv = a.add_view(struct.pack("<%d%s" % (len(indices), indices_fmt), *indices))
            vv = a.add_view(floats([x for v in values for x in v]))
            a.gltf["accessors"][POSITION]["sparse"] = {
                "count": len(indices) if count is None else count,
                "indices": {"bufferView": iv, "componentType": {"B": UBYTE, "H": USHORT, "I": UINT}[indices_fmt]},
                "values": {"bufferView": vv}}
        return f
    cat.gltf("sparse_index_out_of_range", edit(base, sparse("H", [1, 9], [(2, 0, 0), (3, 0, 0)])),
             r"mesh 0 primitive 0 POSITION \(accessor 0\): has sparse index 9, but count is 4")
    cat.gltf("sparse_indices_not_increasing", edit(base, sparse("H", [2, 1], [(2, 0, 0), (3, 0, 0)])),
             r"mesh 0 primitive 0 POSITION \(accessor 0\): has sparse indices that do not strictly increase")
    cat.gltf("sparse_indices_repeated", edit(base, sparse("B", [1, 1], [(2, 0, 0), (3, 0, 0)])),
             r"mesh 0 primitive 0 POSITION \(accessor 0\): has sparse indices that do not strictly increase")
    cat.gltf("sparse_count_above_count", edit(base, sparse("H", [0, 1, 2, 3, 4], [(0, 0, 0)] * 5)),
             r"mesh 0 primitive 0 POSITION \(accessor 0\): has sparse count 5, which must be 1..4")
    cat.gltf("sparse_values_past_view", edit(base, sparse("H", [0, 1, 2], [(0, 0, 0)] * 2)),
             r"mesh 0 primitive 0 POSITION \(accessor 0\) sparse values: 3 elements of 12 bytes .*do not fit")

    # ---- Mesh data (§3.7.2) ------------------------------------------------------------------------
    def f(a):
        struct.pack_into("<H", a.bin, a.accessor_offset(INDICES) + 2 * 4, 4)
    cat.gltf("index_out_of_range", edit(base, f),
             r"mesh 0 primitive 0: index 4 is 4, but there are 4 vertices")

    def f(a):
        a.bin[a.accessor_offset(JOINTS) + 4 * 2 + 1] = 7
    cat.gltf("joint_out_of_range", edit(base, f),
             r"mesh 0 primitive 0: vertex 2 uses joint 7, but skin 0 has 2 joints")

    def f(a):
        struct.pack_into("<f", a.bin, a.accessor_offset(WEIGHTS) + 16 * 1 + 4, -0.5)
    cat.gltf("negative_weight", edit(base, f), r"mesh 0 primitive 0: WEIGHTS_0 of vertex 1 is negative")

    def f(a):
        struct.pack_into("<f", a.bin, a.accessor_offset(POSITION) + 12 * 2 + 4, float("nan"))
    cat.gltf("position_nan", edit(base, f), r"mesh 0 primitive 0 POSITION \(accessor 0\): element 2 is NaN")

    def f(a):
        struct.pack_into("<f", a.bin, a.accessor_offset(POSITION) + 12 * 3, float("inf"))
    cat.gltf("position_infinity", edit(base, f), r"mesh 0 primitive 0 POSITION \(accessor 0\): element 3 is infinite")

    def f(a):
        struct.pack_into("<f", a.bin, a.accessor_offset(NORMAL) + 8, float("-inf"))
    cat.gltf("normal_minus_infinity", edit(base, f), r"mesh 0 primitive 0 NORMAL \(accessor 1\): element 0 is infinite")

    def f(a):
        del a.gltf["meshes"][0]["primitives"][0]["attributes"]["POSITION"]
    cat.gltf("primitive_without_position", edit(base, f), r"mesh 0 primitive 0: has no POSITION")

    def f(a):
        a.gltf["accessors"][NORMAL]["count"] = 3
    cat.gltf("attribute_counts_differ", edit(base, f), r"mesh 0 primitive 0: NORMAL has 3 elements, POSITION has 4")

    def f(a):
        del a.gltf["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"]
    cat.gltf("weights_without_joints", edit(base, f), r"mesh 0 primitive 0: has WEIGHTS_0 without JOINTS_0")

    def f(a):
        a.gltf["accessors"][JOINTS]["componentType"] = FLOAT
    cat.gltf("joints_are_floats", edit(base, f),
             r"mesh 0 primitive 0 JOINTS_0 \(accessor 2\): has float components where integers are required")

    def f(a):
        a.gltf["meshes"][0]["primitives"][0]["mode"] = 9
    cat.gltf("primitive_mode_invalid", edit(base, f), r".*mode 9")

    def f(a):
        a.gltf["meshes"][0]["primitives"] = []
    cat.gltf("mesh_without_primitives", edit(base, f), r".*(mesh 0.*primitives|primitives)")

    def f(a):
        a.gltf["nodes"][0]["mesh"] = 5
    cat.gltf("node_mesh_out_of_range", edit(base, f), r"node 0: mesh 5 does not exist")

    def with_morph_targets(a):
        offsets = a.add_view(floats([0, 0, 0.1] * 4))
        return a.add("accessors", {"bufferView": offsets, "componentType": FLOAT, "count": 4, "type": "VEC3"})

    def f(a):
        target = with_morph_targets(a)
        p0 = a.gltf["meshes"][0]["primitives"][0]
        p1 = copy.deepcopy(p0)
        p0["targets"] = [{"POSITION": target}]
        a.gltf["meshes"][0]["primitives"].append(p1)
    cat.gltf("morph_target_count_differs", edit(base, f),
             r"mesh 0: its primitives have different numbers of morph targets")

    def f(a):
        target = with_morph_targets(a)
        a.gltf["meshes"][0]["primitives"][0]["targets"] = [{"POSITION": target}]
        a.gltf["meshes"][0]["weights"] = [0.5, 0.5]
    cat.gltf("mesh_weights_count_differs", edit(base, f), r"mesh 0: has 2 weights for 1 morph targets")

    def f(a):
        a.gltf["extensionsUsed"] = ["EXT_mesh_gpu_instancing"]
        a.gltf["extensionsRequired"] = ["EXT_mesh_gpu_instancing"]
    cat.gltf("required_extension_gpu_instancing", edit(base, f),
             r"requires extension EXT_mesh_gpu_instancing, which dqskin does not support")

    # ---- Nodes and scenes (§3.5) ---------------------------------------------------------------------
    # JSON has no infinity; 1e400 overflows a double. Written into the text after serialisation.
    text = base.gltf_bytes().replace(b'"translation":[0,1,0]', b'"translation":[1e400,1,0]')
    assert b"1e400" in text
    cat.case("node_translation_1e400.gltf", text, r".*(number overflow parsing '1e400'|node 2: translation is not finite)")

    def f(a):
        a.gltf["nodes"][2]["children"] = [1]
        a.gltf["scenes"][0]["nodes"] = [0]
    cat.gltf("node_hierarchy_cycle", edit(base, f), r"node [12]: is its own ancestor \(the hierarchy has a cycle\)")

    def f(a):
        a.gltf["nodes"].append({"name": "own child", "children": [3]})  # in no scene: its only parent is itself
    cat.gltf("node_is_its_own_child", edit(base, f), r"node 3: is its own ancestor")

    def f(a):
        a.gltf["nodes"].append({"name": "second parent", "children": [2]})
        a.gltf["scenes"][0]["nodes"].append(3)
    cat.gltf("node_with_two_parents", edit(base, f), r"node 2: has two parents \(nodes 1 and 3\)")

    def f(a):
        a.gltf["scenes"][0]["nodes"].append(17)
    cat.gltf("scene_node_missing", edit(base, f), r"scene 0: node 17 does not exist")

    def f(a):
        a.gltf["scene"] = 4
    cat.gltf("default_scene_missing", edit(base, f), r"scene 4 \(the default scene\) does not exist")

    def f(a):
        a.gltf["nodes"][1]["children"] = [2, 9]
    cat.gltf("node_child_missing", edit(base, f), r"node 1: child 9 does not exist")

    def f(a):
        a.gltf["nodes"][1]["matrix"] = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0.5, 1]
        a.gltf["nodes"][1]["matrix"][3] = 0.25  # column 0, row 3: the last row is (0.25, 0, 0, 1)
    cat.gltf("node_matrix_not_affine", edit(base, f),
             r"node 1: matrix is not affine \(its last row must be 0, 0, 0, 1\)")

    def f(a):
        a.gltf["nodes"][2]["rotation"] = [0, 0, 0, 0]
    cat.gltf("node_rotation_zero", edit(base, f), r"node 2: rotation is a zero quaternion")

    # ---- Skins (§3.7.3) --------------------------------------------------------------------------------
    def f(a):
        a.gltf["skins"][0]["joints"] = []
        del a.gltf["skins"][0]["inverseBindMatrices"]
    cat.gltf("skin_without_joints", edit(base, f), r".*(skin 0: has no joints|joints)")

    def f(a):
        a.gltf["skins"][0]["joints"] = [1, 12]
    cat.gltf("skin_joint_node_missing", edit(base, f), r"skin 0: joint node 12 does not exist")

    def f(a):
        a.gltf["skins"][0]["joints"] = [1, 1]
    cat.gltf("skin_joint_listed_twice", edit(base, f), r"skin 0: lists node 1 twice")

    def f(a):
        a.gltf["accessors"][IBM]["count"] = 1
    cat.gltf("inverse_bind_matrices_too_few", edit(base, f), r"skin 0: has 1 inverse bind matrices for 2 joints")

    def f(a):
        struct.pack_into("<f", a.bin, a.accessor_offset(IBM) + 64 + 5 * 4, float("nan"))
    cat.gltf("inverse_bind_matrix_nan", edit(base, f),
             r"skin 0 inverseBindMatrices \(accessor 5\): element 1 is NaN")

    # ---- Animations (§3.11) -------------------------------------------------------------------------------
    def f(a):
        a.gltf["accessors"][TRANSLATIONS]["count"] = 2
    cat.gltf("sampler_count_mismatch", edit(base, f),
             r"animation 0 sampler 0: output has 6 values for 3 keys \(expected 9\)")

    def f(a):
        struct.pack_into("<f", a.bin, a.accessor_offset(TIMES) + 8, 0.25)
    cat.gltf("key_times_not_increasing", edit(base, f),
             r"animation 0 sampler 0: key times do not increase \(key 2\)")

    def f(a):
        struct.pack_into("<f", a.bin, a.accessor_offset(TIMES) + 4, 0.0)
    cat.gltf("key_times_repeated", edit(base, f), r"animation 0 sampler 0: key times do not increase \(key 1\)")

    def f(a):
        struct.pack_into("<f", a.bin, a.accessor_offset(TIMES), -1.0)
        a.gltf["accessors"][TIMES]["min"] = [-1.0]
    cat.gltf("key_time_negative", edit(base, f), r"animation 0 sampler 0: key time -1(\.0*)? is negative")

    def f(a):
        struct.pack_into("<f", a.bin, a.accessor_offset(ROTATIONS) + 16 + 8, float("nan"))
    cat.gltf("animation_output_nan", edit(base, f),
             r"animation 0 sampler 1 output \(accessor 8\): element 1 is NaN")

    def f(a):
        a.gltf["animations"][0]["samplers"][0]["interpolation"] = "BEZIER"
    cat.gltf("unknown_interpolation", edit(base, f), r".*(unknown interpolation 'BEZIER'|interpolation)")

    def f(a):
        a.gltf["animations"][0]["samplers"][1]["interpolation"] = "CUBICSPLINE"
    cat.gltf("cubicspline_without_tangents", edit(base, f),
             r"animation 0 sampler 1: output has 12 values for 3 keys \(expected 36\)")

    def f(a):
        a.gltf["animations"][0]["channels"][0]["target"]["node"] = 30
    cat.gltf("channel_node_missing", edit(base, f), r"animation 0 channel 0: target node 30 does not exist")

    def f(a):
        a.gltf["animations"][0]["channels"][1]["sampler"] = 5
    cat.gltf("channel_sampler_missing", edit(base, f), r".*(sampler 5 does not exist|sampler)")

    def f(a):
        a.gltf["animations"][0]["channels"][0]["target"]["path"] = "color"
    cat.gltf("channel_unknown_path", edit(base, f), r".*(unknown target path 'color'|path)")

    def f(a):
        del a.gltf["nodes"][2]["translation"]
        a.gltf["nodes"][2]["matrix"] = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 1]
    cat.undeformable_gltf("channel_animates_matrix_node", edit(base, f),
                          r"animation 0 channel 0: animates node 2, which has a matrix \(.*3\.11 forbids it\)$")


    def f(a):
        a.gltf["animations"][0]["channels"][0]["target"]["path"] = "weights"
        # Its output as a weights channel's must be: scalars (the key times serve), so that only the
        # missing morph targets are wrong.
        sampler = a.gltf["animations"][0]["samplers"][a.gltf["animations"][0]["channels"][0]["sampler"]]
        sampler["output"] = sampler["input"]
    cat.undeformable_gltf("weights_channel_without_targets", edit(base, f),
                          r"animation 0 channel 0: animates weights of a node without morph targets$")

    # ---- Cases the loader gets wrong today (see the report in the commit that added them): each test
    # states the correct behaviour and fails until the loader is fixed.
    # GLB header version 1 (glTF 2.0 §4.4.3.1: this specification defines container version 2).
    cat.case("glb_version_1.glb", patched(glb, 4, "<I", 1), r".*version")
    # asset.version / asset.minVersion name a major version dqskin does not read (glTF 2.0 §3.2).
    a = base.copy()
    a.gltf["asset"]["version"] = "1.0"
    cat.gltf("asset_version_1_0", a, r".*version")
    a = base.copy()
    a.gltf["asset"]["minVersion"] = "2.1"
    cat.gltf("asset_min_version_2_1", a, r".*(minVersion|version)")
    # A BIN chunk whose length claims 8 bytes more than the file holds, with the buffer's byteLength
    # claiming them too: tinygltf checks chunk length + 20 + JSON length, forgetting the chunk's own
    # 8-byte header, so it copies 8 bytes from past the end of the file into the buffer.
    g = copy.deepcopy(base.gltf)
    g["buffers"][0]["byteLength"] = len(base.bin) + 8
    d = bytearray(Asset(g, base.bin).glb_bytes(to_json(g)))
    struct.pack_into("<I", d, 20 + struct.unpack_from("<I", d, 12)[0], len(base.bin) + 8)
    cat.case("glb_bin_chunk_8_bytes_past_end.glb", bytes(d), r".*(BIN|[Cc]hunk|length|size|past the end)")
    # A GLB buffer with byteLength 0 (glTF 2.0: byteLength ≥ 1) and no uri: tinygltf calls
    # data.at(0) on the empty vector, and std::out_of_range escapes the loader (abort, exit status 134).
    g = copy.deepcopy(base.gltf)
    g["buffers"].append({"byteLength": 0})
    cat.case("glb_buffer_byte_length_0.glb", Asset(g, base.bin).glb_bytes(to_json(g)),
             r".*(byteLength|buffer 1|[Bb]uffer)")
    # The buffer is missing beside the .gltf but exists in the current directory (the test runs in
    # OUTDIR/cwd): tinygltf also searches ".", so the loader reads a file the asset does not refer to
    # (load.hpp: external buffers are looked up in base_dir).
    os.makedirs(os.path.join(outdir, "cwd"))
    with open(os.path.join(outdir, "cwd", "only_in_cwd.bin"), "wb") as f_:
        f_.write(bytes(base.bin))
    cat.external("external_bin_only_in_current_directory", base, r".*(only_in_cwd\.bin|not found|[Ff]ile)",
                 uri="only_in_cwd.bin")
    # 2^26 inverse bind matrices (max_unbacked_elements) without a bufferView: a 3 kB file that makes
    # the loader allocate 8 GiB of doubles and 4 GiB of floats (12.6 GB resident, 35 s). The limit counts
    # elements, not components or bytes; a MAT4 element is 16 components.
    def f(a):
        a.gltf["accessors"][IBM] = {"componentType": FLOAT, "count": 1 << 26, "type": "MAT4"}
    cat.gltf("accessor_unbacked_2e26_mat4", edit(base, f),
             r"loading it needs about [0-9.]+ GiB \(.*, 12.0 GiB while the largest is decoded, .*\), more than --max-memory")

    # An image stored in a bufferView that runs past the end of its buffer (no accessor uses the view, so
    # the accessor checks never see it): tinygltf hands &buffer.data[byteOffset] and byteLength to the
    # image callback unchecked, and model_io.cpp's keep_encoded_image copies byteLength bytes: a heap
    # read past the end of the buffer (silent in a Release build, which then loads the file).
    def image_view(length):
        def f(a):
            a.gltf["bufferViews"].append({"buffer": 0, "byteOffset": 0, "byteLength": length})
            a.gltf["images"] = [{"bufferView": len(a.gltf["bufferViews"]) - 1, "mimeType": "image/png"}]
        return f
    cat.gltf("image_buffer_view_past_buffer", edit(base, image_view(4096)), r".*(image|bufferView 9)")
    # The same with byteLength 3e9: the callback's int size is negative, and std::length_error escapes
    # the loader (abort, exit status 134).
    cat.gltf("image_buffer_view_3e9_bytes", edit(base, image_view(3000000000)), r".*(image|bufferView 9)")

    schema_value_cases(cat, base)
    undeformable_cases(cat, base)
    hostile_cases(cat, base, glb, outdir)
    meshopt_cases(cat, base)
    draco_cases(cat, base)
    animation_channel_cases(cat, base)
    texture_extension_cases(cat, base)
    influence_set_cases(cat, base)

    # A valid file that must load in time: a chain of 200000 nodes (4 MB). A cycle check that walks up
    # from every node is quadratic (about 45 s in a Release build), which the test's timeout catches.
    a = base.copy()
    nodes = a.gltf["nodes"]
    start = len(nodes)
    nodes[1]["children"] = [2, start]
    chain = 200000
    for i in range(chain):
        nodes.append({"children": [start + i + 1]} if i + 1 < chain else {"name": "deepest"})
    cat.write("valid_deep_hierarchy.gltf", a.gltf_bytes())
    cat.valid.append("valid_deep_hierarchy.gltf")

    cat.finish()
    job_inputs(base, os.path.join(outdir, "jobs"))
    print("make_malformed: %d cases, %d valid files in %s" % (len(cat.cases), len(cat.valid), outdir))


if __name__ == "__main__":
    main()
