"""What every kind of mechanism owes the command line (one test for all of ``mechanisms.REGISTRY``,
on each kind's cheapest design): ``partgen build`` writes a whole kit; check, trace, report and
tolerance run on the design file AND on the kit folder (exit 0, one JSON object of the kind, their
outputs written where they belong); an unknown key under the kind's own section is exit 2 naming
the file and the key path, with nothing written; a kit folder with one byte of an STL changed fails
its check naming that STL, one with a byte of its design.yaml changed is refused naming design.yaml.

What a kind computes (its figures, its own rules and bad values) is tested in its own files; this
file holds what is the same for all of them. One `partgen build` per kind (module-scoped) whose kit
the commands on the design share, and one rebuild from the kit folder's own design.yaml that the
commands on the folder share (``pipeline.make_kit`` keeps one kit per process: ``Kit.shared``)."""

from __future__ import annotations

import contextlib
import io
import json
import os
import re
import shutil
from pathlib import Path

import pytest
import yaml
from helpers import ROOT, modified

from partgen import pipeline
from partgen.cli.main import main
from partgen.export.outputs import MARKER
from partgen.mechanisms import REGISTRY

# the cheapest design of each kind that passes its check (not butterfly_liu2017, which fails by design);
# where a kind's shipped designs are slow to build, check or trace (the exact 3-D contact of the
# crossed and bevel pairs), a small variant of one in tests/designs
DESIGNS = {
    "gear_chain": "configs/star.yaml",
    "wrist": "tests/designs/wrist_small.yaml",  # the shipped wrists take 30-50 s to build
    "bennett_butterfly": "tests/designs/bennett_contract.yaml",  # the shipped design less its layout search, coarser
    "gear_pair": "configs/gear_pair.yaml",
    "gear_train": "configs/gear_train_rack.yaml",
    "crossed_helical": "tests/designs/crossed_small.yaml",  # the shipped pair, coarser, at 4 phases
    "bevel": "tests/designs/bevel_small.yaml",  # the shipped mitre pair, coarser, at 4 phases
}
HEADER = ("kind", "name", "description", "printer", "material")
# a heading of the kind's own report sections (the page holds the kind's sections, not only the common ones)
OWN_SECTION = {"gear_chain": "Stacking", "wrist": "Math", "bennett_butterfly": "Balance", "gear_pair": "Trace",
               "gear_train": "Trace", "crossed_helical": "Trace", "bevel": "Trace"}

# command -> (its options here, the folder it writes: -o DIR for a design file, KITDIR/<name> for a kit)
COMMANDS = {
    "check": (["--samples", "4"], "plates"),
    "trace": ([], "trace"),
    "report": (["--samples", "4"], "report"),
    "tolerance": (["--samples", "200", "--workers", "1", "--check-samples", "4"], "tolerance"),
}


def run(*argv) -> tuple[int, str, str]:
    """``partgen ARGV`` in this process: (exit code, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main([str(a) for a in argv])
    return code, out.getvalue(), err.getvalue()


def own_section(design: Path) -> str:
    """The kind's own first section of a design: its first mapping after the common header."""
    return next(k for k, v in yaml.safe_load(design.read_text()).items() if k not in HEADER and isinstance(v, dict))


def listing(folder: Path) -> list[str]:
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


class Kit:
    """One kind's design, its kit folder as `partgen build --json` wrote it and what it printed."""

    def __init__(self, kind: str, config: Path, dest: Path, code: int, out: str, err: str):
        self.kind, self.config, self.dest, self.code, self.out, self.err = kind, config, dest, code, out, err
        self._kits = {"design": dict(pipeline._KITS), "kit": {}}  # the kit `build` made; the kit folder's

    @contextlib.contextmanager
    def shared(self, on: str):
        """Commands on the design (``on="design"``) share the kit `build` made; commands on the kit
        folder (``"kit"``) the kit its design.yaml built for the first of them (printer.yaml beside it
        makes it another document: that first command rebuilds the kit from the folder, as a user's
        would). Another kind's kit may have taken the process's place since."""
        pipeline._KITS.clear()
        pipeline._KITS.update(self._kits[on])
        try:
            yield
        finally:
            self._kits[on] = dict(pipeline._KITS)


@pytest.fixture(scope="module", params=list(REGISTRY))
def kit(request, tmp_path_factory) -> Kit:
    kind = request.param
    assert kind in DESIGNS, f"no design for kind {kind} in tests/cli/test_contract.py's DESIGNS"
    config = ROOT / DESIGNS[kind]
    dest = tmp_path_factory.mktemp(f"contract_{kind}") / "kit"
    pipeline._KITS.clear()
    code, out, err = run("build", config, "-o", dest, "--json")
    return Kit(kind, config, dest, code, out, err)


def test_every_kind_has_a_design_of_its_kind():
    assert set(DESIGNS) == set(REGISTRY) == set(OWN_SECTION)
    for kind, path in DESIGNS.items():
        assert yaml.safe_load((ROOT / path).read_text())["kind"] == kind, path


