"""Calibrate to a printer: the coupon it prints (``coupon``) and the profile its results give
(``calibrate``). The CLI's ``coupon`` and ``calibrate`` commands call these."""

from __future__ import annotations

import datetime
import json
from dataclasses import dataclass
from pathlib import Path

from .config.loader import command_line_printer, printer_limits, read_yaml, validate
from .config.schema import Printer
from .config.yamlio import parse_yaml
from .design.calibration import (CALIPERS, GEAR_STATES, PRESS_STATES, RUNNING_STATES, Calibrated, Inconsistent,
                                 Observations, calibrate)
from .design.coupon import PRESS, RUNNING, coupon_design
from .errors import ConfigError
from .export.coupon import TEMPLATE_VERSION, write_coupon
from .export.outputs import claim_output, write_text_file
from .geometry.coupon import coupon_solids

__all__ = ["ProfileRef", "load_printer", "coupon", "read_results", "profile_text", "calibrate_profile", "SIGNATURE"]


@dataclass(frozen=True)
class ProfileRef:
    """A printer profile as named on the command line: its file, stem, mapping and validated model."""

    path: Path
    stem: str
    data: dict
    printer: Printer


def load_printer(value: str) -> ProfileRef:
    """``--printer NAME|FILE``: a shipped name or a .yaml profile (usage error / ConfigError otherwise)."""
    path = command_line_printer(value)
    data = read_yaml(path)
    return ProfileRef(path, path.stem, data, validate(Printer, data, path))


def coupon(printer: str, dest: str | Path | None = None, notify=None) -> tuple[Path, dict, ProfileRef]:
    """Write the calibration coupon of ``printer`` into ``dest`` (default out/coupon_<printer>/):
    STLs, coupon.3mf, coupon.png, instructions.html, results.yaml. Returns the folder, a summary and
    the profile."""
    ref = load_printer(printer)
    dest = Path(dest) if dest is not None else Path("out") / f"coupon_{ref.stem}"
    claim = claim_output(dest, "coupon", "-o", (ref.path,), notify)
    lim = printer_limits(ref.printer)
    c = coupon_design(lim.line_width, lim.layer_height)
    summary = write_coupon(claim, c, coupon_solids(c), ref.stem, ref.printer.name, not ref.printer.measured)
    return claim.dest, summary, ref


# --------------------------------------------------------------------------------- calibrate
SIGNATURE = "# partgen calibrate: a printer profile measured with partgen's calibration coupon"
_KEYS = {"coupon", "printer", "printed_on", "filament", "slicer", "running", "press", "gears", "calipers"}


def _states(path: Path, data: dict, section: str, numbers: range, states: tuple[str, ...]) -> dict[int, str]:
    got = data.get(section)
    if got is None:
        return {}
    if not isinstance(got, dict):
        raise ConfigError(path, section, f"expected a mapping of feature number to one of {', '.join(states)}")
    out = {}
    for k, v in got.items():
        if not isinstance(k, int) or isinstance(k, bool) or k not in numbers:
            raise ConfigError(path, f"{section}.{k}", f"no such feature: {section} are numbered "
                              f"{numbers.start}-{numbers.stop - 1}")
        if v is None:
            continue
        if v not in states:
            raise ConfigError(path, f"{section}.{k}", f"should be one of {', '.join(states)} (or null), got {v!r}")
        out[k] = v
    return out


def _readings(path: Path, data: dict) -> dict[str, tuple[float, ...]]:
    got = data.get("calipers")
    if not isinstance(got, dict):
        raise ConfigError(path, "calipers", "required: the caliper readings (mm) of the results template")
    out = {}
    for k, v in got.items():
        if k not in CALIPERS:
            raise ConfigError(path, f"calipers.{k}", f"unknown reading (readings: {', '.join(CALIPERS)})")
        if v is None:
            continue
        xs = v if isinstance(v, list) else [v]
        if not xs or len(xs) > 100 or not all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in xs):
            raise ConfigError(path, f"calipers.{k}", "should be a reading in mm or a list of readings")
        out[k] = tuple(float(x) for x in xs)
    return out


def read_results(path: str | Path) -> tuple[Observations, dict]:
    """A filled-in results.yaml as Observations, and its mapping; ConfigError naming the entry."""
    path = Path(path)
    data = read_yaml(path)
    for k in data:
        if k not in _KEYS:
            raise ConfigError(path, str(k), f"unknown key (keys: {', '.join(sorted(_KEYS))})")
    if data.get("coupon") != TEMPLATE_VERSION:
        raise ConfigError(path, "coupon", f"these are results of coupon layout {data.get('coupon')!r}; this partgen "
                          f"reads layout {TEMPLATE_VERSION}: print a new coupon")
    for k in ("printed_on", "filament", "slicer", "printer"):
        if data.get(k) is not None and not isinstance(data[k], (str, int, float)):
            raise ConfigError(path, k, "should be text")
    obs = Observations(_states(path, data, "running", range(1, 14), RUNNING_STATES),
                       _states(path, data, "press", range(14, 21), PRESS_STATES),
                       _states(path, data, "gears", range(23, 26), GEAR_STATES), _readings(path, data))
    return obs, data


def _r(x: float) -> float:
    return round(float(x), 3) + 0.0


def _yaml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, list):
        return "[" + ", ".join(_yaml_value(x) for x in v) + "]"
    return json.dumps(str(v))


