"""`gearcli design` warns (check ``steel_stiffness``) on a mesh whose pairing is not steel on steel: c′ = c′_th C_M
C_R C_B cos β is steel's (the contract's formula has no material term), where ISO 6336-1 scales it by E/E_st,
E = 2 E1 E2 / (E1 + E2), E_st = 206,000 N/mm², for other pairings."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import pytest

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design

CONFIGS = Path(__file__).resolve().parents[2] / "configs"


def _pair(wheel: dict) -> DesignFile:
    steel = {"density_kg_m3": 7800, "youngs_modulus_MPa": 2.07e5, "poisson_ratio": 0.29}
    doc = {"materials": {"steel": steel, "wheel": wheel},
           "stage": [{"normal_module_mm": 3.0, "normal_pressure_angle_deg": 20.0, "helix_angle_deg": 0.0,
                      "pinion": {"teeth": 20, "face_width_mm": 30.0},
                      "gear": {"teeth": 60, "face_width_mm": 30.0, "material": "wheel"}}],
           "input": {"speed_rpm": 1000.0}, "load": {"torque_Nm": 500.0}}
    return DesignFile.model_validate(doc)


def _checks(design) -> list[dict]:
    return [d.data for d in design.diagnostics if d.data.get("check") == "steel_stiffness"]


def test_a_grey_iron_wheel_is_warned_with_isos_modulus_ratio():
    iron = {"density_kg_m3": 7200, "youngs_modulus_MPa": 1.1e5, "poisson_ratio": 0.26, "treatment": "grey_iron"}
    design = compute_design(_pair(iron))
    (found,) = _checks(design)
    by_hand = 2 * 2.07e5 * 1.1e5 / (2.07e5 + 1.1e5) / 206_000  # 0.6974
    assert math.isclose(found["modulus_ratio"], by_hand, rel_tol=1e-12)
    assert found["stage"] == 1 and found["mesh"] == "mesh"
    assert any("steel/wheel" in w and "E/E_st" in w and "0.697" in w for w in design.warnings)


def test_a_cast_iron_treatment_counts_even_at_a_steel_like_modulus():
    # a nodular iron entered with a steel's modulus is still not steel: the warning follows the treatment
    iron = {"density_kg_m3": 7100, "youngs_modulus_MPa": 2.0e5, "poisson_ratio": 0.28, "treatment": "nodular_iron"}
    (found,) = _checks(compute_design(_pair(iron)))
    assert math.isclose(found["modulus_ratio"], 2 * 2.07e5 * 2.0e5 / 4.07e5 / 206_000, rel_tol=1e-12)


@pytest.mark.parametrize("modulus", [1.93e5, 2.06e5, 2.12e5])  # stainless, ISO's E_st, a high steel
def test_steel_pairs_are_not_warned(modulus):
    steel = {"density_kg_m3": 7850, "youngs_modulus_MPa": modulus, "poisson_ratio": 0.3}
    assert _checks(compute_design(_pair(steel))) == []


def test_a_bronze_ring_warns_the_planet_ring_mesh_only():
    doc = tomllib.loads((CONFIGS / "planetary_stage.toml").read_text())
    doc["materials"]["bronze"] = {"density_kg_m3": 8800, "youngs_modulus_MPa": 1.1e5, "poisson_ratio": 0.34}
    doc["stage"][0]["ring"]["material"] = "bronze"
    doc.pop("rating")  # the rating asks a bronze for ISO 6336-5 data it has none of
    (found,) = _checks(compute_design(DesignFile.model_validate(doc)))
    assert found["mesh"] == "planet_ring"
    assert math.isclose(found["modulus_ratio"], 2 * 206_000 * 1.1e5 / (206_000 + 1.1e5) / 206_000, rel_tol=1e-12)
