"""The gear chain (``kind: gear_chain``, with its belt variant) behind the Mechanism protocol: a
Fourier linkage whose links are turned by gear (or belt) stages, drawn by a pen. The adapter: its
members call into checks.py, trace.py, report.py, tolerance.py and exact.py; the kit's own members
(build, refuse, the manifest's design, the kit files) are still here (to move into kit.py)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ...config.loader import LoadedDesign
from ...config.yamlio import dump_yaml
from ...core.findings import Result
from ...core.protocol import Motion, Trace
from ...errors import ConfigError, DesignError
from ...geometry.measure import empty_parts, oversize
from . import report as _report
from . import trace as _trace
from .kit import Kit, build_kit
from .resolve import ChainSpec, resolve_spec
from .schema import Design

__all__ = ["GearChain", "MECHANISM"]

CSV_HEADER = "theta_rad,x_mm,y_mm\n"
ROLE_COLOURS = {"gear": "#4c78a8", "link": "#f58518", "base": "#8c8c8c", "leg": "#b0b0b0", "axle": "#54a24b",
                "crank": "#e45756", "pen_holder": "#b279a2", "pulley": "#4c78a8", "idler": "#72b7b2"}


def _r6(x) -> float:
    return float(round(float(x), 6))


def size_key(spec: ChainSpec, name: str) -> str:
    """The config key a part's size traces back to."""
    mech = spec.mechanism
    if name.startswith("B"):
        j = int(name[1:])
        return {"curve": "curve.scale_mm_per_unit", "drawing": "curve.scale"}.get(mech.source, f"links[{j - 1}].length_mm")
    if name in ("G1", "drive"):
        return "drive.teeth"
    if name[0] in "DMG" and name[1:].isdigit():
        j = int(name[1:]) - (1 if name[0] == "G" else 0)
        return "teeth" if mech.auto_teeth else f"teeth[{j - 1}].{name[0]}"
    return {"base": "base", "crank": "base.crank_radius_mm", "pen_holder": "pen"}.get(name, name)


def oversize_parts(spec: ChainSpec, kit: Kit) -> list[tuple[str, str, np.ndarray]]:
    """Parts whose extents (any axis order) exceed the printer envelope: (name, key, extents)."""
    return [(p.name, size_key(spec, p.name), ext) for p, ext in oversize(kit.parts, kit.params.printer.envelope)]


