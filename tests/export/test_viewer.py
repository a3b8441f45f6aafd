"""The report's interactive 3-D view (export.viewer): embedded whole in the one page (three.js and the
kit's animated GLB, nothing fetched), and working in headless Chromium: no console error, the canvas
draws, moving the input moves the picture, a click picks a part and highlights its bill row."""

import base64
import json
import math
import re

import pytest

from partgen.cli.main import main
from partgen.core.findings import Finding, Result
from partgen.export.viewer import tightest_clearance

from viewer_probe import changed, drawn, need_browser, probe


@pytest.fixture(scope="module")
def pair_report(kit_of, tmp_path_factory):
    import shutil
    kit = tmp_path_factory.mktemp("viewer") / "gear_pair"
    shutil.copytree(kit_of("gear_pair").dest, kit)
    assert main(["report", str(kit)]) == 0
    return kit, kit / "report" / "index.html"


def test_view_is_first_and_embeds_the_kits_glb_and_three_offline(pair_report):
    kit, page = pair_report
    text = page.read_text()
    first = re.search(r'<h2 id="([^"]+)"', text).group(1)
    assert first == "3-d-view"
    glb = re.search(r'<script type="application/octet-stream" id="pg-glb">([^<]+)</script>', text).group(1)
    assert base64.b64decode(glb) == (kit / "assembly.glb").read_bytes()  # the kit's own file, reused
    imports = json.loads(re.search(r'<script type="importmap">(.*?)</script>', text).group(1))["imports"]
    assert set(imports) == {"three", "three/addons/utils/BufferGeometryUtils.js",
                            "three/addons/loaders/GLTFLoader.js", "three/addons/controls/OrbitControls.js"}
    assert all(v.startswith("data:text/javascript;base64,") for v in imports.values())
    assert not re.search(r"""(src|href)=["']?(https?:|//|file:)""", text)
    data = json.loads(re.search(r'id="pg-viewer-data">(.*?)</script>', text).group(1))
    assert data["label"] == "output angle" and data["range"] == pytest.approx([0, 2 * math.pi])
    assert data["rows"] == {"base": "base", "gear1": "gear1", "gear2": "gear2"}


def test_tightest_clearance_is_the_least_that_says_where_and_when():
    r = Result([Finding("clearance", "fail", "x", ("a", "b"), 0.5, 0.12, "mm", (1.0, 2.0, 3.0)),
                Finding("clearance", "fail", "y", ("c", "d"), None, 0.01, "mm", None)],  # says no where/when
               {"motion": {"closest_approach": {"mm": 0.3, "parts": ["e", "f"], "theta_deg": 90.0,
                                                "location_mm": [0, 0, 0]}}})
    t = tightest_clearance(r)
    assert t["parts"] == ["a", "b"] and t["mm"] == 0.12 and t["theta"] == 0.5 and t["location_mm"] == [1, 2, 3]
    r.findings.clear()
    assert tightest_clearance(r)["theta"] == pytest.approx(math.pi / 2)
    assert tightest_clearance(Result()) is None


def test_view_works_in_headless_chromium(pair_report):
    need_browser()
    _, page = pair_report
    got = probe(page)
    assert got["ready"], got.get("view_error")
    assert got["errors"] == []
    assert drawn(got["first"]) > 0.05  # the parts cover part of the canvas
    assert len({tuple(c) for c in got["first"].reshape(-1, 3)[::7]}) > 50  # shaded, not flat
    assert got["input"] == pytest.approx(math.pi / 2, abs=1e-6)
    assert changed(got["first"], got["moved"]) > 0.005  # the gears turned a quarter (about 2 % of the canvas changes)
    assert got["picked"] in ("base", "gear1", "gear2")
    assert got["rows_highlighted"] == [got["picked"]] and got["picked"] in got["status"]
    assert got["cleared"]


def test_page_links_the_kits_files_relative_to_itself(pair_report):
    kit, page = pair_report
    hrefs = dict((name, href) for href, name in re.findall(r'<a href="([^"#][^"]*)">([^<]+)</a>', page.read_text()))
    assert set(hrefs) == {"assembly.glb", "manifest.json", "base.stl", "gear1.stl", "gear2.stl"}
    for name, href in hrefs.items():
        assert (page.parent / href).resolve() == (kit / name).resolve()
