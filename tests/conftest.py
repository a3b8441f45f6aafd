"""Shared fixtures: each kit is built once per test session (per xdist worker), and the test
files that share an expensive kit run on one worker (``SHARED``, by the xdist scheduler at the end of this file)."""

import atexit
import os
import shutil
import tempfile
from pathlib import Path

import pytest

# partgen remembers its auto choices and searched layouts (core.cache): the tests keep theirs in a
# folder of their own (never the user's ~/.cache/partgen), one per test run that its xdist workers
# share (a worker's parent is the run's main process, which removes it at exit; its writes are atomic
# and its keys hold everything a decision depends on, so a worker reads only what it would compute)
if os.environ.get("PYTEST_XDIST_WORKER"):
    _CACHE = os.path.join(tempfile.gettempdir(), f"partgen-test-cache-{os.getppid()}")
    os.makedirs(_CACHE, exist_ok=True)
else:
    _CACHE = os.path.join(tempfile.gettempdir(), f"partgen-test-cache-{os.getpid()}")
    shutil.rmtree(_CACHE, True)
    os.makedirs(_CACHE)
    atexit.register(shutil.rmtree, _CACHE, True)
os.environ["PARTGEN_CACHE_DIR"] = _CACHE

from partgen import pipeline

ROOT = Path(__file__).parent.parent
CONFIGS = ROOT / "configs"


@pytest.fixture(scope="session")
def built_kits(kit_of):
    """name -> (Loaded, Kit, manifest dict, kit folder) for the two butterfly designs."""
    return {name: kit_of(name) for name in ("butterfly", "butterfly_liu2017")}


@pytest.fixture(scope="session")
def kit_of(tmp_path_factory):
    """``kit_of(name)`` -> Built (loaded, kit, manifest, dest) of configs/<name>.yaml (or of
    <name>.yaml from the project's root when ``name`` has a slash: ``tests/designs/…``), built in-process
    once per test session (per xdist worker) on first use. The folder is shared: read it, never
    write into it (use ``kit_copy`` for a folder a test may change)."""
    cache = {}

    def get(name: str) -> pipeline.Built:
        if name not in cache:
            cfg = ROOT / f"{name}.yaml" if "/" in name else CONFIGS / f"{name}.yaml"  # "tests/designs/x": a test design
            cache[name] = pipeline.build(cfg, tmp_path_factory.mktemp("kit_of") / Path(name).name)
        return cache[name]
    return get


@pytest.fixture
def kit_copy(kit_of, tmp_path):
    """``kit_copy(name)`` -> a fresh copy (Path) of the session's built kit folder of configs/<name>.yaml,
    the test's own to change."""
    def copy(name: str, dest: Path | None = None) -> Path:
        dest = dest or tmp_path / f"{name}_kit"
        shutil.copytree(kit_of(name).dest, dest)
        return dest
    return copy


@pytest.fixture(scope="session")
def checked_default_kit(tmp_path_factory, kit_of):
    """`partgen check KITDIR --samples 12 --json` on a copy of the session's default kit folder (not
    primed: check rebuilds the kit from the folder's own design.yaml and compares the STLs), run once
    per session (per worker) for tests/export/test_plates.py (``SHARED`` with tests/mechanisms/gear_chain/test_check.py). Returns
    {"folder": the checked kit folder with its plates/ (read it, never write into it),
    "code"/"out": the exit code and JSON of its check}. (A tampered kit folder of every kind:
    tests/cli/test_contract.py.)"""
    import contextlib
    import io
    import json

    from partgen.cli.main import main

    def check(folder: Path) -> tuple[int, dict]:
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            code = main(["check", str(folder), "--samples", "12", "--json"])
        return code, json.loads(out.getvalue())

    base = tmp_path_factory.mktemp("checked")
    folder = base / "butterfly_kit"
    shutil.copytree(kit_of("butterfly").dest, folder)
    code, out = check(folder)
    return {"folder": folder, "code": code, "out": out}


@pytest.fixture
def prime_kit_cache():
    """``prime_kit_cache(built, target=None)``: make ``built.kit`` (or ``built`` itself, a kit built
    from the config ``target``) the kit pipeline.make_kit hands out
    for ``target`` (default: the config it was built from; give only a file with the same bytes).
    check, trace and report share one built kit per process; this lets a test's command on a config
    reuse the session's build of that same config. Don't prime a kit folder: its check must rebuild
    from the folder's own design.yaml to test that it reproduces the STLs."""
    def prime(built, target=None) -> None:
        kit = built.kit if isinstance(built, pipeline.Built) else built
        loaded = built.loaded if target is None else pipeline.load(target)
        if isinstance(built, pipeline.Built):
            assert loaded.path.read_bytes() == built.loaded.path.read_bytes(), "not the design it was built from"
        assert loaded.kit_dir is None, "a kit folder's check must rebuild from its own design.yaml"
        pipeline._KITS.clear()
        pipeline._KITS[pipeline.kit_key(loaded)] = kit
    return prime


# Test files (or single tests) that share an expensive kit run on one worker. With
# ``pytest -n auto --dist loadfile`` the scheduler below (xdist's hook) hands out whole files, as
# loadfile does, except that these join the named file's worker and reuse its session kits
# (``kit_of``). (xdist's own ``--dist loadgroup`` does not group under pytest 9.)
@pytest.fixture(scope="session", autouse=True)
def _project_out_untouched():
    """No test writes into the project's own out/ (a user's kits live there): every test names its
    output folder. A test that leaves anything new or removes anything there fails the session."""
    out = ROOT / "out"

    def listing() -> list[str]:
        return sorted(str(p.relative_to(out)) for p in out.rglob("*")) if out.is_dir() else []
    before = listing()
    yield
    after = listing()
    assert after == before, f"tests changed {out}: {sorted(set(after) ^ set(before))[:8]}"