class GearChain:
    kind = "gear_chain"
    title = "gear chain"
    schema = Design
    motion = Motion("crank angle", "rad", (0.0, 2 * math.pi))
    csv_header = CSV_HEADER
    trace_needs_kit = False
    role_colours = ROLE_COLOURS

    def resolve(self, raw: LoadedDesign) -> ChainSpec:
        return resolve_spec(raw)


    def build(self, spec: ChainSpec, progress=None) -> Kit:
        try:
            kit = build_kit(spec.mechanism, spec.params, progress)
        except DesignError as e:
            raise ConfigError(spec.path, e.key_path, e.problem) from None
        return kit

    def refuse(self, spec: ChainSpec, kit: Kit) -> None:
        """``build`` writes no kit with an empty part or a part larger than the printer (``check`` reports them)."""
        for part in empty_parts(kit.parts):
            raise ConfigError(spec.path, size_key(spec, part.name), f"part {part.name} comes out empty: a size in the "
                              "design leaves it no material")
        big = oversize_parts(spec, kit)
        if big:
            name, key, ext = big[0]
            env = " × ".join(f"{x:g}" for x in spec.params.printer.envelope)
            raise ConfigError(spec.path, key, f"part {name} measures {' × '.join(f'{x:.1f}' for x in ext[::-1])} mm "
                              f"and does not fit the printer's {env} mm envelope in any orientation"
                              + (f" (and {len(big) - 1} more parts)" if len(big) > 1 else ""))

    def findings(self, spec: ChainSpec):
        """What the design rules found before any geometry (build prints them)."""
        return list(spec.mechanism.findings)

    def design_summary(self, spec: ChainSpec, kit: Kit) -> dict:
        """The manifest's "design" entry: chain, stages, drive, stack, findings."""
        from ...design.trace import crank_turns

        mech, params = spec.mechanism, spec.params
        return {
            "name": params.name,
            "kind": self.kind,
            "config": spec.path.name,
            "printer": params.printer.name,
            "material": params.material,
            "density_g_cm3": _r6(params.density * 1000),
            "crank_angle_rad": 0.0,
            "crank_turns_per_drawing": str(crank_turns(mech)),
            "module_mm": params.system.module,
            "pressure_angle_deg": _r6(math.degrees(params.system.pressure_angle)),
            "teeth_mode": "auto" if mech.auto_teeth else "explicit",
            "ground_offset_mm": [_r6(mech.chain.offset.real), _r6(mech.chain.offset.imag)],
            "links": [{"j": j, "name": l.name, "speed": l.speed, "length_mm": _r6(l.length),
                       "initial_angle_deg": _r6(math.degrees(l.phase))} for j, l in enumerate(mech.chain.links, 1)],
            "stages": [{"j": s.j, "ratio": str(s.ratio), "teeth": {"D": s.D.teeth, "M": s.M.teeth, "G": s.G.teeth},
                        "profile_shift": {"D": _r6(s.D.profile_shift), "M": _r6(s.M.profile_shift),
                                          "G": _r6(s.G.profile_shift)},
                        "a_DM_mm": _r6(s.a_DM), "a_MG_mm": _r6(s.a_MG),
                        "idler_mm": [_r6(s.idler[0]), _r6(s.idler[1])]} for s in mech.stages],
            "drive": {"teeth": mech.drive.teeth, "centre_mm": [_r6(c) for c in mech.drive_centre]},
            "stack_mm": {"axial_gap": kit.stack.gap, "face_width": kit.stack.face, "plate": kit.stack.plate,
                         "layers": [_r6(kit.stack.layer(j)) for j in range(len(mech.stages) + 1)],
                         "plates": [_r6(kit.stack.plate_z(j)) for j in range(1, len(mech.chain.links) + 1)]},
            "findings": [{"severity": f.severity, "code": f.rule, "key": f.key, "message": f.message}
                         for f in mech.findings],
        }

    def kit_files(self, spec: ChainSpec, kit: Kit, raw: LoadedDesign) -> dict[str, bytes]:
        """The design and its printer profile, as a kit folder keeps them: design.yaml names
        printer.yaml beside it."""
        data = raw.document()
        data["printer"] = "printer.yaml"
        if isinstance(data.get("gears"), dict) and data["gears"].get("module_mm") == "auto":
            data["gears"]["module_mm"] = spec.params.system.module  # the module auto chose, pinned
        c = raw.design.curve
        if c is not None and c.drawn and c.scale == "auto":
            data["curve"] = {**data["curve"], "scale": spec.mechanism.drawing.scale}  # the scale auto chose, pinned
        files = {}
        if c is not None and c.drawn and (c.svg is not None or isinstance(c.points, str)):
            from ...config.drawing import curve_file

            key, suffix = ("svg", ".svg") if c.svg is not None else ("points", ".csv")
            src = curve_file(getattr(c, key), raw.path, f"curve.{key}", suffix)
            data["curve"] = {**data["curve"], key: f"curve{suffix}"}  # the kit keeps its own copy
            files[f"curve{suffix}"] = src.read_bytes()
        return {"design.yaml": dump_yaml(data), "printer.yaml": dump_yaml(raw.printer_document()), **files}

    def plate_margin(self, spec: ChainSpec) -> float:
        return spec.params.checks.plate_margin

    def check(self, spec: ChainSpec, kit: Kit, samples: int | None = None, progress=None) -> Result:
        from .checks import check_kit

        return check_kit(kit, samples, progress)

    def tolerance_model(self, spec: ChainSpec, kit: Kit, result: Result, accuracy_mm: float, seated: bool = True):
        """The margins of the nominal check ``result`` as a ``design.tolerance.MarginModel`` (``seated``: gears
        sit where their meshes push them in their bores; otherwise centred, the worst case)."""
        from .tolerance import tolerance_model

        return tolerance_model(kit, result, accuracy_mm, seated)

    def tolerance_exact(self, spec: ChainSpec, kit: Kit, result: Result, model, seated: bool = True):
        """(task function, shared data) of the exact Monte Carlo: ``fn(shared, seed, index)`` makes
        print ``index`` (its meshes on the printed gear outlines, its fits and clearances by their
        margins) and says whether it jams (``exact``)."""
        from .exact import exact_print, exact_shared

        return exact_print, exact_shared(kit, result, model, seated)

    def trace(self, spec: ChainSpec, kit: Kit | None, samples: int | None, out: Path | None,
              animate: bool = True) -> Trace:
        return _trace.trace(spec, kit, samples, out, animate)

    def csv(self, trace: Trace) -> str:
        return _trace.csv(self.csv_header, trace)

    def bill_text(self, spec: ChainSpec, man: dict, dest, seconds: float) -> str:
        return _report.bill_text(spec, man, dest, seconds)

    def check_text(self, spec: ChainSpec, result: Result, folder, seconds: float) -> str:
        from .checks import check_text

        return check_text(spec, result, folder, seconds)

    def trace_text(self, spec: ChainSpec, trace: Trace, folder) -> str:
        return _trace.trace_text(spec, trace, folder)

    def assembly_steps(self, spec: ChainSpec, kit: Kit) -> list[tuple[str, tuple[str, ...]]]:
        return _report.assembly_steps(spec, kit)

    def report_sections(self, spec: ChainSpec, kit: Kit, result: Result, trace: Trace, files: dict) -> list[tuple[str, str]]:
        return _report.report_sections(spec, kit, result, trace, files)

    def subtitle(self, spec: ChainSpec) -> str:
        return _report.subtitle(spec)


MECHANISM = GearChain()
