"""A load class's stress carries ISO 6336-1's load-dependent factors at the class's own load (ISO 6336-6: the
factors K_Hβ, K_Hα, K_Fβ, K_Fα of each load level), not the duty point's.

The defect: life scaled a point's rated stress to a class force (σ_H ∝ √F_t, σ_F ∝ F_t) with the point's factors
held. A start from an idle point (a crane's empty hook: 400 N m at the drum, 11 N/mm of line load) peaks at many
times the idle load, and the idle point's K_Hβ 3.3 and K_Hα 1.8 made its start classes' stress 2490 MPa at a peak
of 16.3 kN, where the same force from a rated-load start was 1680 MPa: the empty-hook starts gave 0.83 of the
pinion's pitting damage, 270 times the rated-load starts' with their higher peaks."""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from gearcli import api
from gearcli.design.iso6336 import ISO6336

HOIST = """
title = "Crane hoist, first stage"
[materials.steel18]
density_kg_m3 = 7850
youngs_modulus_MPa = 2.06e5
poisson_ratio = 0.3
treatment = "case_carburized"
contact_fatigue_limit_MPa = 1500
bending_fatigue_limit_MPa = 500
[[stage]]
normal_module_mm = 3
helix_angle_deg = 14
accuracy_grade = 6
pinion = { teeth = 19, face_width_mm = 60, hand = "left", material = "steel18", profile_shift = 0.3, flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10 }
gear   = { teeth = 87, face_width_mm = 55, hand = "right", material = "steel18", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10 }
[input]
speed_rpm = 1470
[load]
torque_Nm = 1300
[lubricant]
viscosity_40C_mm2_s = 220
[rating]
required_life_h = 12500
"""

IDLE_NM, CLASS_RATIO = 90.0, 24.7  # an idle point (line load ~11 N/mm) and a start peak 24.7 times its load


def _design(path, torque_Nm: float):
    # as life designs a point: K_A = 1, the spectrum replacing K_v
    return api.load_and_design(str(path), [f"load.torque_Nm={torque_Nm!r}", "load.application_factor=1.0",
                                           "rating.dynamic_factor=1.0"])


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    path = tmp_path_factory.mktemp("hoist") / "hoist.toml"
    path.write_text(HOIST, encoding="utf-8")
    return _design(path, IDLE_NM), _design(path, IDLE_NM * CLASS_RATIO)


def test_a_class_is_rated_as_the_design_at_its_own_load(pair):
    """The class at 24.7x the idle force is rated as `gearcli design` rates the pair at 24.7x the idle torque
    (the static route's reference: the whole design computed again at that load)."""
    (idle_loaded, idle), (_, full) = pair
    rated = ISO6336.rate_at_force(idle_loaded.design, idle.stages[0], CLASS_RATIO)
    ref = full.stages[0].rating
    for member in ("pinion", "gear"):
        for mode in ("pitting", "bending"):
            assert_allclose(getattr(rated, member).stress_MPa(mode), getattr(ref, member).stress_MPa(mode),
                            rtol=1e-12, err_msg=f"{member} {mode}")
    for factor in ("K_Hbeta", "K_Halpha", "K_Fbeta", "K_Falpha"):
        assert_allclose(getattr(rated, factor), getattr(ref, factor), rtol=1e-12, err_msg=factor)


def test_the_class_stress_follows_isos_stress_formulas(pair):
    """By hand, ISO 6336-2 and -3: σ_H = σ_H0 √(K_A K_v K_Hβ K_Hα) with σ_H0 ∝ √F_t, σ_F = σ_F0 K_A K_v K_Fβ K_Fα
    with σ_F0 ∝ F_t (every other factor independent of the load). So the class's stress is the idle point's scaled
    by √ratio (or ratio) AND by the factors' change; the idle factors held (the old scaling) overstate it."""
    (_, idle), (_, full) = pair
    ri, rf = idle.stages[0].rating, full.stages[0].rating
    hand_h = ri.pinion.sigma_H_MPa * math.sqrt(CLASS_RATIO * (rf.K_Hbeta * rf.K_Halpha) / (ri.K_Hbeta * ri.K_Halpha))
    hand_f = ri.pinion.sigma_F_MPa * CLASS_RATIO * (rf.K_Fbeta * rf.K_Falpha) / (ri.K_Fbeta * ri.K_Falpha)
    assert_allclose(rf.pinion.sigma_H_MPa, hand_h, rtol=1e-12)
    assert_allclose(rf.pinion.sigma_F_MPa, hand_f, rtol=1e-12)
    # ISO's factors fall as the line load rises: at 11 N/mm K_Hβ > 2.5, at 24.7x it below 1.6
    assert ri.K_Hbeta > 2.5 and rf.K_Hbeta < 1.6
    held = ri.pinion.sigma_H_MPa * math.sqrt(CLASS_RATIO)
    assert held > 1.4 * rf.pinion.sigma_H_MPa  # the defect's size: 40 % too high a stress, ~80x the damage


