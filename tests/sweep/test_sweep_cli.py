"""`gearcli sweep` end to end: rows, failed points, exit codes, resume, Ctrl-C, JSON, Dask == process pool."""

from __future__ import annotations

import csv
import io
import json
import math
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.sweep import worker

SEED = str(Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml")
SPEEDS = ["--vary", "input.speed_rpm=400:1000:3"]
REAL_EVALUATE = worker._evaluate


def sweep(*args, input=None):
    return CliRunner().invoke(cli, ["sweep", SEED, *args], input=input)


def read_csv(path: Path) -> tuple[str, list[dict]]:
    first, _, rest = path.read_text().partition("\n")
    return first, list(csv.DictReader(io.StringIO(rest)))


def strip_wall(rows):
    return [{k: v for k, v in r.items() if k != "wall_s"} for r in rows]


def test_rows_one_per_point_and_a_failed_point_is_a_row(tmp_path):
    out = tmp_path / "s.csv"
    res = sweep(*SPEEDS, "--vary", "stage.0.pinion.teeth=21,3", "--jobs", "1", "-o", str(out))
    assert res.exit_code == 1, res.stderr  # some point failed
    first, rows = read_csv(out)
    assert first.startswith("# gearcli sweep: ") and json.loads(first[17:])["sweep"]["vary"][0]["values"] == [
        400, 700, 1000]
    assert [(r["input.speed_rpm"], r["stage.0.pinion.teeth"]) for r in rows] == [
        ("400", "21"), ("400", "3"), ("700", "21"), ("700", "3"), ("1000", "21"), ("1000", "3")]
    bad = [r for r in rows if r["stage.0.pinion.teeth"] == "3"]
    assert {r["status"] for r in bad} == {"failed"}
    assert all("stage[0].pinion.teeth" in r["message"] and "≥ 5" in r["message"] for r in bad)
    assert all(r["stage1_tangential_N_mean"] == "" and r["nfev"] == "" for r in bad)
    good = [r for r in rows if r["status"] == "ok"]
    assert len(good) == 3 and all(int(r["nfev"]) > 0 for r in good)
    # the output speed follows the input speed through the seed's ratio 21/51 * 17/50 * 17/53 (by hand)
    ratio = (21 / 51) * (17 / 50) * (17 / 53)
    for r in good:
        assert float(r["output_speed_rpm"]) == pytest.approx(float(r["input.speed_rpm"]) * ratio, rel=5e-3)
    # window mean of stage 1's F_t = input torque / pitch radius, lossless: T_L / i_total / (z_1 m_n / cos(beta) / 2)
    f_t = 5310.0 / ((51 / 21) * (50 / 17) * (53 / 17)) / (21 * 12e-3 / math.cos(math.radians(12)) / 2)  # 1851 N
    assert [float(r["stage1_tangential_N_mean"]) for r in good] == pytest.approx([f_t] * 3, rel=0.02)  # ringing
    # issue 13: the mesh response fills in; the loaded seed mesh never lifts off, and its deflection is positive
    assert all(float(r["stage1_contact_loss_fraction"]) == 0.0 and float(r["stage1_dte_um_mean"]) > 0 for r in good)
    assert "6 points, 3 failed" in res.stderr


def test_all_points_ok_is_exit_0_and_stdout_is_csv():
    res = sweep("--vary", "input.speed_rpm=500,900", "--jobs", "1")
    assert res.exit_code == 0, res.stderr
    rows = list(csv.DictReader(io.StringIO(res.stdout)))
    assert [r["input.speed_rpm"] for r in rows] == ["500", "900"] and {r["direction"] for r in rows} == {"none"}


@pytest.mark.parametrize("args, needle", [
    (["--vary", "input.sped_rpm=1,2"], "input.sped_rpm"),
    (["--vary", "input.speed_rpm=1:2"], "START:STOP:N"),
    ([], "nothing to sweep"),
    (["--random", "input.speed_rpm=uniform(1,2)"], "--samples"),
    (["--samples", "3", "--random", "input.speed_rpm=lognormal(1,2)"], "normal(mu,sigma)"),
    (["--samples", "3", "--random", "stage.0.pinion.teeth=normal(21,1)"], "takes no real number"),
    # a list (a TE's harmonics) is drawn entry by entry: the message shows how, not "a whole number"
    (["--samples", "3", "--set", "contact.transmission_error_um=[1.0, 0.5]",
      "--random", "contact.transmission_error_um=normal(1,0.1)"], "'contact.transmission_error_um.0=normal(...)'"),
    # a table is neither a whole number nor a choice: the message says to draw one of its keys
    (["--samples", "3", "--random", "stage.0.mesh=uniform(0,1)"], "stage.0.mesh is a table"),
    (["--samples", "3", "--random", "contact=normal(1,0.1)"], "--random 'contact.KEY=normal(...)'"),
])
def test_bad_usage_is_exit_2_one_line(args, needle):
    res = sweep(*args)
    assert res.exit_code == 2, res.output
    assert needle in res.stderr and "Traceback" not in res.stderr


def test_different_arguments_against_an_existing_file_are_exit_2(tmp_path):
    out = tmp_path / "s.csv"
    assert sweep("--vary", "input.speed_rpm=500,900", "--jobs", "1", "-o", str(out)).exit_code == 0
    before = out.read_bytes()
    res = sweep("--vary", "input.speed_rpm=500,901", "--jobs", "1", "-o", str(out))
    assert res.exit_code == 2 and "different sweep" in res.stderr and "--vary" in res.stderr
    res = sweep("--vary", "input.speed_rpm=500,900", "--set", "load.torque_Nm=4000", "-o", str(out))
    assert res.exit_code == 2 and "input sha256" in res.stderr
    assert out.read_bytes() == before  # not a mix
    other = tmp_path / "other.csv"
    other.write_text("a,b\n1,2\n")
    res = sweep("--vary", "input.speed_rpm=500,900", "-o", str(other))
    assert res.exit_code == 2 and "not a gearcli sweep file" in res.stderr


def _counting(monkeypatch, fail_after=None):
    calls = []
    real = REAL_EVALUATE

    def evaluate(evaluator, scene, point, prev, check=False):
        if fail_after is not None and len(calls) == fail_after:
            raise KeyboardInterrupt
        calls.append(point.index)
        return real(evaluator, scene, point, prev, check)

    monkeypatch.setattr(worker, "_evaluate", evaluate)
    return calls


@pytest.mark.parametrize("suffix", [".csv", ".json"])
def test_ctrl_c_then_resume_gives_the_uninterrupted_file(tmp_path, monkeypatch, suffix):
    args = ["--vary", "input.speed_rpm=400:1000:4", "--vary", "load.torque_Nm=4000,5310", "--jobs", "1"]
    full, part = tmp_path / f"full{suffix}", tmp_path / f"part{suffix}"
    assert sweep(*args, "-o", str(full)).exit_code == 0
    calls = _counting(monkeypatch, fail_after=3)
    res = sweep(*args, "-o", str(part))
    assert res.exit_code == 130 and res.stderr.strip().endswith("interrupted")
    if suffix == ".csv":
        assert len(read_csv(part)[1]) == 3  # every finished point, a valid file
    else:
        assert len(json.loads(part.read_text())["rows"]) == 3
    calls = _counting(monkeypatch)
    res = sweep(*args, "-o", str(part))
    assert res.exit_code == 0, res.stderr
    assert sorted(calls) == [3, 4, 5, 6, 7]  # only the missing points ran
    if suffix == ".csv":
        (fa, ra), (fb, rb) = read_csv(full), read_csv(part)
        assert fa == fb and strip_wall(ra) == strip_wall(rb)
    else:
        a, b = json.loads(full.read_text()), json.loads(part.read_text())
        assert a["sweep"] == b["sweep"] and strip_wall(a["rows"]) == strip_wall(b["rows"])


def test_a_row_cut_short_by_a_hard_kill_is_recomputed(tmp_path):
    args = ["--vary", "input.speed_rpm=500,700,900", "--jobs", "1"]
    out = tmp_path / "s.csv"
    assert sweep(*args, "-o", str(out)).exit_code == 0
    whole = read_csv(out)
    text = out.read_text()
    out.write_text(text[: text.rindex("\n", 0, len(text) - 1) + 20])  # keep 2 rows and a stub of the third
    assert sweep(*args, "-o", str(out)).exit_code == 0
    assert strip_wall(read_csv(out)[1]) == strip_wall(whole[1])


def test_missing_dask_is_a_usage_error(monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)  # import distributed -> ImportError
    res = sweep(*SPEEDS, "--scheduler", "tcp://127.0.0.1:1")
    assert res.exit_code == 2 and "pip install 'gearcli[distributed]'" in res.stderr


def test_dask_local_cluster_gives_the_rows_of_the_process_pool(tmp_path):
    distributed = pytest.importorskip("distributed")
    args = ["--vary", "input.speed_rpm=300:1500:4", "--direction", "both", "--vary", "stage.0.pinion.teeth=21,3"]
    pool = sweep(*args, "--jobs", "2", "-o", str(tmp_path / "pool.csv"))
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as c:
        dask = sweep(*args, "--scheduler", c.scheduler_address, "-o", str(tmp_path / "dask.csv"))
    assert pool.exit_code == dask.exit_code == 1  # the teeth = 3 points fail on both
    (fa, ra), (fb, rb) = read_csv(tmp_path / "pool.csv"), read_csv(tmp_path / "dask.csv")
    assert fa == fb and len(ra) == 16
    assert strip_wall(ra) == strip_wall(rb)


def test_plots_response_campbell_and_distributions(tmp_path):
    pytest.importorskip("matplotlib")
    res = sweep("--vary", "input.speed_rpm=500,900", "--jobs", "1", "--plots", str(tmp_path / "p"))
    assert res.exit_code == 0, res.stderr
    assert sorted(p.name for p in (tmp_path / "p").iterdir()) == ["campbell.png", "response_input_speed_rpm.png"]
    res = sweep("--samples", "3", "--random", "load.torque_Nm=normal(5310,200)", "--seed", "1", "--jobs", "1",
                "--plots", str(tmp_path / "q"))
    assert res.exit_code == 0 and [p.name for p in (tmp_path / "q").iterdir()] == ["distributions.png"]
    assert all((tmp_path / d / n).read_bytes()[:4] == b"\x89PNG" for d, n in [("p", "campbell.png")])


def test_plots_without_matplotlib_warn_and_exit_0(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    monkeypatch.setitem(sys.modules, "matplotlib.figure", None)
    monkeypatch.setitem(sys.modules, "matplotlib.backends.backend_agg", None)
    res = sweep("--vary", "input.speed_rpm=500", "--jobs", "1", "--plots", str(tmp_path / "p"))
    assert res.exit_code == 0 and "pip install 'gearcli[plot]'" in res.stderr


def test_a_grid_whose_span_overflows_is_written_as_json_rows(tmp_path):
    """-1e308:1e308:3: the points -1e308, 0 and 1e308 (by hand) fail their key's bounds as rows of a valid JSON
    file; the grid's nan and inf points were an internal error (exit 1, no file) writing JSON."""
    out = tmp_path / "s.json"
    res = sweep("--vary", "input.speed_rpm=-1e308:1e308:3", "--jobs", "1", "-o", str(out))
    assert res.exit_code == 1 and "internal error" not in res.stderr, res.stderr
    rows = json.loads(out.read_text())["rows"]
    assert [r["input.speed_rpm"] for r in rows] == [-1e308, 0.0, 1e308]
    assert [r["status"] for r in rows] == ["failed"] * 3
    assert all("input.speed_rpm: must be" in r["message"] for r in rows)
