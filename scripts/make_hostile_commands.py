#!/usr/bin/env python3
"""Crafted inputs for the commands that came after the loader's hardening (app/tests/command_limits.cmake,
docs/SECURITY.md "Every command"): each made a command crash, hang, take memory past --max-memory, leak a
file's content or leave a half-written output; each class of problem is one small generated case here,
never a downloaded file.

    make_hostile_commands.py OUTDIR

writes one folder per command under OUTDIR (report/, verify/), deterministic, byte for byte. Python 3 standard
library only.
"""

import copy
import json
import os
import shutil
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
    for name, make in [("report", report_cases), ("verify", verify_cases)]:
        os.makedirs(os.path.join(out, name))
        make(os.path.join(out, name))


if __name__ == "__main__":
    main()
