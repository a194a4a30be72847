"""The glTF 2.0 container code that scripts/testdata/make_rigs.py, make_big_rig.py and make_malformed.py share.

A Builder holds one document (a dict) and its single buffer (buffer 0). It appends data as bufferViews and
accessors, and encodes the whole as a .gltf (buffer embedded as a base64 data: URI, or in a file beside it)
or as a .glb. What it writes is deterministic, byte for byte: accessor data is rounded to float32 before it
is stored or bounded, nothing depends on the host's byte order, and the JSON is written in one fixed format.
The geometry, and what each script puts in the document, stay in the scripts.

The scripts import it from their own folder (Python puts a script's folder first on sys.path), so they run
from any current directory. Python 3 standard library only.
"""

import base64
import json
import os
import struct
import sys
from array import array

# glTF constants: accessor component types, bufferView targets.
FLOAT, UNSIGNED_BYTE, UNSIGNED_SHORT, UNSIGNED_INT = 5126, 5121, 5123, 5125
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
_TYPECODE = {FLOAT: "f", UNSIGNED_BYTE: "B", UNSIGNED_SHORT: "H", UNSIGNED_INT: "I"}
_COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}
assert [array(c).itemsize for c in "fBHI"] == [4, 1, 2, 4], "array's item sizes must be glTF's component sizes"


