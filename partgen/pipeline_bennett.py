"""`partgen build / check / report` for a balanced Bennett butterfly (``kind: bennett_butterfly``)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import yaml

from .assembly import bennett as A
from .config.bennett import resolve_bennett
from .config.loader import LoadedDesign, read_yaml
from .errors import ConfigError, DesignError

__all__ = ["BennettLoaded", "build_bennett_kit", "check_bennett_design", "bill", "report_bennett"]


class BennettLoaded:
    """What the CLI needs to know of a loaded Bennett design (mirrors pipeline.Loaded)."""

    mechanism = None
    kind = "bennett_butterfly"

    def __init__(self, raw: LoadedDesign, params):
        self.path, self.printer_path, self.params = raw.path, raw.printer_path, params


def _kit(raw: LoadedDesign, progress=None) -> tuple[BennettLoaded, A.BennettKit]:
    p = resolve_bennett(raw)
    try:
        kit = A.build_bennett(p, progress)
    except DesignError as e:
        raise ConfigError(raw.path, e.key_path or "counterweights", e.problem) from None
    return BennettLoaded(raw, p), kit


def layout_yaml(kit: A.BennettKit) -> dict:
    """The kit's stack layout as the config's ``parts.layout`` (so a kit folder rebuilds without a search)."""
    return {"layers": {i: int(kit.layout.layer[i]) for i in range(1, 13)},
            "shifts_mm": {j: float(v) for j, v in sorted(kit.layout.shift.items()) if v}}


def bill(kit: A.BennettKit) -> list[dict]:
    """Every part with its masses (g): solid, as printed (FDM), counterweight fill; pins and fill bought."""
    p = kit.params
    rows = []
    for i, lm in kit.masses.items():
        rows.append({"part": f"link{i:02d}", "layer": kit.layout.layer[i], "solid_g": lm.solid_mass,
                     "printed_g": lm.fdm_mass, "fill_g": kit.fill["fdm"].get(i, 0.0),
                     "pins_g": sum(m for m, _ in kit.pins[i])})
    for part in kit.parts:
        if part.role == "pin":
            info = dict(part.info)
            rows.append({"part": part.name, "layer": None, "solid_g": None, "printed_g": None, "fill_g": 0.0,
                         "pins_g": p.pin_density * math.pi * p.pin_radius ** 2 * info["length_mm"],
                         "bought": f"{p.pin_radius * 2:g} × {info['length_mm']:.1f} mm {info['material']}"})
    return rows


def build_bennett_kit(raw: LoadedDesign, dest=None, progress=None):
    """Build the kit into ``dest`` (default out/<name>/): STLs, manifest (with the bill of masses and
    the chosen layout), GLB, and the design with its layout pinned."""
    from .export.kit import write_kit
    from .geometry.solid import mesh_arrays

    loaded, kit = _kit(raw, progress)
    p = kit.params
    env = np.sort(np.asarray(p.printer.envelope, float))
    for part in kit.parts:
        if part.printed:
            v, _ = mesh_arrays(part.solid)
            ext = np.sort(v.max(axis=0) - v.min(axis=0))
            if np.any(ext > env):
                raise ConfigError(raw.path, "linkage.a_mm", f"{part.name} measures {ext.round(1)} mm and does not fit "
                                  "the printer in any orientation")
    data = read_yaml(raw.path)
    data["printer"] = "printer.yaml"
    data.setdefault("parts", {})["layout"] = layout_yaml(kit)
    dump = lambda d: yaml.safe_dump(d, sort_keys=False, allow_unicode=True).encode()  # noqa: E731
    files = {"design.yaml": dump(data), "printer.yaml": dump(read_yaml(raw.printer_path))}
    design = {"name": p.name, "kind": "bennett_butterfly", "config": raw.path.name,
              "a_mm": p.bb.a, "b_mm": p.bb.b, "alpha_deg": math.degrees(p.bb.alpha), "beta_deg": math.degrees(p.bb.beta),
              "scales": [1.0, p.bb.s2, p.bb.s3, p.bb.s4], "home_angle_deg": math.degrees(p.home),
              "workspace_deg": [math.degrees(x) for x in p.workspace], "layout": layout_yaml(kit),
              "counterweights": {f"link{i:02d}": {"fill_g": kit.fill["fdm"][i], "fill": p.fill_name,
                                                  "pocket_offset_mm": kit.figures["pocket_offsets_mm"][i]}
                                 for i in p.cw_links},
              "bill": bill(kit), "infill_percent": 100 * p.infill, **{k: v for k, v in kit.figures.items()
                                                                     if k not in ("pocket_offsets_mm",)}}
    dest = Path(dest) if dest is not None else Path("out") / p.name
    man = write_kit(kit, dest, design, files, progress=progress)
    return loaded, kit, man, dest


def check_bennett_design(raw: LoadedDesign, progress=None):
    """Balance over the input grid, interference over the workspace, stacks, pockets, printer fit."""
    from .checks.bennett import check_bennett

    loaded, kit = _kit(raw)
    return loaded, kit, check_bennett(kit), None
