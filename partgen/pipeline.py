"""The whole job for any mechanism: load → resolve → build → write / check / trace / report, each
step dispatched through the mechanism's protocol (``partgen.mechanisms.REGISTRY``).

``load`` and ``build`` raise ``ConfigError`` (file + key path) for anything the user can fix; the
CLI turns those into exit code 2. A target is a design YAML or a kit folder (its design.yaml).
"""

from __future__ import annotations

import copy
import tempfile
from dataclasses import dataclass, replace
from pathlib import Path
from typing import NamedTuple

from .config.loader import LoadedDesign
from .config.overrides import Overrides, parse_set
from .core.findings import Finding, Result
from .core.protocol import Kit, Mechanism, Trace, tolerance_hook
from .design.tolerance import run_chunk, summarise
from .errors import ConfigError, DesignError, OptionError
from .export.gltf import motion_of
from .export.kit import atomic_dir, write_kit
from .export.outputs import claim_output, is_partgen_kit, read_marker
from .export.prints import plan_plates, plate_pngs, printed_groups, stale_finding, write_plate_files
from .export.studies import saved_tolerance
from .mechanisms import REGISTRY, autoplay, load_design

__all__ = ["Loaded", "load", "make_kit", "build", "check", "trace", "report", "overrides"]


@dataclass(frozen=True)
class Loaded:
    """A design resolved by its mechanism: ``spec`` is what the mechanism builds from."""

    raw: LoadedDesign
    mechanism: Mechanism
    spec: object
    kit_dir: Path | None = None
    auto: dict | None = None  # what `auto` play chose (mechanisms.autoplay), None when the design gives numbers

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
    auto, spec = None, None
    if autoplay.wants_auto(raw):
        start = mech.resolve(autoplay.at_start(raw))  # the design's own errors first (exit 2 before any build)
        raw, auto = autoplay.resolve_auto(raw, mech, start)
        spec = autoplay.searched_spec(raw, mech)  # the search resolved its choice already
    return Loaded(raw, mech, mech.resolve(raw) if spec is None else spec, kit_dir, auto)


_KITS: dict = {}  # one built kit per process: (design bytes, printer bytes) -> kit


def kit_key(loaded: Loaded) -> tuple:
    """What a kit is built from: the kind, the resolved design and printer documents."""
    return loaded.mechanism.kind, loaded.raw.digest()


def make_kit(loaded: Loaded, progress=None, fresh: bool = False) -> Kit:
    """The kit of a loaded design, built once per process (check, trace and report share it);
    ``fresh``: not the process's kit (what `build` writes is built by this call, or is the kit the
    ``auto`` search of this very design built and checked while ``load`` chose its play:
    ``autoplay.searched_kit``, handed over once — the same resolved design object, so the same
    digest, by the same code in the same process: the kit this call would build)."""
    key = kit_key(loaded)
    if fresh or key not in _KITS:
        kit = autoplay.searched_kit(loaded.raw, loaded.mechanism, loaded.spec)
        if kit is None:
            try:
                kit = loaded.mechanism.build(loaded.spec, progress)
            except DesignError as e:
                raise ConfigError(loaded.path, e.key_path, e.problem) from None
        _KITS.clear()
        _KITS[key] = kit
    return _KITS[key]


_CHECKS: dict = {}  # the last checks of this process: (kit_key, samples) -> their Result (a copy kept)
_CHECKS_KEPT = 4
_TRACES: dict = {}  # the last traces: (kit_key, samples) -> (a copy of the Trace, {file: bytes} or None)
_TRACES_KEPT = 2


def _keep(memo: dict, key, value, kept: int):
    """``memo[key] = value``, the oldest entries dropped past ``kept``; returns ``value``."""
    memo.pop(key, None)
    memo[key] = value
    while len(memo) > kept:
        del memo[next(iter(memo))]
    return value


def checked(loaded: Loaded, kit: Kit, samples: int | None = None, progress=None) -> Result:
    """The mechanism's check of a loaded design's kit at ``samples``, made once per process for a design
    (``check`` then ``report``, or a notebook, check it once): a copy of the result the first check
    gave. The key is ``kit_key`` — what the kit is built from, as ``make_kit``'s — and the samples;
    the check is a function of them (the kit of one design is the same kit every time it is built).
    A kit an ``auto`` search built and checked of its choice at the design's own samples is not
    checked again (``autoplay.searched_check``)."""
    key = (kit_key(loaded), samples)
    if key not in _CHECKS:
        handed = autoplay.searched_check(loaded.raw, loaded.mechanism, kit) if samples is None else None
        _keep(_CHECKS, key, handed if handed is not None else loaded.mechanism.check(loaded.spec, kit, samples, progress),
              _CHECKS_KEPT)
    return copy.deepcopy(_CHECKS[key])


