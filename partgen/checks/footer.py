"""The end of every mechanism's `check` text, written once: the bed and bores line (when the check
measured printability), one line per failure, and the verdict with the time and where the plates went."""

from __future__ import annotations

from ..core.findings import Result
from .bed import bed_summary

__all__ = ["check_footer"]


def check_footer(result: Result, seconds: float, folder, bed: bool = True) -> list[str]:
    """Lines closing a check's text: ``  <bed summary>`` (if ``result.figures`` holds printability
    and ``bed``: gear trains say it in their own table),
    ``  FAIL  check: message`` per failure, the quick tolerance study's finding (``ok|WARN|FAIL
    tolerance: P(jam) …``, whatever its severity), then ``OK|FAILED in N s[; K build plate(s) in
    folder/]``."""
    f = result.figures
    lines = ["  " + bed_summary(f["printability"])] if bed and "printability" in f else []
    lines += [f"  FAIL  {x.check}: {x.message}" for x in result.findings if x.severity == "fail" and x.check != "tolerance"]
    lines += [f"  {dict(fail='FAIL', warn='WARN', info='ok').get(x.severity)}  tolerance: {x.message}"
              for x in result.findings if x.check == "tolerance"]
    lines.append(f"{'OK' if result.ok else 'FAILED'} in {seconds:.1f} s"
                 + (f"; {f.get('plates', '?')} build plate(s) in {folder}/" if folder else ""))
    return lines
