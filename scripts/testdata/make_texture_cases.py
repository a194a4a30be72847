#!/usr/bin/env python3
"""Writes the texture-extension cases of the textured cylinder (testdata/textured_cylinder.gltf) into a folder.

    python3 scripts/testdata/make_texture_cases.py OUTDIR

Each case is the same rig with its checker texture stored another way, so that a render of it can be
compared with a render of the PNG-textured original:

  webp_only.gltf        the checker as a lossless WebP through EXT_texture_webp, no core source (the
                        extension is then required, as the extension's README says)
  webp_fallback.gltf    the WebP checker through EXT_texture_webp, and a core `source` fallback that is a
                        plain magenta PNG: a viewer that reads WebP draws the checker
  basisu_fallback.gltf  a KTX2 image through KHR_texture_basisu and the checker PNG as the core `source`
  basisu_only.gltf      a KTX2 image through KHR_texture_basisu and no fallback (required); the KTX2 bytes
                        are a header only, never decoded: drawn with the material's factors
  untextured.gltf       the original without its base color texture: what basisu_only.gltf must look like
  checker.webp          the WebP image alone (for a reader to check it against the PNG)

The WebP is written here (VP8L, lossless, RFC 9649 §3) from the PNG's pixels, so the two hold the same
colours and the renders compare equal. Python 3 standard library only; deterministic.
"""

import base64
import json
import os
import struct
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.join(HERE, "..", "..", "testdata", "textured_cylinder.gltf")


# -- PNG (decode: 8-bit RGB or RGBA, not interlaced, as make_rigs.py writes) ----------------------------


