"""Calibrate to a printer: the coupon it prints (``coupon``) and the profile its results give
(``calibrate``). The CLI's ``coupon`` and ``calibrate`` commands call these."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from .config.loader import command_line_printer, printer_limits, read_yaml, validate
from .config.schema import Printer
from .design.coupon import coupon_design
from .export.coupon import write_coupon
from .export.outputs import claim_output
from .geometry.coupon import coupon_solids

__all__ = ["ProfileRef", "load_printer", "coupon"]


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
