"""partgen starts fast: ``--help`` imports no numerical library, and ``build`` imports none of the
libraries it does not build with (matplotlib, trimesh with the scipy and networkx it imports):
they load only where they are used (a report's pictures, the tests' mesh measurements). The time
itself is measured by benchmarks/bench_build.py, not here."""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("matplotlib", "trimesh", "scipy", "networkx")


def _loaded(argv: list[str], cwd: Path) -> tuple[int, set[str]]:
    code = ("import sys\nfrom partgen.cli.main import main\n"
            f"try:\n    code = main({argv!r})\nexcept SystemExit as e:\n    code = e.code\n"
            "print(code, ' '.join(sorted({m.split('.')[0] for m in sys.modules})))\n")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, cwd=cwd)
    assert proc.returncode == 0, proc.stderr[-3000:]
    exit_code, names = proc.stdout.strip().splitlines()[-1].split(" ", 1)
    return int(exit_code), set(names.split())


def test_help_imports_no_numerical_library(tmp_path):
    code, mods = _loaded(["--help"], tmp_path)
    assert code == 0
    assert not mods & {"numpy", "manifold3d", "shapely", *HEAVY}, mods & {"numpy", "manifold3d", "shapely", *HEAVY}


def test_build_imports_only_what_it_builds_with(tmp_path):
    # backlash pinned: an `auto` design would also check candidate kits (the check draws nothing either)
    code, mods = _loaded(["build", str(ROOT / "configs" / "butterfly.yaml"), "-o", str(tmp_path / "kit"), "-q",
                          "--set", "gears.backlash_per_gear_mm=0.1"], tmp_path)
    assert code == 0 and (tmp_path / "kit" / "assembly.glb").is_file()
    assert {"numpy", "manifold3d", "shapely"} <= mods  # the checker sees what was imported
    assert not mods & set(HEAVY), sorted(mods & set(HEAVY))
