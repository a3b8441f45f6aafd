"""`partgen report`: one self-contained page that a real headless browser renders, every image loaded."""

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from partgen.cli.main import main

ROOT = Path(__file__).parent.parent
BROWSER = shutil.which("chromium") or shutil.which("chromium-browser")
PROBE = """<script>window.addEventListener('load', () => {
  const imgs = [...document.images];
  const ok = imgs.filter(i => i.complete && i.naturalWidth > 0).length;
  document.title = 'IMAGES:' + imgs.length + ':' + ok + ':H2:' + document.querySelectorAll('h2').length;
});</script></body>"""


@pytest.fixture(scope="module")
def page(tmp_path_factory, kit_of):
    out = tmp_path_factory.mktemp("report")
    from partgen import pipeline
    b = kit_of("butterfly")  # the report's kit is the session's build of the same design
    pipeline._KITS.clear()
    pipeline._KITS[pipeline.kit_key(b.loaded)] = b.kit
    assert main(["report", str(ROOT / "configs" / "butterfly.yaml"), "-o", str(out), "--samples", "24"]) == 0
    return out / "index.html"


def test_page_is_self_contained(page):
    text = page.read_text()
    assert not re.search(r"""(src|href)=["']?(https?:|//|file:)""", text)
    srcs = re.findall(r'<img src="([^"]+)"', text)
    assert srcs and all(s.startswith(("data:image/png;base64,", "data:image/gif;base64,")) for s in srcs)
    for heading in ("Design", "Bill of parts", "Stacking", "Trace", "Check"):
        assert f">{heading}</h2>" in text
    assert "Every check holds" in text


@pytest.mark.skipif(BROWSER is None and not os.environ.get("CI"), reason="no chromium (scripts/install-browser.sh)")
def test_page_renders_in_headless_chromium_with_every_image(page, tmp_path):
    assert BROWSER, "chromium missing: .ci/run installs it with scripts/install-browser.sh"
    probe = tmp_path / "probe.html"
    probe.write_text(page.read_text().replace("</body>", PROBE, 1))
    cmd = [BROWSER, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
           "--disable-background-networking", "--disable-component-update", "--disable-sync",
           f"--user-data-dir={tmp_path / 'profile'}", "--virtual-time-budget=15000", "--dump-dom", probe.as_uri()]
    dom = subprocess.run(cmd, capture_output=True, text=True, timeout=120).stdout
    m = re.search(r"<title>IMAGES:(\d+):(\d+):H2:(\d+)</title>", dom)
    assert m, dom[:500]
    total, loaded, headings = map(int, m.groups())
    assert total >= 40 and loaded == total and headings == 7  # design, bill of parts, filament, stacking, trace, check, build plates
    shot = tmp_path / "shot.png"
    subprocess.run(cmd[:-2] + ["--window-size=1280,2000", f"--screenshot={shot}", probe.as_uri()],
                   capture_output=True, timeout=120)
    from PIL import Image
    img = Image.open(shot).convert("RGB")
    assert img.size == (1280, 2000)
    assert len(img.getcolors(1 << 22)) > 50  # the page drew pictures, not a blank
