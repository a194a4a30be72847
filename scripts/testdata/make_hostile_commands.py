#!/usr/bin/env python3
"""Crafted inputs for the commands that came after the loader's hardening (app/tests/command_limits.cmake,
docs/SECURITY.md "Every command"): each made a command crash, hang, take memory past --max-memory, leak a
file's content or leave a half-written output; each class of problem is one small generated case here,
never a downloaded file.

    make_hostile_commands.py OUTDIR

writes one folder per command under OUTDIR (report/, diff/, lint/, verify/), deterministic, byte for byte.
Python 3 standard library only.
"""

import copy
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import make_malformed as malformed  # noqa: E402  (the quad skinned to two joints, and its accessors)


def write(folder, name, data):
    path = os.path.join(folder, name)
    with open(path, "wb") as f:
        f.write(data)


def report_cases(folder):
    """dqskin report.

    clips_1000.gltf   the quad with its clip repeated 1,000 times (a 120 KB file): each clip's contact sheet
                      and the page that embeds them all took 5.7 GB whatever --max-memory said
    clip_2e5.gltf     the quad whose clip lasts 2·10^5 s: at 1 fps, 200,000 frames of figures; past
                      --max-memory the report's document was destroyed while the refusal unwound, and its
                      destructor's own allocation ended the process (abort, two lines, a stray sheet)
    rig_300_joints.glb  a tube of 6,000 vertices on 300 joints (scripts/testdata/make_big_rig.py): its report.json
                      is tens of MB, so a signal during the writing found the sheet written and no page
    """
    a = malformed.base_asset()
    a.gltf["animations"] = [copy.deepcopy(a.gltf["animations"][0]) for _ in range(1000)]
    for i, animation in enumerate(a.gltf["animations"]):
        animation["name"] = "clip%d" % i
    write(folder, "clips_1000.gltf", a.gltf_bytes())

    a = malformed.base_asset()
    offset = a.accessor_offset(malformed.TIMES)
    a.bin[offset:offset + 12] = struct.pack("<3f", 0.0, 0.5, 2e5)
    a.gltf["accessors"][malformed.TIMES]["max"] = [2e5]
    write(folder, "clip_2e5.gltf", a.gltf_bytes())

    subprocess.run([sys.executable, os.path.join(HERE, "make_big_rig.py"), os.path.join(folder, "rig_300_joints.glb"),
                    "--vertices", "6000", "--joints", "300", "--seconds", "4"], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)


# OpenEXR files (the OpenEXR file layout: single-part scanline images): the magic and version 2, the
# header's attributes (name, type, size, value) up to an empty name, one offset per block of rows, then
# the blocks, each its first row, its byte count and its rows, every channel's row in turn (channels in
# name order). NO_COMPRESSION stores one row a block; ZIP 16 rows, their bytes split into even and odd
# ones, delta-coded and deflated.
EXR_NONE, EXR_ZIP = 0, 3
EXR_HALF, EXR_FLOAT = 1, 2


def exr_header(width, height, channels, pixel_type, compression):
    def attribute(name, type_, value):
        return name.encode() + b"\0" + type_.encode() + b"\0" + struct.pack("<i", len(value)) + value
    chlist = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", pixel_type, 0, 1, 1) for c in sorted(channels))
    window = struct.pack("<4i", 0, 0, width - 1, height - 1)
    return (struct.pack("<ii", 20000630, 2) + attribute("channels", "chlist", chlist + b"\0") +
            attribute("compression", "compression", bytes([compression])) +
            attribute("dataWindow", "box2i", window) + attribute("displayWindow", "box2i", window) +
            attribute("lineOrder", "lineOrder", b"\0") + attribute("pixelAspectRatio", "float", struct.pack("<f", 1)) +
            attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0)) +
            attribute("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")


def exr_zip(raw):
    """A ZIP block's data: even bytes then odd ones, each byte the difference to the one before plus 128."""
    split = raw[0::2] + raw[1::2]
    coded = bytes([split[0]]) + bytes((b - a + 128) & 255 for a, b in zip(split, split[1:])) if split else b""
    packed = zlib.compress(coded, 9)
    return packed if len(packed) < len(raw) else raw


def exr(width, height, channels, pixel_type, value, compression=EXR_NONE):
    """A valid image whose channel c at (x, y) is value(x, y, c). Blocks of equal rows are coded once."""
    code = "<%d%s" % (width, "e" if pixel_type == EXR_HALF else "f")
    rows_per_block = 16 if compression == EXR_ZIP else 1
    coded = {}
    blocks = []
    for y in range(0, height, rows_per_block):
        raw = b"".join(struct.pack(code, *[value(x, row, c) for x in range(width)])
                       for row in range(y, min(height, y + rows_per_block)) for c in sorted(channels))
        if raw not in coded:
            coded[raw] = exr_zip(raw) if compression == EXR_ZIP else raw
        blocks.append(struct.pack("<ii", y, len(coded[raw])) + coded[raw])
    header = exr_header(width, height, channels, pixel_type, compression)
    offsets, at = [], len(header) + 8 * len(blocks)
    for block in blocks:
        offsets.append(at)
        at += len(block)
    return header + struct.pack("<%dQ" % len(offsets), *offsets) + b"".join(blocks)


