"""`report` where the drive settles away from its nominal point, or nowhere (tr21b).

A VFD above its motor's base speed whose weakened curve cannot carry a fan load at ``speed_rpm`` stalls at the
first crossing of its curve with the load from rest, below its breakdown speed: the run settles there, so the
theory is taken there (it was the unreachable nominal point: -16 % speed and -30 % force "errors", and a dynamic
factor of 0.70 against the nominal load). A motor that cannot start, and a torque drive a constant load does not
balance, settle nowhere: the comparison gives no speed or force error (it was -3030 % and +114 %), only ratios.
The stall speed is computed here from docs/physics.md's extended Kloss curve (nameplate fit by hand, the VFD's
supply shift and (w_B / w_s')^2 field weakening, the torque limit's smooth minimum) against the quadratic load
reflected through the train (1 / eta per stage), with scipy's brentq: none of gearcli's motor code.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from gearcli import api
from gearcli.model import TorsionalModel
from gearcli.model.damping import settling_speed_rad_s
from gearcli.report.build import theory_point

RPM = 2 * math.pi / 60
I1, I2 = 75 / 19, 68 / 19
ETA = 0.98 ** 2

MOTOR_VFD = Path(__file__).resolve().parents[2] / "configs" / "motor_vfd.toml"  # 1300 N m, VFD 1460 rpm, 150 N m limit


def _scene(*overrides: str):
    loaded = api.load(str(MOTOR_VFD), list(overrides))
    return loaded, api.design(loaded)


def _hand_vfd_stall_rpm(n_in: float, load_Nm: float) -> float:
    """The first crossing from rest of the weakened VFD curve with the fan load (module text)."""
    tr, kb, kl, sr = 15e3 / (1460 * RPM), 2.8, 2.3, 40 / 1500
    tb = kb * tr

    def kloss(s, a, sb):
        return 2 * tb * (1 + a * sb) * s * sb / (s * s + sb * sb + 2 * a * sb * sb * abs(s))

    def a_of(sb):  # the locked-rotor point T(1) = kl tr, linear in a
        return (kl * tr * (1 + sb * sb) - 2 * tb * sb) / (2 * sb * sb * (tb - kl * tr))

    sb = brentq(lambda x: kloss(sr, a_of(x), x) - tr, sr * (1 + 1e-9), 1 - 1e-9, xtol=1e-15)
    a = a_of(sb)
    ws = (1500 + n_in - 1460) * RPM  # the supply shifted by the rated slip speed above speed_rpm
    db, scale, lim = sb * 1500 * RPM, (1500 * RPM / ws) ** 2, 150.0

    def motor(w):
        d = ws - w
        t = scale * 2 * tb * (1 + a * sb) * d * db / (d * d + db * db + 2 * a * sb * db * abs(d))
        return 0.5 * (t + lim - math.sqrt((t - lim) ** 2 + (0.02 * lim) ** 2))  # the limit's smooth minimum

    def net(w):
        return motor(w) - load_Nm * (w / (n_in * RPM)) ** 2 / (I1 * I2) / ETA

    grid = np.linspace(0.0, ws, 20001)
    f = np.array([net(w) for w in grid])
    k = next(j for j in range(grid.size - 1) if f[j] > 0.0 >= f[j + 1])
    return brentq(net, grid[k], grid[k + 1], xtol=1e-13) / RPM


def test_a_stalled_vfds_theory_is_where_it_settles():
    loaded, design = _scene("input.speed_rpm=3000", "load.speed_exponent=2")
    n = _hand_vfd_stall_rpm(3000.0, 1300.0)
    assert 2400 < n < 2530  # below the weakened curve's breakdown speed (2533 rpm): a stall, not the stable branch
    lay = TorsionalModel(api.model_spec(loaded.design, design)).layout
    assert settling_speed_rad_s(lay) / RPM == pytest.approx(n, rel=1e-9)
    p = theory_point(lay, design)
    assert p is not None and p.reached
    assert p.input_speed_deg_s / 6.0 == pytest.approx(n, rel=1e-9)
    assert p.load_factor == pytest.approx((n / 3000.0) ** 2, rel=1e-9)


def test_a_stalled_vfds_report_meets_its_stall_point():
    loaded, design = _scene("input.speed_rpm=3000", "load.speed_exponent=2")
    rep = api.report_file(loaded, design, quick=True)
    n = _hand_vfd_stall_rpm(3000.0, 1300.0)
    rows = {(r.stage, r.quantity): r for r in rep.comparison}
    assert rows[(None, "input_speed_deg_s")].theory / 6.0 == pytest.approx(n, rel=1e-9)
    # the run settles at the stall: its mean speed and force within 0.5 % of the hand point's (it was -16 %, -30 %)
    for key in ((None, "input_speed_deg_s"), (1, "tangential_N"), (2, "tangential_N")):
        assert abs(rows[key].error_percent) < 0.5
    # the dynamic factor against the load there, not the nominal 3000 rpm's (it was 0.70)
    for s in rep.stages:
        assert 1.0 <= s.dynamic_factor < 1.02
    # the stall warning stands under the comparison it qualifies
    from gearcli.io.report_sections import comparison_section
    assert any("stalls at" in note for note in comparison_section(rep).notes)


def test_a_motor_that_cannot_start_gives_no_speed_or_force_error():
    # 5000 N m reflected: 5000 / 14.127 / 0.9604 = 368.5 N m at the motor, over its 2.8 x 98.1 = 274.7 N m breakdown
    # and the VFD's 150 N m limit: it cannot start
    loaded, design = _scene("load.torque_Nm=5000", "simulation.duration_s=0.3")
    lay = TorsionalModel(api.model_spec(loaded.design, design)).layout
    assert settling_speed_rad_s(lay) is None
    rep = api.report_file(loaded, design, quick=True)
    assert rep.theory_point is not None and not rep.theory_point.reached
    for r in rep.comparison:
        assert (r.error_percent is not None) == (r.quantity == "ratio"), r
    from gearcli.io.report_sections import comparison_section
    notes = comparison_section(rep).notes
    assert any(note.startswith("NO steady operating point") for note in notes)
    assert any("cannot start" in note for note in notes)


@pytest.mark.parametrize(("exponent", "torque", "balanced"), [(0, 150.0, False), (0, 96.5, True), (2, 150.0, True)])
def test_a_torque_drive_settles_where_its_torque_meets_the_load(exponent, torque, balanced):
    # the load reflected at the nominal 1460 rpm: 1300 / (i1 i2) / eta = 95.81 N m; 96.5 is within the design check's
    # 1 % (a constant load: balanced at the nominal speed); a fan law balances 150 N m at 1460 sqrt(150 / 95.81)
    loaded, design = _scene("input.drive=torque", f"input.torque_Nm={torque}", f"load.speed_exponent={exponent}")
    lay = TorsionalModel(api.model_spec(loaded.design, design)).layout
    need = 1300.0 / (I1 * I2) / ETA
    w = settling_speed_rad_s(lay)
    if not balanced:
        assert w is None
        p = theory_point(lay, design)
        assert p is not None and not p.reached
    elif exponent == 0:
        assert w / RPM == pytest.approx(1460.0, rel=1e-12)
    else:
        assert w / RPM == pytest.approx(1460.0 * math.sqrt(torque / need), rel=1e-9)


def _hand_vfd_stable_rpm(load_Nm: float, limit: float) -> float:
    """The stable-branch crossing of the VFD's full curve at 1460 rpm (supply 1500 rpm, no field weakening) with a
    constant load, the torque limit's smooth minimum included (docs/physics.md), by brentq above the breakdown."""
    tr, kb, kl, sr = 15e3 / (1460 * RPM), 2.8, 2.3, 40 / 1500
    tb = kb * tr

    def kloss(s, a, sb):
        return 2 * tb * (1 + a * sb) * s * sb / (s * s + sb * sb + 2 * a * sb * sb * abs(s))

    def a_of(sb):
        return (kl * tr * (1 + sb * sb) - 2 * tb * sb) / (2 * sb * sb * (tb - kl * tr))

    sb = brentq(lambda x: kloss(sr, a_of(x), x) - tr, sr * (1 + 1e-9), 1 - 1e-9, xtol=1e-15)
    a, ws = a_of(sb), 1500 * RPM

    def net(w):
        t = kloss((ws - w) / ws, a, sb)
        return 0.5 * (t + limit - math.sqrt((t - limit) ** 2 + (0.02 * limit) ** 2)) - load_Nm / (I1 * I2) / ETA

    return brentq(net, (1 - sb) * ws, ws, xtol=1e-13) / RPM


