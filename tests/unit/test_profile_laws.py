"""The drive's and the load's STEP profiles and the energy integrands: the scalar laws both engines call
(gearcli.model.elements.profile) against the closed form and against the array form the outputs use
(gearcli.model.step)."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli.model import step
from gearcli.model.elements import energy, profile

TIMES = np.concatenate([np.linspace(0.0, 0.5, 41), [0.25 - 1e-12, 0.25, 0.25 + 1e-12, 3.0]])


@pytest.mark.parametrize("ramp_s", [0.0, 0.25])
def test_ramp_is_the_adams_step(ramp_s):
    value = 123.5
    for t in TIMES:
        s = min(max(t / ramp_s, 0.0), 1.0) if ramp_s > 0 else 1.0
        assert_allclose(profile.ramp(t, value, ramp_s), value * s * s * (3 - 2 * s), rtol=1e-14, atol=0)
    assert_allclose([profile.ramp(t, value, ramp_s) for t in TIMES], step.ramp(TIMES, ramp_s, value),
                    rtol=1e-14, atol=0)  # the same profile, scalar and array


@pytest.mark.parametrize(("ramp_s", "start"), [(0.0, 0.0), (0.25, 0.0), (0.25, 0.7)])
def test_input_motion_integrates_and_differentiates_its_speed(ramp_s, start):
    """The angle is the speed's integral from ``start`` and the acceleration its derivative (central differences,
    independent of the closed form), and the triple equals the array form's."""
    v = 40.0
    h = 1e-6
    for t in TIMES[TIMES > 2 * h]:
        th, w, a = profile.input_motion(t, v, ramp_s, start)
        assert_allclose(w, profile.ramp(t, v, ramp_s), rtol=1e-14)
        dth = (profile.input_motion(t + h, v, ramp_s, start)[0] - profile.input_motion(t - h, v, ramp_s, start)[0])
        assert_allclose(dth / (2 * h), w, rtol=1e-6, atol=1e-6)
        dw = (profile.ramp(t + h, v, ramp_s) - profile.ramp(t - h, v, ramp_s)) / (2 * h)
        assert_allclose(a, dw, rtol=1e-5, atol=1e-3 * v)
        ath, aw, aa = step.ramp_motion(t, ramp_s, v)
        assert_allclose((th - start, w, a), (ath, aw, aa), rtol=1e-13, atol=1e-13)
    assert profile.input_motion(0.0, v, ramp_s, start)[0] == start  # it starts at its start angle


def test_energy_integrands_are_the_drive_and_load_powers():
    """A speed drive puts in the torque that makes body 0 follow its motion, times its speed: for a rigid body 0
    alone (no connector: reaction 0) that is J a w = d/dt (J w^2 / 2), the kinetic energy's rate, checked by
    central differences of the profile; a torque's power is T w."""
    J, v, T = 0.35, 40.0, 0.25
    h = 1e-6
    for t in (0.05, 0.125, 0.2):
        _, w, a = profile.input_motion(t, v, T, 0.0)
        ke = [0.5 * J * profile.ramp(t + d, v, T) ** 2 for d in (-h, h)]
        assert_allclose(energy.speed_drive_power(0.0, J, a, w), (ke[1] - ke[0]) / (2 * h), rtol=1e-7)
    assert energy.speed_drive_power(12.0, J, 0.0, 3.0) == 36.0  # at constant speed: the reaction's power
    assert energy.torque_power(-250.0, 4.0) == -1000.0