def _trace_copy(trace: Trace, files: tuple) -> Trace:
    return replace(trace, stats=copy.deepcopy(trace.stats), files=files,
                   data=None if trace.data is None else trace.data.copy())


def traced(loaded: Loaded, kit: Kit | None, samples: int | None, out: Path | None, animate: bool = True) -> Trace:
    """The mechanism's trace of a loaded design (its figures into ``out`` when given), made once per
    process for a design and samples as ``checked`` is (``trace`` then ``report`` trace once): a copy
    of the first, its figures' bytes written into ``out``. A trace kept without figures makes them
    anew for a folder; one kept without its animation (``Trace.animation``) makes it anew when
    asked to animate, and one kept with it leaves it out when not."""
    key = (kit_key(loaded), samples)
    got = _TRACES.get(key)
    if got is not None and out is not None:
        files = got[1]
        if files is None or (animate and not set(got[0].animation) <= set(files)):
            got = None
    if got is None:
        trace = loaded.mechanism.trace(loaded.spec, kit, samples, out, animate)
        files = None if out is None else {name: (out / name).read_bytes() for name in trace.files}
        _keep(_TRACES, key, (_trace_copy(trace, trace.files), files), _TRACES_KEPT)
        return trace
    trace, files = got
    if out is None:
        return _trace_copy(trace, ())
    names = tuple(n for n in files if animate or n not in trace.animation)
    for name in names:
        (out / name).write_bytes(files[name])
    return _trace_copy(trace, names)


def output_claim(raw: LoadedDesign, dest, kind: str, default_sub: str | None, option: str, notify=None,
                 kit_dir: Path | None = None, over: Overrides | None = None):
    """Claim the output folder of a command before any work: ``dest`` or out/<name>[/<sub>].

    A derived output (plates, trace, report, tolerance) goes into a kit folder only when it is made
    from that kit: into KITDIR/<sub> for a KITDIR without --set or --printer, into
    out/<name>/<sub> for a CONFIG only when out/<name>/ holds no kit or the kit this very design (the
    file as it is now, with these overrides, on this printer) built — its marker records the design's
    digest. Anything else is refused (exit 2), saying where to write instead: a kit folder's
    plates, trace and report always match its STLs."""
    if kind == "kit":
        return claim_output(dest if dest is not None else Path("out") / raw.design.name, kind, option,
                            (raw.path, raw.printer_path), notify, source=raw.digest())
    if dest is None and kit_dir is not None:
        if over:
            raise OptionError(option, str(kit_dir / default_sub),
                              f"{kit_dir} is the kit of its design.yaml as it is; with --set or --printer the design "
                              f"is another, whose {default_sub} would not match the kit's STLs: give {option} DIR, or "
                              f"build the changed design into its own folder (partgen build {kit_dir} --set … -o DIR) "
                              "and use that folder")
        dest = kit_dir / default_sub
    elif dest is None:
        home = Path("out") / raw.design.name
        dest = home / default_sub if default_sub else home
        if default_sub and is_partgen_kit(home):
            made = (read_marker(home) or {}).get("source")
            if made != raw.digest():
                why = ("this design with these --set/--printer changes" if over else "this design file as it is now (it was built from "
                       "another version of it, or with other --set/--printer changes)" if made else
                       "a design partgen cannot tell (it was built by an earlier partgen)")
                raise OptionError(option, str(dest),
                                  f"{home} holds a kit not built from {why}, and a kit folder's {default_sub} must "
                                  f"match its STLs: give {option} DIR, or build this design into its own folder "
                                  f"(partgen build {raw.path} {'--set … ' if over else ''}-o DIR) and use that folder, "
                                  f"or rebuild {home} from it")
    return claim_output(dest, kind, option, (raw.path, raw.printer_path), notify)


