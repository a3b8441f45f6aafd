"""Drive a report's 3-D view in headless Chromium (playwright with Debian's chromium): what the browser
tests of the viewer share. ``probe(page_path, out_dir)`` returns what it saw."""

from __future__ import annotations

import io
import os
import shutil

import pytest

BROWSER = shutil.which("chromium") or shutil.which("chromium-browser")
ARGS = ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist",
        "--disable-background-networking", "--disable-component-update", "--disable-sync", "--no-first-run"]


def need_browser():
    """Skip (fail on CI) unless playwright and a chromium are installed."""
    why = None
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        why = "playwright is not installed (pip install -e '.[test]')"
    if why is None and BROWSER is None:
        why = "no chromium (scripts/install-browser.sh installs Debian's)"
    if why:
        if os.environ.get("CI"):
            pytest.fail(why)
        pytest.skip(why)


def _pixels(png: bytes):
    import numpy as np
    from PIL import Image
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(int)


def probe(page_path, timeout_s: float = 90.0) -> dict:
    """Open the page, wait for the view; canvas pixels at the start and a quarter of the way along the
    input; click over the canvas until a part is picked (real mouse clicks), then on empty background.
    Returns {"errors", "ready", "first", "moved", "picked", "row", "rows_highlighted", "cleared",
    "input", "range", "load_s", "tight": (input after the tightest-clearance button, or None)}."""
    import time

    from playwright.sync_api import sync_playwright

    out: dict = {"errors": []}
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=BROWSER, args=ARGS)
        try:
            page = browser.new_page(viewport={"width": 1280, "height": 900})
            page.on("console", lambda m: out["errors"].append(m.text) if m.type == "error" else None)
            page.on("pageerror", lambda e: out["errors"].append(str(e)))
            page.on("request", lambda r: None if r.url.startswith(("file:", "data:", "blob:"))
                    else out["errors"].append(f"fetched {r.url}"))
            t0 = time.perf_counter()
            page.goto(page_path.as_uri())
            page.wait_for_function("window.partgenViewer && (window.partgenViewer.ready || window.partgenViewer.error)",
                                   timeout=timeout_s * 1000)
            out["load_s"] = time.perf_counter() - t0
            out["ready"] = page.evaluate("window.partgenViewer.ready")
            out["view_error"] = page.evaluate("window.partgenViewer.error")
            if not out["ready"]:
                return out
            canvas = page.locator("#pg-canvas")
            lo, hi = page.evaluate("[+document.getElementById('pg-input').min, +document.getElementById('pg-input').max]")
            out["range"] = (lo, hi)
            page.evaluate("window.partgenViewer.setInput(%r)" % lo)
            out["first"] = _pixels(canvas.screenshot())
            out["input"] = page.evaluate("window.partgenViewer.setInput(%r)" % (lo + (hi - lo) / 4))
            out["moved"] = _pixels(canvas.screenshot())
            box = canvas.bounding_box()
            out["picked"] = None
            for fy in (0.5, 0.4, 0.6, 0.3, 0.7):
                for fx in (0.5, 0.45, 0.55, 0.4, 0.6, 0.35, 0.65, 0.3, 0.7):
                    page.mouse.click(box["x"] + fx * box["width"], box["y"] + fy * box["height"])
                    name = page.evaluate("window.partgenViewer.selected")
                    if name:
                        out["picked"] = name
                        break
                if out["picked"]:
                    break
            rows = page.evaluate("[...document.querySelectorAll('tr.pg-picked')].map(tr => "
                                 "tr.querySelectorAll('td')[1].textContent.trim())")
            out["rows_highlighted"] = rows
            out["status"] = page.locator("#pg-status").text_content()
            page.mouse.click(box["x"] + 3, box["y"] + 3)  # the corner: background
            out["cleared"] = page.evaluate("window.partgenViewer.selected") is None and \
                page.evaluate("document.querySelectorAll('tr.pg-picked').length") == 0
            out["tight"] = None
            if page.locator("#pg-tight").count():
                page.locator("#pg-tight").click()
                out["tight"] = page.evaluate("window.partgenViewer.input()")
        finally:
            browser.close()
    return out


def drawn(pixels, background=(247, 247, 247)) -> float:
    """The share of the canvas that is not background."""
    import numpy as np
    return float(np.mean(np.abs(pixels - np.array(background)).sum(axis=2) > 24))


def changed(a, b) -> float:
    """The share of pixels that differ between two shots of the canvas."""
    import numpy as np
    return float(np.mean(np.abs(a - b).sum(axis=2) > 24))
