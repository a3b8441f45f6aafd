"""`partgen sweep` plots P(jam) against what play costs (the trade-off a designer chooses on): a gear
train's lost motion at the output, a chain's pen error across its path (export.studies)."""

import csv
import json

from partgen.cli.main import main
from partgen.export.studies import play_cost, tradeoff_rows

PNG = b"\x89PNG\r\n\x1a\n"


def test_sweep_writes_the_tradeoff_plot_and_table(tmp_path, capsys):
    """The reducer's running fits from 0.1 to 0.4 mm: P(jam) falls as the play grows while the lost
    motion at the output grows; tradeoff.png is a picture, tradeoff.csv the table, least cost first."""
    out = tmp_path / "sweep"
    key = "shafts.running_clearance_diametral_mm"
    assert main(["sweep", "configs/gear_train_reducer.yaml", "--vary", f"{key}=0.1:0.4:3", "--tolerance-samples",
                 "2000", "--workers", "1", "--check-samples", "8", "--json", "-o", str(out)]) == 0
    json.loads(capsys.readouterr().out)
    assert (out / "tradeoff.png").read_bytes()[:8] == PNG and (out / "tradeoff.png").stat().st_size > 5000
    rows = list(csv.DictReader((out / "tradeoff.csv").open()))
    assert [float(r[key]) for r in rows] == [0.1, 0.25, 0.4]
    lost = [float(r["lost_motion_arcmin"]) for r in rows]
    p = [float(r["jam_probability"]) for r in rows]
    assert lost == sorted(lost) and lost[-1] > lost[0] + 10  # the bores' play shows at the output
    assert p == sorted(p, reverse=True) and p[0] > 0.05 and p[-1] < 0.01  # and frees the fits
    page = (out / "index.html").read_text()
    assert "The trade-off: P(jam) against what play costs" in page and "lost motion at the output" in page
    points = list(csv.DictReader((out / "points.csv").open()))
    assert [float(r["lost_motion_arcmin"]) for r in points] == lost


def test_the_chain_plots_its_pen_error_across_the_path():
    """A chain's trace gives the pen band: the trade-off's x is its 95 % across the path."""
    stats = {"pen_error_band_mm": {"path_worst_case_max": 37.5, "path_p95_max": 17.9, "worst_case_max": 107.6}}
    assert play_cost(stats) == {"pen_error_mm": 37.5, "pen_error_p95_mm": 17.9}
    rows = [{"point": i, "values": {"k": i}, "status": "pass", "jam_probability": p, "jam_ci95_low": p,
             "jam_ci95_high": p, **play_cost({"pen_error_band_mm": {"path_worst_case_max": 2 * e,
                                                                    "path_p95_max": e}})}
            for i, (p, e) in enumerate([(0.01, 12.0), (0.2, 8.0)])]
    col, label, ordered = tradeoff_rows(rows)
    assert col == "pen_error_p95_mm" and "pen error" in label and [r["point"] for r in ordered] == [1, 0]
    assert play_cost({"samples": 3}) == {} and tradeoff_rows([{**rows[0], "pen_error_p95_mm": None}]) is None
