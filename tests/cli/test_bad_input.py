"""Bad input to ``partgen build``: exit code 2, one message naming the file and the key path, no
traceback, and nothing written (no half kit, no temporary folders, an earlier kit left intact).

Each case copies a shipped config, breaks one thing and builds it into a folder whose parent holds
only a marker file. And a seeded, bounded fuzz of every shipped design (tests/fuzzing.py).
"""

from __future__ import annotations

import copy
import hashlib
import json
import os
import shutil
import subprocess
import sys
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import pytest
import yaml

from partgen.cli.main import main

ROOT = Path(__file__).resolve().parents[2]
CONFIGS = ROOT / "configs"
MARKER = "KEEP_ME.txt"


def _config(name: str) -> dict:
    return yaml.safe_load((CONFIGS / name).read_text(encoding="utf-8"))


def _default() -> dict:
    return _config("butterfly.yaml")


def _liu() -> dict:
    return _config("butterfly_liu2017.yaml")


@dataclass
class Case:
    """``write(tmp_path, id) -> (config path, name of the file the message must name)``; ``key`` is the
    key path the message must give right after that file name (None: no key applies), ``also`` are
    further fragments the message must contain."""

    id: str
    write: Callable[[Path, str], tuple[Path, str]]
    key: str | None
    also: list[str] = field(default_factory=list)
    marks: tuple = ()


def _setup_printers(tmp_path: Path) -> None:
    dest = tmp_path / "printers"
    if not dest.exists():
        shutil.copytree(CONFIGS / "printers", dest)


def design(base: Callable[[], dict], mutate: Callable[[dict], None] | None = None):
    """A writer for ``base()`` changed by ``mutate`` (in place), next to a copy of configs/printers."""

    def write(tmp_path: Path, _id: str) -> tuple[Path, str]:
        _setup_printers(tmp_path)
        data = copy.deepcopy(base())
        if mutate is not None:
            mutate(data)
        path = tmp_path / f"bad_{_id}.yaml"
        path.write_text(yaml.safe_dump(data, sort_keys=False), encoding="utf-8")
        return path, path.name

    return write


def text(content: str):
    """A writer for a design file with exactly ``content``."""

    def write(tmp_path: Path, _id: str) -> tuple[Path, str]:
        _setup_printers(tmp_path)
        path = tmp_path / f"bad_{_id}.yaml"
        path.write_text(content, encoding="utf-8")
        return path, path.name

    return write


def missing_file(tmp_path: Path, _id: str) -> tuple[Path, str]:
    path = tmp_path / f"no_such_design_{_id}.yaml"
    return path, path.name


def bad_printer(tmp_path: Path, _id: str) -> tuple[Path, str]:
    """A good design whose printer profile has a negative build envelope: the profile is named."""
    _setup_printers(tmp_path)
    prof = yaml.safe_load((CONFIGS / "printers" / "fortus450mc.yaml").read_text(encoding="utf-8"))
    prof["build_envelope_mm"] = [-406, 355, 406]
    (tmp_path / "printers" / "broken_printer.yaml").write_text(yaml.safe_dump(prof), encoding="utf-8")
    path, _ = design(_default, lambda d: d.update(printer="printers/broken_printer.yaml"))(tmp_path, _id)
    return path, "broken_printer.yaml"


def _set(section: str, key: str, value):
    return lambda d: d[section].__setitem__(key, value)


def _rename(section: str, old: str, new: str):
    def f(d):
        d[section][new] = d[section].pop(old)
    return f


def _teeth(i: int, gear: str, value):
    return lambda d: d["teeth"][i].__setitem__(gear, value)


def _both_sources(d):
    d["links"] = _liu()["links"]


_broken_yaml = (CONFIGS / "butterfly.yaml").read_text(encoding="utf-8").replace(
    "module_mm: 1.25", "module_mm: [1.25", 1)

