"""The report's interactive 3-D view: the kit's animated assembly.glb in three.js, embedded in the one
HTML page (no CDN: three.js r170 is vendored in ``export/vendor/three``, MIT, and embedded as data:
modules through an import map; the GLB as base64), so the page works offline from ``file://`` and
stays one file you can mail.

What the view offers: orbit (drag), zoom (wheel), pan (right drag); play / pause; a slider that scrubs
the mechanism's input (its own label and range, in degrees for an angle); parts coloured by role (the
GLB's materials); a click on a part names it and highlights its row in the bill of parts; the
tightest clearance over the motion (the check's closest approach, or its least clearance finding)
marked with a red ring where it happens, and a button that takes the mechanism to when it happens.

For tests (and anyone scripting the page) the module sets ``window.partgenViewer``: ``ready``,
``error``, ``setInput(value)``, ``input()``, ``pickAt(x, y)`` (canvas pixels; the part's name or
null), ``selected``, ``play()``, ``pause()``.
"""

from __future__ import annotations

import base64
import html
import json
import math
from importlib import resources

import numpy as np

from ..core.findings import Result
from ..core.protocol import Kit

__all__ = ["viewer_section", "tightest_clearance", "VENDOR"]

VENDOR = ("three.module.min.js", "BufferGeometryUtils.js", "GLTFLoader.js", "OrbitControls.js")


def _vendor(name: str) -> str:
    return resources.files("partgen.export").joinpath("vendor", "three", name).read_text(encoding="utf-8")


def _module(src: str) -> str:
    return "data:text/javascript;base64," + base64.b64encode(src.encode("utf-8")).decode("ascii")


def _import_map() -> str:
    """The import map: ``three`` and the three add-ons the view uses, each a data: module. A data:
    module has no base to resolve a relative import against, so GLTFLoader's one relative import is
    named by its bare specifier (mapped here too)."""
    gltf = _vendor("GLTFLoader.js").replace("'../utils/BufferGeometryUtils.js'",
                                            "'three/addons/utils/BufferGeometryUtils.js'")
    imports = {"three": _module(_vendor("three.module.min.js")),
               "three/addons/utils/BufferGeometryUtils.js": _module(_vendor("BufferGeometryUtils.js")),
               "three/addons/loaders/GLTFLoader.js": _module(gltf),
               "three/addons/controls/OrbitControls.js": _module(_vendor("OrbitControls.js"))}
    return f'<script type="importmap">{json.dumps({"imports": imports})}</script>'


def tightest_clearance(result: Result) -> dict | None:
    """The tightest clearance over the motion the check found, with where (world mm) and when
    (motion parameter, rad): the sweep's ``closest_approach`` figure, else the least ``clearance``
    finding that says where; None when the check measured none."""
    found = []

    def walk(x):
        if isinstance(x, dict):
            c = x.get("closest_approach")
            if isinstance(c, dict) and c.get("location_mm") is not None and c.get("theta_deg") is not None:
                found.append({"mm": float(c["mm"]), "parts": list(c["parts"]), "theta": math.radians(c["theta_deg"]),
                              "location_mm": [float(v) for v in c["location_mm"]]})
            for v in x.values():
                walk(v)
    walk(result.figures)
    for f in result.findings:
        if f.check == "clearance" and f.location is not None and f.theta is not None and f.value is not None:
            found.append({"mm": float(f.value), "parts": list(f.parts), "theta": float(f.theta),
                          "location_mm": [float(v) for v in f.location]})
    found = [x for x in found if math.isfinite(x["mm"])]
    return min(found, key=lambda x: x["mm"]) if found else None


CSS = """
.pg-viewer{position:relative;border:1px solid #ddd;border-radius:4px;background:#f7f7f7}
.pg-viewer canvas{display:block;width:100%;height:520px;cursor:grab}
.pg-bar{display:flex;gap:.8em;align-items:center;padding:.4em .6em;font-size:.9em;flex-wrap:wrap}
.pg-bar input[type=range]{flex:1;min-width:200px}.pg-bar button{min-width:5em}
.pg-status{font-size:.85em;color:#555;padding:0 .6em .5em}
tr.pg-picked td{background:#fff3bf}
"""

