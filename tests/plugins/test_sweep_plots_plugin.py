"""``gearcli sweep --plots`` over the input speed of a train with a plug-in stage (plug_chain's chain between two
helical stages): the Campbell points carry each gear stage's first mesh frequency z_p n_p / 60 (by hand below) and
0 for the chain, which has no mesh; the command draws its figures (it was an internal error: AttributeError, the
chain's result has no pinion)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import plug_chain as pc
import pytest
import tomli_w
from click.testing import CliRunner

from gearcli.api import design_case
from gearcli.cli import cli
from gearcli.sweep.modes import campbell
from gearcli.sweep.worker import Scene

ROOT = Path(__file__).resolve().parents[2]
CHAIN = {"type": pc.KIND, "driver_teeth": 17, "driven_teeth": 34, "pitch_mm": 19.05, "chain_efficiency": 0.96,
         "stiffness_N_m": 2.0e7, "damping_Ns_m": 200.0, "driver_inertia_kg_m2": 0.01, "driven_inertia_kg_m2": 0.05}


@pytest.fixture
def chain():
    pc.register()
    yield
    pc.withdraw()


def _text() -> str:
    doc = tomllib.loads((ROOT / "configs" / "industrial_two_stage_rated.toml").read_text(encoding="utf-8"))
    doc.pop("target")
    doc["stage"] = [doc["stage"][0], CHAIN, doc["stage"][1]]
    doc["simulation"] = {"duration_s": 0.05, "steps": 200}
    return tomli_w.dumps(doc)


def test_the_campbell_points_of_a_train_with_a_plug_in_stage(chain):
    points = campbell(Scene(_text().encode(), "train.toml"), "input.speed_rpm", [1000, 1450], design_case)
    for p, n in zip(points, (1000.0, 1450.0), strict=True):
        # stage 1: pinion 19 at n; stage 3: pinion 19 at n / (75/19) / (34/17); the chain: no mesh
        assert p.mesh_Hz == pytest.approx((19 * n / 60, 0.0, 19 * n / (75 / 19) / 2 / 60), rel=1e-12)


def test_sweep_plots_of_a_train_with_a_plug_in_stage(chain, tmp_path):
    text = _text()
    path = tmp_path / "train.toml"
    path.write_text(text, encoding="utf-8")
    plots = tmp_path / "plots"
    r = CliRunner().invoke(cli, ["sweep", str(path), "--vary", "input.speed_rpm=1000,1450", "--jobs", "1",
                                 "-o", str(tmp_path / "rows.csv"), "--plots", str(plots), "-q"])
    assert r.exit_code == 0, r.output
    assert sorted(p.name for p in plots.iterdir()) == ["campbell.png", "response_input_speed_rpm.png"]
