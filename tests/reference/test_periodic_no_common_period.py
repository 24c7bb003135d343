"""``steady = "periodic"`` where the excitations share no period: the statistics are the motion's, not a fake orbit's.

Scene: configs/spur_oscillator_te.toml made linear (no backlash: e = 1 acts on both flanks) and run at 2300 rpm, its
5 um transmission error at the 958 Hz mesh frequency near the 999 Hz mesh mode, and a load fluctuation of 20 % at 77.7 Hz, which no rational ratio (with the
denominators the period search allows) ties to the mesh period. The response is quasi-periodic: no periodic orbit
exists. Shooting over the slowest excitation's period found a "fixed point" x(T) = x(0) anyway (converged, period-1),
which closes the period by adding free vibration of the mesh mode: here F_t std 4175 N against the motion's 4917 N,
max 9439 N beyond the largest the motion can reach (9201 N); on a two-stage version the std came out 26 % high.

Reference: the scene is a linear single-degree-of-freedom oscillator (the input speed prescribed, the gear free):
m_e q'' + c q' + k q = T_L(t) / r_bg - m_e e''(t), q the dynamic transmission error, m_e = J_g / r_bg^2,
c = 2 zeta sqrt(k m_e); its steady response is the sum of the two harmonic responses, whose F_t = (k q + c q')
cos alpha_t has the variance of the sum of both amplitudes squared over 2 (distinct frequencies), and swings
between the static force minus and plus the sum of both amplitudes (the two phases drift through every pairing).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.simulate import run_simulation

SCENE = Path(__file__).resolve().parents[2] / "configs" / "spur_oscillator_te.toml"
FLUCTUATION_HZ, FLUCTUATION = 77.7, 0.20
SETS = ["stage.0.backlash_mm=0", f"load.fluctuation=[{{amplitude_percent={FLUCTUATION * 100:g}, "
        f"frequency_Hz={FLUCTUATION_HZ}}}]", "simulation.steady=periodic", "simulation.duration_s=0.5", "input.speed_rpm=2300"]
# the scene's numbers (configs/spur_oscillator_te.toml)
M_N, Z_P, Z_G, ALPHA = 3e-3, 25, 25, math.radians(20.0)
J_G, K, ZETA, TE, T_L, RPM = 0.0063, 2e5 * 1e3, 0.05, 5e-6, 70.5, 2300.0


def _hand_amplitudes_N() -> tuple[float, float]:
    """The F_t amplitudes of the linear oscillator's steady response to the transmission error and to the load."""
    r_bg = Z_G * M_N / 2 * math.cos(ALPHA)
    m_e = J_G / r_bg ** 2
    c = 2 * ZETA * math.sqrt(K * m_e)

    def amplitude(w: float, force: float) -> float:  # |F| of the response to a harmonic force on the DTE
        q = force / complex(K - m_e * w ** 2, c * w)
        return abs(complex(K, c * w) * q) * math.cos(ALPHA)

    w_mesh = 2 * math.pi * Z_P * RPM / 60
    w_load = 2 * math.pi * FLUCTUATION_HZ
    te = amplitude(w_mesh, m_e * w_mesh ** 2 * TE)  # -m_e e'' = m_e w^2 e
    return te, amplitude(w_load, FLUCTUATION * T_L / r_bg)


@pytest.fixture(scope="module")
def sim():
    cfg = load_design(str(SCENE), SETS).design
    return run_simulation(cfg, compute_design(cfg), want_series=False)


def test_no_common_period_is_searched_by_the_motion_not_by_newton(sim):
    st = sim.steady
    assert st.method == "brute force" and not st.converged and st.periodicity == "none"
    assert "no common period" in st.note


def test_the_window_statistics_are_the_quasi_periodic_motions(sim):
    stage = sim.stages[0]
    static = 2 * T_L / (Z_G * M_N)
    te, load = _hand_amplitudes_N()
    # the window holds whole periods of neither excitation: its mean is off the static force by at most each
    # amplitude over pi x the cycles the window holds of it (the integral of a partial cycle)
    span = sim.window_s[1] - sim.window_s[0]
    bias = te / (math.pi * span * Z_P * RPM / 60) + load / (math.pi * span * FLUCTUATION_HZ)
    assert abs(stage.tangential_N.mean - static) <= bias
    assert stage.tangential_N.std == pytest.approx(math.sqrt((te ** 2 + load ** 2) / 2), rel=1e-2)
    # within the motion's bounds (the window's samples reach them to a few per cent of the amplitudes)
    assert static - te - load <= stage.tangential_N.min <= static - 0.97 * (te + load)
    assert static + 0.97 * (te + load) <= stage.tangential_N.max <= static + te + load


def test_the_report_reads_the_lines_between_the_bins():
    """No repetition found (``periodicity`` "none"): the window's whole periods of the load fluctuation hold no
    whole number of mesh cycles, so the report's spectrum is the Hann-weighted one, whose peak and 1x mesh order
    are the hand TE line; the plain DFT of those samples read the peak's bin at 5756 N (scalloping) and the order's
    rectangular projection 6934.75 N with 19.2 N of leakage at 2x, where the linear response has no 2x line."""
    from click.testing import CliRunner

    from gearcli.cli import cli

    te, _ = _hand_amplitudes_N()
    args = ["report", str(SCENE), "--quick", "--format", "json", "-q"] + [x for s in SETS for x in ("--set", s)]
    res = CliRunner().invoke(cli, args)
    assert res.exit_code == 0, res.output
    sp = json.loads(res.output)["dynamics"][0]["spectrum"]
    assert sp["peak_amplitude_N"] == pytest.approx(te, rel=5e-4)
    orders = {o["order"]: o["tangential_N"] for o in sp["mesh_orders"]}
    assert orders[1] == pytest.approx(te, rel=5e-4)
    assert orders[2] < 1e-4 * te
