"""Planet pins and central members of a lossy planetary stage against the stage's moment balance (tr23f).

With a stage efficiency below 1 the sun, ring and carrier torques no longer stand in the lossless ratio
1 : u : -(1 + u). Whatever the friction inside the meshes, each member's external torque is carried by the
forces the planets exert on it, so the statics must close three exact balances (per planet, N identical equally
spaced planets, K_gamma = 1):
- the carrier: the pin forces' tangential sum is |T_c| / (N r_c), r_c the carrier radius (a pin bearing carries
  the carrier's reaction, and nothing else reaches the carrier);
- the sun: its tooth forces' tangential sum is |T_s| / (N r_w,s), so its axial force is |T_s| tan(beta) / r_w,s;
- a rotating ring: |T_r| tan(beta) / r_w,r on its locating bearing.
The torques come from textbook efficiencies (Mueller; Niemann-Winter, the basic efficiency eta_0 of the stage with
the carrier held), written here without gearcli:
- ring held, sun in:     eta = (1 + eta_0 u) / (1 + u),   |T_r| = eta_0 u |T_s|     (sun drives, carrier frame)
- carrier held, sun in:  eta = eta_0,                     |T_r| = eta_0 u |T_s|
- ring held, carrier in: eta = (1 + u) / (1 + u / eta_0), |T_r| = u |T_s| / eta_0   (ring drives)
and |T_c| = |T_s| + |T_r| (the three sum to zero). The statics took the sun mesh's (driving-side) line force for
both meshes of every planet: 1/eta = 3.1 % too much on the pins of a sun-driven stage of eta 0.97 (the design's
pin load 622.47 N per bearing against 603.79 N), 1 % too little on a carrier-driven one, and the sun-mesh force on a
rotating ring's axial bearing.
"""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from tests.life.scenes import design_of
from tests.life.test_planetary_bearings import BETA, K_GAMMA, M_N, PLANETARY, SPAN, Z_P, Z_R, Z_S, N

ETA = 0.97
T_OUT = 400.0  # N m on the output member (the file's load)
U = Z_R / Z_S


def _eta0(fixed: str, driven: str) -> float:
    if (fixed, driven) == ("ring", "sun"):
        return (ETA * (1 + U) - 1) / U
    if (fixed, driven) == ("carrier", "sun"):
        return ETA
    return U * ETA / (1 + U - ETA)  # ring held, carrier in


def _torques(fixed: str, driven: str) -> tuple[float, float, float]:
    """|T_s|, |T_r|, |T_c| in N mm for T_OUT on the output member."""
    e0 = _eta0(fixed, driven)
    if (fixed, driven) == ("ring", "sun"):  # carrier out: |T_c| = |T_s| (1 + eta_0 u)
        t_s = T_OUT / (1 + e0 * U)
        t_r = e0 * U * t_s
    elif (fixed, driven) == ("carrier", "sun"):  # ring out
        t_r = T_OUT
        t_s = t_r / (e0 * U)
    else:  # sun out, the ring drives in the carrier's frame
        t_s = T_OUT
        t_r = U * t_s / e0
    return 1e3 * t_s, 1e3 * t_r, 1e3 * (t_s + t_r)


def _scene(fixed: str, driven: str) -> str:
    text = PLANETARY.replace('fixed = "ring"\ninput = "sun"', f'fixed = "{fixed}"\ninput = "{driven}"\nefficiency = {ETA}')
    text = text.replace(f"load_sharing_factor = {K_GAMMA}", "load_sharing_factor = 1.0")
    text = text.replace('ring = { teeth', 'ring = { axial_position_mm = 100, teeth')
    assert f"efficiency = {ETA}" in text and "load_sharing_factor = 1.0" in text and "ring = { axial" in text
    return text


ARRANGEMENTS = [("ring", "sun"), ("carrier", "sun"), ("ring", "carrier")]


@pytest.mark.parametrize(("fixed", "driven"), ARRANGEMENTS)
def test_lossy_stage_pins_carry_the_carrier_torque(fixed, driven):
    _, design = design_of(_scene(fixed, driven))
    t_s, t_r, t_c = _torques(fixed, driven)
    mt = M_N / math.cos(math.radians(BETA))
    r_ws, r_wp = 0.5 * Z_S * mt, 0.5 * Z_P * mt  # x = 0: working = reference circles
    # the design's own balance is the textbook's (the hand's eta_0 is right for the arrangement)
    moments = design.stages[0].planetary.moment_balance_Nm
    assert_allclose([abs(moments["sun"]), abs(moments["ring"]), abs(moments["carrier"])],
                    [t_s / 1e3, t_r / 1e3, t_c / 1e3], rtol=1e-9)
    pins = [b for b in design.bearings if b.planet_stage == 1]
    tangential = t_c / (N * (r_ws + r_wp))  # the pin's load: the carrier's reaction per planet
    assert_allclose(sum(abs(b.radial_z_N) for b in pins), tangential, rtol=1e-9)
    # the planet's two meshes' axial forces (F_t tan(beta) each, at r_w,p either side of its axis): a couple
    couple = 2 * (0.5 * tangential) * math.tan(math.radians(BETA)) * r_wp / SPAN
    for b in pins:
        assert_allclose(abs(b.radial_y_N), couple, rtol=1e-9)


@pytest.mark.parametrize(("fixed", "driven"), ARRANGEMENTS)
def test_lossy_stage_central_members_carry_their_own_torque(fixed, driven):
    _, design = design_of(_scene(fixed, driven))
    t_s, t_r, _ = _torques(fixed, driven)
    mt = M_N / math.cos(math.radians(BETA))
    r_ws, r_wr = 0.5 * Z_S * mt, 0.5 * Z_R * mt
    tan_b = math.tan(math.radians(BETA))
    shaft = {driven: 1, ({"sun", "ring", "carrier"} - {fixed, driven}).pop(): 2}
    for member, torque, radius in (("sun", t_s, r_ws), ("ring", t_r, r_wr)):
        if member not in shaft:
            continue
        loc = next(b for b in design.bearings if b.shaft == shaft[member] and b.locating)
        assert_allclose(abs(loc.axial_N), torque * tan_b / radius, rtol=1e-9)
