"""The design files shipped in configs/: each validates, designs, and says what its header promises."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import pytest
from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design, contact_stiffness_N_mm_e

CONFIGS = Path(__file__).resolve().parents[2] / "configs"


def load(name):
    with (CONFIGS / name).open("rb") as fh:
        return DesignFile.model_validate(tomllib.load(fh))


@pytest.fixture(scope="module")
def industrial():
    cfg = load("industrial_two_stage.toml")
    return cfg, compute_design(cfg)


def test_industrial_reducer_has_no_warnings(industrial):
    _, r = industrial
    assert r.warnings == ()


def test_industrial_reducer_meets_its_header(industrial):
    cfg, r = industrial
    # i = 75/19 · 68/19 = 5100/361 = 14.1274; n_out = 1450 · 361/5100 = 102.637 rpm (target 103.6 ± 2 %)
    assert_allclose(r.total_ratio, 5100 / 361, rtol=1e-14)
    assert_allclose(r.output_speed_rpm, 102.637, rtol=5e-6)
    # input power = T_out ω_out / η² = 1340 N·m · 10.74813 rad/s / 0.9604 = 14996 W ≈ 15 kW
    p_in_W = r.input_torque_Nmm * 1e-3 * r.shafts[0].speed_rpm * 2 * math.pi / 60
    assert_allclose(p_in_W, 14996.4, rtol=1e-5)
    # the profile-shift sums were chosen for round working centre distances (shifts rounded to 4 decimals)
    assert_allclose([s.center_distance_mm for s in r.stages], [145.0, 225.0], rtol=2e-6)
    assert all(s.pinion.profile_shift > 0 for s in r.stages)
    assert all(s.contact_ratio_transverse > 1.2 for s in r.stages)
    assert_allclose([s.overlap_ratio for s in r.stages], 0.99271, rtol=5e-6)  # 45 sin 12°/(3π) = 75 sin 12°/(5π)


def test_industrial_reducer_exercises_the_iso6336_law_and_a_stage_override(industrial):
    cfg, r = industrial
    assert cfg.contact_for(0).stiffness == "iso6336" and cfg.contact_for(1).damping_Ns_mm == 20.0
    for k, s in enumerate(r.stages):
        # e = 1: K = k_n = c_γα b 1000 / cos² β_b, and the static point is linear
        k_n = s.iso6336_mesh_stiffness_N_mm_um * s.face_width_mm * 1000 / math.cos(
            math.radians(s.base_helix_angle_deg)) ** 2
        assert_allclose(contact_stiffness_N_mm_e(s, cfg.contact_for(k)), k_n, rtol=1e-12)
        assert_allclose(s.linearised_stiffness_N_mm, k_n, rtol=1e-12)


@pytest.mark.parametrize("name", ["concrete_mixer.toml", "industrial_two_stage.toml"])
def test_every_number_is_finite(name):
    r = compute_design(load(name))
    values = [r.total_ratio, r.output_speed_deg_s, r.input_torque_Nmm]
    for s in r.stages:
        values += [v for v in vars(s).values() if isinstance(v, float)]
        values += [v for g in (s.pinion, s.gear) for v in vars(g).values() if isinstance(v, float)]
        values += list(vars(s.static_force_N).values())
    assert all(math.isfinite(v) for v in values)
