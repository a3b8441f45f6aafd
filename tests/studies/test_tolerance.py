"""`partgen tolerance`: the margin model of the gear chain, the Monte Carlo and its engine.

Each kit is built and checked once (few crank angles: the chain's margins that decide whether it
turns do not depend on them, bar the motion gaps, which the Eq 12 tip-circle margin covers)."""

import json
import time
from pathlib import Path

import numpy as np
import pytest

from partgen import cluster, studies
from partgen.cli.main import main
from partgen.design.tolerance import add_tallies, chunk_sizes, run_chunk, summarise, wilson

ROOT = Path(__file__).resolve().parents[2]
CONFIGS = ROOT / "configs"
FORTUS = 0.127


@pytest.fixture(scope="module")
def nominal(kit_of):
    """name -> (loaded, kit, nominal check result): the session's build of each (``kit_of``), checked
    once (4 crank angles)."""
    out = {}
    for name in ("butterfly", "butterfly_liu2017"):
        loaded, kit = kit_of(name)[:2]
        out[name] = (loaded, kit, loaded.mechanism.check(loaded.spec, kit, 4, None))
    return out


def model_of(nominal, name, accuracy, seated=True):
    loaded, kit, result = nominal[name]
    return loaded.mechanism.tolerance_model(loaded.spec, kit, result, accuracy, seated=seated)


def run_local(model, samples, seed=0, chunk=500):
    tallies = [run_chunk(model, seed, i, n) for i, n in enumerate(chunk_sizes(samples, chunk))]
    return summarise(model, add_tallies(tallies))


def test_margins_come_from_the_nominal_check(nominal):
    loaded, kit, result = nominal["butterfly"]
    m = model_of(nominal, "butterfly", FORTUS)
    running = [c for c in kit.contacts if c.kind == "running"]
    joints = [x for x in m.margins if x.group == "joint"]
    assert len(joints) == len(running) == 22
    assert all(abs(x.nominal - 0.15) < 0.02 for x in joints)  # 0.3 mm diametral, measured in the section
    measured = {" / ".join(r["pair"]).replace(" / ", "/"): r["backlash_mm"] for r in result.figures["meshes"]}
    centred = model_of(nominal, "butterfly", FORTUS, seated=False)
    assert {x.unit: x.nominal for x in centred.margins if x.what == "backlash"} == measured
    # seated: each mesh's backlash grows by the play its bodies give it (never shrinks); the drive
    # gear and the last link have one mesh each, so drive/G1 gets all of the drive's 0.15 mm radial
    seated = {x.unit: x.nominal for x in m.margins if x.what == "backlash"}
    assert all(seated[u] >= measured[u] - 1e-12 for u in measured)
    assert 2 * np.tan(np.radians(20)) * 0.14 < seated["G1/drive"] - measured["G1/drive"] < 2 * np.tan(np.radians(25)) * 0.16
    # Eq 12 on link 10 of the default: S − r_tip(D10) − r_tip(G11) = the 1.5 mm tip gap or more
    eq12 = next(x for x in m.margins if x.unit == "D10–G11")
    assert eq12.nominal >= 1.5 - 1e-9


def test_a_margin_moves_by_its_feature():
    """One feature moved by 1 σ moves the margin by its coefficient × σ, the others by nothing."""
    from partgen.design.tolerance import Feature, Margin, MarginModel

    feats = (Feature("a", "hole", "p"), Feature("b", "pin", "p"))
    margins = (Margin("j", "joint", "radial gap", 0.05), Margin("k", "joint", "radial gap", 10.0))
    coeff = np.array([[0.5, 0.0], [-0.5, 0.0]])
    model = MarginModel(feats, margins, coeff, np.array([0.03, 0.03]), np.array([0.05, 10.0]), 0.09)
    r = run_local(model, 20_000, seed=3)
    # margin 0.05 + 0.5(δa − δb), σ of it 0.03/√2: P = Φ(−0.05/0.0212) = 0.00917
    p = r["units"][0]["probability"]
    assert r["units"][0]["unit"] == "j" and abs(p - 0.00917) < 0.003
    assert r["units"][1]["jams"] == 0
    assert {k["kind"] for k in r["sensitivity"]["by_kind"] if k["share"] > 0} == {"hole", "pin"}
    assert wilson(0, 100)[0] == 0.0 and 0.03 < wilson(0, 100)[1] < 0.04


