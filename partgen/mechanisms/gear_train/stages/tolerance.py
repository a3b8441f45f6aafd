"""The gear train's tolerance model (spur and helical trains): every running fit, every mesh as an
external mesh between axes that stand in both plates, the gears seated by their meshes in their bores
or centred, the clearances over the motion (``common/tolerance.py``, docs/tolerance.md "Gear trains")."""

from __future__ import annotations

import numpy as np

from ....core.findings import Result
from ....design.tolerance import MarginModel, ModelBuilder, Play, seat_credit, seat_factor
from ..common.tolerance import axis_features, external_mesh, gap_margins, project_axis, running_fits
from .kit import TrainKit
from .resolve import TrainSpec

__all__ = ["tolerance_model"]


def tolerance_model(kit: TrainKit, result: Result, accuracy_mm: float, seated: bool = True) -> MarginModel:
    """The margins of ``result`` (the nominal check of ``kit``) for a printer accuracy of ± ``accuracy_mm``
    (``seated``: gears and shafts where their meshes push them in their bores; otherwise centred)."""
    s: TrainSpec = kit.params
    b = ModelBuilder()
    plays = running_fits(b, kit, result)

    def body_play(k: int) -> Play | None:
        """The play of shaft k's gear part: its gear on a fixed pin, or its shaft in the plates."""
        return plays.get(f"gears{k}") or plays.get(f"shaft{k}")
    centre = {sh.index: np.asarray(sh.centre, dtype=float) for sh in s.shafts}
    rows = {tuple(r["pair"]): r for r in result.figures.get("meshes", [])}
    dirs: dict[int, list] = {}
    for m in s.meshes:
        i, j = s.gear(m.driver).shaft, s.gear(m.driven).shaft
        u = (centre[j] - centre[i]) / np.linalg.norm(centre[j] - centre[i])
        dirs.setdefault(i, []).append(-u)
        dirs.setdefault(j, []).append(u)
    kappa = {k: seat_factor(v) for k, v in dirs.items()} if seated else {}
    meshing = set()
    for m in s.meshes:
        row = rows.get((m.driver, m.driven))
        if row is None:
            continue
        i, j = s.gear(m.driver).shaft, s.gear(m.driven).shaft
        meshing.add(frozenset((f"gears{i}", f"gears{j}")))
        u = (centre[j] - centre[i]) / np.linalg.norm(centre[j] - centre[i])
        da: dict = {}
        project_axis(da, axis_features(f"shaft{j}"), u)
        project_axis(da, axis_features(f"shaft{i}"), u, -1.0)
        credit = seat_credit([(kappa.get(k, 0.0), body_play(k)) for k in (i, j) if body_play(k) is not None])
        external_mesh(b, f"{m.driver}/{m.driven}", f"gears{j}", row, s.gear(m.driver).spec, s.gear(m.driven).spec,
                  (f"gears{i}", f"gears{j}"), da, credit)

    def axis_of(name: str):
        for prefix in ("gears", "shaft"):
            if name.startswith(prefix) and name[len(prefix):].isdigit():
                k = int(name[len(prefix):])
                return centre[k], axis_features(f"shaft{k}")
        return None
    gap_margins(b, kit, result, meshing, axis_of)
    return b.model(accuracy_mm, kit.name, "gears and shafts seated by their meshes in their bores" if seated else "every gear and shaft centred in its bores (no play credited)")