SCRIPT = r"""
import * as THREE from 'three';
import {GLTFLoader} from 'three/addons/loaders/GLTFLoader.js';
import {OrbitControls} from 'three/addons/controls/OrbitControls.js';
const api = window.partgenViewer = {ready: false, error: null, selected: null};
const data = JSON.parse(document.getElementById('pg-viewer-data').textContent);
const canvas = document.getElementById('pg-canvas');
const status = document.getElementById('pg-status');
const slider = document.getElementById('pg-input');
const shown = document.getElementById('pg-value');
const playBtn = document.getElementById('pg-play');
const fmt = v => data.unit === 'rad' ? (v * 180 / Math.PI).toFixed(1) + '°' : v.toFixed(2) + ' ' + data.unit;
try {
  const renderer = new THREE.WebGLRenderer({canvas, antialias: true, preserveDrawingBuffer: true});
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xf7f7f7);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8a8a, 2.2));
  const sun = new THREE.DirectionalLight(0xffffff, 2.0); sun.position.set(1, 2, 1.5); scene.add(sun);
  const fill = new THREE.DirectionalLight(0xffffff, 0.8); fill.position.set(-1.5, 0.5, -1); scene.add(fill);
  const camera = new THREE.PerspectiveCamera(35, 1, 0.001, 100);
  const controls = new OrbitControls(camera, canvas);
  controls.enableDamping = false;
  const bytes = Uint8Array.from(atob(document.getElementById('pg-glb').textContent.trim()), c => c.charCodeAt(0));
  new GLTFLoader().parse(bytes.buffer, '', gltf => {
    const root = gltf.scene;
    scene.add(root);
    root.updateMatrixWorld(true);
    const box = new THREE.Box3().setFromObject(root);
    const size = box.getSize(new THREE.Vector3()), centre = box.getCenter(new THREE.Vector3());
    const radius = Math.max(size.length() / 2, 1e-3);
    camera.position.copy(centre).add(new THREE.Vector3(0.9, 0.75, 1.25).normalize().multiplyScalar(radius * 2.3));
    camera.near = radius / 100; camera.far = radius * 100; camera.updateProjectionMatrix();
    controls.target.copy(centre); controls.update();
    const clip = gltf.animations[0];
    const mixer = new THREE.AnimationMixer(root);
    const action = clip ? mixer.clipAction(clip) : null;
    if (action) action.play();
    const duration = clip ? clip.duration : 1;
    const [lo, hi] = data.range;
    const outAndBack = data.mode === 'out_and_back';
    const timeOf = u => { const s = (hi > lo) ? (u - lo) / (hi - lo) : 0; return Math.min(Math.max(s, 0), 1) * (outAndBack ? duration / 2 : duration); };
    const inputOf = t => { let s = t / (outAndBack ? duration / 2 : duration); if (outAndBack && s > 1) s = 2 - s; return lo + Math.min(Math.max(s, 0), 1) * (hi - lo); };
    let time = 0, playing = !!action && !data.still, last = performance.now();
    const setTime = t => { time = ((t % duration) + duration) % duration; if (action) mixer.setTime(time); };
    slider.min = lo; slider.max = hi; slider.step = (hi - lo) / 720;
    // the tightest clearance: a ring where it happens (in the kit's mm, Z up: a child of the root node)
    const assembly = root.getObjectByName('assembly') || root;
    let marker = null;
    if (data.tightest) {  // in the frame of the first part named, so it rides along with that part
      const t = data.tightest, r = Math.max(2.0, radius * 1000 * 0.02);
      marker = new THREE.Mesh(new THREE.TorusGeometry(r, r * 0.18, 12, 48),
                              new THREE.MeshBasicMaterial({color: 0xd62728, depthTest: false, transparent: true}));
      marker.renderOrder = 10; marker.position.set(...t.local_mm);
      (root.getObjectByName(t.parts[0]) || assembly).add(marker);
      document.getElementById('pg-tight').onclick = () => { pause(); setTime(timeOf(t.theta)); frame(); };
    }
    const rows = new Map();  // the bill's row of each part (a part printed several times: its group's row)
    const bill = document.getElementById('bill-of-parts')?.closest('section');
    for (const tr of bill ? bill.querySelectorAll('tbody tr') : []) {
      const cells = [...tr.querySelectorAll('td')].map(td => td.textContent.trim());
      for (const [part, row] of Object.entries(data.rows)) if (!rows.has(part) && cells[1] === row) rows.set(part, tr);
    }
    const highlight = new Map();
    function select(name) {
      for (const tr of document.querySelectorAll('tr.pg-picked')) tr.classList.remove('pg-picked');
      for (const [obj, mat] of highlight) obj.material = mat;
      highlight.clear();
      api.selected = name;
      if (!name) { status.textContent = data.hint; return; }
      const obj = root.getObjectByName(name);
      obj?.traverse(o => { if (o.isMesh) { highlight.set(o, o.material); o.material = o.material.clone(); o.material.emissive = new THREE.Color(0x996600); } });
      const tr = rows.get(name);
      if (tr) tr.classList.add('pg-picked');
      const role = data.roles[name] || '';
      status.textContent = `${name} (${role})` + (tr ? ` — highlighted in the bill of parts (row ${data.rows[name]})` : ' — a bought part');
    }
    const ray = new THREE.Raycaster();
    function pickAt(x, y) {
      const rect = canvas.getBoundingClientRect();
      const p = new THREE.Vector2((x / rect.width) * 2 - 1, -(y / rect.height) * 2 + 1);
      ray.setFromCamera(p, camera);
      const hit = ray.intersectObject(root, true).find(h => h.object !== marker);
      let o = hit ? hit.object : null;
      while (o && !(o.name in data.roles)) o = o.parent;
      select(o ? o.name : null);
      frame();
      return o ? o.name : null;
    }
    let down = null;
    canvas.addEventListener('pointerdown', e => { down = [e.offsetX, e.offsetY]; });
    canvas.addEventListener('pointerup', e => { if (down && Math.hypot(e.offsetX - down[0], e.offsetY - down[1]) < 4) pickAt(e.offsetX, e.offsetY); down = null; });
    function resize() {
      const w = canvas.clientWidth, h = canvas.clientHeight;
      if (canvas.width !== Math.round(w * renderer.getPixelRatio()) || canvas.height !== Math.round(h * renderer.getPixelRatio())) {
        renderer.setSize(w, h, false); camera.aspect = w / h; camera.updateProjectionMatrix();
      }
    }
    function frame() {
      resize();
      const u = inputOf(time);
      slider.value = u; shown.textContent = `${data.label} ${fmt(u)}`;
      if (marker) marker.material.opacity = Math.abs(u - data.tightest.theta) < (hi - lo) / 36 ? 1.0 : 0.35;
      marker?.lookAt(camera.position);
      renderer.render(scene, camera);
    }
    function loop(now) {  // draws only while playing: a still view costs nothing
      if (playing) { setTime(time + (now - last) / 1000); frame(); }
      last = now; requestAnimationFrame(loop);
    }
    function play() { if (!action) return; playing = true; playBtn.textContent = 'Pause'; last = performance.now(); }
    function pause() { playing = false; playBtn.textContent = 'Play'; }
    playBtn.onclick = () => (playing ? pause() : play());
    slider.oninput = () => { pause(); setTime(timeOf(parseFloat(slider.value))); frame(); };
    controls.addEventListener('change', () => { if (!playing) frame(); });
    window.addEventListener('resize', () => { if (!playing) frame(); });
    setTime(0); playBtn.textContent = playing ? 'Pause' : 'Play';
    if (!action) { playBtn.disabled = true; slider.disabled = true; }
    select(null); frame(); requestAnimationFrame(loop);
    Object.assign(api, {setInput: u => { pause(); setTime(timeOf(u)); frame(); return inputOf(time); },
                        input: () => inputOf(time), pickAt, play, pause, select, ready: true});
  }, err => { api.error = String(err && err.message || err); status.textContent = 'The 3-D view could not load: ' + api.error; });
} catch (err) {
  api.error = String(err && err.message || err);
  status.textContent = 'The 3-D view needs WebGL, which this browser did not give: ' + api.error;
}
"""


