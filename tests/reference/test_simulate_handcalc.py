"""`simulate` from a design file against hand numbers, on trains nobody tuned (found by the independent audit's
seeded generator: module, teeth, helix, pressure angle, shifts, widths, efficiencies, speed and load drawn at random).

The default mesh law (DESIGN §13: iso6336-calibrated, e = 1.5, viscous zeta = 0.05) and stage efficiency in the
dynamics (§9). Once the run-up has died out, the window means obey the statics whatever the vibration does: the
mean of each shaft's acceleration is zero, so the mean line force of every mesh carries the load down the chain
with the design's losses (F_t = T_pinion / r_pinion, T_pinion = T_gear / (i η)), F_r = F_t tan α_t, F_a = F_t tan β,
and the mean speeds keep the ratio chain z_gear / z_pinion. Hand values, written out below.
"""

from __future__ import annotations

import io
import math

import pytest
from numpy.testing import assert_allclose

from gearcli import api
from gearcli.config import load_design
from gearcli.design import compute_design

# (m_n, alpha_n, beta, z1, z2, b1, b2, x1, x2, eta) per stage; input rpm; output torque N m
TRAINS = [
    ([(4.2, 17.5, 23.0, 19, 71, 48.0, 44.0, 0.25, -0.1, 0.97)], 1450.0, 900.0),
    ([(3.0, 22.5, 0.0, 23, 61, 30.0, 32.0, 0.0, 0.2, 1.0), (5.5, 20.0, 31.0, 17, 53, 60.0, 58.0, 0.35, 0.0, 0.985)],
     980.0, 4200.0),
]


def toml(stages, rpm, torque) -> str:
    out = []
    for m_n, a_n, beta, z1, z2, b1, b2, x1, x2, eta in stages:
        hands = ('hand = "left", ', 'hand = "right", ') if beta else ("", "")
        out += ["[[stage]]", f"normal_module_mm = {m_n}", f"normal_pressure_angle_deg = {a_n}",
                f"helix_angle_deg = {beta}", f"efficiency = {eta}",
                f"pinion = {{ teeth = {z1}, face_width_mm = {b1}, {hands[0]}profile_shift = {x1} }}",
                f"gear = {{ teeth = {z2}, face_width_mm = {b2}, {hands[1]}profile_shift = {x2} }}"]
    out += ["[input]", f"speed_rpm = {rpm}", "ramp_s = 0.1", "[load]", f"torque_Nm = {torque}", "ramp_s = 0.1",
            "[simulation]", "duration_s = 0.6", "steps = 1200"]
    return "\n".join(out) + "\n"


@pytest.mark.parametrize(("stages", "rpm", "torque"), TRAINS)
def test_window_means_are_the_hand_statics_with_losses(stages, rpm, torque):
    cfg = load_design("-", (), stdin=io.BytesIO(toml(stages, rpm, torque).encode())).design
    sim = api.simulate(cfg, compute_design(cfg), want_series=False)
    # torques from the output back: T_p = T_g / (i eta) (power to the load)
    t_pinion, t = [], torque
    for *_, z1, z2, _b1, _b2, _x1, _x2, eta in reversed(stages):
        t = t / (z2 / z1 * eta)
        t_pinion.insert(0, t)
    ratio = math.prod(s[4] / s[3] for s in stages)
    # the window is whole mesh periods of a settled run (rtol 1e-6): its means are the statics to ~1e-5; 1e-4 margin
    assert_allclose(sim.ratio, ratio, rtol=1e-6)
    for (m_n, a_n, beta, z1, *_), tp, st in zip(stages, t_pinion, sim.stages, strict=True):
        b_rad, a_t = math.radians(beta), math.atan(math.tan(math.radians(a_n)) / math.cos(math.radians(beta)))
        f_t = tp * 1e3 / (z1 * m_n / math.cos(b_rad) / 2)  # N, on the reference pitch circle of the pinion
        assert_allclose([st.tangential_N.mean, st.radial_N.mean], [f_t, f_t * math.tan(a_t)], rtol=1e-4)
        assert_allclose(st.axial_N.mean, f_t * math.tan(b_rad), rtol=1e-4, atol=1e-9 * f_t)
    assert abs(sim.solver.energy_residual) < 1e-5  # the run's own balance closes (rtol 1e-6 run)
