# Blender's side of scripts/bench/bake.sh: bakes a skinned glTF to one OBJ per frame in Blender headless,
# with dual-quaternion skinning (the Armature modifiers' Preserve Volume), the way an artist would without
# dqskin. Prints "frames N", "import_s S" and "export_s S" for the benchmark to read.
#
# Usage: blender --background --factory-startup --python scripts/bench/blender_bake_obj.py -- INPUT OUT_DIR FPS [--positions-only]
#   FPS               the scene's frame rate while importing: the glTF importer keys the animation at it,
#                     so the frames are the clip sampled at FPS, as `dqskin bake --fps FPS`
#   --positions-only  OBJ with positions alone (no normals, no UVs)
import math
import os
import sys
import time

import bpy

# Debian 12's Blender 3.4 glTF importer still calls numpy.bool, which NumPy 1.24 (Debian 12's) removed.
try:
    import numpy
    if "bool" not in numpy.__dict__:
        numpy.bool = bool
except ImportError:
    pass  # the importer says itself that it needs NumPy

args = sys.argv[sys.argv.index("--") + 1:]
if len(args) < 3:
    sys.exit("usage: blender --background --python blender_bake_obj.py -- INPUT OUT_DIR FPS [--positions-only]")
source, out_dir, fps = args[0], args[1], int(args[2])
positions_only = "--positions-only" in args[3:]

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.fps = fps
start = time.perf_counter()
bpy.ops.import_scene.gltf(filepath=source)
import_s = time.perf_counter() - start

armatures = 0
for obj in scene.objects:
    for modifier in obj.modifiers:
        if modifier.type == "ARMATURE":
            modifier.use_deform_preserve_volume = True  # dual-quaternion skinning
            armatures += 1
if armatures == 0:
    sys.exit(source + ": no Armature modifier after import: nothing is skinned")

# The frames of the clip that plays (the importer gives each object the first animation's action), keyed at
# FPS from frame 1; Blender 3.4 leaves the scene's range at its default 1-250.
ranges = [obj.animation_data.action.frame_range for obj in scene.objects
          if obj.animation_data and obj.animation_data.action]
if not ranges:
    sys.exit(source + ": no animation after import")
first, last = int(min(r[0] for r in ranges)), int(math.ceil(max(r[1] for r in ranges)))
os.makedirs(out_dir, exist_ok=True)
start = time.perf_counter()
bpy.ops.wm.obj_export(filepath=os.path.join(out_dir, "frame.obj"), export_animation=True, start_frame=first,
                      end_frame=last, apply_modifiers=True, export_selected_objects=False,
                      export_uv=not positions_only, export_normals=not positions_only, export_materials=False)
export_s = time.perf_counter() - start
print("frames %d" % (last - first + 1))
print("import_s %.3f" % import_s)
print("export_s %.3f" % export_s)
