"""A planetary stage's dynamic factor (K_v), run-up factor and run peak are its most loaded planet's, not planet 1's.

The field test: a 3-planet stage with unequal spacing and a 2 µm TE reported K_v 1.262 (planet 1's window max
1752.6 N over the static 1388.9 N) while planet 2 reached 2239.3 N (1.612); the rating's simulated K_v already took
the largest planet. Reference: the hand model of load sharing (tests/reference/test_planetary_dynamics.py) with a
position error e on planet 2 alone: each planet's sun and ring meshes in series, k_eq = k_sp k_rp / (k_sp + k_rp);
planet equilibrium and the carrier's moment balance give F_j = F_mean + k_eq (e_j - mean(e)) along the line of
action, so in the settled (heavily damped, unexcited) window
  planet 2: F_2 / F_mean = 1 + k_eq e (1 - 1/N) / F_mean   (the stage's K_v),
  planet 1: F_1 / F_mean = 1 - k_eq e / (N F_mean)          (what the stage reported before).
"""

from __future__ import annotations

import tomllib

from numpy.testing import assert_allclose

from gearcli import api
from gearcli.report.compare import comparison_rows

Z_S, Z_P, Z_R, N, M_N, E_UM, T_LOAD = 24, 30, 84, 3, 4.0, 5.0, 400.0

SCENE = f"""
[[stage]]
type = "planetary"
normal_module_mm = {M_N}
sun = {{ teeth = {Z_S}, face_width_mm = 40 }}
planet = {{ teeth = {Z_P}, face_width_mm = 40, count = {N}, position_error_um = [0.0, {E_UM}, 0.0] }}
ring = {{ teeth = {Z_R}, face_width_mm = 40 }}
carrier = {{ inertia_kg_m2 = 0.8 }}
fixed = "ring"
input = "sun"

[contact]
stiffness = "iso6336"
exponent = 1.0
damping_ratio = 0.2

[input]
speed_rpm = 300
ramp_s = 0.05

[load]
torque_Nm = {T_LOAD}
ramp_s = 0.05

[simulation]
duration_s = 0.3
steps = 600
window_start_s = 0.2
rtol = 1e-9
"""


def series_stiffness(ds) -> tuple[float, float]:
    """The hand model's k_eq (N/m) of a planet's sun and ring meshes in series, and the mean planet's line force F_mean
    (N along the line of action) of SCENE's stage design ``ds`` (as tests/reference/test_planetary_dynamics.py)."""
    k_sp = ds.iso6336_mesh_stiffness_N_mm_um * ds.face_width_mm * 1e6
    k_rp = ds.planetary.planet_ring.iso6336_mesh_stiffness_N_mm_um * ds.planetary.planet_ring.face_width_mm * 1e6
    return k_sp * k_rp / (k_sp + k_rp), T_LOAD / (1 + Z_R / Z_S) / (N * 0.5e-3 * ds.pinion.base_diameter_mm)


def test_the_stage_dynamic_factor_is_the_most_loaded_planets(tmp_path):
    path = tmp_path / "planetary.toml"
    path.write_text(SCENE)
    loaded, design = api.load_and_design(str(path))
    result = api.simulate(loaded.design, design)
    st, ds = result.stages[0], design.stages[0]
    k_eq, f_mean = series_stiffness(ds)  # the hand model
    most, planet_1 = 1 + k_eq * E_UM * 1e-6 * (1 - 1 / N) / f_mean, 1 - k_eq * E_UM * 1e-6 / (N * f_mean)
    assert most > 1.05 and planet_1 < 0.99  # the check has teeth: the planets differ by several per cent
    assert tomllib.loads(SCENE)["stage"][0]["planet"]["position_error_um"][1] == E_UM  # on planet 2, not 1
    # the settled window: max = mean to the residual ringing (ζ = 0.2, rtol 1e-9), well below 1e-3 of F
    assert_allclose(st.tangential_N.max / st.simulated_static_tangential_N, planet_1, rtol=1e-3)  # planet 1's channel
    assert_allclose(st.dynamic_factor, most, rtol=1e-3)
    assert_allclose(st.dynamic_factor, st.load_sharing_factor, rtol=1e-3)  # statics: K_v of the stage = K_gamma
    # the run peak and the run-up factor are the most loaded planet's too, and agree with each other
    peak = max(abs(p.sun.tangential_N.max) for p in st.planets)
    assert st.peak_tangential_N >= peak * (1 - 1e-12)
    assert_allclose(st.runup_factor, st.peak_tangential_N / st.simulated_static_tangential_N, rtol=1e-12)
    # report's theory against simulation: the planets' mean meets the static per-planet force (moment balance:
    # sum F_j = N F_mean), not planet 1's share (-0.8 % in the field test, here 1 - planet_1 = 4 %)
    rows = {r.quantity: r for r in comparison_rows(design, result) if r.stage == 1}
    assert_allclose(rows["tangential_N"].simulated, ds.static_force_N.tangential, rtol=1e-4)
    assert_allclose(rows["radial_N"].simulated, ds.static_force_N.radial, rtol=1e-4)
