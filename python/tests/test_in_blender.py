"""dqskin inside Blender: run by Blender's own Python (3.11 on Debian, as the module is built for), it
imports dqskin, deforms a clip, and compares it with Blender's armature modifier on the same file imported
by Blender's glTF importer, at a key time (so neither resamples): linear blending against dqskin's lbs, and
the modifier's "Preserve Volume" (Blender's dual-quaternion skinning) against dqskin's dqs.

    blender -b --factory-startup --python-exit-code 1 --python test_in_blender.py -- MODULE_DIR SOURCE_DIR

Vertices are matched by position (each of Blender's to its nearest of dqskin's: the importer may reorder
or split them), Blender's Z-up turned back to glTF's Y-up. The tolerance, 1e-5 of the model's diagonal,
is float32 rounding on both sides with room to spare (measured: 1e-7); a wrong mode misses it by far, and
the test checks that too, so that it can fail. Exit status 1 on any mismatch (--python-exit-code).
"""
import pathlib
import sys

args = sys.argv[sys.argv.index("--") + 1:]
sys.path.insert(0, args[0])
SOURCE = pathlib.Path(args[1])

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import dqskin  # noqa: E402

# Debian's Blender 3.4 glTF importer still uses np.bool, which NumPy 1.24 removed (the builtin is what
# it meant).
if "bool" not in np.__dict__:
    np.bool = bool

TOLERANCE = 1e-5


def blender_positions(mesh, time, preserve_volume):
    for modifier in mesh.modifiers:
        if modifier.type == "ARMATURE":
            modifier.use_deform_preserve_volume = preserve_volume
    scene = bpy.context.scene
    frame = time * scene.render.fps / scene.render.fps_base
    assert abs(frame - round(frame)) < 1e-9, f"t = {time} s is not on a frame at {scene.render.fps} fps"
    scene.frame_set(int(round(frame)))
    evaluated = mesh.evaluated_get(bpy.context.evaluated_depsgraph_get())
    data = evaluated.to_mesh()
    points = np.array([evaluated.matrix_world @ v.co for v in data.vertices], dtype=np.float64)
    evaluated.to_mesh_clear()
    return np.stack([points[:, 0], points[:, 2], -points[:, 1]], axis=1)  # Z-up (x, y, z) to Y-up (x, z, -y)


def farthest_miss(blender, ours):
    """The largest distance from one of Blender's vertices to the nearest of ours."""
    worst = 0.0
    for start in range(0, len(blender), 512):
        block = blender[start:start + 512]
        d = ((block[:, None, :] - ours[None, :, :]) ** 2).sum(axis=-1)
        worst = max(worst, float(np.sqrt(d.min(axis=1)).max()))
    return worst


def check(path, clip, time):
    bpy.ops.wm.read_homefile(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=str(path))
    meshes = [o for o in bpy.data.objects if o.type == "MESH" and any(m.type == "ARMATURE" for m in o.modifiers)]
    assert len(meshes) == 1, f"{path}: {len(meshes)} skinned meshes"
    asset = dqskin.load(str(path))
    chosen = asset.clip(clip)
    # Blender names an action by its animation, or "Anim_<index>" when the file leaves the animation unnamed
    # (dqskin then calls it "animation<index>").
    names = (chosen.name, f"Anim_{chosen.index}")
    # The importer makes one action per animation and plays the first: play this one, alone.
    for armature in (o for o in bpy.data.objects if o.type == "ARMATURE"):
        data = armature.animation_data
        actions = [a for a in bpy.data.actions if any(a.name == n or a.name.startswith(n + "_") for n in names)]
        assert data and actions, f"{path}: no action of animation {names} ({[a.name for a in bpy.data.actions]})"
        for track in data.nla_tracks:
            track.mute = True
        data.action = actions[0]
    frames = {mode: asset.deform(clip, [time], mode=mode, backend="fast-cpu").positions[0].astype(np.float64)
              for mode in ("lbs", "dqs")}
    diagonal = float(np.linalg.norm(frames["lbs"].max(axis=0) - frames["lbs"].min(axis=0)))
    for mode, preserve in (("lbs", False), ("dqs", True)):
        blender = blender_positions(meshes[0], time, preserve)
        miss = farthest_miss(blender, frames[mode]) / diagonal
        other = farthest_miss(blender, frames["dqs" if mode == "lbs" else "lbs"]) / diagonal
        print(f"test_in_blender: {path.name} {clip} t = {time} s: Blender's {mode} against dqskin's: {miss:.3g} of the "
              f"diagonal; against the other mode: {other:.3g}")
        assert miss < TOLERANCE, f"{path.name}: Blender's {mode} is {miss:.3g} of the diagonal from dqskin's"
        assert other > 100 * TOLERANCE, f"{path.name}: lbs and dqs agree at t = {time} s: the check shows nothing"


def check_example():
    """examples/blender_bake_dqs.py on the bending arm: its baked mesh, played by Blender at frame 12
    (t = 0.5 s), is dqskin's dqs there."""
    sys.path.insert(0, str(SOURCE / "examples"))
    import blender_bake_dqs
    import tempfile
    path = SOURCE / "testdata" / "bending_arm.gltf"
    bpy.ops.wm.read_homefile(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=str(path))
    with tempfile.TemporaryDirectory() as folder:
        made = blender_bake_dqs.bake_with_dqskin(folder=folder)
        meshes = [o for o in made if o.type == "MESH"]
        assert len(meshes) == 1 and meshes[0].data.shape_keys, f"the example made {[o.name for o in made]}"
        baked = blender_positions(meshes[0], 0.5, False)
    ours = dqskin.load(str(path)).deform("bend", [0.5], backend="fast-cpu").positions[0].astype(np.float64)
    diagonal = float(np.linalg.norm(ours.max(axis=0) - ours.min(axis=0)))
    miss = farthest_miss(baked, ours) / diagonal
    print(f"test_in_blender: examples/blender_bake_dqs.py: its mesh at t = 0.5 s against dqskin's dqs: {miss:.3g} "
          "of the diagonal")
    assert miss < TOLERANCE, f"the example's baked mesh is {miss:.3g} of the diagonal from dqskin's dqs"


check(SOURCE / "testdata" / "bending_arm.gltf", "bend", 0.5)
check_example()
# The shared sample models, when they are there (CI has them): key times at Blender's 24 frames a second.
shared = SOURCE.parent / "shared" / "testdata"
for model, clip, time in (("Fox", "Walk", 0.5), ("CesiumMan", 0, 1.0)):
    path = shared / model / f"{model}.glb"
    if path.exists():
        check(path, clip, time)
    else:
        print(f"test_in_blender: SKIPPED {model}: {path} is missing (the shared sample models)")
print("test_in_blender: OK")