CASES = [
    # --- the file itself
    Case("yaml_syntax", text(_broken_yaml), None, ["invalid YAML", "line "]),
    Case("empty_file", text(""), None, ["empty"]),
    Case("top_level_list", text("- name: butterfly\n- printer: printers/fortus450mc.yaml\n"), None, ["list"]),
    Case("missing_file", missing_file, None, ["no such file"]),
    # --- schema: keys
    Case("unknown_top_level_key", design(_default, lambda d: d.update(colour="red")), "colour", ["unknown key"]),
    # (an unknown key under each kind's own section: tests/cli/test_contract.py)
    # A real typo renames the key: the message must name the key in the file that has to change
    # (gears.modul_mm), not the required key its absence leaves missing.
    Case("typo_nested_key", design(_default, _rename("gears", "module_mm", "modul_mm")), "gears.modul_mm",
         ["unknown key", "did you mean 'module_mm'"]),
    # --- schema: values
    Case("module_zero", design(_default, _set("gears", "module_mm", 0)), "gears.module_mm"),
    Case("module_negative", design(_default, _set("gears", "module_mm", -1.25)), "gears.module_mm"),
    Case("string_for_number", design(_default, _set("gears", "face_width_mm", "six")), "gears.face_width_mm",
         ["'six'"]),
    Case("fractional_teeth", design(_liu, _teeth(2, "D", 20.5)), "teeth[2].D", ["20.5"]),
    Case("teeth_below_4", design(_liu, _teeth(3, "G", 3)), "teeth[3].G"),
    Case("pressure_angle_95", design(_default, _set("gears", "pressure_angle_deg", 95)), "gears.pressure_angle_deg"),
    Case("negative_plate_thickness", design(_default, _set("plates", "thickness_mm", -4.0)), "plates.thickness_mm"),
    Case("zero_scale", design(_default, _set("curve", "scale_mm_per_unit", 0)), "curve.scale_mm_per_unit"),
    Case("drive_teeth_string", design(_default, _set("drive", "teeth", "40")), "drive.teeth"),
    # --- schema: either/or (a whole-design rule: the keys are named in the problem)
    Case("curve_and_links", design(_default, _both_sources), None, ["'curve'", "'links'"]),
    Case("neither_curve_nor_links", design(_default, lambda d: d.pop("curve")), None, ["'curve'", "'links'"]),
    Case("radial_and_diametral_clearance", design(_default, _set("joints", "running_clearance_radial_mm", 0.1)),
         "joints", ["running_clearance_radial_mm", "running_clearance_diametral_mm"]),
    # --- printer profile
    Case("missing_printer_file", design(_default, lambda d: d.update(printer="printers/no_such_printer.yaml")),
         "printer", ["no_such_printer.yaml"]),
    Case("bad_printer_profile", bad_printer, "build_envelope_mm[0]"),
    # --- design rules (after the schema)
    Case("unknown_drop_link", design(_default, _set("curve", "drop_links", ["L2", "L99", "M8"])),
         "curve.drop_links[1]", ["L99"]),
    Case("auto_teeth_impossible", design(_default, _set("gears", "module_mm", 3.0)), "teeth"),
    Case("same_speed_links", design(_liu, lambda d: d["links"][3].__setitem__("speed", 3)), "links[2].speed",
         ["same speed"]),
    Case("idler_cannot_reach", design(_liu, _teeth(0, "M", 10)), "teeth[0].M"),
    Case("wrong_teeth_rows", design(_liu, lambda d: d["teeth"].pop()), "teeth"),
    Case("cutter_fillets_overlap", design(_liu, lambda d: d["gears"].update(cutter_tip_radius_coeff=0.6,
                                                                          pressure_angle_deg=30)),
         "gears.cutter_tip_radius_coeff", ["overlap"]),
    Case("pointed_teeth", design(_liu, _set("gears", "profile_shift", 1.5)), "gears.profile_shift", ["pointed"]),
    # --- found while building the geometry (slow: ~1 s each)
    Case("legs_too_short", design(_default, _set("base", "leg_height_mm", 5.0)), "base.leg_height_mm"),
    Case("part_larger_than_printer", design(_default, _set("curve", "scale_mm_per_unit", 80.0)),
         "curve.scale_mm_per_unit", ["B1", "406"]),
]


def _run_bad(tmp_path: Path, case: Case, capsys) -> tuple[int, str, str, Path, str]:
    cfg, named = case.write(tmp_path, case.id)
    parent = tmp_path / "outparent"
    parent.mkdir()
    (parent / MARKER).write_text("marker\n")
    code = main(["build", str(cfg), "-o", str(parent / "kit"), "-q"])
    out, err = capsys.readouterr()
    return code, out, err, parent, named


@pytest.mark.parametrize("case", [pytest.param(c, id=c.id, marks=c.marks) for c in CASES])
def test_bad_input(tmp_path, capsys, case: Case):
    code, out, err, parent, named = _run_bad(tmp_path, case, capsys)
    assert "Traceback" not in out and "Traceback" not in err, err
    assert code == 2, f"exit code {code}, stderr: {err!r}"
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("partgen: error: "), f"expected one error line, got {err!r}"
    msg = lines[0]
    assert named in msg, f"{named!r} not named in {msg!r}"
    if case.key is not None:
        assert f"{named}: {case.key}: " in msg, f"key path {case.key!r} not given after {named!r} in {msg!r}"
    for frag in case.also:
        assert frag in msg, f"{frag!r} not in {msg!r}"
    # nothing written: no kit, no temporary or backup folders, the marker untouched
    assert sorted(os.listdir(parent)) == [MARKER], sorted(os.listdir(parent))
    assert (parent / MARKER).read_text() == "marker\n"