def test_a_vfd_ramp_starts_a_load_its_full_curve_cannot_at_standstill():
    # 3380 N m: 249.1 N m at the motor, above the full curve's 2.3 x 98.1 = 225.6 N m at standstill and below the
    # 274.7 N m breakdown torque the ramp's low frequencies give: the ramp runs it up to the stable crossing. Was a
    # stall warning ("never reaches its operating point 1263.4 rpm") and, after the first fix, no theory at all
    loaded, design = _scene("load.torque_Nm=3380", "input.torque_limit_Nm=300")
    n = _hand_vfd_stable_rpm(3380.0, 300.0)
    lay = TorsionalModel(api.model_spec(loaded.design, design)).layout
    assert settling_speed_rad_s(lay) / RPM == pytest.approx(n, rel=1e-9)
    rep = api.report_file(loaded, design, quick=True)
    assert not any(d.code == "motor_stalls" for d in rep.diagnostics)
    rows = {(r.stage, r.quantity): r for r in rep.comparison}
    assert rows[(None, "input_speed_deg_s")].theory / 6.0 == pytest.approx(n, rel=1e-9)
    assert abs(rows[(None, "input_speed_deg_s")].error_percent) < 0.01


def test_a_vfd_that_falls_out_of_its_ramp_is_not_said_to_stall_at_standstill():
    # speed_rpm 3000, constant 1300 N m: the ramp runs the motor up at full flux; above ~2540 rpm of supply the
    # weakened breakdown torque (1500 / w_s)^2 274.7 N m falls below the 95.8 N m load and the motor falls out
    loaded, design = _scene("input.speed_rpm=3000")
    rep = api.report_file(loaded, design, quick=True)
    stall = [d.message for d in rep.diagnostics if d.code == "motor_stalls"]
    assert len(stall) == 1 and "ran it up to" in stall[0] and "at standstill" not in stall[0]
    assert rep.theory_point is not None and not rep.theory_point.reached
