"""ISO 6336-1 numbers index the smaller wheel 1 whichever member drives: swapping which member drives
(pinion ↔ gear, with their shifts, widths and bodies) must leave every ISO figure of the mesh unchanged."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design


def shifts(lo: float, hi: float):
    """Profile shifts in [lo, hi]: 0, or a magnitude of at least 1e-6 (the design file refuses a nonzero shift
    below that, a subnormal included: docs/design-file.md)."""
    return st.floats(lo, hi).map(lambda x: x if abs(x) >= 1e-6 else 0.0)


def _design(members, m_n, beta, speed_rpm, torque_Nm):
    stage = {"normal_module_mm": m_n, "helix_angle_deg": beta, "pinion": members[0], "gear": members[1]}
    doc = {"stage": [stage], "input": {"speed_rpm": speed_rpm}, "load": {"torque_Nm": torque_Nm}}
    return compute_design(DesignFile.model_validate(doc)).stages[0]


@settings(max_examples=40, deadline=None)
@given(z=st.tuples(st.integers(14, 120), st.integers(14, 120)), x=st.tuples(shifts(0, 0.5), shifts(-0.3, 0.5)),
       beta=st.one_of(st.just(0.0), st.floats(5.0, 30.0)), m_n=st.sampled_from([1.0, 3.0, 8.0]),
       line_load=st.floats(5.0, 500.0), webbed=st.booleans())
def test_iso_stiffness_and_resonance_are_symmetric_in_the_driving_member(z, x, beta, m_n, line_load, webbed):
    hands = ("left", "right") if beta else (None, None)
    members = []
    for teeth, shift, hand in zip(z, x, hands, strict=True):
        g = {"teeth": teeth, "face_width_mm": 12.0 * m_n, "profile_shift": shift}
        if hand:
            g["hand"] = hand
        members.append(g)
    if webbed:
        members[1].update(rim_thickness_mm=2.5 * m_n, web_thickness_mm=4.0 * m_n, bore_diameter_mm=2.0 * m_n)
    # the same mesh force in both directions: F_t = T_1/r_1 = T_2/r_2 (no losses); the smaller wheel at 500 rpm
    b = 12.0 * m_n
    f_t = line_load * b
    small, large = min(z), max(z)
    speeds = [500.0 * small / z[0], 500.0 * small / z[1]]  # rpm of the driving member in each direction
    forward = _design(members, m_n, beta, speeds[0], f_t * _radius(z[1], m_n, beta) / 1000.0)
    backward = _design(members[::-1], m_n, beta, speeds[1], f_t * _radius(z[0], m_n, beta) / 1000.0)
    assert large >= small
    for name in ("iso6336_single_pair_stiffness_N_mm_um", "iso6336_mesh_stiffness_N_mm_um",
                 "iso6336_mesh_stiffness_beta_N_mm_um", "reduced_mass_kg_mm", "resonance_speed_rpm",
                 "resonance_ratio", "contact_ratio_transverse", "center_distance_mm"):
        assert_allclose(getattr(forward, name), getattr(backward, name), rtol=1e-10, err_msg=name)
    assert_allclose(forward.iso6336_factors.C_R, backward.iso6336_factors.C_R, rtol=1e-14)


def _radius(teeth, m_n, beta):
    import math

    return 0.5 * teeth * m_n / math.cos(math.radians(beta))