def test_build_writes_the_whole_kit(kit):
    assert kit.code == 0, kit.err
    out = json.loads(kit.out)
    assert out["ok"] is True and out["kind"] == kit.kind and Path(out["kit"]) == kit.dest
    man = json.loads((kit.dest / "manifest.json").read_text())
    assert man["design"]["kind"] == kit.kind
    assert [p["file"] for p in out["parts"]] == [p["file"] for p in man["parts"]] and man["parts"]
    files = set(os.listdir(kit.dest))
    assert {"manifest.json", "design.yaml", "assembly.glb", MARKER} <= files
    for p in man["parts"]:
        stl = (kit.dest / p["file"]).read_bytes()
        assert len(stl) == 84 + 50 * int.from_bytes(stl[80:84], "little") > 84, p["file"]  # a whole binary STL
    assert yaml.safe_load((kit.dest / "design.yaml").read_text())["kind"] == kit.kind


@pytest.mark.parametrize("on", ["design", "kit"])
@pytest.mark.parametrize("command", list(COMMANDS))
def test_command(kit, command, on, tmp_path):
    options, sub = COMMANDS[command]
    if on == "design":
        target, folder, where = kit.config, tmp_path / sub, ["-o", tmp_path / sub]
    else:
        target, folder, where = kit.dest, kit.dest / sub, []
    with kit.shared(on):
        code, out, err = run(command, target, *options, *where, "--json")
    assert code == 0, err[-2000:] + out[-2000:]
    got = json.loads(out)
    assert got["ok"] is True
    assert (folder / MARKER).is_file(), f"{command} wrote no {folder}"
    written = [p for p in folder.iterdir() if not p.name.startswith(".")]
    assert written and all(p.stat().st_size > 0 for p in written), written
    names = {p.name for p in written}
    if command == "check":
        assert not [f for f in got["findings"] if f["severity"] == "fail"]
        assert "plates.png" in names and any(n.endswith(".3mf") for n in names), names
    elif command == "trace":
        assert got["kind"] == kit.kind
    elif command == "report":
        assert Path(got["report"]) == folder / "index.html"
        page = (folder / "index.html").read_text(encoding="utf-8")
        name = yaml.safe_load(kit.config.read_text())["name"]
        assert name in page and all(f">{h}</h2>" in page for h in ("Bill of parts", OWN_SECTION[kit.kind])), \
            re.findall(r">([^<]+)</h2>", page)
    elif command == "tolerance":
        assert got["samples"] == 200 and 0.0 <= got["overall"]["probability"] <= 1.0
        assert json.loads((folder / "result.json").read_text())["samples"] == 200


def test_an_unknown_key_is_exit_2_naming_file_and_key(kit, tmp_path):
    section = own_section(kit.config)
    key = f"{section}.contract_unknown_mm"
    bad = modified(kit.config, tmp_path / "d", {key: 1.0}, name="bad.yaml")
    before = listing(tmp_path)
    code, out, err = run("build", bad, "-o", tmp_path / "kit", "-q")
    assert code == 2 and out == "", out
    assert err.count("\n") == 1 and err.startswith(f"partgen: error: {bad}: {key}: unknown key"), err
    code, out, err = run("check", bad, "--samples", "4", "-o", tmp_path / "plates", "--json")
    error = json.loads(out)["error"]
    assert code == 2 and (error["file"], error["key"]) == (str(bad), key), error
    assert listing(tmp_path) == before, "a bad design wrote something"


def test_a_tampered_kit_folder_is_caught(kit, tmp_path):
    copy = tmp_path / "kit"
    shutil.copytree(kit.dest, copy)
    stl = copy / json.loads((copy / "manifest.json").read_text())["parts"][-1]["file"]
    data = bytearray(stl.read_bytes())
    data[len(data) // 2] ^= 0x01  # one bit, mid-file
    stl.write_bytes(bytes(data))
    with kit.shared("kit"):  # the same design.yaml: the kit the kit folder's commands share
        code, out, err = run("check", copy, "--samples", "4", "--no-plates", "--json")
    assert code == 1, err
    fails = [f for f in json.loads(out)["findings"] if f["severity"] == "fail"]
    assert [f["check"] for f in fails] == ["kit"] and stl.name in fails[0]["message"], fails

    copy2 = tmp_path / "kit2"
    shutil.copytree(kit.dest, copy2)
    design = copy2 / "design.yaml"
    section = own_section(design)
    text = design.read_text()
    assert text.count(f"\n{section}:") == 1
    design.write_text(text.replace(f"\n{section}:", f"\n{section[:-1]}_:", 1))  # one byte: the section's key misspelt
    code, out, err = run("check", copy2, "--samples", "4", "--no-plates")
    assert code == 2 and err.startswith(f"partgen: error: {design}: {section[:-1]}_: unknown key"), err