def f32(x):
    """x rounded to the nearest float32, as a Python float (the value the file will hold)."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


def data_uri(data, mime="application/octet-stream"):
    """`data` as a base64 data: URI, the way a .gltf embeds a buffer or an image."""
    return "data:%s;base64,%s" % (mime, base64.b64encode(bytes(data)).decode("ascii"))


def json_bytes(doc, indent=None, sort_keys=True):
    """The document as ASCII JSON: compact (indent None), or indented and ending with a newline (a .gltf meant
    to be read and diffed). Sorted keys make the output independent of the order it was built in; a caller
    whose key order matters (a test that edits the text) passes sort_keys=False. NaN and infinity raise:
    JSON has no spelling for them."""
    if indent is None:
        text = json.dumps(doc, sort_keys=sort_keys, separators=(",", ":"), ensure_ascii=True, allow_nan=False)
    else:
        text = json.dumps(doc, indent=indent, sort_keys=sort_keys, ensure_ascii=True, allow_nan=False) + "\n"
    return text.encode("ascii")


def glb_parts(json_chunk, buffer):
    """A .glb as a list of byte strings (glTF 2.0 §4.4): the 12-byte header, the JSON chunk padded with
    spaces, the BIN chunk padded with zeros. A list, so that a large buffer is written without a copy."""
    json_chunk = bytes(json_chunk) + b" " * (-len(json_chunk) % 4)
    padding = b"\0" * (-len(buffer) % 4)
    bin_length = len(buffer) + len(padding)
    return [
        struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(json_chunk) + 8 + bin_length),
        struct.pack("<I4s", len(json_chunk), b"JSON"),
        json_chunk,
        struct.pack("<I4s", bin_length, b"BIN\0"),
        buffer,
        padding,
    ]


def write_file(path, *parts):
    """Writes the byte strings `parts` to `path` through a temporary beside it and os.replace, so that an
    interrupted run never leaves a truncated file under the final name."""
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        for part in parts:
            f.write(part)
    os.replace(tmp, path)


class Builder:
    """One glTF document and its single buffer (buffer 0), built together.

    generator: asset.generator of a new document, whose only member is then `asset`; the other top-level
    arrays appear when something is added to them. Or doc: a document to go on with, as it is, and buffer:
    its data so far (kept, not copied). indent and sort_keys: the JSON format of what is written (json_bytes).
    """

    def __init__(self, generator=None, doc=None, buffer=None, indent=None, sort_keys=True):
        assert (generator is None) != (doc is None), "a generator for a new document, or a document"
        self.doc = {"asset": {"version": "2.0", "generator": generator}} if doc is None else doc
        self.buffer = bytearray() if buffer is None else buffer
        self.indent = indent
        self.sort_keys = sort_keys

    def add(self, kind, item):
        """Appends `item` to the top-level array `kind` ("nodes", "meshes", ...); returns its index."""
        items = self.doc.setdefault(kind, [])
        items.append(item)
        return len(items) - 1

    def pad(self):
        """Pads the buffer with zeros to a multiple of 4 bytes: every bufferView starts 4-byte aligned, so that
        every accessor is aligned to its component size, as glTF requires."""
        self.buffer += b"\0" * (-len(self.buffer) % 4)

    def view(self, data, target=None, stride=None):
        """Appends the bytes `data` to the buffer, 4-byte aligned, as a new bufferView; returns its index."""
        self.pad()
        view = {"buffer": 0, "byteOffset": len(self.buffer), "byteLength": len(data)}
        if target is not None:
            view["target"] = target
        if stride is not None:
            view["byteStride"] = stride
        self.buffer += data
        return self.add("bufferViews", view)

    def accessor(self, values, element_type, component_type=FLOAT, target=None, with_bounds=False,
                 normalized=False):
        """Appends `values` as one accessor in its own bufferView; returns the accessor's index. values: an
        array.array of the component type's typecode, flat (used as it is: the fast path for large meshes),
        or a list of numbers or of tuples of numbers (flattened; floats rounded to float32, so that min and
        max are the values the file holds)."""
        typecode = _TYPECODE[component_type]
        if isinstance(values, array):
            assert values.typecode == typecode, (values.typecode, component_type)
            data = values
        else:
            flat = []
            for v in values:
                if isinstance(v, (list, tuple)):
                    flat.extend(v)
                else:
                    flat.append(v)
            convert = float if component_type == FLOAT else int
            data = array(typecode, [convert(x) for x in flat])
        n = _COMPONENTS[element_type]
        assert len(data) % n == 0 and len(data) > 0, (element_type, len(data))
        if sys.byteorder != "little":  # glTF's buffers are little-endian
            stored = array(typecode, data)
            stored.byteswap()
        else:
            stored = data
        acc = {
            "bufferView": self.view(stored.tobytes(), target),
            "componentType": component_type,
            "count": len(data) // n,
            "type": element_type,
        }
        if normalized:
            acc["normalized"] = True
        if with_bounds:  # the array holds the file's values (float32 for FLOAT): its min/max are the file's
            acc["min"] = [min(data[i::n]) for i in range(n)]
            acc["max"] = [max(data[i::n]) for i in range(n)]
        return self.add("accessors", acc)

    # -- encoding -------------------------------------------------------------------------------------

    def document(self, uri=None):
        """The document to write: buffer 0 gets `uri` (none: for a .glb, whose buffer is the BIN chunk) and
        the buffer's byteLength. A copy as deep as those edits, so the builder can go on; the other members
        keep their place (the key order matters when sort_keys is False)."""
        doc = dict(self.doc)
        buffers = [dict(b) for b in doc.get("buffers") or [{}]]
        if uri is None:
            buffers[0].pop("uri", None)
        else:
            buffers[0]["uri"] = uri
        buffers[0]["byteLength"] = len(self.buffer)
        doc["buffers"] = buffers
        return doc

    def gltf_bytes(self):
        """The .gltf with the buffer embedded as a base64 data: URI, as it is (not padded)."""
        return json_bytes(self.document(data_uri(self.buffer)), self.indent, self.sort_keys)

    def glb_bytes(self, json_chunk=None):
        """The .glb of the document and buffer; json_chunk: other bytes for the JSON chunk (a broken one)."""
        if json_chunk is None:
            json_chunk = json_bytes(self.document(), self.indent, self.sort_keys)
        return b"".join(glb_parts(json_chunk, self.buffer))

    def write_gltf(self, path, external=None):
        """Writes the .gltf `path`, with the buffer embedded as a base64 data: URI (one self-contained file),
        or, given `external` (a file name that needs no URI escaping), in that file beside it. The buffer is
        padded to 4 bytes first, so that its byteLength covers every byte. Returns the .gltf's size."""
        self.pad()
        if external is None:
            uri = data_uri(self.buffer)
        else:
            write_file(os.path.join(os.path.dirname(path), external), self.buffer)
            uri = external
        text = json_bytes(self.document(uri), self.indent, self.sort_keys)
        write_file(path, text)
        return len(text)

    def write_glb(self, path):
        """Writes the .glb `path`; the buffer is padded to 4 bytes first (its byteLength is then the BIN
        chunk's length). Returns the file's size."""
        self.pad()
        parts = glb_parts(json_bytes(self.document(), self.indent, self.sort_keys), self.buffer)
        write_file(path, *parts)
        return sum(len(p) for p in parts)
