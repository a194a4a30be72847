#!/usr/bin/env python3
"""The layering of lib/ as a test: reads every #include of the C++ sources and fails, one line per include,
on those the rules below forbid (docs/ARCHITECTURE.md, "Who may include whom").

    include_rules.py [ROOT]      ROOT: the repository (default: this script's)

A folder may include itself and the folders its rule lists; a public header (lib/include/dqskin/X.hpp)
counts as its owner folder's. Tests (*_test.cpp) are the library's first users, not part of it: they build
their inputs with the loader and the commands, so they may include any folder, as may app/, fuzz/ and bench/,
which drive the library, and python/ (the module). Only the loader compiles tinygltf, Draco and meshoptimizer; its tests may too.
Only the image module's files (named *_oiio.cpp or *_oiio.hpp, built into libdqskin_image.so and opened
at run time: lib/base/image_module.hpp) include OpenImageIO; tests and drivers may too.
Exit status 0 when every include is allowed, 1 otherwise, 2 when a folder or public header has no rule.
"""
import os
import re
import sys

# The layers, from the bottom: each folder and what it may include besides itself.
MAY_INCLUDE = {
    "math": [],
    "base": ["math"],  # what every stage uses; nothing of lib/ above it
    "asset": ["base", "math"],  # the neutral data model, its geometry, the .glb container
    "load": ["asset", "base", "math"],  # glTF 2.0 → Asset
    "anim": ["asset", "base", "math"],  # sample
    "skin": ["anim", "asset", "base", "math"],  # palette, pack, the CPU reference
    "deform": ["gpu", "skin", "anim", "asset", "base", "math"],  # deformers; the factory makes the GPU one
    "gpu": ["deform", "skin", "anim", "asset", "base", "math"],  # contexts and the GPU deformer
    "write": ["deform", "skin", "anim", "asset", "base", "math"],  # never the loader
    "texture": ["write", "deform", "skin", "anim", "asset", "base", "math"],
    "draw": ["gpu", "deform", "skin", "anim", "asset", "base", "math"],
    "job": ["load", "deform", "gpu", "skin", "anim", "asset", "base", "math"],
    "kit": ["base"],  # the shader kits `bake --shader-kit` writes: embedded text, nothing of the pipeline
    "test_support": None,  # test helpers: anything but a command
}
# The commands: each may include every folder above, never another command, and nothing includes them but
# app/ (and the drivers beside it).
COMMANDS = ["bake", "render", "diff", "lint", "report", "verify", "info", "optimize", "bench"]
for command in COMMANDS:
    MAY_INCLUDE[command] = [f for f in MAY_INCLUDE if f != "test_support"]
MAY_INCLUDE["test_support"] = [f for f in MAY_INCLUDE if f not in COMMANDS and f != "test_support"]

# The owner of each public header.
PUBLIC = {
    "dual_quat": "math",
    "error": "base", "memory_ceiling": "base", "atomic_file": "base", "version": "base",
    "asset": "asset", "triangles": "asset",
    "load": "load",
    "animation": "anim",
    "skinning": "skin", "bone_texture": "skin",
    "deformer": "deform", "deformed_batch": "deform", "frame_view": "deform",
    "gpu_context": "gpu", "gpu_deform": "gpu",
    "glb_images": "write",
    "camera": "draw", "renderer": "draw", "image_output": "draw",
    "job": "job",
    "bake": "bake", "render": "render", "lint": "lint", "optimize": "optimize", "report": "report", "verify": "verify", "info": "info",
    "bench": "bench",
    "image_diff": "diff", "diff_report": "diff", "geometry_diff": "diff", "geometry_report": "diff",
    "ci_annotations": "diff", "diff_page": "diff", "golden_approval": "diff",
}

# Third-party headers only the loader compiles.
LOADER_ONLY = re.compile(r"^(tiny_gltf\.h|draco/|meshoptimizer\.h)")
DRIVERS = ("app", "fuzz", "bench", "python")
# OpenImageIO: the image module only.
IMAGE_MODULE_ONLY = re.compile(r"^OpenImageIO/")

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)


def folder_of(root, path):
    """The lib/ folder a source file belongs to (public headers: their owner), or the top-level folder."""
    rel = os.path.relpath(path, root).replace(os.sep, "/")
    parts = rel.split("/")
    if parts[0] != "lib":
        return parts[0]
    if parts[1] == "include":
        return PUBLIC.get(os.path.splitext(parts[-1])[0], "?" + parts[-1])
    return parts[1]


def target_folder(root, source, spelled):
    """The folder an include names, or None for a header outside lib/ (the standard library, GLM, ...)."""
    if spelled.startswith("dqskin/"):
        return PUBLIC.get(os.path.splitext(spelled[len("dqskin/"):])[0], "?" + spelled)
    resolved = os.path.normpath(os.path.join(os.path.dirname(source), spelled))
    rel = os.path.relpath(resolved, root).replace(os.sep, "/")
    if rel.startswith("lib/") and os.path.exists(resolved):
        return folder_of(root, resolved)
    return None


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
    problems, unknown = [], []
    for top in ("lib",) + DRIVERS:
        for directory, _, names in os.walk(os.path.join(root, top)):
            for name in sorted(names):
                if not name.endswith((".cpp", ".hpp", ".h")):
                    continue
                path = os.path.join(directory, name)
                rel = os.path.relpath(path, root)
                here = folder_of(root, path)
                is_test = name.endswith("_test.cpp")
                with open(path, encoding="utf-8") as f:
                    text = f.read()
                for line_no, (quote, spelled) in ((text.count("\n", 0, m.start()) + 1, m.groups())
                                                  for m in INCLUDE.finditer(text)):
                    where = f"{rel}:{line_no}: #include {quote}{spelled}{'>' if quote == '<' else quote}"
                    if quote == "<" and LOADER_ONLY.match(spelled) and here != "load" and here not in DRIVERS:
                        problems.append(f"{where}: only lib/load compiles tinygltf, Draco and meshoptimizer")
                    if (quote == "<" and IMAGE_MODULE_ONLY.match(spelled) and "_oiio." not in name and not is_test
                            and here not in DRIVERS):
                        problems.append(f"{where}: only the image module's *_oiio files include OpenImageIO "
                                        f"(lib/base/image_module.hpp)")
                    if quote == "<" and not spelled.startswith("dqskin/"):
                        continue
                    there = target_folder(root, path, spelled)
                    if there is None or there == here or here in DRIVERS or is_test:
                        continue
                    if there.startswith("?"):
                        unknown.append(f"{where}: {there[1:]} has no owner in include_rules.py's PUBLIC table")
                        continue
                    if here not in MAY_INCLUDE:
                        unknown.append(f"{where}: folder lib/{here} has no rule in include_rules.py")
                        continue
                    if there in COMMANDS:
                        problems.append(f"{where}: lib/{there} is a command; only app/ includes a command's folder")
                    elif there not in MAY_INCLUDE[here]:
                        problems.append(f"{where}: lib/{here} may not include lib/{there} "
                                        f"(it may include: {', '.join(MAY_INCLUDE[here]) or 'nothing of lib/'})")
    for line in unknown + problems:
        print(line)
    if unknown:
        return 2
    if problems:
        print(f"include_rules: {len(problems)} include(s) break the layering")
        return 1
    print("include_rules: every include follows the layering")
    return 0


if __name__ == "__main__":
    sys.exit(main())