def profile_text(base: ProfileRef, cal: Calibrated, results: Path, data: dict, today: str) -> tuple[str, list[str]]:
    """The calibrated profile (YAML with provenance comments) and the diff lines against ``base``."""
    old = base.data
    fits_old = dict(old.get("fits") or {})
    b_old = dict(old.get("biases") or {})
    new = {k: v for k, v in old.items() if k not in ("fits", "biases", "calibration", "name", "measured")}
    src = f"coupon {results.name}" + (f", printed {data['printed_on']}" if data.get("printed_on") else "")
    name = f"{base.printer.name} (calibrated {today})"
    fits = dict(fits_old)
    fits["running_clearance_diametral_mm"] = _r(cal.running_clearance)
    fits["press_fit_clearance_diametral_mm"] = _r(cal.press_clearance)
    if cal.gear_backlash is not None:
        fits["gear_backlash_circumferential_mm"] = _r(cal.gear_backlash)
    if cal.xy_accuracy is not None:
        new["xy_accuracy_mm"] = _r(cal.xy_accuracy)
    biases = {"hole_diametral_mm": _r(cal.hole_bias), "pin_diametral_mm": _r(cal.pin_bias),
              "outline_diametral_mm": _r(cal.outline_bias), "compensate": True}
    why = {
        "xy_accuracy_mm": "3 x pooled std of repeated caliper readings" if cal.xy_accuracy is not None else
        "kept: no feature was read twice",
        "running_clearance_diametral_mm": f"as printed: hole {cal.running_hole} turned free "
        f"({RUNNING[cal.running_hole - 1]:.2f} mm modelled) + hole bias - pin bias",
        "press_fit_clearance_diametral_mm": f"as printed: hole {cal.press_hole} holds "
        f"({PRESS[cal.press_hole - 14]:+.2f} mm modelled) + hole bias - pin bias",
        "gear_backlash_circumferential_mm": f"gear grade {cal.gear_grade} turned smooth (modelled)",
        "hole_diametral_mm": "hole 22 - 10 mm", "pin_diametral_mm": "mean of boss 21 - 10 mm, key post 27 - 5 mm",
        "outline_diametral_mm": "mean of bar 26 length - 30 mm, width - 10 mm",
        "compensate": "build opens holes, trims pins and outlines by these: slicer XY compensation 0",
    }
    lines = [SIGNATURE, f"# {src}; calibrated {today} from {base.path.name}"
             + (f"; filament {data['filament']}" if data.get("filament") else "")
             + (f"; slicer {data['slicer']}" if data.get("slicer") else ""),
             "# Fits are as printed (printed hole minus printed pin, diametral); biases are printed minus modelled,",
             "# as a diameter. Every length in mm.", f"name: {_yaml_value(name)}"]
    for k, v in new.items():
        lines.append(f"{k}: {_yaml_value(v)}" + (f"    # {why[k]}" if k in why else ""))
    lines.append("fits:")
    lines += [f"  {k}: {_yaml_value(v)}" + (f"    # {why[k]}" if k in why else "") for k, v in fits.items()]
    lines.append("measured: true    # by the coupon: fits, xy accuracy and biases below")
    lines.append("biases:")
    lines += [f"  {k}: {_yaml_value(v)}    # {why[k]}" for k, v in biases.items()]
    lines += ["calibration:", f"  coupon: {TEMPLATE_VERSION}", f"  results: {_yaml_value(results.name)}",
              f"  printed_on: {_yaml_value(data['printed_on']) if data.get('printed_on') else 'null'}",
              f"  calibrated_on: {_yaml_value(today)}", f"  from_profile: {_yaml_value(base.path.name)}", ""]
    diff = []
    for key, before, after in (("xy_accuracy_mm", old.get("xy_accuracy_mm", 0.1), new.get("xy_accuracy_mm")),
                               *((f"fits.{k}", fits_old.get(k), v) for k, v in fits.items()),
                               *((f"biases.{k}", b_old.get(k, 0.0 if k != "compensate" else False), v)
                                 for k, v in biases.items())):
        if after is None or before == after:
            continue
        diff.append(f"  {key}: {_yaml_value(before) if before is not None else '(none)'} -> {_yaml_value(after)}")
    return "\n".join(lines), diff


def calibrate_profile(printer: str, results: str | Path, out: str | Path | None = None, today: str | None = None):
    """Read ``results``, compute the profile, write it to ``out`` (default my_<printer>.yaml; never a
    user's file). Returns (path written, Calibrated, diff lines, profile text)."""
    base = load_printer(printer)
    results = Path(results)
    obs, data = read_results(results)
    named = data.get("printer")
    if named is not None and str(named) not in (base.stem,) and not base.printer.measured:
        raise ConfigError(results, "printer", f"these are results of a coupon for {named!r}, but --printer is "
                          f"{printer!r}: give --printer {named}")
    try:
        cal = calibrate(obs)
    except Inconsistent as e:
        raise ConfigError(results, e.key, e.problem) from None
    today = today or datetime.date.today().isoformat()
    text, diff = profile_text(base, cal, results, data, today)
    validate(Printer, parse_yaml(text, results), results)  # what we write reads back as a profile
    dest = Path(out) if out is not None else Path(f"my_{base.stem}.yaml")
    write_text_file(dest, text, "-o", (base.path, results))
    return dest, cal, diff, text
