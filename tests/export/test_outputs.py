"""A user's files are sacred: every way the issue found to lose one, each with its own test.

partgen writes only into folders it made (marked ``.partgen``, or a kit of an earlier partgen),
refuses (exit 2, nothing touched) a folder holding anything else, a file, the current folder and
the folder holding the design; ``name`` is a file name, never a path; a rebuild keeps a kit's
plates/trace/report when nothing changed and removes them, saying so, when it did. Interrupted
or racing builds leave one whole kit and no temporary folders.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
import yaml
from helpers import modified

from partgen.cli.main import main
from partgen.export.outputs import MARKER

ROOT = Path(__file__).resolve().parents[2]
DEFAULT = ROOT / "configs" / "butterfly.yaml"
SCRIPT = Path(sys.executable).parent / "partgen"


def snapshot(folder: Path) -> dict[str, str]:
    """relative path -> sha256 of every file under ``folder`` (and '/' for folders)."""
    out = {}
    for p in sorted(folder.rglob("*")):
        rel = str(p.relative_to(folder))
        out[rel] = "/" if p.is_dir() else hashlib.sha256(p.read_bytes()).hexdigest()
    return out


def user_folder(tmp_path: Path, name: str = "mine") -> Path:
    d = tmp_path / name
    d.mkdir()
    (d / "thesis.txt").write_text("years of work\n")
    (d / "photos").mkdir()
    (d / "photos" / "a.jpg").write_bytes(b"\xff\xd8jpeg")
    return d


@pytest.fixture(scope="module")
def kit(tmp_path_factory, kit_of) -> Path:
    """A copy of the session's build of the default design (this module's own)."""
    dest = tmp_path_factory.mktemp("k") / "kit"
    shutil.copytree(kit_of("butterfly").dest, dest)
    return dest


def test_build_refuses_a_folder_with_the_users_files(tmp_path, capsys):
    mine = user_folder(tmp_path)
    before = snapshot(tmp_path)
    assert main(["build", str(DEFAULT), "-o", str(mine), "-q"]) == 2
    err = capsys.readouterr().err
    assert "partgen did not make" in err and "-o" in err and "Traceback" not in err
    assert snapshot(tmp_path) == before


def test_build_refuses_the_folder_holding_the_design(tmp_path, capsys):
    cfg = modified(DEFAULT, tmp_path, name="design.yaml")
    before = snapshot(tmp_path)
    assert main(["build", str(cfg), "-o", str(tmp_path), "-q"]) == 2
    assert "design.yaml" in capsys.readouterr().err
    assert snapshot(tmp_path) == before


def test_build_refuses_a_file_and_the_current_folder(tmp_path, capsys, monkeypatch):
    afile = tmp_path / "afile.txt"
    afile.write_text("mine\n")
    assert main(["build", str(DEFAULT), "-o", str(afile), "-q"]) == 2
    assert afile.read_text() == "mine\n" and sorted(os.listdir(tmp_path)) == ["afile.txt"]
    monkeypatch.chdir(tmp_path)
    for dest in (".", "..", str(tmp_path)):
        assert main(["build", str(DEFAULT), "-o", dest, "-q"]) == 2, dest
    assert sorted(os.listdir(tmp_path)) == ["afile.txt"]
    assert "current folder" in capsys.readouterr().err


@pytest.mark.parametrize("name", [".", "..", "-rf", "../escape", "a/b", "/abs", "x" * 101, "tab\there", ".hidden"])
def test_a_name_is_a_file_name_not_a_path(kit, tmp_path, capsys, monkeypatch, name):
    """``name`` decides out/<name>: a path, a dot or an option-like name is refused on ``name``."""
    monkeypatch.chdir(tmp_path)
    other = tmp_path / "out" / "butterfly"
    shutil.copytree(kit, other)
    cfg = modified(DEFAULT, tmp_path, {"name": name}, name="evil.yaml")
    before = snapshot(tmp_path)
    assert main(["build", str(cfg), "-q"]) == 2
    err = capsys.readouterr().err
    assert f"{cfg}: name: " in err, err
    assert snapshot(tmp_path) == before and other.is_dir()


@pytest.mark.parametrize("cmd", [
    lambda kit, mine: ["check", str(kit), "--samples", "8", "--plates", str(mine)],
    lambda kit, mine: ["trace", str(DEFAULT), "--samples", "64", "--plots", str(mine)],
    lambda kit, mine: ["report", str(DEFAULT), "--samples", "8", "-o", str(mine)],
], ids=["check --plates", "trace --plots", "report -o"])
def test_derived_outputs_refuse_the_users_folder(kit, tmp_path, capsys, cmd):
    mine = user_folder(tmp_path)
    before = snapshot(tmp_path)
    assert main(cmd(kit, mine)) == 2
    assert "partgen did not make" in capsys.readouterr().err
    assert snapshot(tmp_path) == before


def test_trace_csv_never_overwrites_a_users_file(tmp_path, capsys):
    mine = tmp_path / "notes.csv"
    mine.write_text("x,y\n1,2\n")
    cases = [mine, tmp_path, tmp_path / "no_such_folder" / "p.csv", DEFAULT]
    for target in cases:
        before = snapshot(tmp_path)
        assert main(["trace", str(DEFAULT), "--samples", "64", "--no-plots", "--csv", str(target)]) == 2, target
        assert "--csv" in capsys.readouterr().err
        assert snapshot(tmp_path) == before
    ours = tmp_path / "path.csv"
    for _ in range(2):  # a file partgen wrote is replaced
        assert main(["trace", str(DEFAULT), "--samples", "64", "--no-plots", "--csv", str(ours)]) == 0
    lines = ours.read_text().splitlines()
    assert lines[0] == "theta_rad,x_mm,y_mm" and len(lines) == 65
    assert sorted(os.listdir(tmp_path)) == ["notes.csv", "path.csv"]


def test_a_kit_folder_with_a_users_file_is_not_replaced(kit, tmp_path, capsys):
    copy = tmp_path / "kit"
    shutil.copytree(kit, copy)
    (copy / "my_notes.txt").write_text("measured the fit: good\n")
    before = snapshot(tmp_path)
    liu = ROOT / "configs" / "butterfly_liu2017.yaml"
    assert main(["build", str(liu), "-o", str(copy), "-q"]) == 2
    assert "my_notes.txt" in capsys.readouterr().err
    assert snapshot(tmp_path) == before


def test_unchanged_rebuild_keeps_derived_outputs_a_changed_one_removes_them(tmp_path, capsys):
    """(on the gear pair, the cheapest kit: what is kept and removed is the same for every mechanism)"""
    pair = ROOT / "configs" / "gear_pair.yaml"
    dest = tmp_path / "kit"
    assert main(["build", str(pair), "-o", str(dest), "-q"]) == 0
    assert main(["check", str(dest), "--samples", "8"]) in (0, 1)
    assert main(["trace", str(dest / "design.yaml"), "--samples", "64", "--plots", str(dest / "trace")]) == 0
    assert (dest / "plates" / MARKER).is_file() and (dest / "trace" / MARKER).is_file()
    capsys.readouterr()
    before = snapshot(dest)
    assert main(["build", str(pair), "-o", str(dest), "-q"]) == 0
    assert snapshot(dest) == before, "an unchanged rebuild touched the kit"
    assert "removed" not in capsys.readouterr().err
    thickness = yaml.safe_load(pair.read_text())["base"]["thickness_mm"]
    changed = modified(pair, tmp_path, {"base.thickness_mm": thickness + 0.5}, name="design.yaml")
    assert main(["build", str(changed), "-o", str(dest), "-q"]) == 0
    err = capsys.readouterr().err
    assert "partgen: note: removed plates/, trace/" in err, err
    assert not (dest / "plates").exists() and not (dest / "trace").exists()
    assert sorted(os.listdir(tmp_path)) == ["design.yaml", "kit"]


def test_an_earlier_partgens_kit_is_still_ours(kit, tmp_path):
    """A kit written before the marker existed (manifest.json, no .partgen) is replaced (by the gear
    pair's, the cheapest build: whose kit replaces it does not matter)."""
    old = tmp_path / "kit"
    shutil.copytree(kit, old)
    (old / MARKER).unlink()
    (old / "B99.stl").write_bytes(b"solid old\n")  # a part of an older design
    assert main(["build", str(ROOT / "configs" / "gear_pair.yaml"), "-o", str(old), "-q"]) == 0
    assert not (old / "B99.stl").exists() and (old / MARKER).is_file()


def _script(*args, **kw):
    return subprocess.Popen([str(SCRIPT), *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)


def test_two_builds_into_one_fresh_folder_end_with_one_whole_kit(kit_of, tmp_path):
    """(the gear pair: the race is the same for every mechanism, and its kit the cheapest)"""
    dest = tmp_path / "kit"
    procs = [_script("build", str(ROOT / "configs" / "gear_pair.yaml"), "-o", str(dest), "-q") for _ in range(2)]
    results = [p.communicate(timeout=300) + (p.returncode,) for p in procs]
    for out, err, code in results:
        assert code in (0, 2) and "Traceback" not in err, err
    assert any(code == 0 for _, _, code in results)
    expect = {k: v for k, v in snapshot(kit_of("gear_pair").dest).items()}
    assert snapshot(dest) == expect
    assert sorted(os.listdir(tmp_path)) == ["kit"]


@pytest.mark.parametrize("sig,delay", [(signal.SIGTERM, 2.2), (signal.SIGINT, 0.3), (signal.SIGKILL, 2.2)],
                         ids=["SIGTERM during the build", "Ctrl-C during the imports", "SIGKILL"])
def test_a_signal_leaves_the_previous_kit_whole(kit, tmp_path, sig, delay):
    dest = tmp_path / "kit"
    shutil.copytree(kit, dest)
    before = snapshot(dest)
    liu = ROOT / "configs" / "butterfly_liu2017.yaml"
    proc = _script("build", str(liu), "-o", str(dest), "-q")
    time.sleep(delay)
    proc.send_signal(sig)
    out, err = proc.communicate(timeout=300)
    if proc.returncode == 0:  # the build won the race: then the new kit is whole
        assert (dest / "manifest.json").is_file() and json.loads((dest / "manifest.json").read_text())["parts"]
    else:
        assert proc.returncode in (-sig, 128 + sig), (proc.returncode, err)
        assert "Traceback" not in err
        if sig != signal.SIGKILL:
            assert snapshot(dest) == before
    if sig == signal.SIGKILL:  # no handler runs: the next run cleans up after the dead process (any
        # design's build: the gear pair's is the cheapest)
        assert main(["build", str(ROOT / "configs" / "gear_pair.yaml"), "-o", str(dest), "-q"]) == 0
    assert sorted(os.listdir(tmp_path)) == ["kit"], os.listdir(tmp_path)


def test_a_closed_stdout_ends_quietly(tmp_path):
    proc = _script("build", str(ROOT / "configs" / "gear_pair.yaml"), "-o", str(tmp_path / "kit"))
    proc.stdout.readline()
    proc.stdout.close()
    err = proc.stderr.read()
    proc.wait(timeout=300)
    assert "Traceback" not in err and "BrokenPipe" not in err, err
    assert proc.returncode in (0, 141)


def test_json_bad_input_is_one_object(tmp_path, capsys):
    cfg = modified(DEFAULT, tmp_path, {"gears": {"module_mm": float("nan"), "face_width_mm": 6.0}}, name="design.yaml")
    assert main(["check", str(cfg), "--json"]) == 2
    out = json.loads(capsys.readouterr().out)
    assert out["ok"] is False and out["error"]["key"] == "gears.module_mm" and out["error"]["file"] == str(cfg)
    assert main(["check", str(cfg), "--json", "--samples", "0"]) == 2
    out = json.loads(capsys.readouterr().out)
    assert out["error"]["key"] == "--samples"


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_read_only_folder_is_bad_input(tmp_path, capsys):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        assert main(["build", str(DEFAULT), "-o", str(ro / "kit"), "-q"]) == 2
        assert "permission denied" in capsys.readouterr().err
    finally:
        ro.chmod(0o755)
