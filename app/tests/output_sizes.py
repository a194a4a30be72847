#!/usr/bin/env python3
"""Outputs at their true size (app/tests/output_sizes.cmake): bakes the cases of
scripts/testdata/make_shared_vertex_cases.py and checks what the files hold. Python 3 standard library only.

    output_sizes.py shared DQSKIN CASES_DIR OUT_DIR
        shared_vertices.gltf (three primitives naming one vertex set) baked to ply, obj, vat (each profile)
        and morph holds each distinct vertex once: its PLY frames and VAT images are byte for byte those of
        shared_vertices_single.gltf (the same vertices as one primitive with the three index lists
        concatenated), so they deform identically; OBJ has the same v and vn lines; vat.json lists one
        source shared by the other two primitives; rest.glb, NAME.glb and animation.glb draw three
        primitives over one vertex set. partly_shared_vertices.gltf (one primitive with a NORMAL accessor of
        its own) writes its vertices twice.
    output_sizes.py wide DQSKIN CASES_DIR OUT_DIR
        wide_tube.gltf (9,000 vertices) baked to a VAT in each profile at the default --max-size: every image
        within 8192 texels a side, the rest mesh's lookups inside the image, the decode-back check passed
        (the bake exits 0 only then).

Exit status 0 when every check passes; 1 with one line per failure.
"""
import json
import os
import shutil
import struct
import subprocess
import sys

FAILURES = []


def check(condition, message):
    if not condition:
        FAILURES.append(message)
    return condition


def bake(dqskin, source, out, *args):
    shutil.rmtree(out, ignore_errors=True)
    command = [dqskin, "bake", source, "-o", out, "--quiet"] + list(args)
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("output_sizes: %s exited %d: %s" % (" ".join(command), result.returncode, result.stderr.strip()))
    stem = os.path.splitext(os.path.basename(source))[0]
    clips = [d for d in sorted(os.listdir(os.path.join(out, stem))) if os.path.isdir(os.path.join(out, stem, d))]
    assert len(clips) == 1, clips
    return os.path.join(out, stem, clips[0])


def read(path):
    with open(path, "rb") as f:
        return f.read()


def glb_json(path):
    data = read(path)
    assert data[:4] == b"glTF", path
    length = struct.unpack("<I", data[12:16])[0]
    return json.loads(data[20:20 + length])


def ply_vertices(path):
    header = read(path).split(b"end_header\n", 1)[0].decode("ascii")
    return int(header.split("element vertex ")[1].split("\n")[0])


def files(folder, suffix):
    return sorted(f for f in os.listdir(folder) if f.endswith(suffix))


def one_vertex_set(doc, name, primitives, vertices):
    """The .glb's mesh draws `primitives` primitives naming the same attribute (and target) accessors, whose
    POSITION holds `vertices` vertices."""
    prims = doc["meshes"][0]["primitives"]
    if not check(len(prims) == primitives, "%s: %d primitives, expected %d" % (name, len(prims), primitives)):
        return
    for p in prims[1:]:
        check(p["attributes"] == prims[0]["attributes"], "%s: a primitive names other vertex accessors" % name)
        check(p.get("targets") == prims[0].get("targets"), "%s: a primitive names other morph target accessors" % name)
    count = doc["accessors"][prims[0]["attributes"]["POSITION"]]["count"]
    check(count == vertices, "%s: POSITION holds %d vertices, expected %d" % (name, count, vertices))