def viewer_section(glb: bytes, kit: Kit, motion, result: Result, rows: dict[str, str],
                   frames: dict[str, np.ndarray] | None = None, links=()) -> tuple[str, str]:
    """("3-D view", html): the view of ``glb`` (the kit's animated assembly) over ``motion``; ``rows``:
    part name -> the bill's row name (a part printed several times shares its group's row);
    ``frames``: part name -> its node's frame in the part's local one (the STL's,
    ``local_from_print``; identity when not given); ``links``: (name, href) of the kit's files."""
    from .gltf import read_glb

    doc, _ = read_glb(glb)
    anim = (doc.get("animations") or [{}])[0]
    extras = anim.get("extras", {})
    lo, hi = (float(x) for x in extras.get("input_range", motion.range))
    tight = tightest_clearance(result)
    if tight is not None:  # where it happens, in the node frame of its first part at that moment
        name = tight["parts"][0]
        node = kit.poses(tight["theta"])[name] @ (frames or {}).get(name, np.eye(4))
        tight["local_mm"] = [float(x) for x in (np.linalg.inv(node) @ np.append(tight["location_mm"], 1.0))[:3]]
    data = {"label": extras.get("input_label", motion.label), "unit": extras.get("input_unit", motion.unit),
            "range": [lo, hi], "mode": extras.get("mode", "turn"), "still": not anim,
            "roles": {p.name: p.role for p in kit.parts}, "rows": rows, "tightest": tight,
            "hint": "Drag to orbit, wheel to zoom, right-drag to pan; click a part to find it in the bill of parts."}
    unit_deg = data["unit"] == "rad"
    span = (f"{math.degrees(lo):g}° to {math.degrees(hi):g}°" if unit_deg else f"{lo:g} to {hi:g} {data['unit']}")
    how = "one turn, forward" if data["mode"] == "turn" else "out and back"
    if tight is not None:
        when = f"{math.degrees(tight['theta']):.1f}°" if unit_deg else f"{tight['theta']:g} {data['unit']}"
        tight_html = (f'<button id="pg-tight" type="button">Show the tightest clearance</button>'
                      f'<span>tightest clearance {tight["mm"]:.3f} mm between {html.escape(" and ".join(tight["parts"]))}'
                      f' at {html.escape(data["label"])} {when} (red ring)</span>')
    else:
        tight_html = "<span>the check measured no clearance to mark</span>"
    payload = json.dumps(data, allow_nan=False).replace("</", "<\\/")
    body = (f"<style>{CSS}</style>"
            f'<div class="pg-viewer"><canvas id="pg-canvas" aria-label="3-D view of the assembly"></canvas>'
            f'<div class="pg-bar"><button id="pg-play" type="button">Play</button>'
            f'<input id="pg-input" type="range" aria-label="{html.escape(data["label"])}">'
            f'<span id="pg-value"></span></div><div class="pg-bar">{tight_html}</div>'
            f'<div class="pg-status" id="pg-status">Loading the 3-D view …</div></div>'
            f"<p>The assembly moves over its {html.escape(data['label'])}, {span} ({how}); the same animation is in "
            "the kit's <code>assembly.glb</code>, which any glTF viewer plays. Parts are coloured by role.</p>"
            + ('<p class="pg-files">The kit\'s files: ' + " · ".join(
                f'<a href="{html.escape(href)}">{html.escape(name)}</a>' for name, href in links) + "</p>"
               if links else "")
            + f'<script type="application/json" id="pg-viewer-data">{payload}</script>'
            f'<script type="application/octet-stream" id="pg-glb">{base64.b64encode(glb).decode("ascii")}</script>'
            f"{_import_map()}<script type=\"module\">{SCRIPT}</script>")
    return ("3-D view", body)
