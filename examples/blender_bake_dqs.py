"""Bake the open Blender file's animation with dqskin's dual-quaternion skinning and load it back.

Run it inside Blender (Scripting workspace, or `blender FILE.blend --python examples/blender_bake_dqs.py`).
It exports the scene as glTF (what dqskin reads), has dqskin bake the active action as a morph-target
animation (every frame of the scene's range, deformed with `dqs`), and imports that back beside the
original, as shape keys that play with the timeline: compare the rig's own skinning with dqskin's, or hand
the baked mesh to a tool that has no skinning.

dqskin must be importable by Blender's Python: Debian's python3-dqskin puts it where Debian's Blender
looks; for a build tree, set DQSKIN_PYTHONPATH to its python/ folder (build/release/python).
"""
import os
import pathlib
import sys
import tempfile

import bpy
import numpy as np

# Debian's Blender 3.4 glTF importer still uses np.bool, which NumPy 1.24 removed; the builtin is what it
# meant.
if "bool" not in np.__dict__:
    np.bool = bool
if os.environ.get("DQSKIN_PYTHONPATH"):
    sys.path.insert(0, os.environ["DQSKIN_PYTHONPATH"])
import dqskin  # noqa: E402


def bake_with_dqskin(mode="dqs", folder=None):
    """Exports the scene, bakes its active action with dqskin and imports the result. Returns the new
    objects. `folder` keeps the files (a temporary folder by default)."""
    scene = bpy.context.scene
    armature = next((o for o in scene.objects if o.type == "ARMATURE" and o.animation_data), None)
    if armature is None or armature.animation_data.action is None:
        raise RuntimeError("the scene has no armature with an active action to bake")
    action = armature.animation_data.action.name
    work = pathlib.Path(folder or tempfile.mkdtemp(prefix="dqskin_"))
    work.mkdir(parents=True, exist_ok=True)
    exported = work / "scene.glb"
    # Only the active action, so that the file's one animation is the one on the timeline.
    bpy.ops.export_scene.gltf(filepath=str(exported), export_format="GLB", export_animations=True,
                              export_skins=True, export_nla_strips=False, export_force_sampling=True)
    asset = dqskin.load(str(exported))
    if not asset.clips:
        raise RuntimeError(f"{exported}: the export holds no animation")
    # The action's frames (frame f is at f / fps seconds, as Blender's glTF exporter writes it).
    fps = scene.render.fps / scene.render.fps_base
    first, last = (int(round(f)) for f in armature.animation_data.action.frame_range)
    frames = f"{max(first, 0)}:{last}"
    summary = dqskin.bake(str(exported), out=str(work / "baked"), format="morph", mode=mode, fps=fps,
                          frames=frames, anim=asset.clips[0].index)
    if summary["failures"]:
        raise RuntimeError(f"dqskin bake: {summary['failures']}")
    baked = sorted((work / "baked").rglob("animation.glb"))
    before = set(bpy.data.objects)
    for path in baked:
        bpy.ops.import_scene.gltf(filepath=str(path))
    made = [o for o in bpy.data.objects if o not in before]
    for o in made:
        o.name = f"{o.name} ({action}, dqskin {mode})"
    print(f"dqskin: baked {action} ({len(asset.clips)} clip, frames {frames} at {fps:g} fps) into {work}")
    return made


if __name__ == "__main__":
    bake_with_dqskin()
