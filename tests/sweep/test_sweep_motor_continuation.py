"""A continued point of a motor-driven speed sweep starts at its own operating speed, not at the previous point's.

docs/sweeps.md: a continued point starts from the previous point's final state with "every shaft's speed moved along
the rigid-body motion to the new operating speed (its deviation from rigid motion kept)". A motor drive's model
starts cold from rest, and the move took the rest speed (0) as both points' rigid speed: the speeds were kept as
they were. configs/motor_vfd.toml (a VFD on a nameplate motor, constant load torque) swept 1400 -> 1000 rpm started
the 1000 rpm point with the motor at 1400 rpm and warned that it "runs away: it passes 1.1 x its synchronous speed
1040 rpm at 0 s" (it was only braking down from the old speed); swept 600 -> 1000 rpm the point ran up from 600 rpm,
a run-up factor of 1.10.

By hand: under a constant load torque the static mesh forces do not depend on the speed, so the previous point's
equilibrium (its deflections), moved rigidly to the new speed, is the new point's equilibrium with the motor at the
same slip: nothing runs up (run-up factor 1: the whole run's peak |F_t| is the static F_t), nothing runs away, and the
mean F_t is the cold start's at that speed.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.scene import build_model
from gearcli.sweep.continuation import NO_RAMPS, continue_state

VFD = Path(__file__).resolve().parents[2] / "configs" / "motor_vfd.toml"


def _model(rpm: float):
    cfg = load_design(str(VFD), [*NO_RAMPS, f"input.speed_rpm={rpm}"]).design
    return build_model(cfg, compute_design(cfg))


def test_the_motor_and_every_shaft_move_rigidly_to_the_new_speed():
    old, new = _model(1400), _model(1000)
    lay = old.layout
    ratios = [1.0, 1.0, 19 / 75, 19 / 75 * 19 / 68]  # rotor, input shaft (coupling), shafts 2 and 3: tooth counts
    w_old, w_new = 1400 * np.pi / 30, 1000 * np.pi / 30
    deviation = np.array([-0.9, -0.85, 0.02, -0.01])  # the motor's slip and a vibration about the rigid motion
    omega = [lay.i_omega(i) for i in range(lay.n_bodies)]
    y = np.zeros(lay.state.n_states)
    y[:lay.n_conn] = np.linspace(1e-5, 3e-5, lay.n_conn)
    y[omega] = np.array(ratios) * w_old + deviation
    y0 = continue_state(y, old, new)
    assert y0 is not None
    assert_allclose(y0[:lay.n_conn], y[:lay.n_conn], rtol=0, atol=0)  # the deflections kept
    assert_allclose(y0[omega], np.array(ratios) * w_new + deviation, rtol=1e-12)  # was 1400 rpm's speeds


def test_a_continued_motor_point_starts_at_its_own_speed(tmp_path):
    out = tmp_path / "vfd.csv"
    res = CliRunner().invoke(cli, ["sweep", str(VFD), "--vary", "input.speed_rpm=1000,1400", "--direction", "both",
                                   "--jobs", "1", "-q", "-o", str(out)])
    assert res.exit_code == 0, res.output
    lines = [ln for ln in out.read_text(encoding="utf-8").splitlines() if not ln.startswith("#")]
    rows = {(r["input.speed_rpm"], r["direction"]): r for r in csv.DictReader(lines)}
    for key, cold in ((("1400", "up"), ("1400", "down")), (("1000", "down"), ("1000", "up"))):
        row = rows[key]  # continued from the other speed
        assert "runs away" not in row["message"] and "backwards" not in row["message"], row["message"]
        for k in (1, 2):
            assert float(row[f"stage{k}_runup_factor"]) == pytest.approx(1.0, abs=1e-6)
            assert float(row[f"stage{k}_tangential_N_mean"]) == pytest.approx(
                float(rows[cold][f"stage{k}_tangential_N_mean"]), rel=1e-6)
        assert float(row["output_speed_rpm"]) == pytest.approx(float(rows[cold]["output_speed_rpm"]), rel=1e-6)
