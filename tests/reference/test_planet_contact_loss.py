"""A planet that a position error leaves inside the backlash carries nothing: the contact-loss warning names it.

The field test (session 16): a star 20/25/70 with three planets, 0.05 mm backlash and position errors [15, 0, -30] µm
ran with planet 3 never touching (its sun-mesh force 0 N, the others 7820 N and 1624 N) and no warning at all, the
stage's `contact_loss_fraction` 0 and `regime` "no impact" (the stage's channel is planet 1's sun mesh alone); with
the errors reversed ([-30, 0, 15]) planet 1 was the idle one and the stage warned "tooth impacts (rattle) — the load
is too small for the vibration", a wrong diagnosis. Reference: the hand model of load sharing with a linear mesh
law (tests/reference/test_planetary_worst_planet.py): each planet's sun and ring meshes in series,
k_eq = k_sp k_rp / (k_sp + k_rp); a planet in contact carries F_j = k_eq (c + e_j) along the line of action, and the
sun's moment balance sums them to N F_mean. With e = 0 on two planets and the third's e below -F/k_eq (the
approach its loaded neighbours need), the third is out of contact and the two carry N F_mean / 2 each.
"""

from __future__ import annotations

import pytest
from numpy.testing import assert_allclose

from gearcli import api
from tests.reference.test_planetary_worst_planet import SCENE, N, series_stiffness

E_UM, BACKLASH_MM = -20.0, 0.05


def scene(errors_um: list[float], backlash_mm: float = BACKLASH_MM) -> str:
    """The worst-planet test's settled linear planetary (ring held, sun in, 3 planets, ζ = 0.2, rtol 1e-9) with
    backlash and these errors."""
    out = SCENE.replace('type = "planetary"', f'type = "planetary"\nbacklash_mm = {backlash_mm}')
    return out.replace("position_error_um = [0.0, 5.0, 0.0]", f"position_error_um = {errors_um}")


@pytest.mark.parametrize("idle", [0, 2])
def test_a_planet_left_in_the_backlash_is_named(tmp_path, idle):
    errors = [0.0] * N
    errors[idle] = E_UM
    path = tmp_path / "planetary.toml"
    path.write_text(scene(errors))
    assert f"position_error_um = {errors}" in path.read_text() and "backlash_mm" in path.read_text()
    loaded, design = api.load_and_design(str(path))
    result = api.simulate(loaded.design, design)
    st, ds = result.stages[0], design.stages[0]
    k_eq, f_mean = series_stiffness(ds)  # the hand model's series stiffness and mean planet's line force
    # the check has teeth: two planets carrying N/2 F_mean need an approach well short of the idle planet's error
    assert k_eq * abs(E_UM) * 1e-6 > 2.0 * (N / 2) * f_mean
    means = [p.sun.tangential_N.mean / ds.static_force_N.tangential for p in st.planets]
    hand = [0.0 if j == idle else N / 2 for j in range(N)]
    assert_allclose(means, hand, atol=1e-3)
    assert_allclose(st.load_sharing_factor, N / 2, rtol=1e-3)
    lost = [d for d in result.diagnostics if d.code == "contact_loss"]
    # every warning names the idle planet and one of its meshes; none blames the load or the vibration
    assert sorted((d.data["planet"], d.data["mesh"]) for d in lost) == [(idle + 1, "planet_ring"), (idle + 1, "sun_planet")]
    assert all(d.data["fraction"] == 1.0 and "carries no load" in d.message for d in lost)


def test_a_planet_pressed_onto_its_back_flank_is_named(tmp_path):
    """Without backlash every planet stays in contact, F_j = F_mean + k_eq (e_j - mean(e)) (the moment balance sums
    them to N F_mean): a planet whose error takes more than F_mean / k_eq off its approach is loaded backwards."""
    errors = [0.0, 0.0, E_UM]
    path = tmp_path / "planetary.toml"
    path.write_text(scene(errors, 0.0))
    loaded, design = api.load_and_design(str(path))
    result = api.simulate(loaded.design, design)
    st, ds = result.stages[0], design.stages[0]
    k_eq, f_mean = series_stiffness(ds)
    hand = [1 + k_eq * (e - sum(errors) / N) * 1e-6 / f_mean for e in errors]
    assert hand[2] < -0.5  # the check has teeth: planet 3 carries a sizeable backward load
    assert_allclose([p.sun.tangential_N.mean / ds.static_force_N.tangential for p in st.planets], hand, rtol=1e-3)
    lost = [d for d in result.diagnostics if d.code == "contact_loss"]
    assert sorted((d.data["planet"], d.data["mesh"]) for d in lost) == [(3, "planet_ring"), (3, "sun_planet")]
    assert all("back flank" in d.message and "vibration" not in d.message for d in lost)
