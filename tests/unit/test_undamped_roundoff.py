"""An undamped chain is undamped, not damped by the eigen solver's roundoff (robustness campaign, round 4).

configs/extreme/zero_damping.toml and rattle_zero_load.toml have no damping anywhere. The eigenvalues of their
linearised chains came out with real parts of 1e-30 .. 1e-15 of their magnitude (roundoff), which the outputs
read as damping: "decay time 1.98e+28 s, 7.1e-30 % of critical damping ... a window from about 7.11e+28 s on
(simulation.window_start_s = 7.11e+28)" and resonances "1.7e+15x its blocked error force". A mode decaying by
less than 1e-6 per period (an e-fold after a million periods) is undamped.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.model.damping import UNDAMPED_PER_PERIOD, decay_rate, modal_damping_ratios
from gearcli.simulate import ringing

ROOT = Path(__file__).resolve().parents[2]


def _two_mass(c: float):
    # by hand: J = 1 kg m^2 each, a spring k = 1e6 N m/rad to ground on body 1 and k between them; C = c between
    # them. Undamped modes from det(K - w^2 J) = 0: w^2 = k (3 -+ sqrt 5) / 2
    k = 1e6
    J = np.array([1.0, 1.0])
    K = np.array([[2 * k, -k], [-k, k]])
    C = np.array([[c, -c], [-c, c]])
    w2, shapes = np.linalg.eigh(K)  # J = I
    assert np.allclose(w2, k * (3 - np.array([1, -1]) * math.sqrt(5)) / 2, rtol=1e-12)
    return J, K, C, shapes, np.sqrt(w2)


def test_an_undamped_chain_has_zero_modal_damping_exactly():
    J, K, C, shapes, omega = _two_mass(0.0)
    assert list(modal_damping_ratios(J, K, C, shapes, omega)) == [0.0, 0.0]


def test_a_lightly_damped_chain_keeps_its_damping():
    # by hand: the second mode's shape is (1.618, -1) (any scale), relative motion 2.618, phi^T J phi = 3.618;
    # modal damping of c between the bodies: zeta = phi^T C phi / (2 w phi^T J phi) = c 2.618^2 / (2 w 3.618),
    # well above the undamped limit
    J, K, C, shapes, omega = _two_mass(0.5)
    zeta = modal_damping_ratios(J, K, C, shapes, omega)
    expected = 0.5 * ((1 + math.sqrt(5)) / 2 + 1) ** 2 / (2 * omega[1] * (1 + ((1 + math.sqrt(5)) / 2) ** 2))
    assert zeta[1] == pytest.approx(expected, rel=1e-3)  # light damping: the projection and eig agree to O(zeta^2)
    assert 2 * math.pi * zeta[1] > UNDAMPED_PER_PERIOD


def test_decay_rate_reads_roundoff_as_undamped():
    w = 2 * math.pi * 112.0
    assert decay_rate(complex(-1e-15 * w, w)) == 0.0  # roundoff
    assert decay_rate(complex(+1e-15 * w, w)) == 0.0  # roundoff the other way: not growing either
    assert decay_rate(complex(-0.5, w)) == 0.5  # zeta 7e-4: 4.5e-3 per period, damped
    assert decay_rate(complex(-1e-6 * w / (2 * math.pi), w)) == pytest.approx(1e-6 * w / (2 * math.pi))  # at the limit


def test_a_roundoff_mode_rings_undamped():
    w = 2 * math.pi * 112.0
    modes = ringing.slow_modes(np.array([complex(-7e-32 * w, w), complex(-7e-32 * w, -w)]), (0.244, 0.5))
    assert modes == [(0.0, w)]


def test_the_zero_damping_scene_warns_undamped_never_a_window_at_1e28_s(tmp_path):
    out = tmp_path / "run.json"
    res = CliRunner().invoke(cli, ["simulate", str(ROOT / "configs" / "extreme" / "zero_damping.toml"), "-o", str(out)])
    assert res.exit_code == 0, res.output
    ringing_warnings = [w for w in json.loads(out.read_text())["warnings"] if w["code"] == "window_ringing"]
    assert ringing_warnings, "the run-up vibration of an undamped chain rings through the window"
    for w in ringing_warnings:
        assert w["decay_time_s"] is None and w["settle_time_s"] is None and w["damping_ratio"] == 0.0
        assert "a later window does not help (the mode is undamped)" in w["message"]