def exr_declaring(width, height, channels="ABGR"):
    """Only the header of a ZIP image of HALF channels and an offset table of zeros, which OpenEXR rebuilds
    when it opens the file: any size, declared in a few kilobytes."""
    return exr_header(width, height, channels, EXR_HALF, EXR_ZIP) + b"\0" * (8 * ((height + 15) // 16))


def diff_cases(folder):
    """dqskin diff: images, bake folders and glTF files.

    wide_a.exr, wide_b.exr        valid 12000x1 images (ZIP, HALF): diff read them through a buffer of
                                  OpenImageIO's of 66 MB, so that --max-memory 16M refused them
    tall.exr                      a valid 12000x2400 image of one FLOAT channel (115 MB as float, 118 KB
                                  as a file): under --max-memory 96M OpenImageIO's ImageBuf could not
                                  allocate it, and diff read it through its null pointer (a crash)
    declared_a.exr, _b.exr        headers that declare 12000x12000 RGBA (2.3 GB as float) in 6 KB
    bake_exr/A, bake_exr/B        bake folders (manifest.json) whose vat.exr is declared_a.exr: the bake diff
                                  allocated the declared size, 2.7 GB at --max-memory 256M
    bake_link/A, bake_link/B      bake folders whose frame.ply is a symbolic link to secret.txt outside them:
                                  the bake diff read it and quoted it in its parse error
    bake_quote/A, bake_quote/B    bake folders whose frame.ply names a secret word as a property and whose
                                  frame.glb holds one in malformed JSON: the errors quoted them
    vertices_a.gltf, _b.gltf      the quad with 22,369,620 vertices of a POSITION accessor without a buffer
                                  (2.7 KB): the geometric diff allocated gigabytes for them
    vertices_6m_a.gltf, _b.gltf   6,000,000 such vertices: the sides fit, a frame of both does not
    quad.gltf, still.gltf         the quad, and the quad without its clip: no clip in common
    apart.gltf                    the quad moved 1000 units away: the meshes do not overlap
    """
    write(folder, "wide_a.exr", exr(12000, 1, "BGR", EXR_HALF, lambda x, y, c: (x % 256) / 255.0, EXR_ZIP))
    write(folder, "wide_b.exr", exr(12000, 1, "BGR", EXR_HALF, lambda x, y, c: (x % 256) / 255.0, EXR_ZIP))
    write(folder, "tall.exr", exr(12000, 2400, "Y", EXR_FLOAT, lambda x, y, c: 0.5, EXR_ZIP))
    for name in ("declared_a.exr", "declared_b.exr"):
        write(folder, name, exr_declaring(12000, 12000))

    secret = b"ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty double SECRET_WORD\nend_header\n"
    write(folder, "secret.txt", secret)
    for side in ("A", "B"):
        for bake in ("bake_exr", "bake_link", "bake_quote"):
            os.makedirs(os.path.join(folder, bake, side))
            write(os.path.join(folder, bake, side), "manifest.json", b"{}\n")
        write(os.path.join(folder, "bake_exr", side), "vat.exr", exr_declaring(12000, 12000))
        os.symlink(os.path.join("..", "..", "secret.txt"), os.path.join(folder, "bake_link", side, "frame.ply"))
        write(os.path.join(folder, "bake_quote", side), "frame.ply", secret)
        write(os.path.join(folder, "bake_quote", side), "frame.glb", b'{"asset":{"version":"2.0"},"x":"SECRET_WORD\x01"}')

    def declaring_vertices(count):
        a = malformed.base_asset()
        values = a.add_view(struct.pack("<3f", 0, 1, 0))
        index = a.add_view(struct.pack("<I", 1))
        a.gltf["accessors"].append({"componentType": malformed.FLOAT, "count": count, "type": "VEC3", "sparse": {
            "count": 1, "indices": {"bufferView": index, "componentType": malformed.UINT}, "values": {"bufferView": values}}})
        a.gltf["meshes"][0]["primitives"] = [{"attributes": {"POSITION": len(a.gltf["accessors"]) - 1}}]
        del a.gltf["nodes"][0]["skin"]
        return a.gltf_bytes()
    # The most vertices an accessor without a buffer may have (LoadOptions::max_unbacked_elements, 2^26
    # values), whole triangles.
    for name in ("vertices_a.gltf", "vertices_b.gltf"):
        write(folder, name, declaring_vertices((1 << 26) // 9 * 3))
    for name in ("vertices_6m_a.gltf", "vertices_6m_b.gltf"):
        write(folder, name, declaring_vertices(6000000))

    quad = malformed.base_asset()
    write(folder, "quad.gltf", quad.gltf_bytes())
    still = quad.copy()
    del still.gltf["animations"]
    write(folder, "still.gltf", still.gltf_bytes())
    apart = quad.copy()
    apart.gltf["nodes"][1]["translation"] = [1000, 1000, 1000]
    write(folder, "apart.gltf", apart.gltf_bytes())


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


# The SHA-256 of no bytes: what a manifest lists for an empty file.
EMPTY_SHA256 = "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"


def manifest_text(outputs, index=0, count=1, output_folder="o"):
    """A manifest as bake writes one (the fields verify and merge read), compact; `outputs` is a list of
    (path, size, sha256)."""
    entries = ",".join('{"path":%s,"sha256":"%s","size":%d}' % (json.dumps(p), h, n) for p, n, h in outputs)
    return ('{"inputs":[{"animations":[],"output_folder":%s,"path":"in.glb"}],"mode":"dqs","outputs":[%s],'
            '"shard":{"count":%d,"index":%d}}' % (json.dumps(output_folder), entries, count, index)).encode()


def verify_cases(folder):
    """dqskin verify and dqskin merge: a folder per case, each holding the manifests named below.

    entries_400k/     manifest.shard-0-of-2.json lists 400,000 files (none there; a 38 MB file) and
                      manifest.shard-1-of-2.json none: verify took 32 s and merge 58 s (the JSON parser's
                      depth callback searched the whole outputs list after each entry)
    deep_path/        one listed path 20,000 folders deep: verify never returned (every ancestor's path
                      split into its parts, and copied, for each ancestor)
    many_shards/      manifest.shard-0-of-999999.json alone: 999,998 shards missing
    truncated/        a manifest cut in the middle of an entry
    huge_numbers/     a size past 2^64 and a shard index of 1e400
    deep_nesting/     a manifest 100,000 arrays deep
    dot_dot/          a listed path ../outside
    absolute/         a listed path /etc/passwd
    symlink/          the output folder o a symbolic link to /etc, listing o/passwd
    nul_name/         a listed path with a NUL byte in it ("o/a\\u0000b")
    conflict/         one path listed twice, with other sizes
    mergeable/        10,000 empty files under o/ and the two shard manifests that list them: a merge that
                      succeeds, to be stopped by a signal at any point
    """
    def case(name, files):
        os.makedirs(os.path.join(folder, name))
        for file_name, data in files.items():
            write(os.path.join(folder, name), file_name, data)

    case("entries_400k", {
        "manifest.shard-0-of-2.json": manifest_text([("o/%06d" % i, 0, EMPTY_SHA256) for i in range(400000)], 0, 2),
        "manifest.shard-1-of-2.json": manifest_text([], 1, 2)})
    case("deep_path", {"manifest.json": manifest_text([("o/" + "a/" * 20000 + "f", 0, EMPTY_SHA256)])})
    case("many_shards", {"manifest.shard-0-of-999999.json": manifest_text([], 0, 999999)})
    whole = manifest_text([("o/%d" % i, 0, EMPTY_SHA256) for i in range(4)])
    case("truncated", {"manifest.json": whole[:len(whole) // 2]})
    case("huge_numbers", {"manifest.json": manifest_text([("o/a", 0, EMPTY_SHA256)]).replace(
        b'"size":0', b'"size":184467440737095516160000').replace(b'"index":0', b'"index":1e400')})
    case("deep_nesting", {"manifest.json": b"[" * 100000 + b"]" * 100000})
    case("dot_dot", {"manifest.json": manifest_text([("../outside", 0, EMPTY_SHA256)])})
    case("absolute", {"manifest.json": manifest_text([("/etc/passwd", 0, EMPTY_SHA256)])})
    case("symlink", {"manifest.json": manifest_text([("o/passwd", 0, EMPTY_SHA256)])})
    os.symlink("/etc", os.path.join(folder, "symlink", "o"))
    case("nul_name", {"manifest.json": manifest_text([("o/a\0b", 0, EMPTY_SHA256)])})
    case("conflict", {"manifest.json": manifest_text([("o/a", 0, EMPTY_SHA256), ("o/a", 1, EMPTY_SHA256)])})
    case("mergeable", {"manifest.shard-%d-of-2.json" % s: manifest_text(
        [("o/%05d" % i, 0, EMPTY_SHA256) for i in range(s, 10000, 2)], s, 2) for s in range(2)})
    os.makedirs(os.path.join(folder, "mergeable", "o"))
    for i in range(10000):
        write(os.path.join(folder, "mergeable", "o"), "%05d" % i, b"")


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make_hostile_commands.py OUTDIR")
    out = sys.argv[1]
    if os.path.exists(out):
        shutil.rmtree(out)
    for name, make in [("report", report_cases), ("diff", diff_cases), ("lint", lint_cases),
                       ("verify", verify_cases)]:
        os.makedirs(os.path.join(out, name))
        make(os.path.join(out, name))


if __name__ == "__main__":
    main()