def test_accuracy_zero_never_jams_the_default(nominal):
    r = run_local(model_of(nominal, "butterfly", 0.0), 2000)
    assert r["overall"]["jams"] == 0 and r["overall"]["ci95"][1] < 0.002


def test_the_papers_design_jams_at_link_10(nominal):
    r = run_local(model_of(nominal, "butterfly_liu2017", FORTUS), 4000)
    assert r["overall"]["probability"] > 0.8
    top = r["units"][0]
    assert top["unit"] == "D10–G11" and top["where"] == "link 10"
    assert 0.4 < top["probability"] < 0.6  # tip circles that touch: any oversize tip clashes
    assert all(u["probability"] < 0.2 for u in r["units"][1:])
    # what drives it: link 10's own length and the two gears' outlines
    feats = [f["feature"] for f in r["sensitivity"]["by_feature"][:4]]
    assert set(feats) == {"B10 proximal hole x", "B10 distal post x", "D10 teeth", "G11 teeth"}


def test_seeds_are_per_chunk(nominal):
    m = model_of(nominal, "butterfly_liu2017", FORTUS)
    child = np.random.SeedSequence(7).spawn(3)[2]
    z = np.random.default_rng(child).standard_normal((5, len(m.features)))
    assert np.array_equal(z, np.random.default_rng(np.random.SeedSequence(7, spawn_key=(2,))).standard_normal(z.shape))


def test_one_worker_and_two_give_the_same_result(nominal):
    m = model_of(nominal, "butterfly_liu2017", FORTUS)
    got = []
    for workers in (1, 2):
        with cluster.cluster(workers, processes=False) as client:
            total, info = studies.sample(client, m, 3000, 11, chunk=400)
        assert info["workers"] == workers and info["computed_chunks"] == 8
        got.append(summarise(m, total))
    assert got[0] == got[1]
    assert got[0] == run_local(m, 3000, seed=11, chunk=400)


def test_resume_runs_only_the_missing_chunks(nominal, tmp_path):
    from partgen.export.outputs import claim_output

    m = model_of(nominal, "butterfly_liu2017", FORTUS)
    dest = tmp_path / "tolerance"
    with cluster.cluster(1, processes=False) as client:
        full, _ = studies.sample(client, m, 2000, 5, claim_output(dest, "tolerance"), chunk=400)
        lines = (dest / "chunks.jsonl").read_text().splitlines()
        assert len(lines) == 1 + 5
        (dest / "chunks.jsonl").write_text("\n".join(lines[:3]) + "\n" + lines[3][:20])  # cut short mid-line
        again, info = studies.sample(client, m, 2000, 5, claim_output(dest, "tolerance"), resume=True, chunk=400)
        assert info["resumed_chunks"] == 2 and info["computed_chunks"] == 3
        assert summarise(m, again) == summarise(m, full)
        with pytest.raises(Exception, match="another study"):
            studies.sample(client, m, 2000, 6, claim_output(dest, "tolerance"), resume=True, chunk=400)


def test_cli_running_clearance_below_the_accuracy_jams(kit_of, prime_kit_cache, tmp_path, capsys):
    """The paper's 0.1 mm diametral (0.05 radial) running fits on a ±0.127 mm printer: most prints
    jam at a joint, besides link 10; --max-jam-probability makes it exit 1; the result is written as
    it goes. (The kit is the session's build of the same design.)"""
    prime_kit_cache(kit_of("butterfly_liu2017"))
    out = tmp_path / "tol"
    code = main(["tolerance", str(CONFIGS / "butterfly_liu2017.yaml"), "--samples", "3000", "--workers", "1",
                 "--check-samples", "4", "--max-jam-probability", "0.5", "--json", "-o", str(out)])
    r = json.loads(capsys.readouterr().out)
    assert code == 1 and r["ok"] is False
    assert r["groups"]["joint"]["probability"] > 0.5  # 22 joints, each ~5 %: 1 − 0.95²² ≈ 0.66
    assert r["groups"]["joint"]["count"] == 22
    joints = [u for u in r["units"] if u["group"] == "joint"]
    assert all(0.02 < u["probability"] < 0.09 for u in joints)
    assert {"hole", "pin"} <= {k["kind"] for k in r["sensitivity"]["by_kind"] if k["share"] > 0.05}
    assert (out / "result.json").is_file()
    assert len((out / "chunks.jsonl").read_text().splitlines()) == 1 + len(chunk_sizes(3000, studies.CHUNK))


