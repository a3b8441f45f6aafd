"""A drawn curve's samples from a design's ``curve.points`` (a CSV file or an inline list) or
``curve.svg`` (a path of an SVG file): (n, 2) float, mm, drawing order, y up.

Files are read only inside the design's folder, up to ``MAX_FILE_BYTES``; every problem is a
ConfigError naming the file and the line (CSV) or the key (YAML). SVG is parsed with defusedxml
(no entity expansion, no external references) and its path data by svgelements.
"""

from __future__ import annotations

import csv
import io
import math
import re
from pathlib import Path

import numpy as np

from ..errors import ConfigError
from .schema import MAX

__all__ = ["MAX_FILE_BYTES", "MAX_POINTS", "curve_file", "read_points_csv", "inline_points", "read_svg_path"]

MAX_FILE_BYTES = 8_000_000
MAX_POINTS = 200_000
SVG_SAMPLES = 4000  # points along an SVG path (more on long, detailed paths: one per segment at least)
UNIT_MM = {"mm": 1.0, "cm": 10.0, "q": 0.25, "in": 25.4, "pt": 25.4 / 72, "pc": 25.4 / 6, "px": 25.4 / 96, "": 25.4 / 96}


def curve_file(value: str, design: Path, key: str, suffix: str) -> Path:
    """The file a design names: relative to the design, inside its folder, ending in ``suffix``."""
    if not value.lower().endswith(suffix):
        raise ConfigError(design, key, f"{value!r} should be a {suffix} file")
    base = design.resolve().parent
    path = (base / value).resolve()
    if base not in path.parents:
        raise ConfigError(design, key, f"{value!r} lies outside the design's folder: put the file beside the design "
                          "(or in a folder under it)")
    if not path.is_file():
        raise ConfigError(design, key, f"no file at {value!r} (looked for {path})")
    size = path.stat().st_size
    if size > MAX_FILE_BYTES:
        raise ConfigError(design, key, f"{value!r} is {size / 1e6:.1f} MB: a curve file may be at most "
                          f"{MAX_FILE_BYTES / 1e6:g} MB (fewer points draw the same curve)")
    return path


def _check_count(n: int, where: Path, key: str) -> None:
    if n < 16:
        raise ConfigError(where, key, f"{n} points: a closed curve needs at least 16 (sample it more finely)")
    if n > MAX_POINTS:
        raise ConfigError(where, key, f"{n} points: at most {MAX_POINTS} (sample it more coarsely)")


def read_points_csv(path: Path, key: str = "curve.points") -> np.ndarray:
    """(n, 2) mm from a CSV with the header ``x_mm,y_mm``; a bad row names its line number."""
    try:
        text = path.read_text(encoding="utf-8-sig")
    except (OSError, UnicodeDecodeError) as e:
        raise ConfigError(path, key, f"cannot be read as UTF-8 text: {e}") from None
    rows = csv.reader(io.StringIO(text))
    header = next(rows, None)
    if header is None or [h.strip().lower() for h in header] != ["x_mm", "y_mm"]:
        raise ConfigError(path, "line 1", f"the header should be 'x_mm,y_mm' (millimetres at print size), got "
                          f"{','.join(header or [])[:60]!r}")
    out = []
    for row in rows:
        line = rows.line_num
        if not row or all(not c.strip() for c in row):
            continue
        if len(row) != 2:
            raise ConfigError(path, f"line {line}", f"expected 2 values (x_mm,y_mm), got {len(row)}")
        xy = []
        for cell in row:
            try:
                v = float(cell)
            except ValueError:
                raise ConfigError(path, f"line {line}", f"{cell.strip()[:40]!r} is not a number") from None
            if not math.isfinite(v):
                raise ConfigError(path, f"line {line}", f"{cell.strip()!r} is not a finite number")
            if abs(v) > MAX:
                raise ConfigError(path, f"line {line}", f"{v:g} mm is beyond ±{MAX:g} mm: not a drawing at print size")
            xy.append(v)
        out.append(xy)
        if len(out) > MAX_POINTS:
            break
    _check_count(len(out), path, key)
    return np.asarray(out, dtype=float)


def inline_points(points, design: Path, key: str = "curve.points") -> np.ndarray:
    """(n, 2) mm from the validated inline list."""
    _check_count(len(points), design, key)
    return np.asarray(points, dtype=float)


_LENGTH = re.compile(r"^\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*([a-zA-Z%]*)\s*$")


def _length_mm(value: str | None) -> tuple[float, float] | None:
    """(number, mm per unit of it) of an SVG length like '210mm'; None for none, % or em."""
    if value is None:
        return None
    m = _LENGTH.match(value)
    if not m or m.group(2).lower() not in UNIT_MM:
        return None
    return float(m.group(1)), UNIT_MM[m.group(2).lower()]