def test_at_least_twenty_cases():
    assert len({c.id for c in CASES}) == len(CASES) >= 20


def _hashes(folder: Path) -> dict[str, str]:
    return {p.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in sorted(folder.iterdir())}


def test_failed_build_keeps_previous_kit(tmp_path, capsys, kit_copy):
    """A good kit in DIR (a copy of the session's `partgen build` of the default design) survives,
    byte for byte, a build that fails late (in the geometry)."""
    parent = tmp_path / "outparent"
    parent.mkdir()
    kit = kit_copy("butterfly", parent / "kit")
    before = _hashes(kit)
    assert "manifest.json" in before and "assembly.glb" in before
    assert any(n.endswith(".stl") for n in before)

    cfg, _ = design(_default, _set("base", "leg_height_mm", 5.0))(tmp_path, "late_failure")
    assert main(["build", str(cfg), "-o", str(kit), "-q"]) == 2
    err = capsys.readouterr().err
    assert "base.leg_height_mm" in err and "Traceback" not in err

    assert _hashes(kit) == before
    assert sorted(os.listdir(parent)) == ["kit"]


FUZZ_CONFIGS = sorted((ROOT / "configs").glob("*.yaml"))
FUZZ_CASES = 70  # the first 70 of the seeded order, whatever the machine's load (a wall-clock budget ran ~70 on
# 2 cores, fewer on a loaded machine); benchmarks/bad_inputs.py runs the large fuzz (469 cases)
FUZZ_BUDGET_S = 120.0  # a safety net only: 70 cases take ~6 s of CPU
FUZZ_CASE_SECONDS = 1.5  # a refusal (exit 2) of these 70 takes under 0.7 s even on a loaded machine; what runs
# longer is a valid design building (4 of the 70: a Bennett, a heart, a lissajous; a worm pair exits 0 in ~2.7 s
# loaded), stopped here as at 4 s before (the stop and what it leaves are the same test), 10 s sooner in all


def test_fuzzed_designs_exit_0_or_2_and_write_nothing_on_failure():
    """A seeded, bounded fuzz of every shipped design (tests/fuzzing.py): each case is exit 0 or 2,
    never a traceback or a crash, and a failed build writes nothing.

    The worker runs in a child process, so a segmentation fault in the geometry kernel fails this test
    with the case that caused it instead of killing the test run. A case still building after
    ``FUZZ_CASE_SECONDS`` (a valid wrist or Bennett design: those take tens of seconds) is stopped and must
    also have left nothing behind; ``benchmarks/bad_inputs.py`` runs every case to the end."""
    assert len(FUZZ_CONFIGS) >= 6
    proc = subprocess.run([sys.executable, str(ROOT / "tests" / "fuzzing.py"), *map(str, FUZZ_CONFIGS), "--seed", "20261122",
                           "--limit", str(FUZZ_CASES), "--budget", str(FUZZ_BUDGET_S), "--case-seconds", str(FUZZ_CASE_SECONDS)],
                          capture_output=True, text=True, timeout=FUZZ_BUDGET_S + 240, cwd=ROOT)
    lines = [json.loads(x) for x in proc.stdout.splitlines() if x.startswith("{")]
    started = {r["i"]: r for r in lines if r.get("start")}
    done = {r["i"]: r for r in lines if not r.get("start")}
    crashed = [started[i] for i in started if i not in done]
    assert proc.returncode == 0 and not crashed, f"the worker died (exit {proc.returncode}) on {crashed}: {proc.stderr[-2000:]}"
    bad = [r for r in done.values() if r["code"] not in (0, 2, "timeout") or r["traceback"] or r["written"]]
    assert not bad, "\n".join(f"{r['config']} {r['kind']} {r['key']}: exit {r['code']}, left {r['left']}: {r['message']}"
                              for r in bad)
    assert len(done) == FUZZ_CASES, f"{len(done)} of {FUZZ_CASES} cases ran within {FUZZ_BUDGET_S} s"
    codes = Counter(r["code"] for r in done.values())
    kinds = {(r["kind"], r["config"]) for r in done.values()}
    assert codes[2] >= 30 and len(kinds) >= 20, (codes, len(kinds))
    # a message names the key it is about: the mutated key, a key above it or below it
    wrong = []
    for r in done.values():
        if r["code"] != 2 or r["kind"] in ("misspelt_kind",):
            continue
        after = r["message"].split(f"{r['config']}: ", 1)[-1]
        named = after.split(": ", 1)[0]
        key = r["key"]
        if not (named == key or key.startswith(named + ".") or key.startswith(named + "[") or named.startswith(key)):
            wrong.append(f"{r['config']} {r['kind']} {key}: {r['message']}")
    assert len(wrong) <= len(done) // 20, "\n".join(wrong[:20])