def test_the_low_load_stiffness_follows_the_line_load(pair):
    """ISO 6336-1, 9: c' carries (F_t K_A / b / 100)^0.25 below 100 N/mm; the stage at the class load has the
    full-load design's c', c_γα and n_E1."""
    (idle_loaded, idle), (_, full) = pair
    st = idle.stages[0]
    from gearcli.design.iso6336 import at_force

    scaled = at_force(idle_loaded.design, st, CLASS_RATIO)
    ref = full.stages[0]
    line_idle = st.static_force_N.tangential / st.face_width_mm
    hand = st.iso6336_single_pair_stiffness_N_mm_um * (min(CLASS_RATIO * line_idle, 100.0) / line_idle) ** 0.25
    assert_allclose(scaled.iso6336_single_pair_stiffness_N_mm_um, hand, rtol=1e-12)
    for name in ("iso6336_single_pair_stiffness_N_mm_um", "iso6336_mesh_stiffness_N_mm_um",
                 "iso6336_mesh_stiffness_beta_N_mm_um", "resonance_speed_rpm", "resonance_ratio",
                 "resonance_lower_limit"):
        assert_allclose(getattr(scaled, name), getattr(ref, name), rtol=1e-12, err_msg=name)
    assert_allclose(scaled.static_force_N.tangential, ref.static_force_N.tangential, rtol=1e-12)


def test_life_rates_a_class_at_its_own_load(pair):
    """The life's class stress (gearcli.life.run._stress) of an idle point at 24.7x its load is the full-load
    design's; at the point's own load (ratio 1) it is the point's rating, unchanged."""
    from gearcli.life import run

    (idle_loaded, idle), (_, full) = pair
    pd = _point(run, idle_loaded.design, idle)
    f0 = idle.stages[0].static_force_N.tangential
    for member in ("pinion", "gear"):
        ref = getattr(full.stages[0].rating, member)
        own = getattr(idle.stages[0].rating, member)
        for mode in ("pitting", "bending"):
            assert_allclose(run._stress(pd, 0, member, mode, CLASS_RATIO * f0, f0), ref.stress_MPa(mode), rtol=1e-12)
            assert run._stress(pd, 0, member, mode, f0, f0) == own.stress_MPa(mode)


def _point(run, cfg, design):
    """A life point's data with the fields _stress reads (its design and file)."""
    from gearcli.life.duty import DutyPoint
    from gearcli.life.result import PointRun

    point = DutyPoint("idle", 1.0, IDLE_NM, 1470.0)
    return run._PointData(point, design, cfg, [], None, PointRun("idle", 1.0, IDLE_NM, 1470.0, (1.0,)))


def test_a_start_with_a_lower_peak_does_less_damage_per_start():
    """configs/crane_hoist_starts.toml end to end: the empty hook's start peaks lower than the rated load's, so each
    of its start classes, rated at its own load, is less stressed than the rated start's class of the same force
    or more, and one empty-hook start does less damage than one rated-load start (it did 270 times more with the
    idle point's factors held)."""
    import json
    from pathlib import Path

    from click.testing import CliRunner

    from gearcli.cli import cli

    config = Path(__file__).resolve().parents[2] / "configs" / "crane_hoist_starts.toml"
    res = CliRunner().invoke(cli, ["life", str(config), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    life = json.loads(res.stdout)["life"]
    points = {p["name"]: p for p in life["points"]}
    rated, empty = points["rated load"]["start"], points["empty hook"]["start"]
    assert empty["peak_tangential_N"][0] < rated["peak_tangential_N"][0]
    per_start = {name: p["start"]["damage"][0]["pinion"]["pitting"] / p["start"]["count"] for name, p in points.items()}
    assert per_start["empty hook"] < per_start["rated load"], per_start
    # the class stress is a function of the class force alone, whichever point's start it comes from: stress
    # rises with force over all the start classes of stage 1's pinion together
    bins = sorted((b["force_N"], b["stress_MPa"]) for b in life["stages"][0]["pinion"]["pitting"]["bins"]
                  if b["point"].endswith("(start)"))
    stresses = [s for _, s in bins]
    assert all(b >= a * (1 - 1e-9) for a, b in zip(stresses, stresses[1:], strict=False))
