"""``partgen build``: reproducible kits, atomic replacement, the default output folder, the
installed console script, usage errors and the manifest of the paper's design."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from partgen.cli.main import main

ROOT = Path(__file__).resolve().parents[2]
CONFIGS = ROOT / "configs"
DEFAULT = CONFIGS / "butterfly.yaml"
LIU = CONFIGS / "butterfly_liu2017.yaml"
SCRIPT = Path(sys.executable).parent / "partgen"


def _files(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


@pytest.fixture(scope="module")
def default_kit(kit_of) -> Path:
    """The default design's kit folder, the session's build of it (read only); the tests below
    build it again through main() (without -q in test_build_is_byte_identical)."""
    return kit_of("butterfly").dest


@pytest.fixture(scope="module")
def liu_kit(tmp_path_factory) -> tuple[subprocess.CompletedProcess, Path]:
    """The paper's design built by the installed console script, from the project folder."""
    assert SCRIPT.is_file(), f"no console script next to the interpreter: {SCRIPT}"
    dest = tmp_path_factory.mktemp("liu") / "kit"
    proc = subprocess.run([str(SCRIPT), "build", "configs/butterfly_liu2017.yaml", "-o", str(dest)],
                          cwd=ROOT, capture_output=True, text=True, timeout=120)
    return proc, dest


def test_build_is_byte_identical(default_kit, tmp_path, capsys):
    d2 = tmp_path / "kit"
    assert main(["build", str(DEFAULT), "-o", str(d2)]) == 0
    a, b = _files(default_kit), _files(d2)
    assert "manifest.json" in a and "assembly.glb" in a
    stls = [n for n in a if n.endswith(".stl")]
    man = json.loads(a["manifest.json"])
    assert sorted(stls) == sorted(p["file"] for p in man["parts"])
    assert sorted(a) == sorted(b)
    differ = [n for n in a if a[n] != b[n]]
    assert not differ, f"files differ between two builds: {differ}"


def test_rebuild_replaces_kit_atomically(default_kit, liu_kit, tmp_path, capsys):
    """A kit of another design in DIR is replaced whole: its parts that the new design lacks go."""
    parent = tmp_path / "parent"
    parent.mkdir()
    kit = parent / "kit"
    shutil.copytree(liu_kit[1], kit)  # the paper's kit, as partgen wrote it
    liu_only = set(os.listdir(kit)) - set(os.listdir(default_kit))
    assert liu_only, "the paper's kit should have parts the default lacks"
    assert main(["build", str(DEFAULT), "-o", str(kit), "-q"]) == 0
    assert not liu_only & set(os.listdir(kit)), "the rebuild merged into the old kit instead of replacing it"
    assert _files(kit) == _files(default_kit)
    siblings = sorted(os.listdir(parent))
    assert siblings == ["kit"], f"leftovers beside the kit: {siblings}"


def test_default_output_folder(tmp_path, monkeypatch, capsys):
    """(on the gear pair, the cheapest kit: out/<name> is the same for every mechanism)"""
    shutil.copytree(CONFIGS, tmp_path / "configs")
    monkeypatch.chdir(tmp_path)
    name = yaml.safe_load((CONFIGS / "gear_pair.yaml").read_text())["name"]
    assert main(["build", "configs/gear_pair.yaml", "-q"]) == 0
    kit = tmp_path / "out" / name
    assert (kit / "manifest.json").is_file() and (kit / "assembly.glb").is_file()
    assert any(p.suffix == ".stl" for p in kit.iterdir())
    assert sorted(os.listdir(tmp_path / "out")) == [name]
    assert f"out/{name}" in capsys.readouterr().out


def test_kit_folder_permissions_follow_umask(default_kit):
    """The kit folder should be created like any other folder (mkdir honours the umask): partgen
    builds it with tempfile.mkdtemp and renames it into place, so it ends up mode 0700."""
    ref = default_kit.parent / "reference_folder"
    ref.mkdir()
    try:
        assert oct(default_kit.stat().st_mode & 0o777) == oct(ref.stat().st_mode & 0o777)
    finally:
        ref.rmdir()


def test_console_script_builds_liu2017_with_warning(liu_kit):
    proc, dest = liu_kit
    assert "Traceback" not in proc.stderr
    assert proc.returncode == 0, proc.stderr
    warnings = [l for l in proc.stderr.splitlines() if l.startswith("partgen: warning:")]
    link10 = [l for l in warnings if "link 10" in l]
    assert link10, f"no warning about link 10 in stderr:\n{proc.stderr}"
    assert any("Eq 12" in l and "butterfly_liu2017.yaml" in l and "teeth[9]" in l for l in link10), link10
    assert (dest / "manifest.json").is_file() and (dest / "assembly.glb").is_file()
    man = json.loads((dest / "manifest.json").read_text())
    assert all((dest / p["file"]).is_file() for p in man["parts"])


def test_missing_config(capsys):
    """In-process: the console script runs this same main() (its exit code passed on by entry(),
    which test_console_script_builds_liu2017_with_warning runs for a build and test_printers'
    test_version_and_python_m for exit 2), and a subprocess only added 2-3 s of imports."""
    code = main(["build", "/nonexistent.yaml"])
    out, err = capsys.readouterr()
    assert code == 2
    assert "Traceback" not in err + out
    assert "/nonexistent.yaml" in err
    assert err.startswith("partgen: error: ")


@pytest.mark.parametrize("argv, code", [([], 2), (["build"], 2), (["--help"], 0), (["build", "--help"], 0),
                                        (["frobnicate"], 2)])
def test_usage(argv, code, capsys):
    assert main(argv) == code
    out, err = capsys.readouterr()
    assert "Traceback" not in out + err
    assert "usage" in (out if code == 0 else err)


def test_liu2017_manifest(liu_kit):
    proc, dest = liu_kit
    assert proc.returncode == 0, proc.stderr
    design = json.loads((dest / "manifest.json").read_text())["design"]
    cfg = yaml.safe_load(LIU.read_text())
    assert [s["teeth"] for s in design["stages"]] == [dict(t) for t in cfg["teeth"]]
    assert [s["j"] for s in design["stages"]] == list(range(1, len(cfg["teeth"]) + 1))
    eq12 = [f for f in design["findings"] if f["code"] == "eq12"]
    assert any("link 10" in f["message"] and f["key"] == "teeth[9]" and f["severity"] == "warn" for f in eq12), \
        design["findings"]