def test_cli_bad_input(tmp_path, capsys, monkeypatch):
    from partgen.mechanisms import REGISTRY

    out = tmp_path / "tol"
    monkeypatch.delattr(type(REGISTRY["wrist"]), "tolerance_model")  # every shipped kind has one: a kind without
    assert main(["tolerance", str(CONFIGS / "butterfly.yaml"), "--samples", "0", "-o", str(out)]) == 2
    assert main(["tolerance", str(CONFIGS / "wrist_sphere.yaml"), "--samples", "10", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert "offers no tolerance study" in err and "gear_chain" in err and "gear_pair" in err and "wrist" not in err.split("runs on")[-1]
    t0 = time.perf_counter()
    assert main(["tolerance", str(CONFIGS / "butterfly.yaml"), "--samples", "10", "--scheduler", "tcp://127.0.0.1:9",
                 "-o", str(out)]) == 2
    assert time.perf_counter() - t0 < 10
    assert "--scheduler" in capsys.readouterr().err
    assert not out.exists()


def test_report_section_of_a_written_result(nominal, tmp_path):
    from partgen.export.studies import saved_tolerance, tolerance_section

    loaded, _, _ = nominal["butterfly_liu2017"]
    r = run_local(model_of(nominal, "butterfly_liu2017", FORTUS), 1000)
    r.update(design_digest=loaded.raw.digest(), seed=0, accuracy_source="test")
    (tmp_path / "tolerance").mkdir()
    (tmp_path / "tolerance" / "result.json").write_text(json.dumps(r))
    assert saved_tolerance(tmp_path / "tolerance", loaded.raw.digest()) == json.loads(json.dumps(r))
    title, body = tolerance_section(r)
    assert title == "Tolerance" and "D10–G11" in body and body.count("<img") == 1
    r["design_digest"] = "another design"
    (tmp_path / "tolerance" / "result.json").write_text(json.dumps(r))
    assert saved_tolerance(tmp_path / "tolerance", loaded.raw.digest()) is None


def test_the_default_chunk_depends_on_the_samples_only():
    """Large studies are cut into about TASKS tasks (the scheduler's cost per task stays small),
    small ones into chunks of CHUNK; never more than MAX_CHUNK samples a task."""
    from partgen.design.tolerance import chunk_sizes
    assert studies.default_chunk(3000) == studies.CHUNK
    assert studies.default_chunk(300_000) == 18_750 and len(chunk_sizes(300_000, 18_750)) == studies.TASKS
    assert studies.default_chunk(10**9) == studies.MAX_CHUNK


def test_the_gear_pair_jams_at_its_mesh_as_the_normal_tail_says(kit_of):
    """The gear pair's model: its least backlash measured by the check, moved by the tooth
    outlines (−δ/cos α_w each) and the posts' x (2 tan α_w Δa); P(jam) of the mesh is the normal
    tail Φ(−m/σ) of that margin, none at ±0; the fits jam only when the accuracy nears their gap."""
    import math

    b = kit_of("gear_pair")
    loaded, kit = b.loaded, b.kit
    result = loaded.mechanism.check(loaded.spec, kit, 24, None)
    s = loaded.spec

    def model(acc, seated=False):
        return loaded.mechanism.tolerance_model(s, kit, result, acc, seated=seated)

    m = model(FORTUS)
    mesh = next(x for x in m.margins if x.what == "backlash")
    assert mesh.nominal == result.figures["backlash_mm"]["min"] > 0
    aw = math.acos((s.gear1.pitch_radius + s.gear2.pitch_radius) * math.cos(s.gear1.system.pressure_angle)
                   / s.centre_distance)
    sd_tooth, sd_pos = FORTUS / 3, FORTUS / 3 / math.sqrt(2)
    sigma = math.hypot(math.sqrt(2) * sd_tooth / math.cos(aw), 2 * math.tan(aw) * math.sqrt(2) * sd_pos)
    expect = 0.5 * math.erfc(mesh.nominal / sigma / math.sqrt(2))
    r = run_local(m, 40_000, seed=5)
    got = next(u for u in r["units"] if u["unit"] == "gear1/gear2")
    assert got["ci95"][0] <= expect <= got["ci95"][1] and 0.0005 < expect < 0.01
    assert [u["jams"] for u in r["units"] if u["group"] == "joint"] == [0, 0]
    assert run_local(model(0.0), 2000)["overall"]["jams"] == 0
    loose = run_local(model(0.6), 4000)  # ±0.6 mm: a 0.2 mm radial gap has σ 0.14 mm, ~8 % grip their post
    assert all(u["jams"] > 0 for u in loose["units"] if u["group"] == "joint")
    # seated (the default): the mesh pushes both gears apart by their printed radial play, so the
    # centre distance grows by gap₁ + gap₂ (each 0.2 mm ± half its bore's and post's deviations)
    acc = 0.3
    seated = loaded.mechanism.tolerance_model(s, kit, result, acc)
    mesh = next(x for x in seated.margins if x.what == "backlash")
    gap = result.figures["radial_gap_mm"]
    assert mesh.nominal == pytest.approx(result.figures["backlash_mm"]["min"] + 2 * math.tan(aw) * 2 * gap, abs=1e-12)
    sd = acc / 3
    sigma = math.sqrt(2 * (sd / math.cos(aw)) ** 2 + 2 * (2 * math.tan(aw) * sd / math.sqrt(2)) ** 2
                      + 4 * (2 * math.tan(aw) * 0.5 * sd) ** 2)
    expect = 0.5 * math.erfc(mesh.nominal / sigma / math.sqrt(2))
    r = run_local(seated, 40_000, seed=5)
    got = next(u for u in r["units"] if u["unit"] == "gear1/gear2")
    assert got["ci95"][0] <= expect <= got["ci95"][1]
    centred = run_local(model(acc), 40_000, seed=5)
    assert got["probability"] < centred["units"][0]["probability"] / 5  # 0.3 % against 11.4 %


def test_local_worker_processes_keep_glibc_off_fresh_mmaps_per_task(recwarn):
    """Dask's nanny sets MALLOC_TRIM_THRESHOLD_, which switches off glibc's sliding mmap threshold:
    every array of a task was then mapped and page-faulted in afresh (a chunk ran ~2x slower on a
    worker than in-process). A local cluster's worker processes get cluster.WORKER_MALLOC, and
    Dask's housekeeping as cluster.LOCAL_QUIET sets it (no profiler sampling the tasks)."""
    import os
    import socket

    import dask

    def seen():
        return ({k: os.environ.get(k) for k in cluster.WORKER_MALLOC},
                {k: dask.config.get(k) for k in cluster.LOCAL_QUIET})
    busy = socket.socket()  # Dask's default HTTP port taken, as by a notebook's cluster: no warning
    try:
        busy.bind(("0.0.0.0", 8787))
        busy.listen(1)
    except OSError:
        pass  # taken already
    try:
        with cluster.cluster(1, processes=True) as client:
            got = list(client.run(seen).values())
    finally:
        busy.close()
    assert got == [({k: str(v) for k, v in cluster.WORKER_MALLOC.items()}, cluster.LOCAL_QUIET)]
    assert not [w for w in recwarn if "already in use" in str(w.message)]
    assert cluster.LOCAL_QUIET["distributed.worker.profile.enabled"] is False


def test_a_local_cluster_starts_beside_the_callers_work(monkeypatch):
    """cluster.starting: the caller goes on while the cluster starts; get() gives the client, or
    raises what starting it raised."""
    import threading

    started = threading.Event()
    real = cluster.cluster

    def slow(*a, **k):
        if not started.wait(5):  # the cluster starts only once the caller has gone on
            raise RuntimeError("the caller waited for the cluster to start")
        return real(*a, **k)
    monkeypatch.setattr(cluster, "cluster", slow)
    with cluster.starting(1, processes=False) as get:
        started.set()  # reached before any client exists
        assert get().submit(sum, [1, 2]).result() == 3

    def broken(*a, **k):
        raise RuntimeError("no cores today")
    monkeypatch.setattr(cluster, "cluster", broken)
    with pytest.raises(RuntimeError, match="no cores today"):
        with cluster.starting(1, processes=False) as get:
            get()


def _server(reply: bytes | None):
    """A local TCP port that takes connections and answers ``reply`` (None: never answers)."""
    import socket
    import threading

    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    srv.listen(8)
    held = []

    def serve():
        while True:
            try:
                conn, _ = srv.accept()
            except OSError:
                return
            held.append(conn)
            if reply is not None:
                conn.sendall(reply)
    threading.Thread(target=serve, daemon=True).start()
    return srv, held


def test_scheduler_addresses_that_are_no_usable_dask_scheduler_are_exit_2(tmp_path, capsys, monkeypatch):
    """A port that answers another protocol (it made Dask allocate 3 EiB, then hang 8 s in a
    half-made Client's clean-up and print a traceback), one that never answers, a Dask worker's
    address, and a scheduler with no workers: each is one message on --scheduler, exit 2, no
    traceback, within the time limit, nothing written."""
    from distributed import LocalCluster

    monkeypatch.setattr(cluster, "CONNECT_TIMEOUT_S", 1.0)
    out = tmp_path / "tol"
    http, held = _server(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n" * 4)
    silent, held2 = _server(None)
    lc = LocalCluster(n_workers=1, processes=False, protocol="tcp", dashboard_address="127.0.0.1:0")
    empty = LocalCluster(n_workers=0, processes=False, protocol="tcp", dashboard_address="127.0.0.1:0")
    try:
        cases = {f"tcp://127.0.0.1:{http.getsockname()[1]}": "not in Dask's protocol",
                 f"tcp://127.0.0.1:{silent.getsockname()[1]}": "nothing answered",
                 lc.workers[0].address: "a Dask Worker answers there",
                 empty.scheduler_address: "has no workers"}
        for address, why in cases.items():
            t0 = time.perf_counter()
            assert main(["tolerance", str(CONFIGS / "butterfly.yaml"), "--samples", "10", "--scheduler", address,
                         "-o", str(out)]) == 2
            assert time.perf_counter() - t0 < 10 * cluster.CONNECT_TIMEOUT_S / 4  # the 10 s limit, scaled
            err = capsys.readouterr().err
            assert why in err and "--scheduler" in err and "Traceback" not in err, err
            assert len(err.strip().splitlines()) == 1, err
            assert not out.exists()
    finally:
        for s in (http, silent):
            s.close()
        for c in held + held2:
            c.close()
        lc.close()
        empty.close()


def test_a_chunk_too_big_for_a_worker_is_refused_before_anything_is_written(tmp_path, capsys):
    """--chunk 10,000,000 of the chain's model (~290 features and margins) would hold ~35 GB on one
    worker: exit 2 on --chunk, nothing written."""
    out = tmp_path / "tol"
    assert main(["tolerance", str(CONFIGS / "butterfly.yaml"), "--samples", "20000000", "--chunk", "10000000",
                 "--check-samples", "8", "--workers", "1", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert "--chunk" in err and "GB" in err and len(err.strip().splitlines()) == 1
    assert not out.exists()


@pytest.mark.parametrize("command", [["tolerance", str(CONFIGS / "butterfly.yaml"), "--samples", "100"],
                                     ["sweep", str(CONFIGS / "gear_pair.yaml"), "--vary", "gears.module_mm=2:2.5:2"]])
def test_more_local_workers_than_the_machine_can_run_is_exit_2_at_once(command, tmp_path, capsys, monkeypatch):
    """--workers 1000 was 1,000 worker processes (~100 GB); beyond 4 a core is refused before any work."""
    monkeypatch.setattr(cluster, "default_workers", lambda: 2)
    out = tmp_path / "out"
    t0 = time.perf_counter()
    assert main([*command, "--workers", "9", "-o", str(out)]) == 2
    assert time.perf_counter() - t0 < 2  # before the kit is built
    err = capsys.readouterr().err
    assert "--workers 9" in err and "more than 8 workers" in err and len(err.strip().splitlines()) == 1
    assert not out.exists()


@pytest.mark.parametrize("address, why", [("tcp://[::1", "not an address"), ("tcp://127.0.0.1:99999", "not an address"),
                                          ("inproc://x", "not inproc://"), ("ucx://127.0.0.1:8786", "not ucx://"),
                                          ("tcp://", "tcp://HOST:PORT")])
def test_scheduler_addresses_that_are_not_addresses_are_exit_2(address, why, tmp_path, capsys):
    """"tcp://[::1" was an internal error with a traceback; other transports got Dask's own riddles."""
    out = tmp_path / "tol"
    assert main(["tolerance", str(CONFIGS / "butterfly.yaml"), "--samples", "10", "--scheduler", address,
                 "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert why in err and "Traceback" not in err and len(err.strip().splitlines()) == 1, err
    assert not out.exists()