def shared(dqskin, cases, out):
    vertices = 117  # 9 rings of 12 + 1 (the UV seam)
    mesh_formats = ["--format", "ply,obj,morph"]
    shared_dir = bake(dqskin, os.path.join(cases, "shared_vertices.gltf"), os.path.join(out, "shared"), *mesh_formats)
    single_dir = bake(dqskin, os.path.join(cases, "shared_vertices_single.gltf"), os.path.join(out, "single"),
                      *mesh_formats)
    plys = files(shared_dir, ".ply")
    check(len(plys) == 31 and plys == files(single_dir, ".ply"), "PLY frames differ in number: %s" % plys[:3])
    for name in plys:
        check(ply_vertices(os.path.join(shared_dir, name)) == vertices,
              "%s: %d vertices, expected %d" % (name, ply_vertices(os.path.join(shared_dir, name)), vertices))
        check(read(os.path.join(shared_dir, name)) == read(os.path.join(single_dir, name)),
              "%s differs from the single primitive's" % name)
    for name in files(shared_dir, ".obj"):
        mine = read(os.path.join(shared_dir, name)).decode().splitlines()
        theirs = read(os.path.join(single_dir, name)).decode().splitlines()
        for tag in ("v ", "vt ", "vn ", "f "):
            check([l for l in mine if l.startswith(tag)] == [l for l in theirs if l.startswith(tag)],
                  "%s: its '%s' lines differ from the single primitive's" % (name, tag.strip()))
        check(sum(l.startswith("usemtl ") for l in mine) == 3, "%s: not one usemtl per primitive" % name)
    one_vertex_set(glb_json(os.path.join(shared_dir, "animation.glb")), "animation.glb", 3, vertices)
    shared_size = os.path.getsize(os.path.join(shared_dir, "animation.glb"))
    single_size = os.path.getsize(os.path.join(single_dir, "animation.glb"))
    check(shared_size < single_size * 1.05,
          "animation.glb: %d bytes, the single primitive's %d" % (shared_size, single_size))

    for profile, mesh in (("dqskin", "rest.glb"), ("openvat", "shared_vertices.glb"),
                          ("houdini", "shared_vertices_mesh.glb")):
        args = ["--format", "vat", "--vat-profile", profile]
        mine = bake(dqskin, os.path.join(cases, "shared_vertices.gltf"), os.path.join(out, "shared_" + profile), *args)
        theirs = bake(dqskin, os.path.join(cases, "shared_vertices_single.gltf"),
                      os.path.join(out, "single_" + profile), *args)
        images = files(mine, ".exr")
        # openvat and houdini name their files after the input
        theirs_of = {name: name.replace("shared_vertices", "shared_vertices_single") for name in images}
        check(images and sorted(theirs_of.values()) == files(theirs, ".exr"), "%s: images %s" % (profile, images))
        for name in images:
            check(read(os.path.join(mine, name)) == read(os.path.join(theirs, theirs_of[name])),
                  "%s: %s differs from the single primitive's" % (profile, name))
        side = json.loads(read(os.path.join(mine, "vat.json")))
        check(side["vertex_count"] == vertices, "%s vat.json: vertex_count %s" % (profile, side["vertex_count"]))
        sources = side["sources"]
        check(len(sources) == 1 and sources[0]["primitive"] == 0 and sources[0].get("shared_by") == [1, 2] and
              sources[0]["vertex_count"] == vertices, "%s vat.json: sources %s" % (profile, sources))
        one_vertex_set(glb_json(os.path.join(mine, mesh)), profile + " " + mesh, 3, vertices)

    partly = bake(dqskin, os.path.join(cases, "partly_shared_vertices.gltf"), os.path.join(out, "partly"),
                  "--format", "ply,vat")
    check(ply_vertices(os.path.join(partly, "frame_0000.ply")) == 2 * vertices,
          "partly shared: %d PLY vertices, expected %d" % (ply_vertices(os.path.join(partly, "frame_0000.ply")),
                                                           2 * vertices))
    side = json.loads(read(os.path.join(partly, "vat.json")))
    check([s.get("shared_by") for s in side["sources"]] == [[1], []], "partly shared vat.json: %s" % side["sources"])


def wide(dqskin, cases, out):
    source = os.path.join(cases, "wide_tube.gltf")
    for profile, mesh in (("dqskin", "rest.glb"), ("openvat", "wide_tube.glb"), ("houdini", "wide_tube_mesh.glb")):
        folder = bake(dqskin, source, os.path.join(out, "wide_" + profile), "--format", "vat", "--vat-profile", profile,
                      "--frames", "0:40")
        side = json.loads(read(os.path.join(folder, "vat.json")))
        width, height = side["width"], side["height"]
        check(width <= 8192 and height <= 8192, "%s: a %d x %d image, over 8192" % (profile, width, height))
        rows = side.get("wraps", side["rows_per_frame"])  # openvat: wraps of every frame's rows
        check(rows > 1, "%s: %d row per frame for 9,000 vertices" % (profile, rows))
        for name in files(folder, ".exr"):
            data = read(os.path.join(folder, name))
            check(len(data) > 0, "%s: %s is empty" % (profile, name))
        check(os.path.exists(os.path.join(folder, mesh)), "%s: no %s" % (profile, mesh))


def main():
    if len(sys.argv) != 5 or sys.argv[1] not in ("shared", "wide"):
        sys.exit("usage: output_sizes.py shared|wide DQSKIN CASES_DIR OUT_DIR")
    (shared if sys.argv[1] == "shared" else wide)(*sys.argv[2:])
    for line in FAILURES:
        print("output_sizes: " + line)
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
