"""The Python module against the command line: what `import dqskin` loads and deforms is what `dqskin bake`
writes, byte for byte; what the CLI refuses, the module refuses with the same message; Ctrl-C stops a long
call. Run by the README's test command (CTest's python.pytest), with the module's folder on PYTHONPATH and
DQSKIN_CLI naming the command line. Tests that need the shared sample models skip with the reason when
they are absent.
"""
import os
import pathlib
import signal
import struct
import subprocess
import sys
import time

import numpy as np
import pytest

import dqskin

SOURCE = pathlib.Path(os.environ.get("DQSKIN_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
SHARED = SOURCE.parent / "shared" / "testdata"
CLI = os.environ.get("DQSKIN_CLI", "dqskin")
ARM = SOURCE / "testdata" / "bending_arm.gltf"


def shared_model(name):
    path = SHARED / name / f"{name}.glb"
    if not path.exists():
        pytest.skip(f"{path} is missing (the shared sample models)")
    return path


def read_ply(path):
    """The vertices of a binary little-endian PLY that `dqskin bake` wrote: positions and normals, float32."""
    data = path.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii")
    count = next(int(line.split()[2]) for line in header.splitlines() if line.startswith("element vertex"))
    # x y z nx ny nz s t: 8 floats per vertex, as the header says
    assert "property float nx" in header and "property float t\nelement face" in header, header
    rows = np.frombuffer(data, dtype="<f4", count=count * 8, offset=end).reshape(count, 8)
    return rows[:, 0:3], rows[:, 3:6]


def bake_ply(model, clip, times, tmp_path, mode="dqs"):
    out = tmp_path / "bake"
    subprocess.run([CLI, "bake", str(model), "--format", "ply", "--anim", clip, "--times",
                    ",".join(repr(float(t)) for t in times), "--mode", mode, "--backend", "fast-cpu",
                    "-o", str(out)], check=True, capture_output=True)
    return sorted(out.rglob("frame_*.ply"))


def test_load_describes_the_file():
    asset = dqskin.load(str(ARM))
    assert asset.path == str(ARM)
    assert [c.name for c in asset.clips] == ["bend"]
    bend = asset.clip("bend")
    assert bend.index == 0 and bend.duration == pytest.approx(1.0)
    assert list(bend.key_times) == [0.0, 0.5, 1.0]
    assert asset.clip(0).name == "bend"
    assert asset.skins[0].joints == ["shoulder", "elbow"]
    assert asset.vertices == 272
    assert "bending_arm.gltf" in repr(asset)


@pytest.mark.parametrize("name, clip", [("Fox", "Walk"), ("CesiumMan", "0")])
def test_deform_is_the_bakes_ply_byte_for_byte(name, clip, tmp_path):
    model = shared_model(name)
    asset = dqskin.load(str(model))
    chosen = asset.clip(int(clip) if clip.isdigit() else clip)
    times = list(chosen.key_times[:4]) + [chosen.duration / 3]
    frames = asset.deform(chosen, times, backend="fast-cpu")
    assert frames.positions.shape == (len(times), asset.vertices, 3)
    assert frames.positions.dtype == np.float32
    plys = bake_ply(model, clip, times, tmp_path)
    assert len(plys) == len(times)
    for f, ply in enumerate(plys):
        positions, normals = read_ply(ply)
        assert frames.positions[f].tobytes() == positions.tobytes(), f"frame {f}: positions differ from {ply}"
        if frames.normals is not None:
            assert frames.normals[f].tobytes() == normals.tobytes(), f"frame {f}: normals differ from {ply}"


def test_modes_differ_and_the_rest_pose_needs_no_clip(tmp_path):
    asset = dqskin.load(str(ARM))
    lbs = asset.deform("bend", [0.5], mode="lbs", backend="fast-cpu").positions
    dqs = asset.deform("bend", [0.5], mode="dqs", backend="fast-cpu").positions
    assert not np.array_equal(lbs, dqs)  # the elbow bends: lbs collapses where dqs keeps volume
    assert lbs.tobytes() == read_ply(bake_ply(ARM, "bend", [0.5], tmp_path, mode="lbs")[0])[0].tobytes()
    rest = asset.deform(None, [0.0, 1.0], backend="fast-cpu").positions
    assert np.array_equal(rest[0], rest[1])


def cli_error(*args):
    """The one line the command line prints for a refusal, without its "dqskin: " prefix."""
    result = subprocess.run([CLI, *args], capture_output=True, text=True)
    assert result.returncode == 2, result
    lines = result.stderr.splitlines()
    assert lines and lines[0].startswith("dqskin: "), result.stderr
    return lines[0][len("dqskin: "):]


@pytest.mark.parametrize("case", ["joint_out_of_range.gltf", "negative_weight.gltf", "missing.glb", "not_gltf.glb",
                                  "truncated.glb"])
def test_what_the_cli_refuses_the_module_refuses_with_its_message(case, tmp_path):
    path = SOURCE / "testdata" / "bad_skins" / case
    if case == "missing.glb":
        path = tmp_path / case
    elif case == "not_gltf.glb":
        path = tmp_path / case
        path.write_text("this is not a glTF file\n")
    elif case == "truncated.glb":
        path = tmp_path / case
        path.write_bytes(ARM.read_bytes()[:10])
    expected = cli_error("bake", str(path), "--format", "ply", "-o", str(tmp_path / "out"))
    with pytest.raises(dqskin.InputError) as raised:
        dqskin.load(str(path))
    assert str(raised.value) == expected
    assert isinstance(raised.value, ValueError) and isinstance(raised.value, dqskin.Error)


def test_bad_arguments_are_type_and_value_errors_naming_the_argument():
    asset = dqskin.load(str(ARM))
    with pytest.raises(TypeError, match="bogus"):
        dqskin.load(str(ARM), bogus=1)
    with pytest.raises(TypeError):
        dqskin.load(123)
    with pytest.raises(TypeError, match="clip must be"):
        asset.deform(2.5, [0.0])
    with pytest.raises(dqskin.InputError, match="no animation 'Nope'"):
        asset.deform("Nope", [0.0])
    with pytest.raises(dqskin.InputError, match="mode 'linear' is not one of lbs, dqs, dib"):
        asset.deform("bend", [0.0], mode="linear")
    with pytest.raises(dqskin.InputError, match="not a finite time"):
        asset.deform("bend", [float("nan")])
    with pytest.raises(dqskin.InputError, match="max_memory"):
        dqskin.load(str(ARM), max_memory="lots")
    with pytest.raises(dqskin.InputError, match="more than max_memory"):
        dqskin.load(str(ARM), max_memory="1M").deform("bend", np.linspace(0, 1, 2000))


def interrupt_after(script, delay):
    """Runs `script` in a Python of its own, which prints "started" first, and sends it SIGINT `delay`
    seconds later. Returns its stdout, its stderr and how long it took to end after the signal."""
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline().strip() == "started"
        time.sleep(delay)
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=10)
        return out, err, time.monotonic() - sent
    finally:
        child.kill()


def test_ctrl_c_stops_a_long_deform_within_a_second():
    model = shared_model("BrainStem")
    script = (
        "import sys, numpy, dqskin\n"
        f"asset = dqskin.load({str(model)!r})\n"
        "print('started', flush=True)\n"
        "try:\n"
        "    asset.deform(0, numpy.linspace(0, 30, 400), backend='cpu')\n"
        "    print('finished', flush=True)\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted', flush=True)\n"
    )
    out, err, took = interrupt_after(script, 0.5)
    assert out.strip() == "interrupted", (out, err)
    assert took < 1.0, f"stopped {took:.2f} s after Ctrl-C"


def test_the_type_stubs_name_what_the_module_has():
    import ast
    stubs = pathlib.Path(dqskin.__file__).with_name("dqskin.pyi")
    assert stubs.exists(), f"{stubs}: the stubs are installed beside the module"
    tree = ast.parse(stubs.read_text())
    stubbed = {n.name for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    stubbed |= {n.target.id for n in tree.body if isinstance(n, ast.AnnAssign)}
    public = {name for name in dir(dqskin) if not name.startswith("_")} | {"__version__"}
    helpers = {"Clip", "Scene", "Skin", "Frames"}  # names of the stubs' SimpleNamespaces, not module attributes
    assert public == stubbed - helpers
    methods = {n.name for n in next(c for c in tree.body if isinstance(c, ast.ClassDef) and c.name == "Asset").body
               if isinstance(n, ast.FunctionDef)}
    assert methods == {name for name in dir(dqskin.Asset) if not name.startswith("_")}
    for name in ("load", "Asset", "InputError"):
        assert getattr(dqskin, name).__doc__, f"{name} has no docstring"


def tree_bytes(root):
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(pathlib.Path(root).rglob("*")) if p.is_file()}


def test_bake_writes_what_the_cli_writes_and_returns_its_summary(tmp_path):
    summary = dqskin.bake(str(ARM), out=str(tmp_path / "py"), format=["ply", "vat"], fps=4, mode="lbs",
                          backend="fast-cpu")
    subprocess.run([CLI, "bake", str(ARM), "-o", str(tmp_path / "cli"), "--format", "ply,vat", "--fps", "4",
                    "--mode", "lbs", "--backend", "fast-cpu"], check=True, capture_output=True)
    py_files, cli_files = tree_bytes(tmp_path / "py"), tree_bytes(tmp_path / "cli")
    assert py_files == cli_files  # every file, byte for byte (the manifest names no folder)
    assert summary["event"] == "summary" and summary["failures"] == []
    assert summary["files_written"] == len(py_files) - 1  # all but the manifest itself
    assert summary["manifest"] == str(tmp_path / "py" / "manifest.json")


def test_diff_and_lint_return_the_clis_json_reports(tmp_path):
    bent = tmp_path / "b.gltf"
    subprocess.run([sys.executable, str(SOURCE / "scripts" / "testdata" / "make_diff_cases.py"), "rotate-key", str(ARM),
                    str(bent), "--joint", "elbow"], check=True, capture_output=True)
    report = dqskin.diff(str(ARM), bent, relative=True, fail=1e-3, backend="fast-cpu")
    cli = subprocess.run([CLI, "diff", str(ARM), str(bent), "--relative", "--fail", "1e-3", "--backend", "fast-cpu",
                          "--json"], capture_output=True, text=True)
    assert cli.returncode == 2  # a failing diff: a result, which the module returns rather than raises
    assert report == __import__("json").loads(cli.stdout)
    assert report["status"] == "FAIL" and report["clips"][0]["worst_joint"] == "elbow"

    bad = SOURCE / "testdata" / "bad_skins" / "negative_weight.gltf"
    lint = dqskin.lint([str(bad), str(ARM)], max_influences=4)
    cli = subprocess.run([CLI, "lint", "--max-influences", "4", "--json", str(bad), str(ARM)], capture_output=True, text=True)
    assert lint == __import__("json").loads(cli.stdout)


def test_report_returns_each_inputs_report_json(tmp_path):
    summary = dqskin.report(str(ARM), out=str(tmp_path), backend="fast-cpu")
    assert "bending_arm/report.json" in summary["files"]
    written = __import__("json").loads((tmp_path / "bending_arm" / "report.json").read_text())
    assert summary["reports"] == [written]


def test_commands_refuse_as_the_cli_does(tmp_path):
    missing = tmp_path / "missing.glb"
    expected = cli_error("bake", str(missing), "-o", str(tmp_path / "out"))
    with pytest.raises(dqskin.InputError) as raised:
        dqskin.bake(str(missing), out=str(tmp_path / "out"))
    assert str(raised.value) == expected
    with pytest.raises(dqskin.InputError, match=r"^--fail must be at least 0, not -1$"):
        dqskin.diff(str(ARM), str(ARM), fail=-1)
    with pytest.raises(TypeError, match="unexpected keyword argument 'colour'"):
        dqskin.bake(str(ARM), colour="red")
    with pytest.raises(TypeError, match="argument 'keys' is a flag"):
        dqskin.bake(str(ARM), keys="yes")
    with pytest.raises(TypeError, match="argument 'fps' takes a string, a number or a path"):
        dqskin.bake(str(ARM), fps={"a": 1})
    with pytest.raises(TypeError, match="unexpected keyword argument 'json'"):
        dqskin.lint(str(ARM), json=True)
    with pytest.raises(TypeError, match="does not take 'dry_run'"):
        dqskin.bake(str(ARM), dry_run=True)
    blocker = tmp_path / "a_file"
    blocker.write_text("")
    expected = cli_error("bake", str(ARM), "-o", str(blocker / "out"))
    with pytest.raises(dqskin.OutputError) as raised:  # a folder that cannot be made: an OSError
        dqskin.bake(str(ARM), out=str(blocker / "out"))
    assert str(raised.value) == expected and isinstance(raised.value, OSError)


def test_ctrl_c_stops_a_long_bake_within_a_second(tmp_path):
    model = shared_model("BrainStem")
    script = (
        "import dqskin\n"
        "print('started', flush=True)\n"
        "try:\n"
        f"    dqskin.bake({str(model)!r}, out={str(tmp_path / 'out')!r}, format='ply', fps=120, backend='cpu')\n"
        "    print('finished', flush=True)\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted', flush=True)\n"
    )
    out, err, took = interrupt_after(script, 1.5)  # loading done, deforming under way
    assert out.strip() == "interrupted", (out, err)
    assert took < 1.0, f"stopped {took:.2f} s after Ctrl-C"
    assert not list((tmp_path / "out").rglob("*.tmp*")), "no temporary file left"


@pytest.fixture(scope="module")
def malformed(tmp_path_factory):
    """The catalogue of malformed glTF files (scripts/testdata/make_malformed.py): (folder, names)."""
    out = tmp_path_factory.mktemp("malformed")
    subprocess.run([sys.executable, str(SOURCE / "scripts" / "testdata" / "make_malformed.py"), str(out)], check=True,
                   capture_output=True)
    names = []
    for listing in ("cases.txt", "undeformable.txt"):
        names += [line.split("\t")[0] for line in (out / listing).read_text().splitlines() if line.strip()]
    return out, names


def test_the_malformed_catalogue_is_refused_with_the_clis_messages(malformed, tmp_path, monkeypatch):
    folder, names = malformed
    assert len(names) > 150
    monkeypatch.chdir(folder / "cwd")  # as the CLI's tests run: a buffer here must not be found
    mismatches, refused = [], 0
    for name in names:
        path = str(folder / name)
        result = subprocess.run([CLI, "bake", path, "--format", "ply", "-o", str(tmp_path / "out")],
                                capture_output=True, text=True)
        assert result.returncode in (0, 1, 2), f"{name}: dqskin bake exited {result.returncode}: {result.stderr}"
        expected = result.stderr.splitlines()[0][len("dqskin: "):] if result.returncode == 2 else None
        refused += expected is not None
        try:
            dqskin.load(path)
            got = None
        except dqskin.InputError as e:
            got = str(e)
        if got != expected:
            mismatches.append(f"{name}: CLI {expected!r}, module {got!r}")
    assert not mismatches, "\n".join(mismatches)
    assert refused > 150, f"the CLI refused only {refused} of {len(names)}: the catalogue is not what it was"
