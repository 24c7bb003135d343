"""Speeds, torques, efficiencies and inertias along the train, by hand."""

from __future__ import annotations

import copy
import tomllib
from pathlib import Path

from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design
from gearcli.design.inertia import solid_disc_inertia_kg_m2
from gearcli.design.kinematics import pinion_torque_Nmm

SEED = Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml"
with SEED.open("rb") as _fh:
    SEED_DOC = tomllib.load(_fh)
I1, I2, I3 = 51 / 21, 50 / 17, 53 / 17


def design(edit=None):
    doc = copy.deepcopy(SEED_DOC)
    if edit:
        edit(doc)
    return compute_design(DesignFile.model_validate(doc))


def test_efficiencies_raise_the_input_torque():
    def edit(d):
        for st, eta in zip(d["stage"], (0.98, 0.97, 0.96), strict=True):
            st["efficiency"] = eta
    r = design(edit)
    # T_in = T_out / (i1 i2 i3 η1 η2 η3) = 5.31e6 / (22.26891 · 0.98 · 0.97 · 0.96)
    #      = 5.31e6 / 20.32207 = 2.61292e5 N·mm
    assert_allclose(r.input_torque_Nmm, 2.61292e5, rtol=5e-6)
    # gear 2 torque = pinion 3 torque = 5.31e6 / (i2 η2 · i3 η3) = 5.31e6 / (2.941176 · 0.97 · 3.117647 · 0.96)
    assert_allclose(r.stages[0].gear.torque_Nmm, 5.31e6 / (I2 * 0.97 * I3 * 0.96), rtol=1e-12)
    assert_allclose(r.stages[1].pinion.torque_Nmm, r.stages[0].gear.torque_Nmm, rtol=0)  # same rigid shaft
    # speeds are unaffected by losses
    assert_allclose(r.output_speed_deg_s, 3600 / (I1 * I2 * I3), rtol=1e-12)


def test_load_reversal_takes_the_loss_on_the_gear_side():
    # power flows back from the load: T_p = T_g η / i. Stage alone: T_g = −1000, i = 3, η = 0.9 -> −300
    assert_allclose(pinion_torque_Nmm(-1000.0, 3.0, 0.9), -300.0, rtol=1e-15)
    assert_allclose(pinion_torque_Nmm(1000.0, 3.0, 0.9), 1000.0 / 2.7, rtol=1e-15)

    def edit(d):
        d["load"]["torque_Nmm"] = -5.31e6
        for st in d["stage"]:
            st["efficiency"] = 0.95
    r = design(edit)
    # T_in = −5.31e6 · 0.95³ / 22.26891 = −5.31e6 · 0.857375 / 22.26891 = −2.04440e5 N·mm
    assert_allclose(r.input_torque_Nmm, -2.04440e5, rtol=5e-6)
    assert r.output_torque_Nmm == -5.31e6
    assert r.stages[0].static_force_N.tangential < 0


def test_shaft_torques_and_inertias_follow_the_shafts():
    r = design()
    s = r.stages
    assert_allclose([sh.torque_Nmm for sh in r.shafts],
                    [s[0].pinion.torque_Nmm, s[1].pinion.torque_Nmm, s[2].pinion.torque_Nmm, 5.31e6], rtol=0)
    expected = [s[0].pinion.inertia_kg_m2, s[0].gear.inertia_kg_m2 + s[1].pinion.inertia_kg_m2,
                s[1].gear.inertia_kg_m2 + s[2].pinion.inertia_kg_m2, s[2].gear.inertia_kg_m2]
    assert_allclose([sh.inertia_kg_m2 for sh in r.shafts], expected, rtol=1e-15)


def test_given_inertia_overrides_the_disc():
    def edit(d):
        d["stage"][0]["pinion"]["inertia_kg_m2"] = 1.25
    r = design(edit)
    p = r.stages[0].pinion
    assert p.inertia_kg_m2 == 1.25 and p.inertia_given  # passed through untouched
    assert_allclose(r.shafts[0].inertia_kg_m2, 1.25, rtol=0)


def test_solid_disc_by_hand():
    # ρ = 7800, b = 190 mm, d = 257.6298 mm: J = π · 7800 · 0.19 · 0.2576298⁴ / 32
    #   = π · 7800 · 0.19 · 4.405479e-3 / 32 = 0.640963 kg·m² (pinion 1 of the seed)
    assert_allclose(solid_disc_inertia_kg_m2(7800.0, 190.0, 257.6298), 0.640963, rtol=5e-6)
    assert_allclose(design().stages[0].pinion.inertia_kg_m2, 0.640963, rtol=5e-6)


def test_gear_material_density_is_used():
    def edit(d):
        d["materials"]["light"] = {"density_kg_m3": 2700, "youngs_modulus_MPa": 7.0e4, "poisson_ratio": 0.33}
        d["stage"][0]["gear"]["material"] = "light"
    r, seed = design(edit), design()
    # inertia scales with density: 2700 / 7800
    assert_allclose(r.stages[0].gear.inertia_kg_m2, seed.stages[0].gear.inertia_kg_m2 * 2700 / 7800, rtol=1e-12)
    # 1/E* = (1 − 0.29²)/2.07e5 + (1 − 0.33²)/7.0e4 = 0.9159/2.07e5 + 0.8911/7.0e4
    #      = 4.424638e-6 + 1.273000e-5 = 1.715464e-5 /MPa -> E* = 58293.3 MPa
    assert_allclose(r.stages[0].effective_modulus_MPa, 58293.3, rtol=5e-6)


def test_input_speed_units_agree():
    def rpm(d):
        d["input"] = {"speed_rpm": 600.0, "ramp_s": 0.18}

    def rad(d):
        d["input"] = {"speed_rad_s": 20.0 * 3.141592653589793, "ramp_s": 0.18}
    for edit in (rpm, rad):
        assert_allclose(design(edit).output_speed_deg_s, 3600 / (I1 * I2 * I3), rtol=1e-12)  # 600 rpm = 3600 °/s


def test_one_stage_and_many_stages():
    def one(d):
        d["stage"] = d["stage"][:1]
    r = design(one)
    assert len(r.shafts) == 2 and len(r.stages) == 1
    assert_allclose(r.total_ratio, I1, rtol=1e-15)

    def six(d):
        d["stage"] = d["stage"] * 2
    r = design(six)
    assert [s.index for s in r.stages] == [1, 2, 3, 4, 5, 6] and len(r.shafts) == 7
    assert_allclose(r.total_ratio, (I1 * I2 * I3) ** 2, rtol=1e-12)