def build(path, dest=None, progress=None, notify=None, over: Overrides | None = None) -> Built:
    """Build the kit of a design into ``dest`` (default out/<name>/). Returns what it made. The kit is
    built by this call: by ``make_kit`` (fresh), or, for a design with ``auto`` play, by the search in
    this call's ``load`` that built and checked the chosen design (``autoplay.searched_kit``: the same
    resolved design, the same code; its files are those a new build writes, byte for byte)."""
    raw, _ = _raw(path, over)
    claim = output_claim(raw, dest, "kit", None, "-o", notify)  # its marker records raw.digest()
    loaded = load(path, raw)
    kit = make_kit(loaded, progress, fresh=True)
    mech, spec = loaded.mechanism, loaded.spec
    try:
        mech.refuse(spec, kit)
    except DesignError as e:
        raise ConfigError(loaded.path, e.key_path, e.problem) from None
    design = mech.design_summary(spec, kit)  # every manifest says its kind, and what it prints on and in what
    design = {**design, **{k: v for k, v in (("kind", mech.kind), ("config", loaded.path.name),
                                             ("printer", kit.printer.name), ("material", kit.material)) if k not in design}}
    man = write_kit(kit, claim, design, mech.kit_files(spec, kit, loaded.raw), progress=progress,  # auto play pinned
                    motion=motion_of(mech, spec, kit), colours=getattr(mech, "role_colours", None))
    return Built(loaded, kit, man, claim.dest)


QUICK_SAMPLES = 20_000  # prints of check's quick linear study (seed 0): ~0.1 s of numpy for the default chain


def jam_finding(loaded: Loaded, kit: Kit, result: Result, limit: float | None = None) -> Finding | None:
    """The quick linear tolerance study of a checked kit (gears seated by their meshes; 20,000
    prints on the printer's accuracy, seed 0) as a finding, and ``result.figures["jam"]``: info at
    or under the design's ``tolerance.max_jam_probability``, a warning above it, a failure above
    ``limit`` (--max-jam-probability). None for a kind with no tolerance model."""
    hook = tolerance_hook(loaded.mechanism)
    if hook is None:
        return None
    acc = kit.printer.xy_accuracy
    model = hook(loaded.spec, kit, result, acc)
    s = summarise(model, run_chunk(model, 0, 0, QUICK_SAMPLES))
    worst = hook(loaded.spec, kit, result, acc, seated=False)
    sw = summarise(worst, run_chunk(worst, 0, 0, QUICK_SAMPLES))
    target = getattr(getattr(loaded.raw.design, "tolerance", None), "max_jam_probability", None)
    p, (lo, hi) = s["overall"]["probability"], s["overall"]["ci95"]
    top = [u["unit"] for u in s["units"] if u["jams"]][:3]
    result.figures["jam"] = {"probability": p, "ci95": [lo, hi], "samples": QUICK_SAMPLES, "accuracy_mm": acc,
                             "target": target, "worst_case": sw["overall"]["probability"], "worst_units": top}
    severity = "fail" if limit is not None and p > limit else ("warn" if target is not None and p > target else "info")
    msg = (f"P(jam) {100 * p:.2f} % (95 % CI {100 * lo:.2f}–{100 * hi:.2f} %; linear study of {QUICK_SAMPLES:,} "
           f"prints at ±{acc:g} mm, {model.credits or 'gears seated by their meshes'}; worst case, "
           f"{worst.credits or 'every gear centred'}: "
           f"{100 * sw['overall']['probability']:.1f} %)"
           + (f"; above the design's target {100 * target:g} %" if target is not None and p > target else "")
           + (f"; above --max-jam-probability {limit:g}" if severity == "fail" else "")
           + (f"; most at {', '.join(top)}" if top else "")
           + ("" if severity == "info" else " (`partgen tolerance` for the whole study; "
              "gears.backlash_per_gear_mm: auto chooses the play)"))
    return Finding("tolerance", severity, msg, value=p, unit="probability",
                   key="tolerance.max_jam_probability" if severity == "warn" else "")


def check(target, samples: int | None = None, progress=None, plates_dir=None, write_plates: bool = True,
          notify=None, over: Overrides | None = None, max_jam: float | None = None) -> Checked:
    """Check a design (CONFIG) or a built kit (KITDIR: its STLs compared byte for byte with what its
    design.yaml builds). Lays the parts out on build plates and writes a 3MF per plate and a picture.
    Adds the quick tolerance study's P(jam) (``jam_finding``; a failure above ``max_jam``)."""
    raw, kit_dir = _raw(target, over)
    claim = None
    if write_plates:
        claim = output_claim(raw, Path(plates_dir) if plates_dir else None, "plates", "plates", "--plates", notify,
                             kit_dir, over)
    loaded = load(target, raw)
    kit = make_kit(loaded)
    result = checked(loaded, kit, samples, progress)
    jam = jam_finding(loaded, kit, result, max_jam)
    if jam is not None:
        result.add(jam)
    _add_stale(result, kit, kit_dir)
    lay, meshes, picture = plan_plates(kit, loaded.mechanism.plate_margin(loaded.spec), result)
    if lay is not None and claim is not None:
        with atomic_dir(claim) as tmp:
            write_plate_files(tmp, kit, lay, meshes, picture)
    return Checked(loaded, kit, result, claim.dest if lay is not None and claim is not None else None)


