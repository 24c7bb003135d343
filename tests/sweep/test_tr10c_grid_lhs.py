"""The tr10c trial's sweeps on a hoist stage of its own (23/71, m_n 3, beta 12 deg, a 3 um transmission error, the
ISO default mesh law): a grid over two keys whose every row is the one-shot ``gearcli simulate`` of the same point
(same engine: the same steps, the same numbers), and a Latin-hypercube tolerance study whose draws are checked
against the distributions: one draw per stratum of each key (normal: Phi((x - mu)/sigma) in [i/N, (i+1)/N)).
"""

from __future__ import annotations

import csv
import io
import json

import numpy as np
import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose
from scipy.stats import norm

from gearcli import engine
from gearcli.cli import cli
from tests.life.test_tr10c_hoist import HOIST

SCENE = HOIST.split("[[duty]]")[0].replace("[input]", "[contact]\ntransmission_error_um = [3.0]\n\n[input]")
ENGINE = "compiled" if engine.available() else "python"
STATS = ("mean", "std", "min", "max")


def _run(*args: str, code: int = 0):
    res = CliRunner().invoke(cli, ["-q", *args])
    assert res.exit_code == code, res.output
    return res


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    path = tmp_path_factory.mktemp("tr10c_sweep") / "hoist_te.toml"
    path.write_text(SCENE, encoding="utf-8")
    return path


def _rows(text: str) -> list[dict]:
    return list(csv.DictReader(io.StringIO("".join(ln for ln in text.splitlines(True) if not ln.startswith("#")))))


def test_grid_rows_are_the_one_shot_runs(scene, tmp_path):
    out = tmp_path / "grid.csv"
    _run("sweep", str(scene), "--vary", "input.speed_rpm=900,1200", "--vary", "load.torque_Nm=600,1000",
         "--set", f"simulation.engine={ENGINE}", "--jobs", "1", "-o", str(out))
    rows = _rows(out.read_text(encoding="utf-8"))
    # the grid in order, the first key slowest
    assert [(float(r["input.speed_rpm"]), float(r["load.torque_Nm"])) for r in rows] == \
        [(900, 600), (900, 1000), (1200, 600), (1200, 1000)]
    for r in rows:
        assert r["status"] == "ok" and r["direction"] == "none"
        doc = json.loads(_run("simulate", str(scene), "--set", f"input.speed_rpm={r['input.speed_rpm']}",
                              "--set", f"load.torque_Nm={r['load.torque_Nm']}", "--set",
                              f"simulation.engine={ENGINE}", "--format", "json").stdout)
        st = doc["summary"]["stages"][0]
        # the same engine takes the same steps: the window statistics agree to round-off
        for s in STATS:
            assert_allclose(float(r[f"stage1_tangential_N_{s}"]), st["tangential_N"][s], rtol=1e-9)
        for s in ("mean", "rms", "min", "max"):
            assert_allclose(float(r[f"stage1_dte_um_{s}"]), st["dte_um"][s], rtol=1e-9, atol=1e-12)
        assert_allclose(float(r["stage1_dynamic_factor"]), st["dynamic_factor"], rtol=1e-9)
        # hand: the window mean is the static force T / (z2 m_t / 2); the output speed n z1 / z2
        m_t = 3.0 / np.cos(np.radians(12.0))
        assert_allclose(float(r["stage1_tangential_N_mean"]), float(r["load.torque_Nm"]) * 1e3 / (71 * m_t / 2),
                        rtol=1e-6)  # the window mean of an excited run: its integral, to rtol
        # the window mean of a vibrating speed over a window that is not a whole number of its cycles: 4e-6 measured
        assert_allclose(float(r["output_speed_rpm"]), float(r["input.speed_rpm"]) * 23 / 71, rtol=2e-5)
        # the dynamic factor is the window max over the static force
        assert_allclose(float(r["stage1_dynamic_factor"]),
                        float(r["stage1_tangential_N_max"]) / (float(r["load.torque_Nm"]) * 1e3 / (71 * m_t / 2)),
                        rtol=1e-9)


def test_latin_hypercube_draws_fill_every_stratum(scene, tmp_path):
    n = 12
    out = tmp_path / "lhs.csv"
    _run("sweep", str(scene), "--samples", str(n), "--random", "load.torque_Nm=normal(1000,50)",
         "--random", "stage.0.backlash_mm=uniform(0.05,0.15)", "--seed", "7", "--jobs", "1",
         "--set", "simulation.duration_s=0.15", "-o", str(out))
    rows = _rows(out.read_text(encoding="utf-8"))
    assert len(rows) == n and all(r["status"] == "ok" for r in rows)
    torque = np.array([float(r["load.torque_Nm"]) for r in rows])
    backlash = np.array([float(r["stage.0.backlash_mm"]) for r in rows])
    i = np.arange(n)
    for u in (np.sort(norm.cdf((torque - 1000.0) / 50.0)), np.sort((backlash - 0.05) / 0.1)):
        assert np.all((u >= i / n) & (u < (i + 1) / n)), u  # one draw in each of the n equal-probability strata
    # stratified draws: the sample mean of the uniform key is within half a stratum's spread of the mean
    assert abs(backlash.mean() - 0.10) <= 0.1 / n / 2
    # the seed reproduces the draws
    out2 = tmp_path / "lhs2.csv"
    _run("sweep", str(scene), "--samples", str(n), "--random", "load.torque_Nm=normal(1000,50)",
         "--random", "stage.0.backlash_mm=uniform(0.05,0.15)", "--seed", "7", "--jobs", "1",
         "--set", "simulation.duration_s=0.15", "-o", str(out2))
    assert [r["load.torque_Nm"] for r in _rows(out2.read_text(encoding="utf-8"))] == [r["load.torque_Nm"] for r in rows]


@pytest.mark.parametrize("vary,key", [("input.speed_rpmx=1:2:3", "input.speed_rpmx"),
                                      ("load.torque_Nm=100:200:0", "load.torque_Nm")])
def test_bad_vary_is_exit_2_naming_the_key(scene, tmp_path, vary, key):
    out = tmp_path / "bad.csv"
    res = _run("sweep", str(scene), "--vary", vary, "-o", str(out), code=2)
    assert key in res.output and "Traceback" not in res.output
    assert not out.exists()
