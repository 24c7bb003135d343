"""Field test: a parametric instability on a lightly damped linear mesh is named as a growth, not as a decaying
transient with a settle time.

One linear spur mesh (the pinion speed-driven, the gear J = 0.0063 kg m^2 free: f_n = 999.3 Hz) with a first
stiffness harmonic s = 0.2 at mesh frequency 2 f_n and mesh damping zeta = 0.02, below the damped Mathieu
equation's threshold s / 4 > zeta (first order): the response grows as exp(sigma t). The reference growth rate
sigma = ln|mu| / T is the largest Floquet multiplier mu of q'' + 2 zeta w_n q' + w_n^2 (1 - s cos(Omega t)) q = 0
over one mesh period T, computed here with scipy (close to the first-order (s / 4 - zeta) w_n = 188 1/s).

Before the fix, the transient fit (whose modes only decay) took the growth for a mode ringing "from the start
with +-5.3e12 N" that "would be settled from about 0.85 s" (steady.settle_time_s 0.85): a later window never
settles it. The model-free growth test ran only where that fit found the window settled, as it does with
zeta = 0.05, whose start-up has decayed before the window (tests/field/test_field_excitation_by_hand.py).
"""

from __future__ import annotations

import csv
import json
import math
import re

import numpy as np
import pytest
from click.testing import CliRunner
from scipy.integrate import solve_ivp
from test_field_excitation_by_hand import TE_SCENE

from gearcli.cli import cli

K = 2e5  # N/mm
ZETA = 0.02
S = 0.2
R_B_M = 25 * 3e-3 * math.cos(math.radians(20.0)) / 2
M_E = 0.0063 / R_B_M**2  # kg
W_N = math.sqrt(K * 1e3 / M_E)  # rad/s
SPEED_RPM = 2 * W_N / (2 * math.pi) * 60 / 25  # mesh frequency 25 n / 60 = 2 f_n

# the hand TE scene of the neighbouring field test, its error off, the harmonic and the light damping set
SCENE = TE_SCENE.format(speed=repr(SPEED_RPM), steady="")
SETS = ["--set", "contact.transmission_error_um=[0.0]", "--set", f"contact.stiffness_harmonics=[{S}]",
        "--set", f"contact.damping_ratio={ZETA}"]


def floquet_rate() -> float:
    """sigma = ln(max |multiplier|) / T of the damped Mathieu equation at the scene's mesh frequency."""
    om = 25 * SPEED_RPM / 60 * 2 * math.pi

    def f(t, y):
        return [y[1], -2 * ZETA * W_N * y[1] - W_N**2 * (1 - S * math.cos(om * t)) * y[0]]

    period = 2 * math.pi / om
    cols = [solve_ivp(f, (0, period), y0, rtol=1e-12, atol=1e-14).y[:, -1] for y0 in ([1.0, 0.0], [0.0, 1.0])]
    return math.log(float(np.max(np.abs(np.linalg.eigvals(np.column_stack(cols)))))) / period


def test_growth_under_light_damping_is_no_ringing_transient(tmp_path):
    path = tmp_path / "mathieu.toml"
    path.write_text(SCENE)
    sigma = floquet_rate()
    assert sigma == pytest.approx((S / 4 - ZETA) * W_N, rel=0.05)  # the first-order rate: a sanity check
    runner = CliRunner()
    out = runner.invoke(cli, ["simulate", str(path), *SETS, "--format", "csv"])
    assert out.exit_code == 0, out.output
    rows = list(csv.DictReader(line for line in out.stdout.splitlines() if not line.startswith("#")))
    t = np.array([float(r["time_s"]) for r in rows])
    q = np.array([float(r["stage1_dte_um"]) for r in rows])

    def ptp(a: float, b: float) -> float:
        part = q[(t >= a) & (t < b)]
        return float(np.ptp(part))

    # the run grows at the Floquet rate (10 ms envelopes, 20 cycles each): the model is unstable where theory says
    measured = math.log(ptp(0.13, 0.14) / ptp(0.08, 0.09)) / 0.05
    assert measured == pytest.approx(sigma, rel=0.02)
    data = json.loads(runner.invoke(cli, ["simulate", str(path), *SETS, "--format", "json"]).stdout)
    steady = data["summary"]["steady"]
    assert steady["settled"] is False
    assert steady["settle_time_s"] is None  # no later window settles an instability
    (warning,) = [w for w in data["warnings"] if w["code"] == "window_not_settled"]
    assert "grows through the window" in warning["message"] and warning["stage"] == 1
    assert "would be settled" not in warning["message"]


def test_periodic_search_names_the_unstable_orbit(tmp_path):
    """steady = "periodic" on the same scene: the shooting finds the periodic orbit (the linear mesh has one) and
    its multiplier outside the unit circle (below -1: it retries over two periods, then falls back to brute
    force, which cannot converge on a growing motion). The fallback's warning names the multiplier, which equals
    the Floquet multiplier over two mesh periods computed here, exp(2 sigma T). Before the fix the fallback
    after the period-2 retry's note was not recognised (its note did not start with it): no warning, only
    `not_periodic`'s "chaotic or quasi-periodic, or still settling; lengthen simulation.duration_s"."""
    path = tmp_path / "mathieu.toml"
    path.write_text(SCENE)
    out = CliRunner().invoke(cli, ["simulate", str(path), *SETS, "--set", 'simulation.steady="periodic"',
                                   "--format", "json"])
    assert out.exit_code == 0, out.output
    data = json.loads(out.stdout)
    assert data["summary"]["steady"]["converged"] is False
    (fallback,) = [w for w in data["warnings"] if w["code"] == "shooting_fallback"]
    found = re.search(r"unstable \(Floquet multiplier of modulus ([0-9.]+)\)", fallback["message"])
    assert found is not None, fallback["message"]
    period = 60 / (25 * SPEED_RPM)
    assert float(found.group(1)) == pytest.approx(math.exp(2 * floquet_rate() * period), abs=6e-4)  # 4 digits
