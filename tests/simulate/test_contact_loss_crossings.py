"""The contact-loss and back-flank fractions split each sample interval where contact begins or ends at the
interpolated crossing, so they do not alias when the samples fall a whole number per mesh period.

Counting samples (the trapezoid rule of the flags) errs by up to a sample at each crossing, and where the output
samples sit at the same phases of every mesh period that error does not average out: the spur oscillator of
configs/spur_oscillator_te.toml at 2400 rpm, 40 samples a mesh period, read 0.400 (80 samples: 0.3875; sweep rows up
and down 0.400 / 0.375) against 0.388 of its continuous response, an independent solve_ivp model of the 1-DOF
backlash oscillator below. In contact the penetration is p = c_b q - h (DTE q, the gap's half h along the normal),
so the penetration the touching side would reach at the gap's sample is known, and the crossing is interpolated.

Closed forms: q = m + A cos(2 pi t) with the gap |q| <= h. For m = 1, A = 1, h = 0.5 the teeth are apart while
cos(2 pi t) <= -1/2, a third of the period; for m = 0 they are apart while |cos| <= 1/2 (a third) and on the back
flank while cos < -1/2 (from 2 pi/3 to 4 pi/3: a third).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from gearcli.simulate.stats import mesh_response


def _signals(m: float, n_per_period: int, periods: int, closing: bool, h: float = 0.5, cb: float = 0.94):
    n = n_per_period * periods + (1 if closing else 0)
    t = (np.arange(n) + 0.3) / n_per_period  # samples at the same phases of every period, none on a crossing
    q = m + np.cos(2 * np.pi * t)  # the DTE (um)
    a = cb * q * 1e-3  # the normal approach (mm); the gap's half h um along the transverse line
    half = cb * h * 1e-3
    pen = np.where(a > half, a - half, np.where(a < -half, a + half, 0.0))
    ft = 2e5 * pen  # a linear mesh: no force inside the gap
    return t, q, ft, pen


def _interpolation_error(crossings: int, n: int) -> float:
    """The bound of the linear interpolation's error, a fraction of the period: at a crossing of cos(2 pi t) the
    line through the two samples around it misses it by at most |f''/f'| dt^2 / 8 = 2 pi |cot| / (8 n^2) periods
    (|cot| = 0.58 at the crossings here, bounded by 1), once a crossing. Counting samples errs by up to 1/n."""
    return crossings * 2 * math.pi / (8 * n**2)


@pytest.mark.parametrize("n_per_period", [8, 12, 16, 40])
@pytest.mark.parametrize("periodic", [True, False])
def test_a_single_sided_loss_of_a_third_of_the_period_is_read_a_third(n_per_period, periodic):
    t, q, ft, pen = _signals(1.0, n_per_period, 5, closing=not periodic)
    got = mesh_response(t, slice(None), q, ft, pen, 1000.0, periodic=periodic)
    tol = _interpolation_error(2, n_per_period)
    assert got["contact_loss_fraction"] == pytest.approx(1 / 3, abs=tol)
    assert got["back_flank_fraction"] == 0.0
    assert got["regime"] == "single-sided impact"


@pytest.mark.parametrize("n_per_period", [12, 40])
def test_a_double_sided_rattle_reads_its_gap_and_back_flank_times(n_per_period):
    t, q, ft, pen = _signals(0.0, n_per_period, 4, closing=False)
    got = mesh_response(t, slice(None), q, ft, pen, 1000.0, periodic=True)
    tol = _interpolation_error(4, n_per_period)
    assert got["contact_loss_fraction"] == pytest.approx(1 / 3, abs=tol)  # |cos| <= 1/2
    assert got["back_flank_fraction"] == pytest.approx(1 / 3, abs=tol)  # cos < -1/2
    assert got["regime"] == "double-sided impact"


def _reference_loss_fraction(rpm: float) -> float:
    """The 1-DOF oscillator of configs/spur_oscillator_te.toml by hand: the pinion speed-driven, the gear's
    J = 0.0063 kg m² on r_b = 25 * 3 mm * cos 20° / 2 (m_e = J / r_b²), a linear mesh k = 2e5 N/mm with
    0.1 mm backlash (h = 0.05 mm), viscous c = 2 zeta sqrt(k m_e), zeta = 0.05, TE e = 5 um sin(z w t), load
    F_0 = 70.5 N m / r_b: m_e d'' + c d' + F(d - e) = F_0; the fraction of the settled time with |d - e| <= h."""
    rb = 25 * 3.0e-3 * math.cos(math.radians(20.0)) / 2
    me, k, h, e = 0.0063 / rb**2, 2e8, 0.05e-3, 5e-6
    c, f0, om = 2 * 0.05 * math.sqrt(k * me), 70.5 / rb, 25 * rpm * 2 * math.pi / 60

    def rhs(t, y):
        q = y[0] - e * math.sin(om * t)
        force = k * (q - h) if q > h else (k * (q + h) if q < -h else 0.0)
        return [y[1], (f0 - force - c * y[1]) / me]

    period = 2 * math.pi / om
    end = 150 * period
    sol = solve_ivp(rhs, (0.0, end), [f0 / k + h, 0.0], method="DOP853", rtol=1e-9, atol=1e-13, dense_output=True,
                    max_step=period / 40)
    tt = np.linspace(end - 20 * period, end, 20 * 5000, endpoint=False)
    q = sol.sol(tt)[0] - e * np.sin(om * tt)
    return float(np.mean(np.abs(q) <= h))


def test_the_spur_oscillator_sampled_40_times_a_mesh_period_reads_its_continuous_loss_fraction():
    ref = _reference_loss_fraction(2400.0)
    assert ref == pytest.approx(0.388, abs=0.002)
    got = [_simulate(2400.0, steps) for steps in (2000, 4000, 8000)]  # 20, 40 and 80 samples a 1 ms mesh period
    assert got == pytest.approx([ref] * 3, abs=0.003)  # was 0.400, 0.400, 0.3875


def _simulate(rpm: float, steps: int) -> float:
    import json
    from pathlib import Path

    from click.testing import CliRunner

    from gearcli.cli import cli

    scene = Path(__file__).resolve().parents[2] / "configs" / "spur_oscillator_te.toml"
    res = CliRunner().invoke(cli, ["simulate", str(scene), "--set", f"input.speed_rpm={rpm}", "--set",
                                   "simulation.duration_s=0.1", "--set", f"simulation.steps={steps}", "--set",
                                   "simulation.window_start_s=0.05", "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)["summary"]["stages"][0]["contact_loss_fraction"]