def png_pixels(data):
    """(width, height, rows of (r, g, b, a) tuples) of an 8-bit RGB or RGBA PNG."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = header
    assert depth == 8 and colour in (2, 6) and interlace == 0, "only 8-bit RGB(A) PNGs without interlacing"
    channels = 3 if colour == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):  # PNG filters (ISO 15948 §9.2)
            left = line[i - channels] if i >= channels else 0
            up = previous[i]
            corner = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + left) & 255
            elif kind == 2:
                line[i] = (line[i] + up) & 255
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                line[i] = (line[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else corner)) & 255
        rows.append([tuple(line[x * channels:(x + 1) * channels]) + ((255,) if channels == 3 else ())
                     for x in range(width)])
        previous = line
    return width, height, rows


def png_rgb(width, height, colour):
    """An 8-bit RGB PNG of one colour."""
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    raw = b"".join(b"\0" + bytes(colour) * width for _ in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


# -- WebP (encode: VP8L lossless, literals only) -------------------------------------------------------


class BitWriter:
    """VP8L's bit order: values are written least significant bit first, bytes filled from bit 0."""

    def __init__(self):
        self.bits, self.count = 0, 0

    def put(self, value, n):
        self.bits |= value << self.count
        self.count += n

    def put_code(self, code, length):
        """A prefix code, its first bit (the most significant of the canonical code) first, as DEFLATE."""
        for i in reversed(range(length)):
            self.put((code >> i) & 1, 1)

    def data(self):
        return self.bits.to_bytes((self.count + 7) // 8, "little")


def canonical_codes(lengths):
    """symbol → (code, length) of the canonical prefix code with these lengths (0: unused), as VP8L builds it
    (shorter codes first, then by symbol)."""
    codes, code = {}, 0
    for length in range(1, 16):
        for symbol, l in enumerate(lengths):
            if l == length:
                codes[symbol] = (code, length)
                code += 1
        code <<= 1
    return codes


def put_prefix_code(w, alphabet, used):
    """Writes the prefix code of one alphabet for the symbols `used` (sorted) and returns symbol → (code,
    length). One or two symbols: a "simple" code (RFC 9649 §3.7.2.1.1); more: a "normal" code whose lengths
    make a complete tree (k−1 bits for the first 2^k − n symbols, k for the rest), its code lengths written
    with a code-length code of 16 four-bit codes for the lengths 0..15."""
    if len(used) <= 2:
        w.put(1, 1)  # simple
        w.put(len(used) - 1, 1)
        first = used[0]
        w.put(1 if first > 1 else 0, 1)
        w.put(first, 8 if first > 1 else 1)
        if len(used) == 2:
            w.put(used[1], 8)
            return {used[0]: (0, 1), used[1]: (1, 1)}
        return {first: (0, 0)}
    n = len(used)
    k = (n - 1).bit_length()
    lengths = [0] * alphabet
    for i, symbol in enumerate(used):
        lengths[symbol] = k - 1 if i < (1 << k) - n else k
    w.put(0, 1)  # normal
    order = [17, 18, 0, 1, 2, 3, 4, 5, 16, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15]
    w.put(len(order) - 4, 4)
    for symbol in order:
        w.put(4 if symbol < 16 else 0, 3)
    w.put(0, 1)  # every symbol's length follows
    for l in lengths:
        w.put_code(l, 4)  # lengths 0..15 all take 4 bits: code == length
    return canonical_codes(lengths)


def webp_lossless(width, height, rows):
    """A VP8L WebP of the pixels: no transforms, no colour cache, one prefix-code group, every pixel a literal."""
    w = BitWriter()
    w.put(0x2F, 8)  # VP8L signature
    w.put(width - 1, 14)
    w.put(height - 1, 14)
    alpha = any(p[3] != 255 for row in rows for p in row)
    w.put(1 if alpha else 0, 1)
    w.put(0, 3)  # version
    w.put(0, 1)  # no transform
    w.put(0, 1)  # no colour cache
    w.put(0, 1)  # no meta prefix codes
    pixels = [p for row in rows for p in row]
    codes = []
    for channel, alphabet in ((1, 256 + 24), (0, 256), (2, 256), (3, 256)):  # green, red, blue, alpha
        codes.append((channel, put_prefix_code(w, alphabet, sorted({p[channel] for p in pixels}))))
    put_prefix_code(w, 40, [0])  # distances: never used
    for p in pixels:
        for channel, code in codes:
            w.put_code(*code[p[channel]])
    body = w.data()
    chunk = b"VP8L" + struct.pack("<I", len(body)) + body + b"\0" * (len(body) % 2)
    return b"RIFF" + struct.pack("<I", 4 + len(chunk)) + b"WEBP" + chunk


# -- the cases -----------------------------------------------------------------------------------------

# A KTX2 file's identifier (KTX 2.0 §3.1) and a header of zeros: enough for a reader to tell the format,
# never decoded.
KTX2 = b"\xabKTX 20\xbb\r\n\x1a\n" + b"\0" * 68


def with_images(doc, buffer, images):
    """A copy of `doc` whose images are `images` (mime type, bytes) appended to the buffer."""
    doc = json.loads(json.dumps(doc))
    data = bytearray(buffer)
    doc["images"] = []
    for mime, content in images:
        data += b"\0" * (-len(data) % 4)
        doc["bufferViews"].append({"buffer": 0, "byteOffset": len(data), "byteLength": len(content)})
        data += content
        doc["images"].append({"bufferView": len(doc["bufferViews"]) - 1, "mimeType": mime})
    doc["buffers"][0] = {"byteLength": len(data),
                         "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(data)).decode("ascii")}
    return doc


def write(folder, name, doc):
    with open(os.path.join(folder, name), "w", encoding="ascii") as f:
        json.dump(doc, f, indent=1, sort_keys=True)
        f.write("\n")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    folder = sys.argv[1]
    os.makedirs(folder, exist_ok=True)
    with open(SOURCE, encoding="utf-8") as f:
        doc = json.load(f)
    uri = doc["buffers"][0]["uri"]
    buffer = base64.b64decode(uri[uri.index(",") + 1:])
    view = doc["bufferViews"][doc["images"][0]["bufferView"]]
    png = buffer[view.get("byteOffset", 0):view.get("byteOffset", 0) + view["byteLength"]]
    webp = webp_lossless(*png_pixels(png))
    with open(os.path.join(folder, "checker.webp"), "wb") as f:
        f.write(webp)
    texture = doc["textures"][0]
    sampler = {"sampler": texture["sampler"]} if "sampler" in texture else {}

    def case(name, images, texture_fields, extension, required):
        out = with_images(doc, buffer, images)
        out["textures"] = [dict(sampler, **texture_fields)]
        out["extensionsUsed"] = [extension]
        if required:
            out["extensionsRequired"] = [extension]
        write(folder, name, out)

    webp_ext = "EXT_texture_webp"
    basisu = "KHR_texture_basisu"
    magenta = png_rgb(8, 8, (255, 0, 255))
    case("webp_only.gltf", [("image/webp", webp)], {"extensions": {webp_ext: {"source": 0}}}, webp_ext, True)
    case("webp_fallback.gltf", [("image/png", magenta), ("image/webp", webp)],
         {"source": 0, "extensions": {webp_ext: {"source": 1}}}, webp_ext, False)
    case("basisu_fallback.gltf", [("image/png", png), ("image/ktx2", KTX2)],
         {"source": 0, "extensions": {basisu: {"source": 1}}}, basisu, False)
    case("basisu_only.gltf", [("image/ktx2", KTX2)], {"extensions": {basisu: {"source": 0}}}, basisu, True)
    plain = json.loads(json.dumps(doc))
    del plain["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]
    for key in ("textures", "images", "samplers"):
        plain.pop(key, None)
    write(folder, "untextured.gltf", plain)


if __name__ == "__main__":
    main()