SHARED = {
    "test_manifest_schema.py::test_manifest_holds_the_schema[wrist_sphere]": "test_wrist.py",
    "test_manifest_schema.py::test_manifest_holds_the_schema[wrist_quasi_ellipsoid]": "test_wrist.py",
    # the shipped Bennett kit (its layout search: the suite's costliest build), built once for all three
    "test_manifest_schema.py::test_manifest_holds_the_schema[bennett_butterfly]": "test_bennett_cli.py",
    "test_bennett_kit.py": "test_bennett_cli.py",
    "test_plates.py": "test_check.py",  # the default kit (kit_of) and `check KITDIR` of it (checked_default_kit)
    "test_manifest_schema.py::test_manifest_holds_the_schema[lissajous]": "test_multi_turn_drawings.py",
    "test_manifest_schema.py::test_manifest_holds_the_schema[gear_train_crossed_helical]": "test_crossed_helical.py",
    "test_manifest_schema.py::test_manifest_holds_the_schema[gear_train_worm]": "test_worm.py",
    "test_manifest_schema.py::test_manifest_holds_the_schema[bevel_mitre]": "test_bevel.py",
    # the kinds the solid pair kernel serves, each test with its kind's file (the shipped kit built there)
    "test_solid_pairs.py[bevel_mitre]": "test_bevel.py",
    "test_solid_pairs.py[gear_train_crossed_helical]": "test_crossed_helical.py",
    "test_tolerance_wrist.py": "test_wrist.py",  # the wrist kits
    "test_tolerance_bennett.py": "test_bennett_cli.py",  # the shipped Bennett kit
    # test_shipped_jam checks every shipped kit: each where the same kit is built already
    "test_shipped_jam.py": "test_manifest_schema.py",
    "test_shipped_jam.py::test_shipped_design_turns_in_99_percent_of_prints[bennett_butterfly]": "test_bennett_cli.py",
    "test_shipped_jam.py::test_shipped_design_turns_in_99_percent_of_prints[wrist_sphere]": "test_wrist.py",
    "test_shipped_jam.py::test_shipped_design_turns_in_99_percent_of_prints[wrist_quasi_ellipsoid]": "test_wrist.py",
    "test_shipped_jam.py::test_shipped_design_turns_in_99_percent_of_prints[lissajous]": "test_multi_turn_drawings.py",
    "test_shipped_jam.py::test_shipped_design_turns_in_99_percent_of_prints[gear_train_crossed_helical]":
        "test_crossed_helical.py",
    "test_shipped_jam.py::test_shipped_design_turns_in_99_percent_of_prints[gear_train_worm]": "test_worm.py",
}
# The groups that take longest go first, longest first, so the two workers end together: every group of
# 5 s or more (summed seconds of a whole `--durations=0` run at fc9f983: 55, 47, 38, 34, 26, 24, 22, 22, 20,
# 19, 16, 14, 12, 11, 10, …, 5); the rest (each under 5 s, 80 s in all) after them in the order collected.
# xdist's own reordering (by the number of tests a group has) is turned off in pytest_configure.
FIRST = ("test_contract.py", "test_check.py", "test_bennett_cli.py", "test_wrist_auto.py", "test_wrist.py",
         "test_manifest_schema.py", "test_throated_wheel.py", "test_printers.py", "test_report.py",
         "test_bench_sweep.py", "test_autoplay.py", "test_bad_input.py", "test_determinism.py", "test_rules.py",
         "test_tolerance.py", "test_exact_chain.py", "test_autoplay_allocate.py", "test_bevel.py", "test_outputs.py",
         "test_crossed_helical.py", "test_kit.py", "test_multi_turn_drawings.py", "test_verify.py",
         "test_wrist_mate.py", "test_contact_pattern.py", "test_autoplay_clearance.py", "test_worm.py",
         "test_autoplay_crossed.py", "test_viewer.py", "test_drawn_curves.py", "test_cli.py")


def _group(nodeid: str) -> str:
    path = nodeid.split("::", 1)[0]
    file, here = path.rsplit("/", 1)[-1], nodeid.rsplit("/", 1)[-1]
    param = here.partition("[")[2].split("-")[0].rstrip("]")  # a test's first parameter: file[param] in SHARED
    return SHARED.get(here, SHARED.get(f"{file}[{param}]", SHARED.get(file, file)))


def pytest_collection_modifyitems(config, items):
    rank = {g: i for i, g in enumerate(FIRST)}
    items.sort(key=lambda it: rank.get(_group(it.nodeid), len(FIRST)))  # stable: a file keeps its order


class _SharedKitsScheduling:
    """xdist's scheduler hook, registered only when xdist is loaded (``pytest -p no:xdist`` and ``-n 0``
    run without it: a conftest hook of an absent plugin is an error)."""

    @staticmethod
    def pytest_xdist_make_scheduler(config, log):
        """Whole files per worker (xdist's loadfile), the ``SHARED`` tests with the file they share a kit with."""
        from xdist.scheduler import LoadScopeScheduling

        class SharedKits(LoadScopeScheduling):
            def _split_scope(self, nodeid: str) -> str:
                return _group(nodeid)

        return SharedKits(config, log)


def pytest_configure(config):
    if config.pluginmanager.hasplugin("xdist"):
        config.option.loadscopereorder = False  # the groups in FIRST's order (xdist sorts by number of tests)
        config.pluginmanager.register(_SharedKitsScheduling(), "partgen-shared-kits")