def _mm_per_user_unit(root, path: Path, key: str) -> float:
    """From the root's width/height and viewBox (one scale for both axes)."""
    w, h = _length_mm(root.get("width")), _length_mm(root.get("height"))
    vb = root.get("viewBox")
    hint = "; give curve.svg_mm_per_unit (millimetres per SVG user unit)"
    if vb is None:
        if w is None:
            raise ConfigError(path, key, "the SVG has no viewBox and no width in absolute units" + hint)
        return w[1]
    try:
        nums = [float(v) for v in re.split(r"[\s,]+", vb.strip())]
    except ValueError:
        nums = []
    if len(nums) != 4 or not all(math.isfinite(v) for v in nums) or nums[2] <= 0 or nums[3] <= 0:
        raise ConfigError(path, key, f"the SVG's viewBox {vb[:60]!r} is not four numbers with a positive size" + hint)
    if w is None or h is None:
        raise ConfigError(path, key, "the SVG's width and height are not both in absolute units (mm, cm, in, pt, "
                          "px)" + hint)
    sx, sy = w[0] * w[1] / nums[2], h[0] * h[1] / nums[3]
    if not (sx > 0 and sy > 0) or abs(sx - sy) > 1e-3 * max(sx, sy):
        raise ConfigError(path, key, f"the SVG's width/height and viewBox give {sx:.4g} and {sy:.4g} mm per unit "
                          "across and down (a stretched drawing)" + hint)
    return sx


def _local(tag) -> str:
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else ""


def _paths(root):
    """(element, transform string chain) of every <path>, in document order."""
    stack = [(root, [])]
    while stack:
        el, chain = stack.pop()
        t = el.get("transform")
        here = ([t] if t else []) + chain  # own transform first, then the ancestors'
        if _local(el.tag) == "path":
            yield el, here
        if _local(el.tag) in ("defs", "clipPath", "mask", "symbol", "pattern", "marker"):
            continue
        stack.extend((c, here) for c in reversed(list(el)))


def read_svg_path(path: Path, path_id: str | None, mm_per_unit: float | None, design: Path,
                  key: str = "curve.svg") -> np.ndarray:
    """(n, 2) mm along the first closed subpath of the named (or first closed) <path>, y up, closed
    (the last point is not repeated)."""
    import defusedxml.ElementTree as DET
    import svgelements as S
    from defusedxml import DefusedXmlException
    from xml.etree.ElementTree import ParseError

    try:
        root = DET.fromstring(path.read_bytes())
    except DefusedXmlException as e:
        raise ConfigError(path, key, f"the SVG declares entities or external references, which are not read "
                          f"({type(e).__name__}): save it as plain SVG") from None
    except (ParseError, ValueError, OSError) as e:
        raise ConfigError(path, key, f"is not well-formed XML: {e}") from None
    if _local(root.tag) != "svg":
        raise ConfigError(path, key, f"the root element is <{_local(root.tag)}>, not <svg>")
    scale = mm_per_unit if mm_per_unit is not None else _mm_per_user_unit(root, path, "curve.svg_mm_per_unit")
    found = [(el, chain) for el, chain in _paths(root)]
    if path_id is not None:
        found = [(el, chain) for el, chain in found if el.get("id") == path_id]
        if not found:
            ids = [el.get("id") for el, _ in _paths(root) if el.get("id")]
            raise ConfigError(design, "curve.svg_path_id", f"{path.name} has no <path> with id {path_id!r}"
                              + (f" (its paths: {', '.join(ids[:12])})" if ids else " (its paths have no ids)"))
    if not found:
        raise ConfigError(path, key, "the SVG has no <path> element (convert shapes and text to paths first)")
    for el, chain in found:
        try:
            p = S.Path(el.get("d") or "")
            for t in chain:
                p = p * S.Matrix(t)
            p.reify()
            subpaths = list(p.as_subpaths())
        except Exception as e:  # svgelements raises plain errors on bad path data
            raise ConfigError(path, key, f"path {el.get('id') or '(no id)'}: its data cannot be read ({e})") from None
        for sp in subpaths:
            pts = _sample_subpath(list(sp))
            if pts is not None:
                out = np.column_stack([pts.real, -pts.imag]) * scale  # SVG's y points down
                if not np.all(np.isfinite(out)) or np.abs(out).max() > MAX:
                    raise ConfigError(path, key, "the path's coordinates are not finite or beyond 10 m")
                return out
    which = f"the path {path_id!r} has" if path_id is not None else "the SVG has"
    raise ConfigError(path, key, f"{which} no closed subpath (one that ends where it starts or with 'Z'): close "
                      "it in the drawing program")


def _sample_subpath(segs) -> np.ndarray | None:
    """(n,) complex points along a closed subpath (lines as their ends, curves finely), or None when
    it is open or has no length."""
    segs = [s for s in segs if type(s).__name__ != "Move"]
    if not segs:
        return None
    start = segs[0].start
    end = segs[-1].end
    lengths = [float(s.length()) for s in segs]
    total = sum(lengths)
    closed = type(segs[-1]).__name__ == "Close" or (
        start is not None and end is not None and abs(complex(*start) - complex(*end)) <= 1e-9 * max(total, 1e-300))
    if not closed or not total > 0:
        return None
    pts = []
    for s, length in zip(segs, lengths):
        if length <= 0:
            continue
        k = max(1 if type(s).__name__ in ("Line", "Close") else 4, math.ceil(SVG_SAMPLES * length / total))
        if type(s).__name__ in ("Line", "Close"):
            a, b = complex(*s.start), complex(*s.end)
            pts.extend(a + (b - a) * np.arange(k) / k)
            continue
        xy = np.asarray(s.npoint(np.arange(k) / k), dtype=float)
        pts.extend(xy[:, 0] + 1j * xy[:, 1])
    return np.asarray(pts, dtype=complex)