def trace(target, samples: int | None = None, plots_dir=None, animate: bool = True,
          over: Overrides | None = None) -> Traced:
    """The mechanism's motion over its range and its figures, written into ``plots_dir`` (default
    out/<name>/trace, or KITDIR/trace; False: none)."""
    loaded = load(target, over=over)
    claim = None if plots_dir is False else output_claim(loaded.raw, plots_dir, "trace", "trace", "--plots",
                                                         kit_dir=loaded.kit_dir, over=over)
    kit = make_kit(loaded) if loaded.mechanism.trace_needs_kit else None
    if claim is None:
        return Traced(loaded, traced(loaded, kit, samples, None, animate), None)
    with atomic_dir(claim) as tmp:
        tr = traced(loaded, kit, samples, tmp, animate)
    return Traced(loaded, tr, claim.dest)


def _add_stale(result: Result, kit: Kit, kit_dir: Path | None) -> None:
    found = stale_finding(kit, kit_dir) if kit_dir is not None else None
    if found is not None:
        result.add(found)


def report_glb(loaded: Loaded, kit: Kit, kit_dir: Path | None, result: Result) -> bytes:
    """The animated assembly the report shows: the kit folder's assembly.glb when the kit is this
    design's (no stale finding) and the file animates over this mechanism's input, else made anew."""
    from .export.gltf import read_glb
    from .export.kit import assembly_glb

    motion = motion_of(loaded.mechanism, loaded.spec, kit)
    if kit_dir is not None and not any(f.check == "kit" for f in result.findings):  # stale_finding: STLs differ
        try:
            data = (kit_dir / "assembly.glb").read_bytes()
            anims = read_glb(data)[0].get("animations") or []
            if anims and anims[0].get("extras", {}).get("input_label") == motion.label:
                return data
        except (OSError, ValueError):
            pass
    return assembly_glb(kit, printed_groups(kit), [p for p in kit.parts if not p.printed], motion,
                        getattr(loaded.mechanism, "role_colours", None))


def kit_links(kit_dir: Path, report_dir: Path) -> list[tuple[str, str]]:
    """(name, relative href from the report's folder) of the kit's files a maker opens: the GLB, the
    manifest, every STL, the build plates' 3MF files (those there now)."""
    import os

    rel = os.path.relpath(kit_dir.resolve(), report_dir.resolve() if report_dir.exists() else report_dir.absolute())
    names = [n for n in ("assembly.glb", "manifest.json") if (kit_dir / n).is_file()]
    names += sorted(p.name for p in kit_dir.glob("*.stl"))
    names += sorted(f"plates/{p.name}" for p in (kit_dir / "plates").glob("*.3mf"))
    return [(n, Path(rel, n).as_posix()) for n in names]


def report(target, dest=None, samples: int | None = None, progress=None, over: Overrides | None = None) -> Path:
    """Write DIR/index.html (default out/<name>/report/, or KITDIR/report): one self-contained page
    with the mechanism's sections, the bill of parts with pictures, what to buy, the build plates.
    The kit is built once and shared by the check, the trace and the pictures."""
    from .export.report_page import kit_page  # matplotlib and the renderer: only the report needs them

    say = progress or (lambda step: None)
    raw, kit_dir = _raw(target, over)
    claim = output_claim(raw, dest, "report", "report", "-o", kit_dir=kit_dir, over=over)
    say("build")
    loaded = load(target, raw)
    kit = make_kit(loaded)
    mech, spec = loaded.mechanism, loaded.spec
    say("check")
    result = checked(loaded, kit, samples)
    _add_stale(result, kit, kit_dir)
    say("trace")
    with tempfile.TemporaryDirectory() as tmpdir:
        tr = traced(loaded, kit, None, Path(tmpdir), False)  # no 2-D animation: the 3-D view moves
        files = {name: (Path(tmpdir) / name).read_bytes() for name in tr.files}
    plates = plate_pngs(kit, mech.plate_margin(spec), result)
    say("pictures")
    tol = saved_tolerance(kit_dir / "tolerance" if kit_dir else Path("out") / raw.design.name / "tolerance",
                          raw.digest())
    glb = report_glb(loaded, kit, kit_dir, result)
    out = claim.dest
    links = kit_links(kit_dir, out) if kit_dir is not None else []
    with atomic_dir(claim) as tmp:
        (tmp / "index.html").write_text(kit_page(mech, spec, kit, result, tr, files, plates, tol, glb, links),
                                        encoding="utf-8")
    return out
