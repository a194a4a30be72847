#!/usr/bin/env python3
"""Writes the inputs of the shared-vertex and texture-size tests (app/tests/output_sizes.cmake).

Usage: python3 scripts/testdata/make_shared_vertex_cases.py OUTPUT_DIR

Shared vertex data: glTF lets several primitives of a mesh name the same accessors (§3.7.2.1); exporters
that split a mesh by material, and VRM files, do so with one vertex set and one index list per material.
  shared_vertices.gltf         a two-joint tube whose mesh has 3 primitives (3 materials) naming one
                               POSITION/NORMAL/TEXCOORD_0/JOINTS_0/WEIGHTS_0 set, with different index
                               lists (a band of the tube each), and one morph target they share too.
  shared_vertices_single.gltf  the same vertices as one primitive whose index list is the three
                               concatenated: what the outputs of the shared file must equal vertex for
                               vertex (the distinct vertices, in accessor order).
  partly_shared_vertices.gltf  shared_vertices.gltf with the third primitive's NORMAL its own accessor
                               (the same values): it does not share, so it adds its vertices again.
Texture sizes:
  wide_tube.gltf               a tube of 9,000 vertices (wider than 8192 texels in one row) with a
                               300 s clip: 9,001 frames at 30 fps, more rows than 8192.

Deterministic: the same bytes on every run (scripts/testdata/gltf_builder.py writes the container).
"""

import os
import sys

from gltf_builder import ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER, UNSIGNED_SHORT
from make_rigs import Gltf, quat_axis_angle, textured_tube, tube, two_joint_weights

# The tube of the shared cases: 9 stations (y = 0 .. 2 in steps of 1/4), 12 around plus a UV seam.
STATIONS = [0.25 * i for i in range(9)]
AROUND = 12
# The three primitives' bands of stations: [0, 3), [3, 6), [6, 8) (quads between station s and s + 1).
BANDS = [(0, 3), (3, 6), (6, 8)]


def band_indices(indices, band):
    """The triangles of `indices` (a flat list of tube() / textured_tube() faces, station by station) whose
    quads lie in `band`."""
    per_station = 2 * 3 * AROUND  # two triangles per quad, AROUND quads a station
    return indices[band[0] * per_station:band[1] * per_station]


def tube_rig(layout):
    """layout: "shared" (three primitives, one vertex set), "single" (one primitive), or "partly" (the third
    primitive with a NORMAL accessor of its own)."""
    g = Gltf()
    g.doc["asset"]["generator"] = "dqskin scripts/testdata/make_shared_vertex_cases.py"
    geo = textured_tube(0.5, STATIONS, AROUND)
    joints, weights = two_joint_weights(STATIONS, geo["station"], 0.75, 1.25)
    # One morph target: the top ring bulges out by a quarter (exact in float32).
    bulge = [(0.125 * p[0], 0.0, 0.125 * p[2]) if s == len(STATIONS) - 1 else (0.0, 0.0, 0.0)
             for p, s in zip(geo["positions"], geo["station"])]
    attributes = {
        "POSITION": g.accessor(geo["positions"], "VEC3", target=ARRAY_BUFFER, with_bounds=True),
        "NORMAL": g.accessor(geo["normals"], "VEC3", target=ARRAY_BUFFER),
        "TEXCOORD_0": g.accessor(geo["uv"], "VEC2", target=ARRAY_BUFFER),
        "JOINTS_0": g.accessor(joints, "VEC4", 5121, target=ARRAY_BUFFER),
        "WEIGHTS_0": g.accessor(weights, "VEC4", target=ARRAY_BUFFER),
    }
    targets = [{"POSITION": g.accessor(bulge, "VEC3", target=ARRAY_BUFFER, with_bounds=True)}]
    colors = [(0.8, 0.2, 0.2, 1.0), (0.2, 0.8, 0.2, 1.0), (0.2, 0.2, 0.8, 1.0)]
    materials = [g.material("band_%d" % i, base_color_factor=c) for i, c in enumerate(colors)]
    primitives = []
    if layout == "single":
        index = g.accessor(geo["indices"], "SCALAR", UNSIGNED_SHORT, target=ELEMENT_ARRAY_BUFFER)
        primitives.append({"attributes": attributes, "indices": index, "material": materials[0], "targets": targets})
    else:
        for i, band in enumerate(BANDS):
            own = dict(attributes)
            if layout == "partly" and i == 2:
                own["NORMAL"] = g.accessor(geo["normals"], "VEC3", target=ARRAY_BUFFER)
            index = g.accessor(band_indices(geo["indices"], band), "SCALAR", UNSIGNED_SHORT, target=ELEMENT_ARRAY_BUFFER)
            primitives.append({"attributes": own, "indices": index, "material": materials[i], "targets": targets})
    mesh = g.add("meshes", {"name": "tube", "primitives": primitives, "weights": [0.0]})
    tube_node = g.node("tube", mesh=mesh, skin=0)
    root = g.node("root", children=[tube_node + 2])
    child = g.node("child", translation=(0.0, 1.0, 0.0))
    g.skin("tube_skin", [root, child], [(0.0, 0.0, 0.0), (0.0, 1.0, 0.0)])
    times = [0.0, 0.25, 0.5, 0.75, 1.0]
    g.animation("bend", [
        (child, "rotation", "LINEAR", times, [tuple(quat_axis_angle((0, 0, 1), 15.0 * i)) for i in range(5)]),
        (tube_node, "weights", "LINEAR", times, [0.0, 0.25, 0.5, 0.75, 1.0]),
    ])
    g.scene("scene", [tube_node, root])
    return g


def wide_tube():
    """9,000 vertices (100 rings of 90 around), two joints, one 300 s clip: a VAT row of every vertex is
    9,000 texels wide, and 9,001 frames at 30 fps take more than 8192 rows."""
    g = Gltf()
    g.doc["asset"]["generator"] = "dqskin scripts/testdata/make_shared_vertex_cases.py"
    stations = [0.0625 * i for i in range(100)]  # y = 0 .. 6.1875
    geo = tube("y", 0.5, stations, 90)
    joints, weights = two_joint_weights(stations, geo["station"], 2.0, 4.0)
    mesh = g.skinned_mesh("wide_tube", geo, [(joints, weights)])
    tube_node = g.node("wide_tube", mesh=mesh, skin=0)
    root = g.node("root", children=[tube_node + 2])
    child = g.node("child", translation=(0.0, 3.0, 0.0))
    g.skin("wide_tube_skin", [root, child], [(0.0, 0.0, 0.0), (0.0, 3.0, 0.0)])
    g.animation("sway", [(child, "rotation", "LINEAR", [0.0, 150.0, 300.0],
                          [tuple(quat_axis_angle((0, 0, 1), a)) for a in (0.0, 30.0, 0.0)])])
    g.scene("scene", [tube_node, root])
    return g


CASES = {
    "shared_vertices.gltf": lambda: tube_rig("shared"),
    "shared_vertices_single.gltf": lambda: tube_rig("single"),
    "partly_shared_vertices.gltf": lambda: tube_rig("partly"),
    "wide_tube.gltf": wide_tube,
}


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    os.makedirs(argv[1], exist_ok=True)
    for name, make in CASES.items():
        make().write_gltf(os.path.join(argv[1], name))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
