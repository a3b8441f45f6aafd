"""The whole job for any mechanism: load → resolve → build → write / check / trace / report, each
step dispatched through the mechanism's protocol (``partgen.mechanisms.REGISTRY``).

``load`` and ``build`` raise ``ConfigError`` (file + key path) for anything the user can fix; the
CLI turns those into exit code 2. A target is a design YAML or a kit folder (its design.yaml).
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple

from .config.loader import LoadedDesign
from .config.overrides import Overrides, parse_set
from .config.yamlio import dump_yaml
from .core.findings import Finding, Result
from .core.protocol import Kit, Mechanism, Trace
from .errors import ConfigError, DesignError
from .export.kit import atomic_dir, group_parts, printed, write_kit
from .export.outputs import claim_output
from .mechanisms import REGISTRY, load_design

__all__ = ["Loaded", "load", "make_kit", "build", "check", "trace", "report", "overrides", "design_digest",
           "tolerance_result"]


@dataclass(frozen=True)
class Loaded:
    """A design resolved by its mechanism: ``spec`` is what the mechanism builds from."""

    raw: LoadedDesign
    mechanism: Mechanism
    spec: object
    kit_dir: Path | None = None

    @property
    def path(self) -> Path:
        return self.raw.path

    @property
    def name(self) -> str:
        return self.raw.design.name


class Built(NamedTuple):
    loaded: Loaded
    kit: Kit
    manifest: dict
    dest: Path


class Checked(NamedTuple):
    loaded: Loaded
    kit: Kit
    result: Result
    plates_dir: Path | None


class Traced(NamedTuple):
    loaded: Loaded
    trace: Trace
    plots_dir: Path | None


def overrides(sets=(), printer: str | None = None) -> Overrides:
    """The command line's changes to a design: ``--set KEY=VALUE`` texts and ``--printer NAME|FILE``
    (a malformed --set raises the usage error)."""
    return Overrides(tuple(parse_set(t) for t in sets), printer)


def _raw(target, over: Overrides | None = None) -> tuple[LoadedDesign, Path | None]:
    target = Path(target)
    kit_dir = target if target.is_dir() else None
    if kit_dir is not None and not (kit_dir / "design.yaml").is_file():
        raise ConfigError(target, "", "a folder that is not a kit (it has no design.yaml): give a design file, or a "
                          "kit folder partgen wrote")
    return load_design(target / "design.yaml" if kit_dir else target, over), kit_dir


def load(target, raw: LoadedDesign | None = None, over: Overrides | None = None) -> Loaded:
    """Read, validate and resolve a design (or a kit folder's design.yaml), with the command line's
    ``over``rides (--set, --printer)."""
    if isinstance(target, Loaded):
        return target
    got, kit_dir = _raw(target, over) if raw is None else (raw, Path(target) if Path(target).is_dir() else None)
    raw = raw or got
    mech = REGISTRY[raw.design.kind]
    return Loaded(raw, mech, mech.resolve(raw), kit_dir)


_KITS: dict = {}  # one built kit per process: (design bytes, printer bytes) -> kit


def make_kit(loaded: Loaded, progress=None, fresh: bool = False) -> Kit:
    """The kit of a loaded design, built once per process (check, trace and report share it);
    ``fresh``: build it anew (what `build` writes is always built by this call)."""
    key = (loaded.mechanism.kind, dump_yaml(loaded.raw.document()), dump_yaml(loaded.raw.printer_document()))
    if fresh or key not in _KITS:
        try:
            kit = loaded.mechanism.build(loaded.spec, progress)
        except DesignError as e:
            raise ConfigError(loaded.path, e.key_path, e.problem) from None
        _KITS.clear()
        _KITS[key] = kit
    return _KITS[key]


def design_digest(raw: LoadedDesign) -> str:
    """A fingerprint of a design as loaded (its YAML with the overrides, and its printer)."""
    import hashlib

    return hashlib.sha256(dump_yaml(raw.document()) + b"\0" + dump_yaml(raw.printer_document())).hexdigest()[:16]


def tolerance_result(raw: LoadedDesign, kit_dir: Path | None) -> dict | None:
    """The result `partgen tolerance` wrote for this design (``<kit>/tolerance/result.json`` or
    ``out/<name>/tolerance/result.json``), if it was made from the same design and printer."""
    import json

    folder = (kit_dir / "tolerance") if kit_dir else Path("out") / raw.design.name / "tolerance"
    try:
        data = json.loads((folder / "result.json").read_text(encoding="utf-8"))
    except (OSError, ValueError, UnicodeDecodeError):
        return None
    return data if isinstance(data, dict) and data.get("design_digest") == design_digest(raw) else None


def output_claim(raw: LoadedDesign, dest, kind: str, default_sub: str | None, option: str, notify=None):
    """Claim the output folder of a command before any work: ``dest`` or out/<name>[/<sub>]."""
    if dest is None:
        dest = Path("out") / raw.design.name / default_sub if default_sub else Path("out") / raw.design.name
    return claim_output(dest, kind, option, (raw.path, raw.printer_path), notify)


def build(path, dest=None, progress=None, notify=None, over: Overrides | None = None) -> Built:
    """Build the kit of a design into ``dest`` (default out/<name>/). Returns what it made."""
    raw, _ = _raw(path, over)
    claim = output_claim(raw, dest, "kit", None, "-o", notify)
    loaded = load(path, raw)
    kit = make_kit(loaded, progress, fresh=True)
    mech, spec = loaded.mechanism, loaded.spec
    try:
        mech.refuse(spec, kit)
    except DesignError as e:
        raise ConfigError(loaded.path, e.key_path, e.problem) from None
    design = {**mech.design_summary(spec, kit)}
    design.setdefault("kind", mech.kind)
    design.setdefault("config", loaded.path.name)
    man = write_kit(kit, claim, design, mech.kit_files(spec, kit, raw), progress=progress)
    return Built(loaded, kit, man, claim.dest)


_GROUPS: dict = {}  # id(kit) -> its printed parts grouped (one kit at a time)


def printed_groups(kit: Kit):
    """The kit's printed parts laid on the plate and grouped by identical STL, made once per kit."""
    if id(kit) not in _GROUPS:
        done: dict = {}
        items = []
        for p in (p for p in kit.parts if p.printed):
            key = (id(p.solid), p.print_flip)  # parts sharing a solid are laid on the plate once
            if key not in done:
                done[key] = printed(p)
            items.append(done[key].__class__(p, done[key].stl, done[key].mesh, done[key].local_from_print))
        _GROUPS.clear()
        _GROUPS[id(kit)] = (kit, group_parts(items))
    return _GROUPS[id(kit)][1]


def stale_files(kit: Kit, kit_dir: Path) -> list[str]:
    """The STLs of ``kit_dir`` missing or different (byte for byte) from what the design builds."""
    groups = printed_groups(kit)
    return [f"{g[0].part.name}.stl" for g in groups if not (kit_dir / f"{g[0].part.name}.stl").is_file()
            or (kit_dir / f"{g[0].part.name}.stl").read_bytes() != g[0].stl]


def plan_plates(loaded: Loaded, kit: Kit, result: Result):
    """Pack the printed parts on build plates; a finding if one cannot fit. Returns the layout (or
    None), the meshes by name and a function that draws the layout to a PNG path."""
    from .export.plates import footprint, layout, plate_picture

    groups = printed_groups(kit)
    env, margin = kit.printer.envelope, loaded.mechanism.plate_margin(loaded.spec)
    meshes = {g[0].part.name: g[0].mesh for g in groups}
    try:
        lay = layout([(g[0].part.name, g[0].mesh, len(g)) for g in groups], (env[0], env[1]), margin)
    except ValueError as e:
        result.add(Finding("printability", "fail", f"build plates: {e}", getattr(e, "parts", ())))
        return None, meshes, None
    result.figures["plates"] = len(lay.plates)

    def picture(path):
        plate_picture(lay, {n: footprint(m, margin) for n, m in meshes.items()}, path,
                      f"{kit.name}: {len(lay.plates)} build plate(s), {env[0]:g} × {env[1]:g} mm")
    return lay, meshes, picture


def check(target, samples: int | None = None, progress=None, plates_dir=None, write_plates: bool = True,
          notify=None, over: Overrides | None = None) -> Checked:
    """Check a design (CONFIG) or a built kit (KITDIR: its STLs compared byte for byte with what its
    design.yaml builds). Lays the parts out on build plates and writes a 3MF per plate and a picture."""
    from .export.plates import plate_3mf

    raw, kit_dir = _raw(target, over)
    claim = None
    if write_plates:
        claim = output_claim(raw, Path(plates_dir) if plates_dir else (kit_dir / "plates" if kit_dir else None),
                             "plates", "plates", "--plates", notify)
    loaded = load(target, raw)
    kit = make_kit(loaded)
    result = loaded.mechanism.check(loaded.spec, kit, samples, progress)
    if kit_dir is not None:
        stale = stale_files(kit, kit_dir)
        if stale:
            result.add(Finding("kit", "fail", f"{len(stale)} STL files in {kit_dir} are missing or differ from what its "
                               f"design.yaml builds ({', '.join(stale[:4])}{' …' if len(stale) > 4 else ''}): rebuild it",
                               tuple(s[:-4] for s in stale)))
    lay, meshes, picture = plan_plates(loaded, kit, result)
    folder = None
    if lay is not None and claim is not None:
        folder = claim.dest
        with atomic_dir(claim) as tmp:
            pr, n = kit.printer, len(lay.plates)
            for i, plate in enumerate(lay.plates, 1):
                (tmp / f"plate{i}.3mf").write_bytes(plate_3mf(plate, meshes, kit.name, kit.material,
                                                              f"build plate {i} of {n} for the {pr.name} "
                                                              f"({lay.size[0]:g} x {lay.size[1]:g} mm)"))
            picture(tmp / "plates.png")
    return Checked(loaded, kit, result, folder)


def trace(target, samples: int | None = None, plots_dir=None, animate: bool = True,
          over: Overrides | None = None) -> Traced:
    """The mechanism's motion over its range and its figures, written into ``plots_dir`` (default
    out/<name>/trace, or KITDIR/trace; False: none)."""
    loaded = load(target, over=over)
    if plots_dir is None and loaded.kit_dir is not None:
        plots_dir = loaded.kit_dir / "trace"
    claim = None if plots_dir is False else output_claim(loaded.raw, plots_dir, "trace", "trace", "--plots")
    kit = make_kit(loaded) if loaded.mechanism.trace_needs_kit else None
    if claim is None:
        return Traced(loaded, loaded.mechanism.trace(loaded.spec, kit, samples, None, animate), None)
    with atomic_dir(claim) as tmp:
        tr = loaded.mechanism.trace(loaded.spec, kit, samples, tmp, animate)
    return Traced(loaded, tr, claim.dest)


def report(target, dest=None, samples: int | None = None, progress=None, over: Overrides | None = None) -> Path:
    """Write DIR/index.html (default out/<name>/report/, or KITDIR/report): one self-contained page
    with the mechanism's sections, the bill of parts with pictures, what to buy, the build plates.
    The kit is built once and shared by the check, the trace and the pictures."""
    from .export import report as R
    from .export.bill import bill_sections

    say = progress or (lambda step: None)
    raw, kit_dir = _raw(target, over)
    claim = output_claim(raw, dest if dest is not None else (kit_dir / "report" if kit_dir else None),
                         "report", "report", "-o")
    say("build")
    loaded = load(target, raw)
    kit = make_kit(loaded)
    mech, spec = loaded.mechanism, loaded.spec
    say("check")
    result = mech.check(spec, kit, samples, None)
    if kit_dir is not None and stale_files(kit, kit_dir):
        result.add(Finding("kit", "fail", f"STL files in {kit_dir} differ from what its design.yaml builds: rebuild it"))
    with tempfile.TemporaryDirectory() as tmpdir:
        tmp = Path(tmpdir)
        say("trace")
        tr = mech.trace(spec, kit, None, tmp, True)
        files = {name: (tmp / name).read_bytes() for name in tr.files}
        _, _, picture = plan_plates(loaded, kit, result)
        plates_png = None
        if picture is not None:
            picture(tmp / "plates.png")
            plates_png = (tmp / "plates.png").read_bytes()
    say("pictures")
    purchased = [{"name": p.name, "role": p.role, **dict(p.info)} for p in kit.parts if not p.printed]
    sections = mech.report_sections(spec, kit, result, tr, files, {})
    own = {title for title, _ in sections}  # a mechanism's own bill (the Bennett's FDM masses) stands
    sections[1:1] = [x for x in bill_sections(kit, mech.role_colours, purchased, printed_groups(kit)) if x[0] not in own]
    tol = tolerance_result(raw, kit_dir)
    if tol is not None:  # `partgen tolerance` ran on this very design: its result is a section
        from .export.studies import tolerance_section

        sections.append(tolerance_section(tol))
    if plates_png:
        sections.append(("Build plates", f"<figure>{R.img(plates_png, 'build plates')}<figcaption>"
                                         f"{result.figures.get('plates', '?')} build plate(s); `partgen check` writes "
                                         "their 3MF files.</figcaption></figure>"))
    out = claim.dest
    with atomic_dir(claim) as tmp:
        (tmp / "index.html").write_text(R.page(f"partgen report: {kit.name}", sections, mech.subtitle(spec)),
                                        encoding="utf-8")
    return out
