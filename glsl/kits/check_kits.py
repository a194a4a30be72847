#!/usr/bin/env python3
"""Checks the shader kits `dqskin bake --shader-kit all` wrote (docs/formats.md, "Shader kits").

    check_kits.py compile KIT_DIR WRAPPER_DIR GLSLANG   every kit file compiles with glslangValidator
    check_kits.py identical KIT_DIR WEB_DIR             the three.js kit is the player's modules, byte for byte

compile: glslangValidator cannot run a shader, so the kits' math is kept formula for formula the player's
(web/bones_material.js) and the test type-checks every file as its engine would call it:
  - unity/, unreal/: HLSL through glslangValidator's HLSL front end (-D), inside a vertex shader
    (WRAPPER_DIR/unity_vertex.hlsl, unreal_vertex.hlsl) that calls every entry point;
  - godot/dqskin.gdshaderinc: its functions are kept to the part of Godot's shading language that is GLSL
    ES 3.00 (no implicit conversions, as in Godot), so they compile pasted into a #version 300 es vertex
    shader (godot_functions.vert) that calls every one; the .gdshader files compile the same way after the
    Godot-only parts are rewritten (shader_type, uniform hints, vertex() built-ins declared as globals);
  - three/: the GLSL ES 3.00 shaders of the player's modules, with each set of defines they are used with.
Every function a kit file defines must be called by its wrapper or by the kit itself, and a deliberately
broken copy of each kind of file must fail to compile (the test can fail). Without glslangValidator it prints
"SKIPPED: glslangValidator missing" (scripts/install/deps.sh installs Debian's glslang-tools).
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

FUNCTION = re.compile(r"^(?:void|float[234]?(?:x[234])?|half[234]?|int[234]?|[iu]?vec[234]|mat[234])\s+(\w+)\s*\(", re.M)


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def glslang(tool, folder, name, args):
    """Compiles folder/name; returns (ok, output)."""
    run = subprocess.run([tool] + args + [name], cwd=folder, capture_output=True, text=True, timeout=120)
    return run.returncode == 0, (run.stdout + run.stderr).strip()


def hlsl(tool, folder, name):
    return glslang(tool, folder, name, ["-D", "-V", "-S", "vert", "-e", "main", "-o", os.devnull])


def glsl(tool, folder, name, stage="vert"):
    return glslang(tool, folder, name, ["-S", stage])


def uncalled(kit_text, wrapper_text):
    """Functions the kit defines that neither the wrapper nor the kit calls."""
    names = FUNCTION.findall(kit_text)
    return [n for n in names if len(re.findall(r"\b%s\s*\(" % n, kit_text)) < 2 and not re.search(r"\b%s\s*\(" % n, wrapper_text)]


def godot_shader_as_glsl(text, include_text):
    """A .gdshader as GLSL ES 3.00: the include pasted, Godot-only syntax rewritten, vertex() called by main()."""
    text = text.replace('#include "dqskin.gdshaderinc"', include_text)
    text = re.sub(r"^shader_type\s+\w+;|^render_mode[^;]*;", "", text, flags=re.M)
    text = re.sub(r"^(uniform\s+\w+\s+\w+)\s*:[^;=]*", r"\1", text, flags=re.M)  # hints
    text = re.sub(r"^(uniform\s+\w+\s+\w+)\s*=[^;]*", r"\1", text, flags=re.M)  # GLSL ES: no initializers
    builtins = ("vec3 VERTEX; vec3 NORMAL; vec2 UV2; float TIME; vec4 INSTANCE_CUSTOM; uvec4 BONE_INDICES; "
                "vec4 BONE_WEIGHTS;\n")
    return "#version 300 es\nprecision highp float;\nprecision highp int;\n" + builtins + text + "\nvoid main() { vertex(); gl_Position = vec4(VERTEX + NORMAL, 1.0); }\n"


def three_shaders(module_text, shading_text):
    """The GLSL ES 3.00 sources of a player module: its `vertex` template string (and the shading fragment)."""
    templates = dict(re.findall(r"const (\w+) = /\* glsl \*/ `(.*?)`;", module_text, re.S))
    shading = dict(re.findall(r"const (\w+) = /\* glsl \*/ `(.*?)`;", shading_text, re.S))
    fragment = shading["normalsFragment"].replace("${srgbGlsl}", shading["srgbGlsl"])
    return templates["vertex"], fragment


class Checker:
    def __init__(self, tool, scratch):
        self.tool, self.scratch, self.failures, self.count = tool, scratch, [], 0

    def expect(self, what, ok_output, should_pass=True):
        ok, output = ok_output
        self.count += 1
        if ok != should_pass:
            self.failures.append(f"{what}: " + ("does not compile:\n" + output if should_pass else
                                                "a deliberately broken copy compiled; the check cannot fail"))
        else:
            print(f"ok: {what}" + ("" if should_pass else " (broken copy refused)"))

    def folder(self, name, files):
        path = os.path.join(self.scratch, name)
        os.makedirs(path)
        for file_name, text in files.items():
            with open(os.path.join(path, file_name), "w", encoding="utf-8") as f:
                f.write(text)
        return path


def compile_kits(kit, wrappers, tool):
    if not tool or not shutil.which(tool):
        print("SKIPPED: glslangValidator missing (scripts/install/deps.sh installs glslang-tools)")
        return 0
    scratch = tempfile.mkdtemp(prefix="dqskin_kits_")
    try:
        c = Checker(tool, scratch)
        core, graph = read(f"{kit}/unity/Dqskin.hlsl"), read(f"{kit}/unity/DqskinShaderGraph.hlsl")
        unity_wrapper, unreal_wrapper = read(f"{wrappers}/unity_vertex.hlsl"), read(f"{wrappers}/unreal_vertex.hlsl")
        ush = read(f"{kit}/unreal/Dqskin.ush")
        gd_include = read(f"{kit}/godot/dqskin.gdshaderinc")
        gd_wrapper = read(f"{wrappers}/godot_functions.vert")

        # Every function is called: by the wrapper (the public ones) or by the kit (the helpers).
        for what, kit_text, wrapper_text in (("unity", core + graph, unity_wrapper), ("unreal", ush, unreal_wrapper),
                                             ("godot", gd_include, gd_wrapper)):
            missing = uncalled(kit_text, wrapper_text)
            if missing:
                c.failures.append(f"{what}: the test wrapper calls no {', '.join(missing)}")

        c.expect("unity/DqskinShaderGraph.hlsl + Dqskin.hlsl (HLSL)",
                 hlsl(tool, c.folder("unity", {"Dqskin.hlsl": core, "DqskinShaderGraph.hlsl": graph,
                                               "wrapper.hlsl": unity_wrapper}), "wrapper.hlsl"))
        c.expect("unreal/Dqskin.ush (HLSL)",
                 hlsl(tool, c.folder("unreal", {"Dqskin.ush": ush, "wrapper.hlsl": unreal_wrapper}), "wrapper.hlsl"))
        gd_functions = gd_wrapper.replace('#include "dqskin.gdshaderinc"', gd_include)
        c.expect("godot/dqskin.gdshaderinc (GLSL ES 3.00)",
                 glsl(tool, c.folder("godot", {"functions.vert": gd_functions}), "functions.vert"))
        for name in ("dqskin_vat.gdshader", "dqskin_bones.gdshader"):
            text = godot_shader_as_glsl(read(f"{kit}/godot/{name}"), gd_include)
            c.expect(f"godot/{name} (as GLSL ES 3.00)", glsl(tool, c.folder(name, {"shader.vert": text}), "shader.vert"))

        shading = read(f"{kit}/three/shading.js")
        variants = {"vat_material.js": [[], ["OPENVAT", "HAS_NORMALS"], ["HOUDINI_PACKED", "HAS_NORMALS"], ["HAS_NORMALS"]],
                    "bones_material.js": [["TEXELS 2", "INFLUENCES 4"], ["TEXELS 5", "INFLUENCES 8"],
                                          ["TEXELS 5", "INFLUENCES 4", "FAULT_LBS"]]}
        fragment = None
        for module, define_sets in variants.items():
            vertex, fragment = three_shaders(read(f"{kit}/three/{module}"), shading)
            for i, defines in enumerate(define_sets):
                # As three.js's RawShaderMaterial with GLSL3 prefixes it: the version, then the defines.
                text = "#version 300 es\n" + "".join(f"#define {d}\n" for d in defines) + vertex
                c.expect(f"three/{module} vertex shader ({', '.join(defines) or 'no defines'}, GLSL ES 3.00)",
                         glsl(tool, c.folder(f"{module}_{i}", {"shader.vert": text}), "shader.vert"))
        c.expect("three/shading.js fragment shader (GLSL ES 3.00)",
                 glsl(tool, c.folder("shading", {"shader.frag": "#version 300 es\n" + fragment}), "shader.frag", "frag"))

        # Deliberately broken copies must fail: a call with a missing argument in each language's kit.
        broken_hlsl = core + "\nfloat3 dqskin_broken() { return dqskin_quat_rotate(float4(0.0, 0.0, 0.0, 1.0)); }\n"
        c.expect("broken unity/Dqskin.hlsl",
                 hlsl(tool, c.folder("unity_broken", {"Dqskin.hlsl": broken_hlsl, "DqskinShaderGraph.hlsl": graph,
                                                      "wrapper.hlsl": unity_wrapper}), "wrapper.hlsl"), False)
        broken_glsl = gd_include.replace("#endif", "vec3 dqskin_broken() { return dqskin_quat_rotate(vec4(0.0)); }\n#endif")
        c.expect("broken godot/dqskin.gdshaderinc",
                 glsl(tool, c.folder("godot_broken", {"functions.vert": gd_wrapper.replace(
                     '#include "dqskin.gdshaderinc"', broken_glsl)}), "functions.vert"), False)
        for line in c.failures:
            print("FAILED: " + line)
        print(f"check_kits: {c.count - len(c.failures)} of {c.count} compile checks passed" if not c.failures else
              f"check_kits: {len(c.failures)} problem(s)")
        return 1 if c.failures else 0
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


def identical(kit, web):
    problems = []
    for name in ("vat_material.js", "bones_material.js", "shading.js"):
        with open(f"{kit}/three/{name}", "rb") as a, open(f"{web}/{name}", "rb") as b:
            if a.read() != b.read():
                problems.append(f"three/{name} differs from web/{name}")
    extra = sorted(set(os.listdir(f"{kit}/three")) - {"vat_material.js", "bones_material.js", "shading.js"})
    if extra:
        problems.append("three/ holds files the player does not: " + ", ".join(extra))
    for line in problems:
        print("FAILED: " + line)
    if not problems:
        print("check_kits: the three.js kit is the player's vat_material.js, bones_material.js and shading.js, byte for byte")
    return 1 if problems else 0


def main(argv):
    if len(argv) == 5 and argv[1] == "compile":
        return compile_kits(argv[2], argv[3], argv[4])
    if len(argv) == 4 and argv[1] == "identical":
        return identical(argv[2], argv[3])
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
