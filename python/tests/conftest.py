# test_in_blender.py runs inside Blender (blender_test.cmake, CTest python.blender), not under pytest: it needs bpy.
collect_ignore = ["test_in_blender.py"]
