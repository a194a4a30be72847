#!/usr/bin/env python3
"""Crafted inputs for the commands that came after the loader's hardening (app/tests/command_limits.cmake,
docs/SECURITY.md "Every command"): each made a command crash, hang, take memory past --max-memory, leak a
file's content or leave a half-written output; each class of problem is one small generated case here,
never a downloaded file.

    make_hostile_commands.py OUTDIR

writes one folder per command under OUTDIR (report/), deterministic, byte for byte. Python 3 standard
library only.
"""

import copy
import os
import shutil
import struct
import subprocess
import sys

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
    clip_1e6.gltf     the quad whose clip lasts 10^6 s: at 1 fps, a million frames of figures; past
                      --max-memory the report's document was destroyed while the refusal unwound, and its
                      destructor's own allocation ended the process (abort, two lines, a stray sheet)
    rig_300_joints.glb  a tube of 6,000 vertices on 300 joints (scripts/make_big_rig.py): its report.json
                      is tens of MB, so a signal during the writing found the sheet written and no page
    """
    a = malformed.base_asset()
    a.gltf["animations"] = [copy.deepcopy(a.gltf["animations"][0]) for _ in range(1000)]
    for i, animation in enumerate(a.gltf["animations"]):
        animation["name"] = "clip%d" % i
    write(folder, "clips_1000.gltf", a.gltf_bytes())

    a = malformed.base_asset()
    offset = a.accessor_offset(malformed.TIMES)
    a.bin[offset:offset + 12] = struct.pack("<3f", 0.0, 0.5, 1e6)
    a.gltf["accessors"][malformed.TIMES]["max"] = [1e6]
    write(folder, "clip_1e6.gltf", a.gltf_bytes())

    subprocess.run([sys.executable, os.path.join(HERE, "make_big_rig.py"), os.path.join(folder, "rig_300_joints.glb"),
                    "--vertices", "6000", "--joints", "300", "--seconds", "4"], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make_hostile_commands.py OUTDIR")
    out = sys.argv[1]
    if os.path.exists(out):
        shutil.rmtree(out)
    for name, make in [("report", report_cases)]:
        os.makedirs(os.path.join(out, name))
        make(os.path.join(out, name))


if __name__ == "__main__":
    main()
