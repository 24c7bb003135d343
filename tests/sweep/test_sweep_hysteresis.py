"""Continuation shows the jump of a backlash oscillator at different speeds up and down.

configs/spur_oscillator_te.toml: one spur mesh with backlash (a Kahraman & Singh type oscillator), the
pinion speed-driven, the loaded gear free, excited by a first-harmonic transmission error e at the mesh
frequency. Backlash is a softening nonlinearity (the spring vanishes while the teeth are apart), so the
resonance curve bends toward lower speeds, and over a band of speeds below the linear resonance a quiet
branch (teeth always in contact) and an impacting branch (contact lost every cycle) coexist (Kahraman &
Singh, J. Sound Vib. 142 (1990) 49-75): sweeping up stays quiet into the band and jumps late; sweeping
down stays on the impacting branch through the band and drops out early. A cold start at each speed
could not show this: continuation (with the mesh phase carried on) is what keeps the branch.

Independent references, by hand from the file's data:
- the linear resonance: m_e = J_g / r_bg^2, f_n = sqrt(k / m_e) / 2 pi, reached by the mesh frequency
  z_p n / 60 at n_res = 60 f_n / z_p;
- where the quiet branch ends: while the teeth stay in contact the mesh is linear and the DTE vibrates with
  the base-excitation amplitude X(r) = e r^2 / sqrt((1 - r^2)^2 + (2 zeta r)^2) (r = mesh frequency / f_n)
  about the static deflection p0 = F / k; the teeth separate once X > p0, so the up sweep must stay quiet
  below the speed where X = p0 and jump at the first speed above it, which lies below n_res (softening).
"""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path

from click.testing import CliRunner
from numpy.testing import assert_allclose
from scipy.optimize import brentq

from gearcli.cli import cli

SCENE = str(Path(__file__).resolve().parents[2] / "configs" / "spur_oscillator_te.toml")

# configs/spur_oscillator_te.toml
Z_P, MODULE_M, ALPHA_DEG = 25, 3e-3, 20.0
J_GEAR, K, ZETA, E_TE, T_LOAD = 0.0063, 2e8, 0.05, 5e-6, 70.5  # kg m^2, N/m, -, m, N m
R_BG = MODULE_M * 25 * math.cos(math.radians(ALPHA_DEG)) / 2  # base radius of the gear
F_N = math.sqrt(K / (J_GEAR / R_BG**2)) / (2 * math.pi)  # 999 Hz
N_RES = 60 * F_N / Z_P  # rpm: mesh frequency = f_n
P0 = T_LOAD / R_BG / K  # static deflection, 10 um


def linear_amplitude(rpm: float) -> float:
    r = Z_P * rpm / 60 / F_N
    return E_TE * r**2 / math.sqrt((1 - r**2) ** 2 + (2 * ZETA * r) ** 2)


N_UP = brentq(lambda n: linear_amplitude(n) - P0, 0.5 * N_RES, N_RES)  # the quiet branch ends: ~1970 rpm


def test_jump_up_and_jump_down_happen_at_different_speeds():
    # short runs: a continued point starts on its branch, 30 ms (10 time constants 1 / (zeta w_n)) settle
    res = CliRunner().invoke(cli, ["sweep", SCENE, "--vary", "input.speed_rpm=1600:2400:9", "--direction", "both",
                                   "--jobs", "1", "--set", "simulation.duration_s=0.06",
                                   "--set", "simulation.steps=2400", "--set", "simulation.window_start_s=0.03"])
    assert res.exit_code == 0, res.stderr
    rows = list(csv.DictReader(io.StringIO(res.stdout)))
    assert {r["status"] for r in rows} == {"ok"}
    branch = {d: {float(r["input.speed_rpm"]): r for r in rows if r["direction"] == d} for d in ("up", "down")}
    speeds = sorted(branch["up"])
    assert sorted(branch["down"]) == speeds

    def impacts(r):  # the teeth separated in the steady window
        return float(r["stage1_contact_loss_fraction"]) > 0.0

    up = [impacts(branch["up"][s]) for s in speeds]
    down = [impacts(branch["down"][s]) for s in speeds]
    assert not up[0] and not down[0], "at the lowest speed both branches are quiet"
    assert up[-1] and down[-1], "at resonance both branches impact"
    jump_up = speeds[up.index(True)]
    assert all(up[up.index(True):]), "the up branch stays on the impacting branch once it jumped"
    drop_down = speeds[max(i for i, d in enumerate(down) if not d) + 1]  # lowest speed of the impacting run down
    assert all(down[speeds.index(drop_down):])

    # the up jump: at the first grid speed past the end of the quiet branch, below the linear resonance
    assert max(s for s in speeds if s < N_UP) < jump_up, (jump_up, N_UP)
    assert jump_up == min(s for s in speeds if s > N_UP), (jump_up, N_UP)
    assert N_UP < jump_up < N_RES
    # the down branch holds on to the impacts below that: hysteresis
    assert drop_down < jump_up, f"no hysteresis: up jumps at {jump_up}, down drops out at {drop_down}"
    band = [s for s, u, d in zip(speeds, up, down, strict=True) if d and not u]
    assert band == [s for s in speeds if drop_down <= s < jump_up] and len(band) >= 2

    for s in (s for s in speeds if s < N_UP):  # the quiet up branch is the linear response (rms = X / sqrt 2)
        assert_allclose(float(branch["up"][s]["stage1_dte_um_rms"]), linear_amplitude(s) / math.sqrt(2) * 1e6,
                        rtol=0.02, err_msg=f"{s} rpm")
    for s in band:  # the coexisting branches differ: the impacting one loses contact for a good part of each
        # cycle and vibrates several times more
        lo, hi = branch["up"][s], branch["down"][s]
        assert float(lo["stage1_contact_loss_fraction"]) == 0.0 < 0.3 < float(hi["stage1_contact_loss_fraction"])
        assert float(hi["stage1_dte_um_rms"]) > 3 * float(lo["stage1_dte_um_rms"])
    for s in speeds:  # where only one branch exists, up and down agree
        if s not in band:
            assert_allclose(float(branch["down"][s]["stage1_dte_um_rms"]), float(branch["up"][s]["stage1_dte_um_rms"]),
                            rtol=0.02, err_msg=f"{s} rpm")
